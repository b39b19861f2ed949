//! Meshes written as binary little-endian Stanford PLY (Turk 1994): the vertex
//! element's x, y, z, then nx, ny, nz and u, v where the mesh has them, and one
//! `vertex_indices` list of three per face. Floats keep their bits, so a mesh read back
//! (by lightlab's or Mitsuba 3's PLY reader) has the same vertices.

use crate::geometry::Mesh;

/// The PLY file of `mesh`, whole.
pub fn ply_bytes(mesh: &Mesh) -> Vec<u8> {
    let normals = !mesh.normals.is_empty();
    let uvs = !mesh.uvs.is_empty();
    let mut header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment written by lightlab\n\
         element vertex {}\nproperty float x\nproperty float y\nproperty float z\n",
        mesh.positions.len()
    );
    if normals {
        header.push_str("property float nx\nproperty float ny\nproperty float nz\n");
    }
    if uvs {
        header.push_str("property float u\nproperty float v\n");
    }
    header.push_str(&format!(
        "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        mesh.indices.len()
    ));
    let per_vertex = 3 + 3 * normals as usize + 2 * uvs as usize;
    let mut out = Vec::with_capacity(
        header.len() + 4 * per_vertex * mesh.positions.len() + 13 * mesh.indices.len(),
    );
    out.extend_from_slice(header.as_bytes());
    let mut put = |x: f32| out.extend_from_slice(&x.to_le_bytes());
    for (i, p) in mesh.positions.iter().enumerate() {
        p.to_array().into_iter().for_each(&mut put);
        if normals {
            mesh.normals[i].to_array().into_iter().for_each(&mut put);
        }
        if uvs {
            mesh.uvs[i].to_array().into_iter().for_each(&mut put);
        }
    }
    for face in &mesh.indices {
        out.push(3);
        for &v in face {
            out.extend_from_slice(&(v as i32).to_le_bytes());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec2, Vec3};

    #[test]
    fn a_mesh_reads_back_bit_for_bit() {
        let mesh = Mesh {
            positions: vec![
                Vec3::new(0.1, -2.5, 3.0),
                Vec3::new(1.0 / 3.0, 0.0, 7.25),
                Vec3::new(-1e-7, 4.0, 1.0),
            ],
            normals: vec![Vec3::X, Vec3::Y, Vec3::new(0.6, 0.0, 0.8)],
            uvs: vec![Vec2::ZERO, Vec2::new(1.0, 0.0), Vec2::new(0.3, 0.7)],
            indices: vec![[0, 1, 2]],
        };
        let dir = std::env::temp_dir().join(format!("lightlab-ply-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("m.ply");
        std::fs::write(&path, ply_bytes(&mesh)).unwrap();
        let back = crate::scene::mesh_io::load_ply(&path).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(back.positions, mesh.positions);
        assert_eq!(back.normals, mesh.normals);
        assert_eq!(back.uvs, mesh.uvs);
        assert_eq!(back.indices, mesh.indices);
    }
}
