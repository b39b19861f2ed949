//! Point lights: a delta distribution in direction.

use super::{LightSample, ShadingPoint};
use crate::math::{PI, Spectrum, spectrum::luminance};
use glam::Vec3;

/// An isotropic point light of radiant intensity `intensity` (W/sr).
#[derive(Clone, Debug)]
pub struct PointLight {
    /// Position.
    pub position: Vec3,
    /// Radiant intensity I.
    pub intensity: Spectrum,
}

impl PointLight {
    /// The only direction: towards the light, carrying I/d² as "radiance" with Dirac
    /// weight pdf = 1.
    #[inline]
    pub fn sample(&self, at: &ShadingPoint) -> Option<LightSample> {
        let d = self.position - at.p;
        let dist2 = d.length_squared();
        if dist2.is_nan() || dist2 <= 0.0 {
            return None;
        }
        let distance = dist2.sqrt();
        let w_in = d / distance;
        (at.n.dot(w_in) > 0.0).then_some(LightSample {
            w_in,
            distance,
            radiance: self.intensity / dist2,
            pdf: 1.0,
            delta: true,
            point: self.position,
            normal: Vec3::ZERO,
        })
    }

    /// Power Φ = 4π·I (luminance).
    pub fn power(&self) -> f32 {
        4.0 * PI * luminance(self.intensity)
    }
}
