//! Scenes: what to render (camera, geometry, materials, lights) and where scenes come
//! from (built-in builders; scene files later). `Scene` is validated when built.

pub mod builder;
pub mod builtin;
mod error;

pub use builder::SceneBuilder;
pub use error::SceneError;

use crate::bsdf::Material;
use crate::geometry::Geometry;
use std::borrow::Cow;

use crate::light::{Light, LightSampling};
use crate::render::camera::Camera;

/// A scene ready to render.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Name shown in reports (`builtin:NAME` or the file path).
    pub name: String,
    /// The camera, with the scene's default resolution.
    pub camera: Camera,
    /// All surfaces.
    pub geometry: Geometry,
    /// Materials, indexed by primitives.
    pub materials: Vec<Material>,
    /// Lights, indexed by primitives that emit.
    pub lights: Vec<Light>,
    /// Index in `lights` of the environment (light at infinity), if any.
    pub environment: Option<usize>,
    /// Default samples per pixel.
    pub spp: u32,
}

impl Scene {
    /// Radiance arriving along a ray that leaves the scene in direction `w` (unit): the
    /// environment's, or zero.
    #[inline]
    pub fn escaped(&self, w: glam::Vec3) -> crate::math::Spectrum {
        match self.environment {
            Some(i) => self.lights[i].infinite_radiance(w),
            None => crate::math::Spectrum::ZERO,
        }
    }

    /// This scene with every area and polygon light sampled by `sampling` (where a shape
    /// lacks that strategy it uses `area`): borrowed when nothing changes, else a copy.
    pub fn with_light_sampling(&self, sampling: LightSampling) -> Cow<'_, Scene> {
        let unchanged = self.lights.iter().all(|l| match l {
            Light::Area(a) => a.sampling == sampling,
            Light::Polygon(p) => p.sampling == sampling,
            Light::Point(_) | Light::Environment(_) => true,
        });
        if unchanged {
            return Cow::Borrowed(self);
        }
        let mut scene = self.clone();
        for light in &mut scene.lights {
            light.set_sampling(sampling);
        }
        Cow::Owned(scene)
    }
}

/// Loads `builtin:NAME` (the only source until scene files land).
pub fn load(spec: &str) -> Result<Scene, SceneError> {
    match spec.strip_prefix("builtin:") {
        Some(name) => builtin::build(name),
        None => Err(SceneError::new(
            spec,
            None,
            "scene files are not supported yet; use builtin:NAME",
        )),
    }
}
