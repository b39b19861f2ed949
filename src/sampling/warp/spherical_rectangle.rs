//! Directions uniform in the solid angle a rectangle subtends at a shading point (Ureña,
//! Fajardo & King 2013, "An Area-Preserving Parametrization for Spherical Rectangles",
//! EGSR), with the inverse map. Internal arithmetic is in f64; rectangles below
//! [`MIN_SOLID_ANGLE`], seen edge-on, or with non-perpendicular
//! edges give `None`.

use std::f64::consts::TAU;

use glam::{DVec3, Vec2, Vec3};

use super::spherical_triangle::MIN_SOLID_ANGLE;

/// The rectangle in its local frame (paper §3): the shading point is the origin, the
/// rectangle spans [x0, x1] × [y0, y1] at height z0 < 0.
#[derive(Clone, Copy, Debug)]
struct Extent {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    z0: f64,
}

/// The angles of paper eq. (2)–(4): solid angle S, k = 2π − γ₂ − γ₃, b0, b1 (the z
/// components of the normals of the planes through the origin and edges y = y0, y = y1)
/// and c = 1 − b0².
struct Angles {
    solid_angle: f64,
    k: f64,
    b0: f64,
    b1: f64,
    c: f64,
}

impl Extent {
    /// Paper eq. (2)–(4) with the normals written out: n0 = (0, z0, −y0)/r_y0,
    /// n1 = (−z0, 0, x1)/r_x1, n2 = (0, −z0, y1)/r_y1, n3 = (z0, 0, −x0)/r_x0 with
    /// r_t = √(z0² + t²), so that −nᵢ·nᵢ₊₁ is one product over two of the four radii
    /// (no vector normalisation).
    fn angles(&self) -> Angles {
        let Extent { x0, x1, y0, y1, z0 } = *self;
        let z2 = z0 * z0;
        let (rx0, rx1) = ((z2 + x0 * x0).sqrt(), (z2 + x1 * x1).sqrt());
        let (ry0, ry1) = ((z2 + y0 * y0).sqrt(), (z2 + y1 * y1).sqrt());
        let gamma = |cos: f64| cos.clamp(-1.0, 1.0).acos();
        let g0 = gamma(y0 * x1 / (ry0 * rx1));
        let g1 = gamma(-(x1 * y1) / (rx1 * ry1));
        let g2 = gamma(x0 * y1 / (ry1 * rx0));
        let g3 = gamma(-(x0 * y0) / (rx0 * ry0));
        let k = TAU - g2 - g3;
        Angles {
            solid_angle: g0 + g1 - k,
            k,
            b0: -y0 / ry0,
            b1: y1 / ry1,
            c: z2 / (ry0 * ry0),
        }
    }
}

/// A rectangle seen from a shading point, ready for uniform solid-angle sampling.
#[derive(Clone, Copy, Debug)]
pub struct SphericalRectangle {
    origin: DVec3,
    /// Local frame: x, y along the edges, z away from the rectangle's side.
    x: DVec3,
    y: DVec3,
    z: DVec3,
    extent: Extent,
    angles_k: f64,
    b0: f64,
    b1: f64,
    /// 1 − b0², computed as z0²/(z0² + y0²).
    c: f64,
    solid_angle: f64,
}

