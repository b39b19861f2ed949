//! Shapes as Mitsuba shape elements: rectangles, spheres and disks by their
//! `to_world`, meshes by their PLY file; each with its material and area emitter.

use std::fmt::Write as _;

use glam::{Affine3A, Mat4, Vec3};

use super::text::{escape, float, matrix, point, rgb};
use crate::geometry::{Mesh, Primitive, Shape};
use crate::math::Spectrum;

/// A rectangle, sphere or disk with its material and emission.
pub fn shape(x: &mut String, prim: &Primitive, emission: Option<Spectrum>) {
    match &prim.shape {
        Shape::Rectangle(r) => {
            // Mitsuba's rectangle is [−1, 1]² in the local xy plane, normal +z, front
            // side dp/du × dp/dv: columns ea/2, eb/2, the normal, the centre.
            // A rectangle whose front is the other side has its normals flipped.
            x.push_str("    <shape type=\"rectangle\">\n");
            let center = r.o + 0.5 * (r.ea + r.eb);
            let front = r.ea.cross(r.eb).normalize();
            let m = Affine3A::from_cols(
                (0.5 * r.ea).into(),
                (0.5 * r.eb).into(),
                front.into(),
                center.into(),
            );
            matrix(x, 2, &Mat4::from(m));
            if r.normal.dot(front) < 0.0 {
                x.push_str("        <boolean name=\"flip_normals\" value=\"true\"/>\n");
            }
        }
        Shape::Sphere(s) => {
            x.push_str("    <shape type=\"sphere\">\n");
            let a = &s.axes;
            if (a.s, a.t, a.n) == (Vec3::X, Vec3::Y, Vec3::Z) {
                point(x, 2, "center", s.center);
                float(x, 2, "radius", s.radius);
            } else {
                // The sphere's own axes (its texture frame) as the rotation of to_world.
                let m = Affine3A::from_cols(a.s.into(), a.t.into(), a.n.into(), s.center.into());
                float(x, 2, "radius", s.radius);
                matrix(x, 2, &Mat4::from(m));
            }
        }
        Shape::Disk(d) => {
            // Mitsuba's disk: the unit disk in the local xy plane, normal +z.
            x.push_str("    <shape type=\"disk\">\n");
            let m = Affine3A::from_cols(
                (d.axes[0] * d.radius).into(),
                (d.axes[1] * d.radius).into(),
                d.normal.into(),
                d.center.into(),
            );
            matrix(x, 2, &Mat4::from(m));
        }
        Shape::Triangle(_) => unreachable!("triangles are written with their mesh"),
    }
    shape_tail(x, prim.material, emission);
}

/// A mesh from its PLY file `file` (world-space vertices: no transform).
pub fn mesh_shape(x: &mut String, file: &str, mesh: &Mesh, material: u32, e: Option<Spectrum>) {
    x.push_str("    <shape type=\"ply\">\n");
    let _ = writeln!(
        x,
        "        <string name=\"filename\" value=\"{}\"/>",
        escape(file)
    );
    if mesh.normals.is_empty() {
        // Without this, Mitsuba (and the loader) would smooth the mesh.
        x.push_str("        <boolean name=\"face_normals\" value=\"true\"/>\n");
    }
    shape_tail(x, material, e);
}

/// A shape's material reference and area emitter, and its closing tag.
fn shape_tail(x: &mut String, material: u32, emission: Option<Spectrum>) {
    let _ = writeln!(x, "        <ref id=\"material-{material}\"/>");
    if let Some(l) = emission {
        x.push_str("        <emitter type=\"area\">\n");
        rgb(x, 3, "radiance", l);
        x.push_str("        </emitter>\n");
    }
    x.push_str("    </shape>\n");
}
