//! The table of BSDF configurations the statistical BSDF tests run over: every new
//! material × distribution × roughness, and the incident angles to test each at.

use glam::Vec3;
use lightlab::bsdf::{
    Conductor, ConductorMaterial, Material, MicrofacetType, Phong, Plastic, PlasticParams,
    RoughConductor, RoughPlastic,
};
use lightlab::math::Spectrum;

/// Roughnesses of every microfacet case, from nearly smooth to very rough.
pub const ALPHAS: [f32; 4] = [0.005, 0.05, 0.3, 1.0];

/// Phong exponents, from a broad lobe to a sharp one (37: not a power of ten).
pub const PHONG_EXPONENTS: [f32; 5] = [1.0, 10.0, 37.0, 100.0, 1000.0];

/// Angles of w_out from the normal, in degrees: normal, 45°, 80° and grazing.
pub const ANGLES: [f32; 4] = [0.0, 45.0, 80.0, 89.0];

/// One BSDF configuration.
pub struct Case {
    /// Row name.
    pub name: String,
    /// The material.
    pub material: Material,
    /// Roughness, for choosing domains (0 for smooth BSDFs).
    pub alpha: f32,
}

/// w_out at `degrees` from the normal, off the xz-plane so that φ plays a part.
pub fn w_out(degrees: f32) -> Vec3 {
    let t = degrees.to_radians();
    Vec3::new(t.sin() * 0.8, t.sin() * 0.6, t.cos())
}

/// Every rough conductor and rough plastic configuration, the smooth plastic, and the
/// modified Phong at [`PHONG_EXPONENTS`] (lobe mixture, rotation to the mirror
/// direction and below-horizon rejection; issue 18).
/// `white` makes them white (Fresnel 1 conductors, unit diffuse albedo) for furnaces.
pub fn cases(white: bool) -> Vec<Case> {
    let metal = if white {
        ConductorMaterial::None
    } else {
        ConductorMaterial::Au
    };
    let diffuse = if white {
        Spectrum::ONE
    } else {
        Spectrum::new(0.2, 0.5, 0.8)
    };
    let mut list = Vec::new();
    for distribution in MicrofacetType::ALL {
        for alpha in ALPHAS {
            list.push(Case {
                name: format!("roughconductor-{distribution}-{alpha}"),
                material: Material::RoughConductor(RoughConductor::from_material(
                    distribution,
                    alpha,
                    metal,
                )),
                alpha,
            });
            let params = PlasticParams {
                distribution,
                alpha,
                diffuse_reflectance: diffuse,
                ..PlasticParams::default()
            };
            list.push(Case {
                name: format!("roughplastic-{distribution}-{alpha}"),
                material: Material::RoughPlastic(RoughPlastic::new(params).expect("valid")),
                alpha,
            });
        }
    }
    let params = PlasticParams {
        diffuse_reflectance: diffuse,
        ..PlasticParams::default()
    };
    list.push(Case {
        name: "plastic".into(),
        material: Material::Plastic(Plastic::new(params).expect("valid")),
        alpha: 0.0,
    });
    list.extend(PHONG_EXPONENTS.map(|n| phong_case(n, white)));
    list.push(Case {
        name: "conductor".into(),
        material: Material::Conductor(Conductor::from_material(metal)),
        alpha: 0.0,
    });
    list
}

/// Modified Phong with exponent `n`; white means kd + ks = 1. Its `alpha` is the
/// Beckmann roughness of the same lobe width, √(2/(n + 2)) (Walter et al. 2007, §5.2),
/// so the table picks caps and quadrature nodes as tight as the lobe.
fn phong_case(n: f32, white: bool) -> Case {
    let (kd, ks) = if white {
        (Spectrum::splat(0.4), Spectrum::splat(0.6))
    } else {
        (Spectrum::new(0.1, 0.3, 0.2), Spectrum::new(0.6, 0.5, 0.4))
    };
    Case {
        name: format!("phong-{n}"),
        material: Material::Phong(Phong {
            kd,
            ks,
            exponent: n,
        }),
        alpha: (2.0 / (n + 2.0)).sqrt(),
    }
}

/// ∫ g(w_in) dω_in over the hemisphere, taken over half vectors h (w_in = reflect(w_out, h),
/// dω_in = 4 (w_out·h) dω_h, Walter et al. 2007, eq. 14) by the midpoint rule in
/// (s, φ) with tan θ_h = k·s/(1 − s), k = max(α, 0.01): the nodes crowd around the
/// normal as tightly as the lobe, so even α = 0.005 at 89° is resolved.
pub fn integrate_over_half_vectors(alpha: f32, w_out: Vec3, g: impl Fn(Vec3) -> f64) -> f64 {
    let (ns, nphi) = (1024, 256);
    let k = alpha.max(0.01) as f64;
    let mut total = 0.0;
    for i in 0..ns {
        let s = (i as f64 + 0.5) / ns as f64;
        let tan = k * s / (1.0 - s);
        let theta = tan.atan();
        // dθ/ds = k/((1 − s)²(1 + tan²θ)); dω = sin θ dθ dφ.
        let weight = theta.sin() * k / ((1.0 - s).powi(2) * (1.0 + tan * tan)) / ns as f64
            * std::f64::consts::TAU
            / nphi as f64;
        for j in 0..nphi {
            let phi = (j as f64 + 0.5) / nphi as f64 * std::f64::consts::TAU;
            let h = Vec3::new(
                (theta.sin() * phi.cos()) as f32,
                (theta.sin() * phi.sin()) as f32,
                theta.cos() as f32,
            );
            let cos = w_out.dot(h);
            if cos <= 0.0 {
                continue;
            }
            let w_in = 2.0 * cos * h - w_out;
            if w_in.z <= 0.0 {
                continue;
            }
            total += g(w_in) * 4.0 * cos as f64 * weight;
        }
    }
    total
}
