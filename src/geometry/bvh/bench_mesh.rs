//! A deterministic benchmark mesh and ray sets for `lightlab bench` and the BVH
//! comparisons: a bumpy sphere tessellated as a subdivided cube projected onto it (a
//! "cube sphere"), displaced by a sum of sines, and rays like a renderer's: primary rays
//! from a camera in scanline order, and shadow rays between points on the surface.

use glam::Vec3;

use crate::geometry::Ray;
use crate::sampling::Rng32;
use crate::sampling::rng::hash_words;
use crate::sampling::warp::sphere::square_to_uniform_sphere;

/// Triangles per face cell: each grid cell is split in two.
const TRIANGLES_PER_CELL: usize = 2;

/// The bumpy sphere's radius along unit direction `w`: 1 plus two octaves of sines
/// (0.08 and 0.02 in amplitude), so the surface is star-shaped and never self-overlaps.
pub fn bench_radius(w: Vec3) -> f32 {
    let low = (5.0 * w.x + 1.0).sin() * (6.0 * w.y + 2.0).sin() * (7.0 * w.z + 3.0).sin();
    let high = (31.0 * w.x).sin() * (37.0 * w.y + 1.0).sin() * (41.0 * w.z + 2.0).sin();
    1.0 + 0.08 * low + 0.02 * high
}

/// The bumpy sphere as a triangle mesh with about `target_triangles` triangles (at least
/// 12): vertex positions and index triples. Each of the 6 cube faces is a k × k grid with
/// 12k² ≈ `target_triangles`; vertices on cube edges are repeated per face.
pub fn bench_mesh(target_triangles: usize) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let k = ((target_triangles as f64 / (6 * TRIANGLES_PER_CELL) as f64)
        .sqrt()
        .round() as usize)
        .max(1);
    let side = k + 1;
    let mut positions = Vec::with_capacity(6 * side * side);
    let mut triangles = Vec::with_capacity(6 * k * k * TRIANGLES_PER_CELL);
    for face in 0..6 {
        // Face normal n and in-face axes u, v of the cube [-1, 1]³.
        let axis = face / 2;
        let sign = if face % 2 == 0 { 1.0 } else { -1.0 };
        let n = Vec3::AXES[axis] * sign;
        let (u, v) = (
            Vec3::AXES[(axis + 1) % 3],
            Vec3::AXES[(axis + 2) % 3] * sign,
        );
        let base = positions.len() as u32;
        for j in 0..side {
            for i in 0..side {
                let (s, t) = (
                    2.0 * i as f32 / k as f32 - 1.0,
                    2.0 * j as f32 / k as f32 - 1.0,
                );
                let w = (n + s * u + t * v).normalize();
                positions.push(w * bench_radius(w));
            }
        }
        let at = |i: usize, j: usize| base + (j * side + i) as u32;
        for j in 0..k {
            for i in 0..k {
                triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    }
    (positions, triangles)
}

/// Benchmark rays: `primary` rays (t_max = ∞) and `shadow` rays with their t_max.
#[derive(Clone, Debug)]
pub struct BenchRays {
    /// Camera rays in scanline order, one jittered ray per pixel of a square image whose
    /// field of view frames the mesh with a margin (some rays miss).
    pub primary: Vec<Ray>,
    /// Unit-direction rays from just above a surface point toward a random other one, with
    /// t_max stopping just short of the target: the shadow rays of direct illumination.
    /// Origins follow a scanline sweep of the surface, so neighbouring rays start close
    /// together as they do in a renderer.
    pub shadow: Vec<(Ray, f32)>,
}

/// `n` primary and `n` shadow rays for the mesh of [`bench_mesh`], the same for the same
/// `(n, seed)` on every machine.
pub fn bench_rays(n: usize, seed: u64) -> BenchRays {
    let mut rng = Rng32::new(hash_words(&[seed, n as u64]));
    let eye = Vec3::new(0.6, 0.9, 3.4);
    let forward = (-eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    // Half-angle tan 0.38 frames the unit sphere from distance ≈ 3.6 with a margin.
    let (width, tan_half) = ((n as f64).sqrt().ceil().max(1.0) as usize, 0.38);
    let primary = (0..n)
        .map(|pixel| {
            let (x, y) = (
                (pixel % width) as f32 + rng.next_f32(),
                (pixel / width) as f32 + rng.next_f32(),
            );
            let s = (2.0 * x / width as f32 - 1.0) * tan_half;
            let t = (1.0 - 2.0 * y / width as f32) * tan_half;
            Ray::new(eye, (forward + s * right + t * up).normalize())
        })
        .collect();
    // Origins sweep the surface in scanline order over a width × width grid of the sphere
    // parameter square, as a renderer's shading points follow its pixels; targets are
    // independent random points, as light samples are.
    let surface_point = |u: glam::Vec2| {
        let w = square_to_uniform_sphere(u).0;
        w * bench_radius(w)
    };
    let shadow = (0..n)
        .map(|cell| {
            let (x, y) = (
                (cell % width) as f32 + rng.next_f32(),
                (cell / width) as f32 + rng.next_f32(),
            );
            let from = surface_point(glam::Vec2::new(x, y) / width as f32);
            let to = surface_point(glam::Vec2::new(rng.next_f32(), rng.next_f32()));
            // Lift the origin along the radial direction, roughly the normal.
            let o = from * 1.001;
            let distance = (to - o).length();
            let d = if distance > 0.0 {
                (to - o) / distance
            } else {
                Vec3::Z
            };
            (Ray::new(o, d), distance * 0.999)
        })
        .collect();
    BenchRays { primary, shadow }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesh_has_the_requested_size_and_valid_indices() {
        for target in [0usize, 12, 1000, 100_000] {
            let (positions, triangles) = bench_mesh(target);
            let k = ((target as f64 / 12.0).sqrt().round() as usize).max(1);
            assert_eq!(triangles.len(), 12 * k * k);
            assert!(
                triangles
                    .iter()
                    .flatten()
                    .all(|&i| (i as usize) < positions.len())
            );
            assert!(
                positions
                    .iter()
                    .all(|p| p.is_finite() && (0.85..1.15).contains(&p.length()))
            );
        }
    }

    #[test]
    fn rays_are_deterministic_and_finite() {
        let (a, b) = (bench_rays(100, 7), bench_rays(100, 7));
        assert_eq!(a.primary.len(), 100);
        assert_eq!(a.shadow.len(), 100);
        for (x, y) in a.shadow.iter().zip(&b.shadow) {
            assert!(x.0.o == y.0.o && x.0.d == y.0.d && x.1 == y.1);
            assert!(x.0.d.is_finite() && x.1 >= 0.0);
        }
        assert!(
            a.primary
                .iter()
                .all(|r| r.d.is_finite() && (r.d.length() - 1.0).abs() < 1e-5)
        );
    }
}