impl SphericalRectangle {
    /// The rectangle `corner + α·ex + β·ey` (α, β ∈ [0, 1], ex ⊥ ey) seen from `p`, all
    /// in world space; `None` if ex and ey are not perpendicular (|cos| > 10⁻⁴), the solid
    /// angle is below [`MIN_SOLID_ANGLE`] (which includes `p` in the rectangle's plane),
    /// or an input is non-finite.
    pub fn new(p: Vec3, corner: Vec3, ex: Vec3, ey: Vec3) -> Option<SphericalRectangle> {
        let (ex, ey) = (ex.as_dvec3(), ey.as_dvec3());
        let (width, height) = (ex.length(), ey.length());
        let (x, y) = (ex.try_normalize()?, ey.try_normalize()?);
        if x.dot(y).abs() > 1e-4 {
            return None;
        }
        let mut z = x.cross(y);
        let d = corner.as_dvec3() - p.as_dvec3();
        let mut z0 = d.dot(z);
        if z0 > 0.0 {
            z = -z;
            z0 = -z0;
        }
        let (x0, y0) = (d.dot(x), d.dot(y));
        let extent = Extent {
            x0,
            x1: x0 + width,
            y0,
            y1: y0 + height,
            z0,
        };
        let angles = extent.angles();
        let solid_angle = angles.solid_angle;
        if !(solid_angle >= MIN_SOLID_ANGLE && solid_angle.is_finite() && z0 < 0.0) {
            return None;
        }
        let Angles { k, b0, b1, c, .. } = angles;
        Some(SphericalRectangle {
            origin: p.as_dvec3(),
            x,
            y,
            z,
            extent,
            angles_k: k,
            b0,
            b1,
            c,
            solid_angle,
        })
    }

