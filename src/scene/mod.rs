//! Scenes: what to render (camera, geometry, materials, lights) and where scenes come
//! from (built-in builders; scene files later). `Scene` is validated when built.

pub mod builder;
pub mod builtin;
mod error;
pub mod mesh_io;
pub mod texture;
pub mod xml;

pub use builder::SceneBuilder;
pub use error::SceneError;

use crate::bsdf::Material;
use crate::geometry::Geometry;
use crate::image::Filter;
use crate::integrator::MisSettings;
use std::borrow::Cow;

use crate::light::{Light, LightSampling};
use crate::render::camera::Camera;
use crate::sampling::SamplerKind;
use texture::MaterialTexture;

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
    /// Materials that reflect from both sides (Mitsuba's `twosided`), by material index;
    /// missing entries are one-sided.
    pub two_sided: Vec<bool>,
    /// Render settings the scene file asks for.
    pub requested: Requested,
    /// Reflectance textures, by material index; missing entries are untextured.
    pub textures: Vec<Option<MaterialTexture>>,
}

/// Render settings a scene file asks for; `None` leaves the renderer's default. Command-
/// line flags override them.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Requested {
    /// Pixel reconstruction filter (default: the one-pixel box).
    pub filter: Filter,
    /// Random number source.
    pub sampler: Option<SamplerKind>,
    /// Seed.
    pub seed: Option<u64>,
    /// MIS sample counts and heuristic.
    pub mis: Option<MisSettings>,
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

    /// This scene with MIS compensation of its environment map on or off (see
    /// [`Environment::set_compensation`](crate::light::Environment::set_compensation)):
    /// borrowed when nothing changes, else a copy.
    pub fn with_env_compensation(&self, on: bool) -> Cow<'_, Scene> {
        let Some(i) = self.environment else {
            return Cow::Borrowed(self);
        };
        match &self.lights[i] {
            Light::Environment(e) if e.compensated() != on => {
                let mut scene = self.clone();
                if let Light::Environment(e) = &mut scene.lights[i] {
                    e.set_compensation(on);
                }
                Cow::Owned(scene)
            }
            _ => Cow::Borrowed(self),
        }
    }

    /// The texture on material `m`'s reflectance, if any.
    #[inline]
    pub fn texture(&self, m: u32) -> Option<&MaterialTexture> {
        self.textures.get(m as usize).and_then(Option::as_ref)
    }

    /// True when material `m` reflects from both sides.
    #[inline]
    pub fn is_two_sided(&self, m: u32) -> bool {
        self.two_sided.get(m as usize).copied().unwrap_or(false)
    }
}

/// Loads `builtin:NAME` or a Mitsuba XML file (warnings go to stderr).
pub fn load(spec: &str) -> Result<Scene, SceneError> {
    load_with(spec, &[])
}

/// Loads `builtin:NAME` or a Mitsuba XML file with `-D name=value` definitions; the
/// loader's located warnings are printed to stderr. A file may also carry definitions
/// in its name, as built-in scenes carry parameters: `scene.xml?spp=64&fov=30` (used
/// when no file has that exact name), so every command that takes a scene can set them.
pub fn load_with(spec: &str, defines: &[(String, String)]) -> Result<Scene, SceneError> {
    match spec.strip_prefix("builtin:") {
        Some(name) => {
            if !defines.is_empty() {
                return Err(SceneError::new(
                    spec,
                    None,
                    "-D applies to scene files only",
                ));
            }
            builtin::build(name)
        }
        None => {
            let (path, mut all) = split_defines(spec)?;
            all.extend_from_slice(defines);
            let loaded = xml::load(std::path::Path::new(path), &all)?;
            for w in &loaded.warnings {
                eprintln!("warning: {w}");
            }
            Ok(loaded.scene)
        }
    }
}

/// `-D name=value` pairs.
pub type Defines = Vec<(String, String)>;

/// `file.xml?a=1&b=2` → (`file.xml`, [(a, 1), (b, 2)]) unless a file is named `spec`.
fn split_defines(spec: &str) -> Result<(&str, Defines), SceneError> {
    match spec.split_once('?') {
        Some((path, query)) if !std::path::Path::new(spec).exists() => {
            let defines = query
                .split('&')
                .map(|kv| match kv.split_once('=') {
                    Some((k, v)) if !k.is_empty() => Ok((k.to_owned(), v.to_owned())),
                    _ => Err(SceneError::new(
                        spec,
                        None,
                        format!("bad parameter \"{kv}\" (expected NAME=VALUE)"),
                    )),
                })
                .collect::<Result<_, _>>()?;
            Ok((path, defines))
        }
        _ => Ok((spec, Vec::new())),
    }
}
