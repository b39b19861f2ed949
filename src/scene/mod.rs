//! Scenes: what to render (camera, geometry, materials, lights) and where scenes come
//! from (built-in builders, Mitsuba 3 XML files, mesh files, textures). `Scene` is
//! validated when built. A scene names the render settings it asks for as a
//! [`RenderPatch`] of the `settings` vocabulary, never in the renderer's types.

pub mod builder;
pub mod builtin;
pub mod camera;
mod environment;
mod error;
pub mod export;
pub mod mesh_io;
pub mod texture;
pub mod xml;

pub use builder::SceneBuilder;
pub use camera::Camera;
pub use environment::environment_from_file;
pub use error::SceneError;

use crate::bsdf::Material;
use crate::geometry::Geometry;
use crate::image::Filter;
use crate::light::Light;
use crate::settings::RenderPatch;
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
    /// Pixel reconstruction filter the scene file asks for (default: the one-pixel box).
    pub filter: Filter,
    /// Render settings the scene file asks for (sampler, seed, MIS); the command line
    /// overrides them.
    pub requested: RenderPatch,
    /// Reflectance textures, by material index; missing entries are untextured.
    pub textures: Vec<Option<MaterialTexture>>,
    /// A hash of what the scene was loaded from (a file's element tree and the files it
    /// names, or a built-in's name and parameters), recorded in rendered EXR files so
    /// that `merge` combines only renders of one scene. Zero for scenes built in code.
    pub content_hash: u64,
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
    load_with_options(spec, defines, xml::LoadOptions::default())
}

/// [`load_with`] with loader options (`lenient`: unused and duplicated properties of a
/// scene file are warnings rather than errors).
pub fn load_with_options(
    spec: &str,
    defines: &[(String, String)],
    options: xml::LoadOptions,
) -> Result<Scene, SceneError> {
    match spec.strip_prefix("builtin:") {
        Some(name) => {
            if !defines.is_empty() {
                return Err(SceneError::new(
                    spec,
                    None,
                    "-D applies to scene files only",
                ));
            }
            let mut scene = builtin::build(name)?;
            scene.content_hash = crate::sampling::rng::hash_bytes(0, spec.as_bytes());
            Ok(scene)
        }
        None => {
            let (path, mut all) = split_defines(spec)?;
            all.extend_from_slice(defines);
            let loaded = xml::load_with_options(std::path::Path::new(path), &all, options)?;
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
