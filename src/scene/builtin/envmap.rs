//! `envmap`: diffuse and glossy spheres on a floor lit only by a procedural sky — a small,
//! very bright sun (1.5° radius) over a dim gradient — so it needs no files. Uniform and
//! cosine sampling rarely find the sun; sampling the map by its luminance does.

use super::stage;
use glam::{Mat3, Vec3};

use crate::bsdf::{Material, Phong};
use crate::light::Environment;
use crate::light::environment::{SkyParameters, procedural_sky};
use crate::math::Spectrum;
use crate::scene::{Scene, SceneBuilder, SceneError};

/// Builds the scene.
pub fn build() -> Result<Scene, SceneError> {
    let mut b = SceneBuilder::new("builtin:envmap");
    let floor = stage::diffuse(&mut b, Spectrum::new(0.5, 0.48, 0.45));
    let matte = stage::diffuse(&mut b, Spectrum::splat(0.75));
    let phong = |n: f32| {
        Material::Phong(Phong {
            kd: Spectrum::new(0.35, 0.12, 0.08),
            ks: Spectrum::splat(0.55),
            exponent: n,
        })
    };
    let glossy = [b.material(phong(20.0)), b.material(phong(300.0))];

    let h = 4.0;
    stage::floor(&mut b, h, floor);
    let r = 0.5;
    b.sphere(Vec3::new(-1.15, r, 0.0), r, matte, None);
    b.sphere(Vec3::new(0.0, r, -0.3), r, glossy[0], None);
    b.sphere(Vec3::new(1.15, r, 0.0), r, glossy[1], None);

    let sky = procedural_sky(&SkyParameters::default());
    let env = Environment::from_image(sky, 1.0, Mat3::IDENTITY)
        .map_err(|e| SceneError::new("builtin:envmap", None, e))?;
    b.environment(env);

    let camera = stage::camera(Vec3::new(0.0, 1.4, 4.6), Vec3::new(0.0, 0.45, 0.0), 45.0);
    b.build(camera, 16)
}
