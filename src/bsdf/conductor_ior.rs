//! Named conductors: complex refractive index η + ik per linear-sRGB channel, the values
//! Mitsuba 3 (3.9, `scalar_rgb`) derives from its measured spectra for `material = "Au"`
//! etc. (printed by `tests/mitsuba/conductor_rgb.py`), so scenes match Mitsuba's colours.

use crate::math::Spectrum;

named_enum! {
    /// A conductor preset, by Mitsuba 3's `material` name.
    pub enum ConductorMaterial: "conductor material" {
        /// η = 0, k = 1: Fresnel = 1 at every angle, a perfect mirror (Mitsuba's default).
        None => "none",
        /// Gold.
        Au => "Au",
        /// Silver.
        Ag => "Ag",
        /// Copper.
        Cu => "Cu",
        /// Aluminium.
        Al => "Al",
        /// Chromium.
        Cr => "Cr",
    }
}

impl ConductorMaterial {
    /// (η, k) per RGB channel.
    pub fn ior(self) -> (Spectrum, Spectrum) {
        let (eta, k) = match self {
            ConductorMaterial::None => ([0.0; 3], [1.0; 3]),
            ConductorMaterial::Au => (
                [0.143_036, 0.375_307, 1.442_05],
                [3.983, 2.385_56, 1.603_36],
            ),
            ConductorMaterial::Ag => (
                [0.155_276, 0.116_728, 0.138_388],
                [4.828_35, 3.122_22, 2.1469],
            ),
            ConductorMaterial::Cu => (
                [0.201_005, 0.923_75, 1.102_22],
                [3.913_26, 2.453_05, 2.142_09],
            ),
            ConductorMaterial::Al => ([1.6575, 0.880_405, 0.521_244], [9.223_81, 6.2695, 4.837]),
            ConductorMaterial::Cr => ([4.369_67, 2.916_51, 1.6549], [5.206_55, 4.231_31, 3.7547]),
        };
        (Spectrum::from_array(eta), Spectrum::from_array(k))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::fresnel::fresnel_conductor;

    #[test]
    fn names_round_trip_and_gold_is_yellow() {
        for m in ConductorMaterial::ALL {
            assert_eq!(m.name().parse::<ConductorMaterial>(), Ok(m));
        }
        let (eta, k) = ConductorMaterial::Au.ior();
        let f = fresnel_conductor(1.0, eta, k);
        assert!(f.x > f.y && f.y > f.z, "{f}");
        assert!("Pt".parse::<ConductorMaterial>().is_err());
    }
}
