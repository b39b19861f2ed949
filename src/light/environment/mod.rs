//! Environment emitters: radiance arriving from infinitely far away, from a latitude–
//! longitude (equirectangular) HDR image or a constant.
//!
//! Conventions follow Mitsuba 3's `envmap`: in the emitter's local frame +y is up; the
//! direction ω = (sin θ sin φ, cos θ, −sin θ cos φ) has image coordinates u = φ/2π,
//! v = θ/π; texel (i, j) of a W×H image sits at (u, v) = ((i + ½)/W, j/(H−1)) — columns
//! wrap around in u, rows end at the poles — and radiance is interpolated bilinearly
//! between texels (checked against Mitsuba 3.9's `envmap.eval`).
//!
//! Sampling (pbrt-v4 §12.5; Mitsuba 3 `envmap`): one of the W×(H−1) cells between texels,
//! each weighted by the exact mean of the bilinear luminance over the cell (the mean of
//! its four corners) times the mean of sin θ over its row, then a point inside it ∝ that
//! bilinear luminance (module `cells`), so every direction with radiance has a positive
//! density and the density follows the radiance inside a cell too. A point (u, v) of
//! density p(u, v) becomes a direction of density p(u, v)/(2π² sin θ) (Jacobian of the
//! map).

mod cells;
mod image;
mod sky;

use cells::CellDistribution;
use image::{TexelCell, bilerp, direction_to_uv, uv_to_direction};

pub use image::LatLongImage;

pub use sky::{SkyParameters, procedural_sky};

use glam::{Mat3, Vec2, Vec3};

use crate::math::{PI, Spectrum, floor, spectrum::luminance};
use crate::sampling::warp::{square_to_uniform_sphere, uniform_sphere_pdf};

#[derive(Clone, Debug)]
enum Radiance {
    Constant(Spectrum),
    Map {
        image: LatLongImage,
        /// Boxed, so that the enum stays small (the `Constant` variant is a few bytes).
        distribution: Box<CellDistribution>,
        /// The MIS-compensated distribution (Karlík et al. 2019), if any texel keeps
        /// weight after the average is subtracted.
        compensated: Option<CellDistribution>,
    },
}

/// An environment emitter.
#[derive(Clone, Debug)]
pub struct Environment {
    radiance: Radiance,
    /// Multiplies the radiance (Mitsuba's `scale`).
    scale: f32,
    /// Rotation from the emitter's frame to the world.
    to_world: Mat3,
    to_local: Mat3,
    /// ∫ L dω over the sphere (luminance, scale included), for the power estimate.
    integral: f32,
    /// Radius of a sphere bounding the scene, for Φ = π r² ∫ L dω.
    pub scene_radius: f32,
}

/// What an environment was made from (for writing it back out as a scene file).
#[derive(Clone, Copy, Debug)]
pub enum EnvironmentSource<'a> {
    /// Mitsuba's `constant`: one radiance from every direction.
    Constant(Spectrum),
    /// Mitsuba's `envmap`: a lat-long image, its scale and its rotation to the world.
    Map {
        /// The image.
        image: &'a LatLongImage,
        /// The factor on its texels.
        scale: f32,
        /// The rotation from the map's frame to the world.
        to_world: Mat3,
    },
}

