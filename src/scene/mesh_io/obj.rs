//! Wavefront OBJ through `tobj`: positions, normals and texture coordinates unified to one
//! index per vertex, polygons fan-triangulated, all objects of the file in one mesh.

use std::path::Path;

use glam::{Vec2, Vec3};

use super::validate;
use crate::geometry::Mesh;

/// Loads every object of an OBJ file into one mesh.
pub fn load_obj(path: &Path) -> Result<Mesh, String> {
    let name = path.display().to_string();
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj(path, &options)
        .map_err(|e| format!("cannot load OBJ mesh \"{name}\": {e}"))?;
    let mut mesh = Mesh::default();
    for m in &models {
        let m = &m.mesh;
        let base = mesh.positions.len() as u32;
        let count = m.positions.len() / 3;
        let has_n = m.normals.len() == m.positions.len();
        let has_uv = m.texcoords.len() / 2 == count;
        if !mesh.positions.is_empty()
            && (has_n == mesh.normals.is_empty() || has_uv == mesh.uvs.is_empty())
        {
            return Err(format!(
                "{name}: objects differ in having normals or texture coordinates"
            ));
        }
        mesh.positions.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        if has_n {
            mesh.normals.extend(
                m.normals
                    .chunks_exact(3)
                    .map(|n| Vec3::new(n[0], n[1], n[2])),
            );
        }
        if has_uv {
            mesh.uvs
                .extend(m.texcoords.chunks_exact(2).map(|t| Vec2::new(t[0], t[1])));
        }
        if m.indices.len() % 3 != 0 {
            return Err(format!("{name}: face index count is not a multiple of 3"));
        }
        for t in m.indices.chunks_exact(3) {
            let tri = [t[0], t[1], t[2]].map(|i| i.checked_add(base));
            match tri {
                [Some(a), Some(b), Some(c)] => mesh.indices.push([a, b, c]),
                _ => return Err(format!("{name}: vertex index overflow")),
            }
        }
    }
    validate(&mesh, &name)?;
    Ok(mesh)
}
