//! `assignment`: the lecture's "current assignment" — a floor and a back wall, a
//! diffuse sphere and three Phong spheres of exponent 10, 100 and 1000, lit only by one
//! small rectangular area light (1/20 of the floor's side).

use super::stage;
use glam::Vec3;

use crate::bsdf::{Material, Phong};
use crate::math::Spectrum;
use crate::scene::builder::Emission;
use crate::scene::{Scene, SceneBuilder, SceneError};

/// Side of the square floor.
pub const FLOOR_SIDE: f32 = 6.0;
/// Side of the square light: 1/20 of the floor's.
pub const LIGHT_SIDE: f32 = FLOOR_SIDE / 20.0;
/// Radiance of the light.
pub const LIGHT_RADIANCE: f32 = 120.0;

/// Builds the scene.
pub fn build() -> Result<Scene, SceneError> {
    let mut b = SceneBuilder::new("builtin:assignment");
    let grey = stage::diffuse(&mut b, Spectrum::splat(0.6));
    let wall = stage::diffuse(&mut b, Spectrum::new(0.55, 0.55, 0.6));
    let matte = stage::diffuse(&mut b, Spectrum::new(0.7, 0.35, 0.25));
    let phong = |n: f32| {
        Material::Phong(Phong {
            kd: Spectrum::new(0.1, 0.15, 0.35),
            ks: Spectrum::splat(0.6),
            exponent: n,
        })
    };
    let phongs = [
        b.material(phong(10.0)),
        b.material(phong(100.0)),
        b.material(phong(1000.0)),
    ];
    let light_mat = stage::diffuse(&mut b, Spectrum::ZERO);

    let h = 0.5 * FLOOR_SIDE;
    // Floor y = 0, front side up; back wall z = −h, front side towards +z.
    stage::floor(&mut b, h, grey);
    stage::back_wall(&mut b, h, wall);

    let r = 0.45;
    b.sphere(Vec3::new(-1.65, r, 0.0), r, matte, None);
    for (i, &m) in phongs.iter().enumerate() {
        b.sphere(Vec3::new(-0.55 + 1.1 * i as f32, r, 0.0), r, m, None);
    }

    // The light: a small square facing down, above and slightly in front of the spheres.
    let s = LIGHT_SIDE;
    b.rectangle(
        Vec3::new(-0.5 * s, 2.4, 1.0 - 0.5 * s),
        Vec3::new(s, 0.0, 0.0),
        Vec3::new(0.0, 0.0, s),
        light_mat,
        Some(Emission::new(Spectrum::splat(LIGHT_RADIANCE))),
    );

    let camera = stage::camera(Vec3::new(0.0, 1.6, 5.2), Vec3::new(0.0, 0.55, 0.0), 45.0);
    b.build(camera, 16)
}
