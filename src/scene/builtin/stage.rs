//! The set every built-in scene stands on: Lambertian materials, a floor, a back wall and
//! the camera, written once.

use glam::Vec3;

use crate::bsdf::{Diffuse, Material};
use crate::math::Spectrum;
use crate::scene::{Camera, SceneBuilder};

/// Adds a Lambertian material of `reflectance` (zero for emitters' own surfaces).
pub(super) fn diffuse(b: &mut SceneBuilder, reflectance: Spectrum) -> u32 {
    b.material(Material::Diffuse(Diffuse { reflectance }))
}

/// A square floor y = 0 over [−h, h]², front side up.
pub(super) fn floor(b: &mut SceneBuilder, h: f32, material: u32) {
    b.rectangle(
        Vec3::new(-h, 0.0, h),
        Vec3::new(2.0 * h, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -2.0 * h),
        material,
        None,
    );
}

/// A back wall z = −h over x ∈ [−h, h], y ∈ [0, 2h], front side towards +z.
pub(super) fn back_wall(b: &mut SceneBuilder, h: f32, material: u32) {
    b.rectangle(
        Vec3::new(-h, 0.0, -h),
        Vec3::new(2.0 * h, 0.0, 0.0),
        Vec3::new(0.0, 2.0 * h, 0.0),
        material,
        None,
    );
}

/// The built-in scenes' camera: 384 × 256 pixels, from `from` towards `at`, +y up,
/// `fov` degrees across the image.
pub(super) fn camera(from: Vec3, at: Vec3, fov: f32) -> Camera {
    Camera::look_at(from, at, Vec3::Y, fov, 384, 256)
}
