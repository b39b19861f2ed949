//! Textures bound to materials' reflectances. The bitmap lookup itself is
//! [`crate::math::texture`]; the loader (`xml/bitmap.rs`) decodes PNG and JPEG from sRGB
//! to linear (unless `raw`) and takes EXR as stored.

use glam::Vec2;

use crate::bsdf::{Diffuse, Material};
use crate::math::Spectrum;
pub use crate::math::texture::{Texture, Wrap};

/// A texture bound to a material's reflectance: diffuse `reflectance` or Phong
/// `diffuse_reflectance`.
#[derive(Clone, Debug)]
pub struct MaterialTexture {
    /// The texture.
    pub texture: Texture,
}

impl MaterialTexture {
    /// `material` with its reflectance replaced by the texture's value at `uv`.
    pub fn apply(&self, material: &Material, uv: Vec2) -> Material {
        let r = self.texture.eval(uv).clamp(Spectrum::ZERO, Spectrum::ONE);
        match material {
            Material::Diffuse(_) => Material::Diffuse(Diffuse { reflectance: r }),
            Material::Phong(p) => {
                let mut p = p.clone();
                p.kd = r;
                Material::Phong(p)
            }
            // The loader binds textures to diffuse and Phong reflectances only.
            other => other.clone(),
        }
    }
}
