//! A procedural sky for the `envmap` scene, so it needs no files: a small, very bright sun
//! disk over a dim sky gradient and a darker ground — the case the lecture gives for
//! importance sampling by emission: uniform or BSDF sampling rarely finds the sun.

use glam::{Vec2, Vec3};

use super::LatLongImage;
use super::image::uv_to_direction;
use crate::math::Spectrum;

/// Parameters of [`procedural_sky`].
#[derive(Clone, Copy, Debug)]
pub struct SkyParameters {
    /// Image width (height is half of it).
    pub width: usize,
    /// Unit direction towards the sun (emitter frame, +y up).
    pub sun_direction: Vec3,
    /// Angular radius of the sun disk, in degrees.
    pub sun_radius_degrees: f32,
    /// Radiance of the sun disk.
    pub sun_radiance: Spectrum,
    /// Sky radiance at the zenith and at the horizon.
    pub zenith: Spectrum,
    /// Sky radiance at the horizon.
    pub horizon: Spectrum,
    /// Radiance of the ground (below the horizon).
    pub ground: Spectrum,
}

impl Default for SkyParameters {
    /// A sun 35° above the horizon of angular radius 1.5°, whose irradiance on the
    /// ground is about 3× the sky's while it covers 1/20000 of the sphere.
    fn default() -> Self {
        let elevation = 35f32.to_radians();
        let azimuth = 40f32.to_radians();
        SkyParameters {
            width: 512,
            sun_direction: Vec3::new(
                elevation.cos() * azimuth.sin(),
                elevation.sin(),
                -elevation.cos() * azimuth.cos(),
            ),
            sun_radius_degrees: 1.5,
            sun_radiance: Spectrum::new(3000.0, 2750.0, 2350.0),
            zenith: Spectrum::new(0.15, 0.25, 0.55),
            horizon: Spectrum::new(0.55, 0.6, 0.7),
            ground: Spectrum::new(0.08, 0.07, 0.06),
        }
    }
}

/// Renders the sky into a lat-long image. Texel (i, j) takes the radiance of the direction
/// at its own (u, v) = ((i + ½)/W, j/(H−1)); sun texels are supersampled 8×8 over the texel's
/// footprint so the small disk keeps its power.
pub fn procedural_sky(p: &SkyParameters) -> LatLongImage {
    let (w, h) = (p.width.max(4), (p.width / 2).max(3));
    let cos_sun = p.sun_radius_degrees.to_radians().cos();
    let sun = p.sun_direction.normalize();
    let radiance = |d: Vec3| -> Spectrum {
        if d.dot(sun) >= cos_sun {
            p.sun_radiance
        } else if d.y >= 0.0 {
            let t = d.y.sqrt();
            p.horizon * (1.0 - t) + p.zenith * t
        } else {
            p.ground
        }
    };
    let mut texels = Vec::with_capacity(w * h);
    for j in 0..h {
        for i in 0..w {
            let uv = Vec2::new((i as f32 + 0.5) / w as f32, j as f32 / (h - 1) as f32);
            let (d, _) = uv_to_direction(uv);
            // Average over the texel's footprint where the sun is near.
            let near_sun = d.dot(sun) > (p.sun_radius_degrees.to_radians() + 0.05).cos();
            let l = if near_sun {
                let mut sum = Spectrum::ZERO;
                for a in 0..8 {
                    for b in 0..8 {
                        let off =
                            Vec2::new((a as f32 + 0.5) / 8.0 - 0.5, (b as f32 + 0.5) / 8.0 - 0.5)
                                / Vec2::new(w as f32, (h - 1) as f32);
                        sum += radiance(uv_to_direction((uv + off).clamp(Vec2::ZERO, Vec2::ONE)).0);
                    }
                }
                sum / 64.0
            } else {
                radiance(d)
            };
            texels.push(l);
        }
    }
    LatLongImage::new(w, h, texels).expect("the procedural sky is finite and positive")
}
