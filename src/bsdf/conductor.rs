//! Mitsuba 3's `conductor`: a smooth metal, one Dirac lobe in the mirror direction
//! weighted by the conductor Fresnel reflectance (and an optional tint).

use glam::{Vec2, Vec3};

use super::fresnel::fresnel_conductor;
use super::{Bsdf, BsdfSample, ConductorMaterial};
use crate::math::Spectrum;

/// A perfectly smooth conductor with complex index η + ik per channel.
#[derive(Clone, Debug)]
pub struct Conductor {
    /// Real part of the relative index of refraction.
    pub eta: Spectrum,
    /// Imaginary part (absorption).
    pub k: Spectrum,
    /// Tint multiplying the Fresnel term (not physical; Mitsuba's `specular_reflectance`).
    pub specular_reflectance: Spectrum,
}

impl Conductor {
    /// A named material with no tint.
    pub fn from_material(material: ConductorMaterial) -> Conductor {
        let (eta, k) = material.ior();
        Conductor {
            eta,
            k,
            specular_reflectance: Spectrum::ONE,
        }
    }
}

impl Default for Conductor {
    /// Mitsuba 3's default: material "none", a perfect mirror.
    fn default() -> Conductor {
        Conductor::from_material(ConductorMaterial::None)
    }
}

impl Bsdf for Conductor {
    /// Zero: a Dirac lobe has no value at any given pair of directions.
    fn eval(&self, _w_in: Vec3, _w_out: Vec3) -> Spectrum {
        Spectrum::ZERO
    }

    /// The mirror direction (−x, −y, z), with Dirac weights pdf = 1 and
    /// f = F(cos θ)·tint/cos θ, so that f·cos θ/pdf = F·tint.
    fn sample(&self, w_out: Vec3, _u: Vec2) -> Option<BsdfSample> {
        if w_out.z <= 0.0 {
            return None;
        }
        let w_in = Vec3::new(-w_out.x, -w_out.y, w_out.z);
        let f = fresnel_conductor(w_out.z, self.eta, self.k) * self.specular_reflectance;
        Some(BsdfSample {
            w_in,
            f: f / w_in.z,
            pdf: 1.0,
            delta: true,
        })
    }

    /// Zero: no density with respect to solid angle.
    fn pdf(&self, _w_in: Vec3, _w_out: Vec3) -> f32 {
        0.0
    }

    fn is_delta(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mirror_throughput_is_fresnel() {
        let c = Conductor::from_material(ConductorMaterial::Cu);
        let w_out = Vec3::new(0.5, 0.1, 0.7).normalize();
        let s = c.sample(w_out, Vec2::splat(0.5)).expect("sample");
        assert!(s.delta && c.is_delta() && c.has_delta_lobe());
        assert!((s.w_in - Vec3::new(-w_out.x, -w_out.y, w_out.z)).length() < 1e-6);
        let throughput = s.f * s.w_in.z / s.pdf;
        let f = fresnel_conductor(w_out.z, c.eta, c.k);
        assert!((throughput - f).abs().max_element() < 1e-6);
        assert_eq!(c.eval(s.w_in, w_out), Spectrum::ZERO);
        assert_eq!(c.pdf(s.w_in, w_out), 0.0);
        assert!(c.sample(-w_out, Vec2::ZERO).is_none());
        let white = Conductor::default()
            .sample(w_out, Vec2::ZERO)
            .expect("sample");
        assert!(
            (white.f * white.w_in.z / white.pdf - Spectrum::ONE)
                .abs()
                .max_element()
                < 1e-6
        );
    }
}
