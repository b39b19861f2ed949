//! Triangle meshes from files: Wavefront OBJ (`tobj`), Stanford PLY (ASCII and binary, our
//! own reader) and Mitsuba's `serialized` format (zlib via `flate2`). Every loader
//! validates counts, indices and finiteness, and returns a message naming the path on
//! error; the XML loader adds the element's location.

mod obj;
mod ply;
mod serialized;

pub use obj::load_obj;
pub use ply::load_ply;
pub use serialized::load_serialized;

use crate::geometry::Mesh;

/// Largest magnitude of a number read from a scene or mesh file: squared distances and
/// areas of larger coordinates overflow f32 (3.4·10³⁸) in the renderer.
pub const MAX_MAGNITUDE: f32 = 1e9;

/// Checks a mesh read from `path`: at least one triangle, indices in range, finite
/// attributes, attribute arrays empty or one per vertex.
pub fn validate(mesh: &Mesh, path: &str) -> Result<(), String> {
    let n = mesh.positions.len();
    if mesh.indices.is_empty() {
        return Err(format!("{path}: mesh has no triangles"));
    }
    if let Some(bad) = mesh.indices.iter().flatten().find(|&&i| i as usize >= n) {
        return Err(format!(
            "{path}: vertex index {bad} out of range ({n} vertices)"
        ));
    }
    if !mesh
        .positions
        .iter()
        // `is_finite` first: `max_element` skips NaN.
        .all(|p| p.is_finite() && p.abs().max_element() <= MAX_MAGNITUDE)
    {
        return Err(format!(
            "{path}: vertex positions are not all finite and within ±{MAX_MAGNITUDE:e}"
        ));
    }
    for (what, len, finite) in [
        (
            "normals",
            mesh.normals.len(),
            mesh.normals.iter().all(|v| v.is_finite()),
        ),
        (
            "texture coordinates",
            mesh.uvs.len(),
            mesh.uvs.iter().all(|v| v.is_finite()),
        ),
    ] {
        if len != 0 && len != n {
            return Err(format!("{path}: {len} {what} for {n} vertices"));
        }
        if !finite {
            return Err(format!("{path}: {what} are not all finite"));
        }
    }
    Ok(())
}

/// Fan triangulation of a polygon's vertex indices (v0, vᵢ, vᵢ₊₁).
pub fn fan(polygon: &[u32], out: &mut Vec<[u32; 3]>) {
    for i in 1..polygon.len().saturating_sub(1) {
        out.push([polygon[0], polygon[i], polygon[i + 1]]);
    }
}

/// Smooth vertex normals for a mesh that has none, as Mitsuba 3 computes them: each face
/// adds its unit normal weighted by the angle at the vertex (Thürmer & Wüthrich 1998,
/// "Computing Vertex Normals from Polygonal Facets").
pub fn compute_vertex_normals(mesh: &mut Mesh) {
    let mut normals = vec![glam::Vec3::ZERO; mesh.positions.len()];
    for tri in &mesh.indices {
        let p = tri.map(|i| mesh.positions[i as usize]);
        let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
        for k in 0..3 {
            let (a, b) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
            let angle = a
                .normalize_or_zero()
                .dot(b.normalize_or_zero())
                .clamp(-1.0, 1.0)
                .acos();
            normals[tri[k] as usize] += n * angle;
        }
    }
    for n in normals.iter_mut() {
        *n = n.normalize_or_zero();
    }
    mesh.normals = normals;
}
