//! `shirley-100`: a hundred luminaires over a floor with objects, after the scene of
//! Shirley, Wang & Zimmerman 1996 ("Monte Carlo Techniques for Direct Lighting
//! Calculations", ACM TOG 15(1)) that the lecture shows at 49 samples per pixel.
//!
//! The luminaires are spheres and quads placed by a fixed random stream: small spheres
//! hovering just above the floor and the objects (close to surfaces), panels just above
//! the floor facing sideways, ceiling panels facing down, and large spheres far away in the
//! background. Radiances are spread log-uniformly over two orders of magnitude.
//! `many-lights?n=N` is the same generator with N luminaires over an area grown with N
//! (same density), for scaling tests.

use super::stage;
use glam::Vec3;

use crate::bsdf::{Material, Phong};
use crate::math::Spectrum;
use crate::sampling::Rng32;
use crate::scene::builder::Emission;
use crate::scene::{Scene, SceneBuilder, SceneError};

/// Luminaires of `shirley-100`.
pub const LUMINAIRES: usize = 100;
/// Largest N of `many-lights?n=N`.
pub const MAX_LUMINAIRES: usize = 1_000_000;
/// Radiance of the dimmest luminaire; the brightest is 100× brighter.
const BASE_RADIANCE: f32 = 0.4;
/// Half the side of the lit area for 100 luminaires.
const HALF_SIDE: f32 = 6.0;

/// Builds `shirley-100`.
pub fn build() -> Result<Scene, SceneError> {
    build_with("builtin:shirley-100", LUMINAIRES)
}

/// Builds `many-lights?n=1000`, the listed default of the generator.
pub fn build_default_many() -> Result<Scene, SceneError> {
    build_many(1000)
}

/// Builds `many-lights?n=N` (1 ≤ N ≤ [`MAX_LUMINAIRES`]).
pub fn build_many(n: usize) -> Result<Scene, SceneError> {
    let name = format!("builtin:many-lights?n={n}");
    if !(1..=MAX_LUMINAIRES).contains(&n) {
        return Err(SceneError::new(
            name,
            None,
            format!("n must be between 1 and {MAX_LUMINAIRES}"),
        ));
    }
    build_with(&name, n)
}

/// The scene called `name` with `n` luminaires.
fn build_with(name: &str, n: usize) -> Result<Scene, SceneError> {
    let mut b = SceneBuilder::new(name);
    let scale = (n as f32 / LUMINAIRES as f32).sqrt().max(1.0);
    let half = HALF_SIDE * scale;
    add_floor_and_objects(&mut b, half + 4.0);
    let black = stage::diffuse(&mut b, Spectrum::ZERO);
    let mut rng = Rng32::new(0x5_1996);
    for i in 0..n {
        add_luminaire(&mut b, &mut rng, i, half, black);
    }
    let camera = stage::camera(Vec3::new(0.0, 4.2, 10.5), Vec3::new(0.0, 0.6, -1.5), 55.0);
    b.build(camera, 49)
}

/// A floor of half-side `half`, two boxes and four spheres (diffuse and Phong).
fn add_floor_and_objects(b: &mut SceneBuilder, half: f32) {
    let floor = stage::diffuse(b, Spectrum::new(0.5, 0.5, 0.48));
    b.rectangle(
        Vec3::new(-half, 0.0, half),
        Vec3::new(2.0 * half, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -2.0 * half),
        floor,
        None,
    );
    let clay = stage::diffuse(b, Spectrum::new(0.7, 0.4, 0.3));
    let stone = stage::diffuse(b, Spectrum::new(0.45, 0.55, 0.6));
    add_box(b, BOXES[0].0, BOXES[0].1, stone);
    add_box(b, BOXES[1].0, BOXES[1].1, clay);
    let glossy = |kd: Spectrum, exponent: f32| {
        Material::Phong(Phong {
            kd,
            ks: Spectrum::splat(0.35),
            exponent,
        })
    };
    let materials = [
        b.material(glossy(Spectrum::new(0.15, 0.2, 0.45), 60.0)),
        clay,
        b.material(glossy(Spectrum::new(0.5, 0.45, 0.1), 300.0)),
        stone,
    ];
    for ((center, radius), m) in SPHERES.into_iter().zip(materials) {
        b.sphere(center, radius, m, None);
    }
}

/// The objects' boxes (min, max).
const BOXES: [(Vec3, Vec3); 2] = [
    (Vec3::new(-3.4, 0.0, -2.2), Vec3::new(-1.8, 1.6, -0.8)),
    (Vec3::new(2.0, 0.0, -3.6), Vec3::new(3.0, 2.6, -2.6)),
];

