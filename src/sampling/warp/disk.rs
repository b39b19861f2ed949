//! Uniform points on the unit disk: polar (r = √u₀), concentric (Shirley & Chiu 1997,
//! "A Low Distortion Map Between Disk and Square") and by rejection from the square.

use glam::Vec2;

use crate::math::{INV_PI, PI};
use crate::sampling::Uniform;

/// Uniform point on the unit disk by polar coordinates: r = √u₀ (so that the area
/// element r dr is uniform), φ = 2πu₁. pdf = 1/π per unit area.
#[inline]
pub fn square_to_uniform_disk_polar(u: Vec2) -> Vec2 {
    let r = u.x.sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    Vec2::new(r * c, r * s)
}

/// Inverse of [`square_to_uniform_disk_polar`].
#[inline]
pub fn uniform_disk_polar_to_square(p: Vec2) -> Vec2 {
    let phi = p.y.atan2(p.x);
    let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
    Vec2::new(p.length_squared(), phi / (2.0 * PI))
}

/// Density of every uniform disk warp: 1/π per unit area inside the disk, else 0.
#[inline]
pub fn uniform_disk_pdf(p: Vec2) -> f32 {
    if p.length_squared() <= 1.0 {
        INV_PI
    } else {
        0.0
    }
}

/// Uniform point on the unit disk by the concentric map (Shirley & Chiu 1997): squares
/// around the centre go to circles, so strata stay compact. pdf = 1/π per unit area.
#[inline]
pub fn square_to_uniform_disk_concentric(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        return Vec2::ZERO;
    }
    let (r, theta) = if o.x.abs() > o.y.abs() {
        (o.x, 0.25 * PI * (o.y / o.x))
    } else {
        (o.y, 0.5 * PI - 0.25 * PI * (o.x / o.y))
    };
    let (s, c) = theta.sin_cos();
    Vec2::new(r * c, r * s)
}

/// Inverse of [`square_to_uniform_disk_concentric`].
#[inline]
pub fn uniform_disk_concentric_to_square(p: Vec2) -> Vec2 {
    let r = p.length();
    if r == 0.0 {
        return Vec2::splat(0.5);
    }
    let mut phi = p.y.atan2(p.x);
    if phi < -0.25 * PI {
        phi += 2.0 * PI;
    }
    // Four wedges, each the image of one triangle of the square [-1, 1]².
    let (a, b) = if phi < 0.25 * PI {
        (r, r * phi / (0.25 * PI))
    } else if phi < 0.75 * PI {
        (-r * (phi - 0.5 * PI) / (0.25 * PI), r)
    } else if phi < 1.25 * PI {
        (-r, -r * (phi - PI) / (0.25 * PI))
    } else {
        (r * (phi - 1.5 * PI) / (0.25 * PI), -r)
    };
    (Vec2::new(a, b) + Vec2::ONE) * 0.5
}

/// Uniform point on the unit disk by rejection from [-1, 1]² (acceptance π/4).
pub fn disk_rejection(src: &mut impl Uniform) -> Vec2 {
    loop {
        let p = 2.0 * src.next_2d() - Vec2::ONE;
        if p.length_squared() <= 1.0 {
            return p;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn disk_inverses_round_trip() {
        for u in [
            Vec2::new(0.3, 0.7),
            Vec2::new(0.9, 0.1),
            Vec2::new(0.6, 0.55),
        ] {
            let p = square_to_uniform_disk_polar(u);
            assert!((uniform_disk_polar_to_square(p) - u).length() < 1e-4);
            let p = square_to_uniform_disk_concentric(u);
            assert!(p.length() <= 1.0 + 1e-6);
            assert!(
                (uniform_disk_concentric_to_square(p) - u).length() < 1e-4,
                "{u}"
            );
        }
    }
}