impl Environment {
    /// What the environment was made from.
    pub fn source(&self) -> EnvironmentSource<'_> {
        match &self.radiance {
            Radiance::Constant(l) => EnvironmentSource::Constant(*l),
            Radiance::Map { image, .. } => EnvironmentSource::Map {
                image,
                scale: self.scale,
                to_world: self.to_world,
            },
        }
    }

    /// A constant environment of radiance `l` (Mitsuba's `constant`), sampled uniformly
    /// over the sphere (not at all under MIS compensation).
    pub fn constant(l: Spectrum) -> Environment {
        Environment {
            radiance: Radiance::Constant(l),
            scale: 1.0,
            to_world: Mat3::IDENTITY,
            to_local: Mat3::IDENTITY,
            integral: 4.0 * PI * luminance(l),
            scene_radius: 1.0,
        }
    }

    /// An environment map from a lat-long image, scaled by `scale` and rotated by
    /// `to_world` (its rotation part is used: directions only).
    pub fn from_image(image: LatLongImage, scale: f32, to_world: Mat3) -> Result<Self, String> {
        if !(scale.is_finite() && scale >= 0.0) {
            return Err(format!(
                "environment scale must be finite and ≥ 0, not {scale}"
            ));
        }
        let rotation = orthonormalize(to_world)
            .ok_or_else(|| "environment to_world has no rotation part (degenerate)".to_string())?;
        let luminance = image.texel_luminance();
        let integral = image.sphere_integral(&luminance);
        let (w, h) = (image.width, image.height);
        let bad = |e| format!("environment sampling distribution: {e:?}");
        let distribution = CellDistribution::new(&luminance, 0.0, w, h)
            .map_err(bad)?
            .into();
        // Compensation (Karlík et al. 2019): texel weights max(0, L − L̄) with
        // L̄ = ∫L dω / 4π, where some texel's luminance is above the mean by more than
        // the mean's rounding (a uniform map of any size has none; pbrt-v4 samples such
        // a map uniformly instead, lightlab not at all, see `has_compensation`).
        let mean = integral / (4.0 * PI);
        let compensated = match luminance.iter().any(|&l| l > mean * (1.0 + 1e-4)) {
            true => Some(CellDistribution::new(&luminance, mean, w, h).map_err(bad)?),
            false => None,
        };
        Ok(Environment {
            radiance: Radiance::Map {
                image,
                distribution,
                compensated,
            },
            scale,
            to_world: rotation,
            to_local: rotation.transpose(),
            integral: integral * scale,
            scene_radius: 1.0,
        })
    }

    /// Radiance arriving from world direction `w` (unit, pointing away from the scene).
    #[inline]
    pub fn eval(&self, w: Vec3) -> Spectrum {
        match &self.radiance {
            Radiance::Constant(l) => *l * self.scale,
            Radiance::Map { image, .. } => {
                image.lookup(direction_to_uv(self.to_local * w)) * self.scale
            }
        }
    }

    /// Draws a world direction; returns it with its radiance and solid-angle density.
    /// `compensate` samples the MIS-compensated distribution (see
    /// [`Environment::has_compensation`]), which is empty, so that nothing is drawn, for
    /// an environment with nothing above its mean ([`Environment::has_compensation`]).
    #[inline]
    pub fn sample(&self, u: Vec2, compensate: bool) -> Option<(Vec3, Spectrum, f32)> {
        match &self.radiance {
            Radiance::Constant(_) if compensate => None,
            Radiance::Constant(l) => {
                let (w, pdf) = square_to_uniform_sphere(u);
                Some((w, *l * self.scale, pdf))
            }
            Radiance::Map { image, .. } => {
                let drawn = self.distribution(compensate)?.sample(u, image);
                let x = drawn.grid.x + image.half_texel();
                let uv = Vec2::new(x - floor(x), drawn.grid.y);
                let (local, sin_t) = uv_to_direction(uv);
                if sin_t <= 0.0 {
                    return None;
                }
                // Radiance and density of the point drawn, as pbrt-v4 and Mitsuba 3 take
                // them from the sampled uv; not from the direction's image coordinates
                // (two atan2 away). A BSDF-sampled ray along this direction (`eval_pdf`)
                // finds the same point up to the rounding of its position, a few 10⁻⁷
                // rad: the same values, but near a cell's edge where the density falls
                // to zero (tests/chi2_environment.rs).
                let w = (self.to_world * local).normalize();
                let radiance = self.radiance(&drawn.texels, drawn.cell.f);
                let pdf = solid_angle_pdf(drawn.pdf, sin_t);
                (pdf > 0.0).then_some((w, radiance, pdf))
            }
        }
    }

    /// [`Environment::eval`] and [`Environment::pdf`] of one direction, bit for bit,
    /// finding its image coordinates once (two `atan2` instead of four: a BSDF-sampled
    /// ray that escapes needs both).
    #[inline]
    pub fn eval_pdf(&self, w: Vec3, compensate: bool) -> (Spectrum, f32) {
        match &self.radiance {
            Radiance::Constant(l) => (*l * self.scale, self.constant_pdf(w, compensate)),
            Radiance::Map { image, .. } => {
                // The radiance and the density read the same four texels.
                let local = self.to_local * w;
                let cell = image.locate(direction_to_uv(local));
                let texels = image.corners(&cell);
                let radiance = self.radiance(&texels, cell.f);
                (radiance, self.map_pdf(local, &cell, &texels, compensate))
            }
        }
    }

    /// The map's solid-angle density of the direction `local` (emitter frame), which lies
    /// in `cell` with corner texels `texels`: the cell grid's density over the lat-long
    /// Jacobian 2π² sin θ.
    #[inline]
    fn map_pdf(
        &self,
        local: Vec3,
        cell: &TexelCell,
        texels: &[Spectrum; 4],
        compensate: bool,
    ) -> f32 {
        let Some(distribution) = self.distribution(compensate) else {
            return 0.0;
        };
        // sin θ from the horizontal components: accurate near the poles.
        let sin_t = (local.x * local.x + local.z * local.z).sqrt();
        if sin_t <= 0.0 {
            return 0.0;
        }
        solid_angle_pdf(distribution.pdf(cell, texels), sin_t)
    }

    /// The map's radiance at `f` in a cell with corner texels `texels`.
    #[inline]
    fn radiance(&self, texels: &[Spectrum; 4], f: Vec2) -> Spectrum {
        bilerp(texels, f) * self.scale
    }

    /// Solid-angle density of [`Environment::sample`] choosing world direction `w`.
    #[inline]
    pub fn pdf(&self, w: Vec3, compensate: bool) -> f32 {
        match &self.radiance {
            Radiance::Constant(_) => self.constant_pdf(w, compensate),
            Radiance::Map { .. } => self.eval_pdf(w, compensate).1,
        }
    }

    /// A constant's density: uniform over the sphere, or zero everywhere under
    /// compensation (max(0, L − L̄) = 0).
    #[inline]
    fn constant_pdf(&self, w: Vec3, compensate: bool) -> f32 {
        if compensate {
            0.0
        } else {
            uniform_sphere_pdf(w)
        }
    }

    /// Whether the map has an MIS-compensated distribution (Karlík, Šik, Vévoda, Skřivan &
    /// Křivánek 2019, "MIS Compensation: Optimizing Sampling Techniques in Multiple
    /// Importance Sampling"): texel weights max(0, L − L̄) instead of L, interpolated
    /// bilinearly as the plain ones are, where L̄ is the mean radiance over the sphere.
    /// Directions whose four nearest texels are all at or below the mean get density zero
    /// under it, so it is only unbiased inside MIS, whose BSDF strategy covers them.
    ///
    /// A constant environment, and a map whose luminance nowhere exceeds its mean by more
    /// than the mean's rounding (10⁻⁴ relative: uniform), have none: max(0, L − L̄) = 0
    /// everywhere. Karlík et al. note that the compensated technique then vanishes and
    /// BSDF sampling alone remains: compensated, such an environment draws no samples and
    /// has density zero in every direction, so the BSDF samples that escape take MIS
    /// weight one, and light selection gives it probability zero where another light can
    /// use the sample ([`crate::light::Light::draws_no_samples`]).
    pub fn has_compensation(&self) -> bool {
        matches!(
            &self.radiance,
            Radiance::Map {
                compensated: Some(_),
                ..
            }
        )
    }

    /// The distribution in use: the compensated one when asked for (none where it is
    /// empty), else the plain one.
    #[inline]
    fn distribution(&self, compensate: bool) -> Option<&CellDistribution> {
        match &self.radiance {
            Radiance::Constant(_) => None,
            Radiance::Map {
                distribution,
                compensated,
                ..
            } => {
                if compensate {
                    compensated.as_ref()
                } else {
                    Some(distribution)
                }
            }
        }
    }

    /// ∫ L dω over the sphere (luminance, scale included).
    pub fn radiance_integral(&self) -> f32 {
        self.integral
    }

    /// Power estimate Φ = π r² ∫ L dω (luminance) for a scene of bounding radius r: the
    /// power the environment sends through a disk that covers the scene (pbrt-v4 §12.5).
    pub fn power(&self) -> f32 {
        PI * self.scene_radius * self.scene_radius * self.integral
    }
}

/// The solid-angle density of a direction at polar angle θ (`sin_t` = sin θ > 0) whose
/// point of the cell grid has density `grid_pdf`: over the lat-long Jacobian 2π² sin θ.
#[inline]
fn solid_angle_pdf(grid_pdf: f32, sin_t: f32) -> f32 {
    grid_pdf / (2.0 * PI * PI * sin_t)
}

/// The nearest rotation to `m` (Gram–Schmidt on its columns), or None if degenerate.
fn orthonormalize(m: Mat3) -> Option<Mat3> {
    let x = m.x_axis.try_normalize()?;
    let y = (m.y_axis - x * x.dot(m.y_axis)).try_normalize()?;
    let z = x.cross(y);
    // Keep handedness: a mirrored to_world flips z.
    let z = if z.dot(m.z_axis) < 0.0 { -z } else { z };
    Some(Mat3::from_cols(x, y, z))
}

#[cfg(test)]
mod tests;