/// The objects' spheres (centre, radius).
const SPHERES: [(Vec3, f32); 4] = [
    (Vec3::new(0.0, 0.9, -1.5), 0.9),
    (Vec3::new(-0.9, 0.4, 1.6), 0.4),
    (Vec3::new(1.7, 0.55, 0.6), 0.55),
    (Vec3::new(-4.5, 0.7, 1.0), 0.7),
];

/// Whether floor position (x, z) keeps `margin` away from every object's footprint: a
/// luminaire touching a surface makes G (and the variance of area sampling) unbounded.
fn clear_of_objects(x: f32, z: f32, margin: f32) -> bool {
    let boxes = BOXES.iter().all(|(lo, hi)| {
        x < lo.x - margin || x > hi.x + margin || z < lo.z - margin || z > hi.z + margin
    });
    let spheres = SPHERES
        .iter()
        .all(|(c, r)| (x - c.x).hypot(z - c.z) > r + margin);
    boxes && spheres
}

/// An axis-aligned box on [min, max] without its bottom face, normals outward.
fn add_box(b: &mut SceneBuilder, min: Vec3, max: Vec3, material: u32) {
    let d = max - min;
    let (x, y, z) = (Vec3::X * d.x, Vec3::Y * d.y, Vec3::Z * d.z);
    let faces = [
        (Vec3::new(min.x, max.y, max.z), x, -z), // top, +y
        (Vec3::new(min.x, min.y, max.z), x, y),  // front, +z
        (Vec3::new(max.x, min.y, min.z), -x, y), // back, −z
        (Vec3::new(max.x, min.y, max.z), -z, y), // right, +x
        (min, z, y),                             // left, −x
    ];
    for (o, ea, eb) in faces {
        b.rectangle(o, ea, eb, material, None);
    }
}

/// Luminaire `i`: one of four kinds in the proportions 4 : 1 : 2 : 3 (near spheres,
/// floor panels, ceiling panels, far spheres), with a colour from a small palette.
fn add_luminaire(b: &mut SceneBuilder, rng: &mut Rng32, i: usize, half: f32, material: u32) {
    const PALETTE: [[f32; 3]; 5] = [
        [1.0, 0.78, 0.5],
        [0.55, 0.72, 1.0],
        [1.0, 1.0, 1.0],
        [1.0, 0.55, 0.62],
        [0.65, 1.0, 0.6],
    ];
    let mut u = || rng.next_f32();
    let c = PALETTE[(u() * PALETTE.len() as f32) as usize % PALETTE.len()];
    // Log-uniform over two decades: L = L₀ · 100^ξ.
    let strength = BASE_RADIANCE * 100f32.powf(u());
    let emission = Some(Emission::new(Spectrum::new(c[0], c[1], c[2]) * strength));
    // Floor position, drawn again (a few times) when it lands on an object.
    let mut xz = || {
        (
            (2.0 * u() - 1.0) * half,
            (2.0 * u() - 1.0) * half * 0.8 - 1.0,
        )
    };
    let (mut x, mut z) = xz();
    for _ in 0..32 {
        if clear_of_objects(x, z, 0.45) {
            break;
        }
        (x, z) = xz();
    }
    match i % 10 {
        0..=3 => {
            // A small sphere close to the floor.
            let r = 0.04 + 0.1 * u();
            let y = r + 0.1 + 0.7 * u() * u();
            b.sphere(Vec3::new(x, y, z), r, material, emission);
        }
        4 => {
            // A panel hovering just above the floor, facing a random horizontal direction.
            let phi = std::f32::consts::TAU * u();
            let facing = Vec3::new(phi.cos(), 0.0, phi.sin());
            let (w, h) = (0.2 + 0.3 * u(), 0.1 + 0.3 * u());
            let along = facing.cross(Vec3::Y) * w;
            b.rectangle(
                Vec3::new(x, 0.15, z) - 0.5 * along,
                Vec3::Y * h,
                along,
                material,
                emission,
            );
        }
        5 | 6 => {
            // A ceiling panel facing down.
            let s = 0.2 + 0.4 * u();
            let y = 3.0 + 2.0 * u();
            b.rectangle(
                Vec3::new(x - 0.5 * s, y, z - 0.5 * s),
                Vec3::X * s,
                Vec3::Z * s,
                material,
                emission,
            );
        }
        _ => {
            // A larger sphere far away in the background.
            let r = 0.25 + 0.35 * u();
            let far = Vec3::new(2.5 * x, 1.0 + 9.0 * u(), -15.0 - (15.0 + half) * u());
            b.sphere(far, r, material, emission);
        }
    }
}
