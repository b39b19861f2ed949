//! Microfacet normal distributions (Walter et al. 2007, "Microfacet Models for
//! Refraction through Rough Surfaces"): Beckmann and GGX/Trowbridge–Reitz with
//! anisotropic roughness (α_u, α_v), Smith's separable shadowing–masking G = G1·G1 as
//! Mitsuba 3 uses by default, and sampling of microfacet normals.
//!
//! Sampling: GGX draws visible normals exactly (Heitz 2018, "Sampling the GGX
//! Distribution of Visible Normals", JCGT 7(4)), density D_v(m) = G1(v, m)·⟨v·m⟩·D(m)/v_z.
//! Beckmann draws m from D(m)·cos θ_m (Walter et al. 2007, eqs. 28–29; anisotropic form
//! as in Mitsuba 3), an exact inversion whose density needs no approximate G1: Beckmann's
//! G1 is Mitsuba's rational fit (< 0.35% error), which would make a visible-normal
//! density disagree with its sampler by that much.

use glam::{Vec2, Vec3};

use crate::math::PI;

const TWO_PI: f32 = std::f32::consts::TAU;

named_enum! {
    /// The shape of the microfacet normal distribution (Mitsuba 3's `distribution`).
    pub enum MicrofacetType: "microfacet distribution" {
        /// Beckmann: Gaussian slopes. Mitsuba 3's default.
        Beckmann => "beckmann",
        /// GGX / Trowbridge–Reitz: heavier tails.
        Ggx => "ggx",
    }
}

/// Smallest roughness; smaller values are clamped to it, as in Mitsuba 3.
pub const MIN_ALPHA: f32 = 1e-4;

/// A microfacet distribution with roughness α_u along local x and α_v along local y.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    /// Beckmann or GGX.
    pub distribution: MicrofacetType,
    /// Roughness along the first tangent.
    pub alpha_u: f32,
    /// Roughness along the second tangent.
    pub alpha_v: f32,
}

impl Microfacet {
    /// An isotropic distribution; α is clamped to [`MIN_ALPHA`] (NaN becomes it too).
    pub fn isotropic(distribution: MicrofacetType, alpha: f32) -> Microfacet {
        Microfacet::anisotropic(distribution, alpha, alpha)
    }

    /// An anisotropic distribution; each α is clamped to [`MIN_ALPHA`].
    pub fn anisotropic(distribution: MicrofacetType, alpha_u: f32, alpha_v: f32) -> Microfacet {
        Microfacet {
            distribution,
            alpha_u: alpha_u.max(MIN_ALPHA),
            alpha_v: alpha_v.max(MIN_ALPHA),
        }
    }

    /// D(m), the density of microfacet normals per unit projected area and steradian
    /// (∫ D(m) cos θ_m dm = 1). Zero for m below the surface.
    /// Beckmann: exp(−(m_x²/α_u² + m_y²/α_v²)/m_z²)/(π α_u α_v m_z⁴);
    /// GGX: 1/(π α_u α_v (m_x²/α_u² + m_y²/α_v² + m_z²)²).
    pub fn d(&self, m: Vec3) -> f32 {
        if m.z <= 0.0 {
            return 0.0;
        }
        let (x, y) = (m.x / self.alpha_u, m.y / self.alpha_v);
        let z2 = m.z * m.z;
        let norm = PI * self.alpha_u * self.alpha_v;
        let value = match self.distribution {
            MicrofacetType::Beckmann => (-(x * x + y * y) / z2).exp() / (norm * z2 * z2),
            MicrofacetType::Ggx => {
                let s = x * x + y * y + z2;
                1.0 / (norm * s * s)
            }
        };
        if value.is_finite() { value } else { 0.0 }
    }

    /// Smith's masking G1(v, m) for direction `v` and microfacet normal `m`: zero when v
    /// sees the back of m. GGX: 2/(1 + √(1 + tan²θ_α)) with tan²θ_α = (α_u² v_x² + α_v² v_y²)/v_z²
    /// (exact); Beckmann: the rational fit in a = 1/tan θ_α of Walter et al. 2007, eq. 27.
    pub fn g1(&self, v: Vec3, m: Vec3) -> f32 {
        if v.dot(m) * v.z <= 0.0 {
            return 0.0;
        }
        let xy = (self.alpha_u * v.x).powi(2) + (self.alpha_v * v.y).powi(2);
        if xy == 0.0 {
            return 1.0;
        }
        let tan2 = xy / (v.z * v.z);
        match self.distribution {
            MicrofacetType::Beckmann => {
                let a = 1.0 / tan2.sqrt();
                if a >= 1.6 {
                    1.0
                } else {
                    (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a)
                }
            }
            MicrofacetType::Ggx => 2.0 / (1.0 + (1.0 + tan2).sqrt()),
        }
    }

    /// Separable Smith shadowing–masking G(w_in, w_out, m) = G1(w_in, m)·G1(w_out, m).
    pub fn g(&self, w_in: Vec3, w_out: Vec3, m: Vec3) -> f32 {
        self.g1(w_in, m) * self.g1(w_out, m)
    }

