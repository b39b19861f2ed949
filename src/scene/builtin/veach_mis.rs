//! `veach-mis`: Veach's multiple-importance-sampling figure (Veach & Guibas 1995, fig. 1;
//! Veach's thesis fig. 9.2). Four plates of rising smoothness, each tilted to reflect a
//! row of four sphere lights whose radii grow in steps of 3 and whose radiances fall as
//! 1/r² so that all four emit the same power; a dim fill light lights the backdrop.
//! Light sampling wins on the rough plates and large lights, BSDF sampling on the smooth
//! plates and small lights; MIS is good everywhere.

use super::stage;
use glam::Vec3;

use crate::bsdf::{Material, Phong};
use crate::math::Spectrum;
use crate::scene::builder::Emission;
use crate::scene::{Scene, SceneBuilder, SceneError};

/// Phong exponents of the plates, nearest (roughest) first.
pub const PLATE_EXPONENTS: [f32; 4] = [30.0, 300.0, 3_000.0, 30_000.0];
/// Radii of the four lights, left to right.
pub const LIGHT_RADII: [f32; 4] = [0.03333, 0.1, 0.3, 0.9];
/// Power-equalising constant: each light has radiance LIGHT_R2 / r².
pub const LIGHT_R2: f32 = 1.0;

const CAMERA: Vec3 = Vec3::new(0.0, 2.0, 15.0);
const LIGHT_ROW_Y: f32 = 0.8;

/// Builds the scene.
pub fn build() -> Result<Scene, SceneError> {
    let mut b = SceneBuilder::new("builtin:veach-mis");
    let backdrop = stage::diffuse(&mut b, Spectrum::splat(0.25));
    let black = stage::diffuse(&mut b, Spectrum::ZERO);

    // Backdrop: a floor far below and a wall behind the lights.
    b.rectangle(
        Vec3::new(-20.0, -4.5, 20.0),
        Vec3::new(40.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -40.0),
        backdrop,
        None,
    );
    b.rectangle(
        Vec3::new(-20.0, -4.5, -4.0),
        Vec3::new(40.0, 0.0, 0.0),
        Vec3::new(0.0, 30.0, 0.0),
        backdrop,
        None,
    );

    // Plates: 9.6 wide, `PLATE_DEPTH` deep, each normal the half vector between the camera
    // and the middle of the light row as seen from the plate's centre, so that the plate
    // mirrors the lights towards the camera.
    const PLATE_DEPTH: f32 = 1.1;
    let centres = [
        Vec3::new(0.0, -3.4, 4.0),
        Vec3::new(0.0, -2.8, 2.7),
        Vec3::new(0.0, -2.2, 1.45),
        Vec3::new(0.0, -1.6, 0.25),
    ];
    for (c, n_exp) in centres.into_iter().zip(PLATE_EXPONENTS) {
        let m = b.material(Material::Phong(Phong {
            // Purely glossy, as Veach's plates: a diffuse part would add BSDF-sampling
            // fireflies (its cosine lobe meeting the tiny bright lights) to every plate.
            kd: Spectrum::ZERO,
            ks: Spectrum::splat(0.8),
            exponent: n_exp,
        }));
        let to_camera = (CAMERA - c).normalize();
        let to_lights = (Vec3::new(0.0, LIGHT_ROW_Y, 0.0) - c).normalize();
        let n = (to_camera + to_lights).normalize();
        let ea = Vec3::new(9.6, 0.0, 0.0);
        let eb = n.cross(Vec3::X) * PLATE_DEPTH; // ea × eb = n
        b.rectangle(c - 0.5 * ea - 0.5 * eb, ea, eb, m, None);
    }

    for (i, r) in LIGHT_RADII.into_iter().enumerate() {
        let x = -3.75 + 2.5 * i as f32;
        let radiance = Spectrum::splat(LIGHT_R2 / (r * r));
        b.sphere(
            Vec3::new(x, LIGHT_ROW_Y, 0.0),
            r,
            black,
            Some(Emission::new(radiance)),
        );
    }
    // Dim fill light, up and to the right.
    b.sphere(
        Vec3::new(10.0, 10.0, 4.0),
        0.5,
        black,
        Some(Emission::new(Spectrum::splat(400.0))),
    );

    let camera = stage::camera(CAMERA, Vec3::new(0.0, -1.6, 2.5), 46.0);
    b.build(camera, 16)
}
