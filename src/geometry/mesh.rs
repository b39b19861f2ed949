//! Triangle meshes: shared vertices, optional per-vertex normals and texture coordinates.

use glam::{Vec2, Vec3};

/// An indexed triangle mesh.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Vertex positions (world space).
    pub positions: Vec<Vec3>,
    /// Per-vertex shading normals (empty: flat shading).
    pub normals: Vec<Vec3>,
    /// Per-vertex texture coordinates (empty: barycentric uv).
    pub uvs: Vec<Vec2>,
    /// Triangles as vertex index triples.
    pub indices: Vec<[u32; 3]>,
}

impl Mesh {
    /// Shading normal at barycentrics (b1, b2) of triangle `index`, if the mesh has normals.
    pub fn shading_normal(&self, index: u32, b1: f32, b2: f32) -> Option<Vec3> {
        if self.normals.is_empty() {
            return None;
        }
        let [i0, i1, i2] = self.indices[index as usize];
        let n = (1.0 - b1 - b2) * self.normals[i0 as usize]
            + b1 * self.normals[i1 as usize]
            + b2 * self.normals[i2 as usize];
        let n = n.normalize_or_zero();
        (n != Vec3::ZERO).then_some(n)
    }

    /// Texture coordinates at barycentrics (b1, b2) of triangle `index`.
    pub fn uv(&self, index: u32, b1: f32, b2: f32) -> Vec2 {
        if self.uvs.is_empty() {
            return Vec2::new(b1, b2);
        }
        let [i0, i1, i2] = self.indices[index as usize];
        (1.0 - b1 - b2) * self.uvs[i0 as usize]
            + b1 * self.uvs[i1 as usize]
            + b2 * self.uvs[i2 as usize]
    }
}