    /// Draws a microfacet normal seen from `v` (v_z > 0): a visible normal for GGX, a
    /// D·cos-distributed one for Beckmann. Returns (m, density of m per steradian), the
    /// density from [`Microfacet::sample_pdf`].
    pub fn sample(&self, v: Vec3, u: Vec2) -> (Vec3, f32) {
        let m = self.sample_normal(v, u);
        (m, self.sample_pdf(v, m))
    }

    /// The normal of [`Microfacet::sample`] without its density (a BSDF that reflects
    /// about it asks for the density of the reflected direction instead).
    #[inline]
    pub fn sample_normal(&self, v: Vec3, u: Vec2) -> Vec3 {
        match self.distribution {
            MicrofacetType::Ggx => self.sample_ggx_visible(v, u),
            MicrofacetType::Beckmann => self.sample_beckmann_cos(u),
        }
    }

    /// Density per steradian of [`Microfacet::sample`] drawing `m` given `v`:
    /// GGX D_v(m) = G1(v, m)·max(0, v·m)·D(m)/v_z; Beckmann D(m)·cos θ_m.
    pub fn sample_pdf(&self, v: Vec3, m: Vec3) -> f32 {
        match self.distribution {
            MicrofacetType::Ggx => self.sample_pdf_from(v, m, self.d(m), self.g1(v, m)),
            MicrofacetType::Beckmann => self.sample_pdf_from(v, m, self.d(m), 1.0),
        }
    }

    /// [`Microfacet::sample_pdf`] given D(m) = `d` and G1(v, m) = `g1_v` (unused for
    /// Beckmann) computed already: a BSDF's [`eval_pdf`](super::Bsdf::eval_pdf) shares
    /// them with f, the same bits as computing them twice.
    #[inline]
    pub fn sample_pdf_from(&self, v: Vec3, m: Vec3, d: f32, g1_v: f32) -> f32 {
        match self.distribution {
            MicrofacetType::Ggx => {
                if v.z <= 0.0 {
                    return 0.0;
                }
                g1_v * v.dot(m).max(0.0) * d / v.z
            }
            MicrofacetType::Beckmann => d * m.z.max(0.0),
        }
    }

    /// Heitz 2018, listing 1: stretch v to the α = 1 configuration, sample the projected
    /// hemisphere as a disk whose far half is squeezed by (1 + v_h,z)/2, lift, unstretch.
    fn sample_ggx_visible(&self, v: Vec3, u: Vec2) -> Vec3 {
        let (sin_phi, cos_phi) = (TWO_PI * u.y).sin_cos();
        self.visible_frame(v).normal(u.x.sqrt(), sin_phi, cos_phi)
    }

    /// The part of GGX visible-normal sampling that depends on v alone (listing 1 up to
    /// the disk sample), for callers that draw many normals seen from one direction.
    #[inline]
    pub fn visible_frame(&self, v: Vec3) -> VisibleFrame {
        let vh = Vec3::new(self.alpha_u * v.x, self.alpha_v * v.y, v.z).normalize();
        let len2 = vh.x * vh.x + vh.y * vh.y;
        let t1 = if len2 > 0.0 {
            Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt()
        } else {
            Vec3::X
        };
        VisibleFrame {
            alpha_u: self.alpha_u,
            alpha_v: self.alpha_v,
            vh,
            t1,
            t2: vh.cross(t1),
            s: 0.5 * (1.0 + vh.z),
        }
    }

    /// Beckmann normals with density D(m)·cos θ_m: φ from the anisotropic ellipse,
    /// tan²θ = −α(φ)² ln(1 − u₀) (Walter et al. 2007, eq. 28).
    fn sample_beckmann_cos(&self, u: Vec2) -> Vec3 {
        let (sin_phi, cos_phi, alpha2) = self.sample_phi(u.y);
        // ln_1p keeps tan²θ accurate for u → 0; sin θ = tan θ·cos θ rather than
        // √(1 − cos²θ), which loses all digits for the α ≈ 10⁻³ lobes.
        let tan2 = -alpha2 * (-u.x).ln_1p();
        let cos_theta = 1.0 / (1.0 + tan2).sqrt();
        let sin_theta = tan2.sqrt() * cos_theta;
        Vec3::new(cos_phi * sin_theta, sin_phi * sin_theta, cos_theta)
    }

    /// The azimuth of a D·cos sample and α(φ)² = 1/(cos²φ/α_u² + sin²φ/α_v²):
    /// tan φ = (α_v/α_u) tan(2π u), continued over the four quadrants.
    fn sample_phi(&self, u: f32) -> (f32, f32, f32) {
        if self.alpha_u == self.alpha_v {
            let (s, c) = (TWO_PI * u).sin_cos();
            return (s, c, self.alpha_u * self.alpha_u);
        }
        let phi = (self.alpha_v / self.alpha_u * (TWO_PI * u).tan()).atan();
        // atan folds to (−π/2, π/2); quadrants 2 and 3 of 2πu take φ + π.
        let phi = if (0.25..0.75).contains(&u) {
            phi + PI
        } else {
            phi
        };
        let (s, c) = phi.sin_cos();
        let alpha2 = 1.0 / ((c / self.alpha_u).powi(2) + (s / self.alpha_v).powi(2));
        (s, c, alpha2)
    }
}

