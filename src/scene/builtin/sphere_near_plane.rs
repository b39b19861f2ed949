//! `sphere-near-plane`: the cases where the geometry term G = cos θx·cos θy/d² varies
//! most over a light. A diffuse floor lit by a sphere light hovering just above it, a
//! rectangle light standing almost edge-on to the floor (grazing), and an emitting
//! octahedron (a triangle mesh, one light per triangle).
//!
//! [`build_with`] builds the same floor with any subset of the emitters (and a concave
//! polygon emitter), so the lab can measure one emitter shape at a time.

use super::stage;
use glam::Vec3;

use crate::geometry::Mesh;
use crate::math::Spectrum;
use crate::scene::builder::Emission;
use crate::scene::{Scene, SceneBuilder, SceneError};

/// The emitters the scene can hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NearPlaneEmitter {
    /// A sphere of radius 0.4 whose lowest point is 0.05 above the floor.
    Sphere,
    /// A 1.2 × 0.8 rectangle standing on the floor, tilted 10° so it faces the floor at
    /// grazing angles.
    Rectangle,
    /// An octahedron of radius 0.3 (8 triangle lights) 0.1 above the floor.
    Mesh,
    /// A concave L-shaped polygon, tilted, 0.1 above the floor at its low edge (not in
    /// the built-in scene; for measurements of polygon strategies).
    Polygon,
    /// A disk of radius 0.5 facing down and towards +z (tilted 30°), 0.1 above the floor
    /// at its lowest point (not in the built-in scene; for measurements of disk
    /// strategies).
    Disk,
}

/// The emitters of the built-in scene.
pub const EMITTERS: [NearPlaneEmitter; 3] = [
    NearPlaneEmitter::Sphere,
    NearPlaneEmitter::Rectangle,
    NearPlaneEmitter::Mesh,
];

/// Sphere centre and radius.
pub const SPHERE: (Vec3, f32) = (Vec3::new(-1.3, 0.45, 0.1), 0.4);

/// Builds the built-in scene.
pub fn build() -> Result<Scene, SceneError> {
    build_with(&EMITTERS)
}

/// The floor and camera with the given emitters.
pub fn build_with(emitters: &[NearPlaneEmitter]) -> Result<Scene, SceneError> {
    let mut b = SceneBuilder::new("builtin:sphere-near-plane");
    let floor = stage::diffuse(&mut b, Spectrum::splat(0.7));
    let dark = stage::diffuse(&mut b, Spectrum::ZERO);
    let h = 4.0;
    stage::floor(&mut b, h, floor);
    let emit = |r: f32, g: f32, bl: f32| Some(Emission::new(Spectrum::new(r, g, bl)));
    for &e in emitters {
        match e {
            NearPlaneEmitter::Sphere => {
                b.sphere(SPHERE.0, SPHERE.1, dark, emit(2.0, 1.8, 1.5));
            }
            NearPlaneEmitter::Rectangle => {
                // Edges along z and (mostly) up; normal ea × eb ≈ (−0.98, −0.17, 0):
                // facing −x and tilted 10° towards the floor.
                let (s, c) = 10f32.to_radians().sin_cos();
                b.rectangle(
                    Vec3::new(1.3, 0.02, -0.4),
                    Vec3::new(0.0, 0.0, 1.2),
                    Vec3::new(-0.8 * s, 0.8 * c, 0.0),
                    dark,
                    emit(1.5, 2.0, 3.0),
                );
            }
            NearPlaneEmitter::Mesh => {
                b.mesh(
                    octahedron(Vec3::new(0.1, 0.4, -1.3), 0.3),
                    dark,
                    emit(3.0, 2.0, 1.0),
                );
            }
            NearPlaneEmitter::Polygon => {
                let l = [
                    (0.0, 0.0),
                    (1.0, 0.0),
                    (1.0, 0.4),
                    (0.4, 0.4),
                    (0.4, 1.0),
                    (0.0, 1.0),
                ];
                // In a plane tilted 30° about x, facing down and towards +z; low edge 0.1 up.
                let (s, c) = 30f32.to_radians().sin_cos();
                let vertices: Vec<Vec3> = l
                    .iter()
                    .rev()
                    .map(|&(x, y)| Vec3::new(-0.5 + x, 0.1 + y * s, 0.6 - y * c))
                    .collect();
                b.polygon(&vertices, dark, emit(2.0, 2.0, 2.0));
            }
            NearPlaneEmitter::Disk => {
                let (s, c) = 30f32.to_radians().sin_cos();
                let normal = Vec3::new(0.0, -c, s);
                let r = 0.5;
                b.disk(
                    Vec3::new(0.0, 0.1 + r * s, 0.2),
                    normal,
                    r,
                    dark,
                    emit(2.0, 2.0, 2.0),
                );
            }
        }
    }
    let camera = stage::camera(Vec3::new(0.0, 4.2, 3.4), Vec3::new(0.0, 0.1, -0.4), 45.0);
    b.build(camera, 16)
}

/// A regular octahedron (outward faces) around `center` with vertex distance `r`.
fn octahedron(center: Vec3, r: f32) -> Mesh {
    let v = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z];
    let positions = v.iter().map(|&d| center + r * d).collect();
    // Faces (x±, y±, z±) wound so that (p1 − p0) × (p2 − p0) points outward.
    let mut indices = Vec::new();
    for &x in &[0u32, 1] {
        for &y in &[2u32, 3] {
            for &z in &[4u32, 5] {
                let (px, py, pz) = (v[x as usize], v[y as usize], v[z as usize]);
                let outward = (py - px).cross(pz - px).dot(px + py + pz) > 0.0;
                indices.push(if outward { [x, y, z] } else { [x, z, y] });
            }
        }
    }
    Mesh {
        positions,
        indices,
        ..Mesh::default()
    }
}