    /// S in steradians.
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle as f32
    }

    /// A unit direction uniform in the rectangle's solid angle and its density 1/S per
    /// sr (paper Algorithm 1): u₀ fixes the x where the sub-rectangle [x0, x] has solid
    /// angle u₀S, u₁ places y uniformly in the projected height h = y/√(x² + y² + z0²).
    ///
    /// ```
    /// use glam::{Vec2, Vec3};
    /// use lightlab::sampling::warp::SphericalRectangle;
    /// let r = SphericalRectangle::new(Vec3::ZERO, Vec3::new(-1., -1., 1.), Vec3::X * 2., Vec3::Y * 2.).unwrap();
    /// let (w, pdf) = r.sample(Vec2::new(0.3, 0.8));
    /// assert!(r.pdf(w) == pdf && (r.to_square(w) - Vec2::new(0.3, 0.8)).length() < 1e-4);
    /// ```
    pub fn sample(&self, u: Vec2) -> (Vec3, f32) {
        let Extent { x0, x1, y0, y1, z0 } = self.extent;
        // Algorithm 1: a_u = u₀S + k, f_u = (cos a_u·b0 − b1)/sin a_u,
        // c_u = sign(f_u)/√(f_u² + b0²), x_u = −c_u·z0/√(1 − c_u²). Substituting,
        // x_u = −z0·sign(n)·s/√(n² − (1 − b0²)·s²) with n = cos a_u·b0 − b1, s = sin a_u:
        // one square root and one division instead of three of each, and s = 0 gives
        // x_u = 0 as the paper's limit does. A vanishing denominator sends x_u to the
        // edge it tends to (the clamp).
        let (s, cos_au) = (u.x as f64 * self.solid_angle + self.angles_k).sin_cos();
        let n = cos_au * self.b0 - self.b1;
        let den = (n * n - self.c * s * s).max(1e-300).sqrt();
        let xu = (-z0 * s / den).copysign(-z0 * s * n).clamp(x0, x1);
        // y_v from h = y/√(d² + y²), uniform between h0 and h1.
        let d2 = xu * xu + z0 * z0;
        let (h0, h1) = (y0 / (d2 + y0 * y0).sqrt(), y1 / (d2 + y1 * y1).sqrt());
        let hv = h0 + u.y as f64 * (h1 - h0);
        let hv2 = hv * hv;
        let yv = if hv2 < 1.0 - 1e-12 {
            (hv * d2.sqrt() / (1.0 - hv2).sqrt()).clamp(y0, y1)
        } else {
            y1
        };
        // (x_u, y_v, z0) lies on the rectangle (both clamped), but the f32 direction of a
        // far rectangle's edge point may round to just outside: its density is what
        // `pdf` says of the direction returned, so the two always agree.
        let w = ((xu * self.x + yv * self.y + z0 * self.z) / (d2 + yv * yv).sqrt()).as_vec3();
        (w, self.pdf(w))
    }

    /// The point (x, y) where direction w meets the rectangle's plane, in local
    /// coordinates, if it does so in front of the shading point.
    fn hit(&self, w: Vec3) -> Option<(f64, f64)> {
        let w = w.as_dvec3();
        let wz = w.dot(self.z);
        if wz >= 0.0 {
            return None;
        }
        let t = self.extent.z0 / wz;
        Some((t * w.dot(self.x), t * w.dot(self.y)))
    }

    /// Density of [`SphericalRectangle::sample`]: 1/S per sr for directions that hit the
    /// rectangle, else 0.
    pub fn pdf(&self, w: Vec3) -> f32 {
        let Extent { x0, x1, y0, y1, .. } = self.extent;
        match self.hit(w) {
            Some((x, y)) if (x0..=x1).contains(&x) && (y0..=y1).contains(&y) => {
                (1.0 / self.solid_angle) as f32
            }
            _ => 0.0,
        }
    }

    /// Inverse of [`SphericalRectangle::sample`]: u₀ is the solid angle of the
    /// sub-rectangle [x0, x] over S, u₁ the position of h(y) between h(y0) and h(y1).
    pub fn to_square(&self, w: Vec3) -> Vec2 {
        let Some((x, y)) = self.hit(w) else {
            return Vec2::ZERO;
        };
        let e = self.extent;
        let x = x.clamp(e.x0, e.x1);
        let sub = Extent { x1: x, ..e }.angles().solid_angle;
        let d2 = x * x + e.z0 * e.z0;
        let h = |y: f64| y / (d2 + y * y).sqrt();
        let u1 = (h(y) - h(e.y0)) / (h(e.y1) - h(e.y0));
        let u0 = if x > e.x0 {
            sub / self.solid_angle
        } else {
            0.0
        };
        Vec2::new(
            u0.clamp(0.0, 1.0) as f32,
            if u1.is_finite() {
                u1.clamp(0.0, 1.0) as f32
            } else {
                0.0
            },
        )
    }

    /// The shading point this rectangle is seen from.
    pub fn origin(&self) -> Vec3 {
        self.origin.as_vec3()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_overhead_has_the_known_solid_angle_and_round_trips() {
        // A 2×2 square at distance 1: Ω = 4·asin(ab/√((a² + d²)(b² + d²))) = 4·asin(1/2) = 2π/3.
        let r = SphericalRectangle::new(
            Vec3::ZERO,
            Vec3::new(-1.0, -1.0, 1.0),
            Vec3::X * 2.0,
            Vec3::Y * 2.0,
        )
        .expect("visible");
        assert!((r.solid_angle() - 2.0 * std::f32::consts::PI / 3.0).abs() < 1e-5);
        for u in [
            Vec2::new(0.1, 0.2),
            Vec2::new(0.5, 0.5),
            Vec2::new(0.9, 0.95),
        ] {
            let (w, pdf) = r.sample(u);
            assert!(pdf > 0.0);
            assert!((r.to_square(w) - u).length() < 1e-4, "{u} -> {w}");
        }
        for u in [
            Vec2::ZERO,
            Vec2::ONE,
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 0.0),
        ] {
            let (w, _) = r.sample(u);
            assert!(w.is_finite() && r.to_square(w).is_finite());
        }
    }

    #[test]
    fn edge_on_tiny_and_skewed_rectangles_give_none() {
        assert!(SphericalRectangle::new(Vec3::ZERO, Vec3::X, Vec3::X, Vec3::Y).is_none());
        assert!(
            SphericalRectangle::new(Vec3::ZERO, Vec3::Z * 1e5, Vec3::X * 1e-2, Vec3::Y * 1e-2)
                .is_none()
        );
        assert!(SphericalRectangle::new(Vec3::ZERO, Vec3::Z, Vec3::X, Vec3::X + Vec3::Y).is_none());
    }
}
