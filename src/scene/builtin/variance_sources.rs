//! `variance-sources`: the lecture's slide "Variance in direct illumination" in one scene:
//! high variance for a glossy BRDF (a Phong n = 300 sphere), for a close light source (a
//! sphere light hovering just above the floor) and along a shadow boundary (a ball
//! floating under a small overhead rectangle light); the rest of the diffuse floor
//! "usually no variance" beyond the light's own.

use super::stage;
use glam::Vec3;

use crate::bsdf::{Material, Phong};
use crate::math::Spectrum;
use crate::scene::builder::Emission;
use crate::scene::{Scene, SceneBuilder, SceneError};

/// Builds the scene (the assignment's camera and stage).
pub fn build() -> Result<Scene, SceneError> {
    let mut b = SceneBuilder::new("builtin:variance-sources");
    let grey = stage::diffuse(&mut b, Spectrum::splat(0.6));
    let wall = stage::diffuse(&mut b, Spectrum::new(0.55, 0.55, 0.6));
    let ball = stage::diffuse(&mut b, Spectrum::new(0.7, 0.35, 0.25));
    let dark = stage::diffuse(&mut b, Spectrum::ZERO);
    let glossy = b.material(Material::Phong(Phong {
        kd: Spectrum::new(0.05, 0.1, 0.25),
        ks: Spectrum::splat(0.7),
        exponent: 300.0,
    }));
    let h = 3.0;
    stage::floor(&mut b, h, grey);
    stage::back_wall(&mut b, h, wall);
    // Glossy lobe: a Phong sphere reflecting both lights.
    b.sphere(Vec3::new(0.0, 0.5, -0.6), 0.5, glossy, None);
    // Close light: a small sphere light 0.08 above the floor.
    b.sphere(
        Vec3::new(1.4, 0.28, 0.6),
        0.2,
        dark,
        Some(Emission::new(Spectrum::new(12.0, 10.0, 7.0))),
    );
    // Shadow boundary: a ball floating under an overhead rectangle light.
    b.sphere(Vec3::new(-1.4, 0.8, 0.6), 0.3, ball, None);
    let s = 0.4;
    b.rectangle(
        Vec3::new(-1.4 - 0.5 * s, 2.4, 0.6 - 0.5 * s),
        Vec3::new(s, 0.0, 0.0),
        Vec3::new(0.0, 0.0, s),
        dark,
        Some(Emission::new(Spectrum::splat(60.0))),
    );
    let camera = stage::camera(Vec3::new(0.0, 1.6, 5.2), Vec3::new(0.0, 0.55, 0.0), 45.0);
    b.build(camera, 16)
}