/// GGX visible-normal sampling (Heitz 2018, listing 1) for one direction v: the
/// stretched v_h, its tangents and the squeeze (1 + v_h,z)/2.
#[derive(Clone, Copy, Debug)]
pub struct VisibleFrame {
    alpha_u: f32,
    alpha_v: f32,
    vh: Vec3,
    t1: Vec3,
    t2: Vec3,
    s: f32,
}

impl VisibleFrame {
    /// The normal for the disk point of radius `r` = √u₀ at angle 2πu₁ (given by its sine
    /// and cosine): squeeze, lift to the hemisphere, unstretch.
    #[inline]
    pub fn normal(&self, r: f32, sin_phi: f32, cos_phi: f32) -> Vec3 {
        let Self { vh, t1, t2, s, .. } = *self;
        let p1 = r * cos_phi;
        let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * sin_phi;
        let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * vh;
        Vec3::new(self.alpha_u * nh.x, self.alpha_v * nh.y, nh.z.max(0.0)).normalize()
    }
}

/// Mirror reflection of `w` about the unit normal `m`: 2(w·m)m − w.
#[inline]
pub fn reflect(w: Vec3, m: Vec3) -> Vec3 {
    2.0 * w.dot(m) * m - w
}

/// The half vector of a reflection pair, or `None` when they cancel out.
#[inline]
pub fn half_vector(w_in: Vec3, w_out: Vec3) -> Option<Vec3> {
    let h = w_in + w_out;
    let len2 = h.length_squared();
    (len2 > 0.0 && len2.is_finite()).then(|| h / len2.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cases() -> Vec<Microfacet> {
        let mut list = Vec::new();
        for t in MicrofacetType::ALL {
            for (au, av) in [(0.05, 0.05), (0.3, 0.3), (1.0, 1.0), (0.1, 0.4)] {
                list.push(Microfacet::anisotropic(t, au, av));
            }
        }
        list
    }

    /// ∫ f over the hemisphere by the midpoint rule in (cos θ, φ), fine near the pole.
    fn integrate_hemisphere(f: impl Fn(Vec3) -> f32) -> f64 {
        let (nt, np) = (2000, 256);
        let mut sum = 0.0f64;
        for i in 0..nt {
            // z = 1 − t², dense near the pole where sharp lobes live; dz = 2t dt.
            let t = (i as f64 + 0.5) / nt as f64;
            let z = 1.0 - t * t;
            let sin = (1.0 - z * z).max(0.0).sqrt();
            for j in 0..np {
                let phi = (j as f64 + 0.5) / np as f64 * std::f64::consts::TAU;
                let w = Vec3::new((sin * phi.cos()) as f32, (sin * phi.sin()) as f32, z as f32);
                sum += f(w) as f64 * 2.0 * t / nt as f64 * std::f64::consts::TAU / np as f64;
            }
        }
        sum
    }

    #[test]
    fn projected_area_is_one() {
        for mf in cases() {
            let total = integrate_hemisphere(|m| mf.d(m) * m.z);
            assert!((total - 1.0).abs() < 2e-3, "{mf:?}: {total}");
        }
    }

    #[test]
    fn visible_normals_integrate_to_one() {
        // ∫ G1(v, m) max(0, v·m) D(m) dm = v_z (exact for GGX, ≤ 0.35% for Beckmann's fit).
        for mf in cases() {
            for theta in [0.0f32, 45.0, 80.0] {
                let t = theta.to_radians();
                let v = Vec3::new(t.sin() * 0.8, t.sin() * 0.6, t.cos());
                let total = integrate_hemisphere(|m| mf.g1(v, m) * v.dot(m).max(0.0) * mf.d(m));
                let tolerance = if mf.distribution == MicrofacetType::Ggx {
                    3e-3
                } else {
                    6e-3
                };
                assert!(
                    (total / v.z as f64 - 1.0).abs() < tolerance,
                    "{mf:?} {theta}: {total}"
                );
            }
        }
    }

    #[test]
    fn samples_are_unit_upper_normals_with_finite_pdf() {
        let top = 1.0 - f32::EPSILON / 2.0;
        for mf in cases() {
            let v = Vec3::new(0.6, 0.0, 0.8);
            for u in [
                Vec2::ZERO,
                Vec2::splat(top),
                Vec2::new(0.0, top),
                Vec2::new(top, 0.5),
            ] {
                let (m, pdf) = mf.sample(v, u);
                assert!(
                    m.is_finite() && (m.length() - 1.0).abs() < 1e-4,
                    "{mf:?} {u}: {m}"
                );
                assert!(
                    m.z >= 0.0 && pdf.is_finite() && pdf >= 0.0,
                    "{mf:?} {u}: {pdf}"
                );
            }
        }
    }

    #[test]
    fn alpha_is_clamped() {
        let mf = Microfacet::isotropic(MicrofacetType::Ggx, 0.0);
        assert_eq!(mf.alpha_u, MIN_ALPHA);
        assert!(mf.d(Vec3::Z).is_finite());
    }
}
