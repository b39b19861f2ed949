//! Shapes: Mitsuba's analytic shapes (`sphere`, `rectangle`, `disk`, `cube`) and meshes
//! (`obj`, `ply`, `serialized`) placed by `to_world`, with `flip_normals`, `face_normals`,
//! a BSDF (nested or by ref; default diffuse 0.5) and an optional `area` emitter.

use glam::{Mat3, Mat4, Vec3};

use super::XmlError;
use super::bitmap::load_bitmap;
use super::build::Context;
use super::props::Props;
use super::tree::Element;
use crate::geometry::Mesh;
use crate::geometry::aabb::Aabb;
use crate::geometry::shape::{Disk, Rectangle, Shape, Sphere};
use crate::math::{Frame, Spectrum};
use crate::scene::builder::Emission;
use crate::scene::mesh_io::{self, MAX_MAGNITUDE};

/// Shape types this loader knows.
const SHAPES: [&str; 7] = [
    "obj",
    "ply",
    "serialized",
    "rectangle",
    "sphere",
    "disk",
    "cube",
];

/// Relative tolerance for "uniform scale" and "perpendicular" checks.
const TOLERANCE: f32 = 1e-4;

/// Adds a `<shape>` to the scene.
pub fn add_shape<'a>(ctx: &mut Context<'a>, el: &'a Element) -> Result<(), XmlError> {
    let ty = el.required("type")?;
    let p = Props::new(el)?;
    let mut material = None;
    let mut emission: Option<Emission> = None;
    let mut emitter_el = None;
    for c in p.nested() {
        let target = ctx.resolve(c, &["bsdf", "emitter"])?;
        if target.tag == "bsdf" {
            if material.is_some() {
                return Err(c.error("a shape takes one BSDF"));
            }
            material = Some(ctx.material(target)?);
        } else {
            if emission.is_some() {
                return Err(c.error("a shape takes one emitter"));
            }
            emission = Some(area_emitter(ctx, target)?);
            emitter_el = Some(c);
        }
    }
    let textured = emission.as_ref().is_some_and(|e| e.texture.is_some());
    // Located at the emitter, which a textured radiance implies.
    let refuse_texture = |what: &str| {
        emitter_el.unwrap_or(el).error(format!(
            "a textured radiance can emit from a rectangle, disk or sphere, not from {what} \
             (lightlab samples it by power over the shape's own texture coordinates)"
        ))
    };
    if textured && !matches!(ty, "rectangle" | "disk" | "sphere") {
        return Err(refuse_texture(&format!("a \"{ty}\" shape")));
    }
    let material = match material {
        Some(m) => m,
        None => ctx.default_material(emission.is_some()),
    };
    let to_world = p.transform("to_world")?;
    let flip = p.bool("flip_normals", false)?;
    let linear = Mat3::from_mat4(to_world);
    if linear.determinant().abs() < 1e-12 {
        return Err(p.error_at("to_world", "to_world is singular"));
    }
    // Normals transform by the inverse transpose (as Mitsuba's Transform does).
    let normal_matrix = linear.inverse().transpose();
    match ty {
        "sphere" => {
            let center = p.vec3("center", Vec3::ZERO)?;
            let radius = p.float("radius", 1.0)?;
            let scale = uniform_scale(linear).ok_or_else(|| {
                p.error_at(
                    "to_world",
                    "a sphere's to_world must be a uniform scale, rotation and translation",
                )
            })?;
            if flip {
                return Err(p.error_at("flip_normals", "flip_normals on a sphere is not supported"));
            }
            // Mitsuba 3 turns a mirrored sphere's normals inward (its ray_intersect reports
            // n = −(p − c) under scale x = −1), as for a negative radius.
            if linear.determinant() < 0.0 {
                return Err(p.error_at(
                    "to_world",
                    "a mirroring to_world turns a sphere's normals inward in Mitsuba 3, which \
                     lightlab does not support",
                ));
            }
            // Mitsuba 3 takes a negative radius as a sphere with inward normals; lightlab
            // has no inward-facing sphere, so it refuses the radius rather than render a
            // different scene.
            let r = radius * scale;
            if r.is_nan() || r <= 0.0 {
                return Err(p.error_at(
                    "radius",
                    format!(
                        "radius must be positive, not {radius} (a negative radius means \
                         inward normals in Mitsuba 3, which lightlab does not support)"
                    ),
                ));
            }
            // Texture coordinates are measured in the sphere's own axes: the rotation part
            // of to_world.
            let rotation = linear / scale;
            let sphere = Sphere {
                axes: Frame {
                    s: rotation.x_axis,
                    t: rotation.y_axis,
                    n: rotation.z_axis,
                },
                ..Sphere::new(to_world.transform_point3(center), r)
            };
            let sphere = Shape::Sphere(sphere);
            within_range(&p, "sphere", sphere.bounds())?;
            ctx.builder.shape(sphere, material, emission);
        }
        "rectangle" => {
            let corner = |x: f32, y: f32| to_world.transform_point3(Vec3::new(x, y, 0.0));
            let o = corner(-1.0, -1.0);
            let (mut ea, mut eb) = (corner(1.0, -1.0) - o, corner(-1.0, 1.0) - o);
            // Mitsuba's rectangle: u along local x, v along local y, normal
            // dp/du × dp/dv (so a mirroring to_world turns it), negated by flip_normals
            // (checked against Mitsuba 3.9's ray_intersect).
            let flipped = flip;
            match Rectangle::new(o, ea, eb) {
                Some(r) => {
                    let r = Shape::Rectangle(if flipped { r.flipped() } else { r });
                    within_range(&p, "rectangle", r.bounds())?;
                    ctx.builder.shape(r, material, emission);
                }
                // A sheared rectangle is a parallelogram: two triangles, wound so that
                // their normal is n.
                None => {
                    if textured {
                        return Err(refuse_texture("a sheared rectangle"));
                    }
                    if flipped {
                        std::mem::swap(&mut ea, &mut eb);
                    }
                    let mesh = Mesh {
                        positions: vec![o, o + ea, o + ea + eb, o + eb],
                        indices: vec![[0, 1, 2], [0, 2, 3]],
                        ..Mesh::default()
                    };
                    within_range(&p, "rectangle", mesh_bounds(&mesh))?;
                    ctx.builder.mesh(mesh, material, emission);
                }
            }
        }
        "disk" => {
            let (ex, ey) = (linear * Vec3::X, linear * Vec3::Y);
            let radius = ex.length();
            if (ey.length() - radius).abs() > TOLERANCE * radius
                || ex.dot(ey).abs() > TOLERANCE * radius * radius
            {
                return Err(p.error_at(
                    "to_world",
                    "a disk's to_world must scale x and y equally (no ellipses)",
                ));
            }
            let n = (normal_matrix * Vec3::Z).normalize() * if flip { -1.0 } else { 1.0 };
            // Mitsuba's disk uv: (r/R, φ/2π) with φ measured from local x towards local y.
            let disk = Disk {
                center: to_world.transform_point3(Vec3::ZERO),
                normal: n,
                radius,
                axes: [ex / radius, ey / radius],
            };
            let disk = Shape::Disk(disk);
            within_range(&p, "disk", disk.bounds())?;
            ctx.builder.shape(disk, material, emission);
        }
        "cube" => {
            let mesh = transform_mesh(cube(), to_world, flip);
            within_range(&p, "cube", mesh_bounds(&mesh))?;
            ctx.builder.mesh(mesh, material, emission);
        }
        "obj" | "ply" | "serialized" => {
            let file = p.string("filename", "")?;
            if file.is_empty() {
                return Err(el.error("missing <string name=\"filename\">"));
            }
            let path = el.dir.join(&file);
            let mesh = match ty {
                "obj" => mesh_io::load_obj(&path),
                "ply" => mesh_io::load_ply(&path),
                _ => {
                    let index = p.count("shape_index", 0, u32::MAX)?;
                    mesh_io::load_serialized(&path, index)
                }
            }
            .map_err(|e| p.error_at("filename", e))?;
            let mut mesh = mesh;
            if p.bool("face_normals", false)? {
                mesh.normals.clear();
            } else if mesh.normals.is_empty() {
                // Mitsuba 3 smooths meshes that come without normals.
                mesh_io::compute_vertex_normals(&mut mesh);
            }
            // Mitsuba flips OBJ texture coordinates by default (v → 1 − v), so that
            // v = 0 is the image's top row.
            if ty == "obj" && p.bool("flip_tex_coords", true)? {
                for uv in mesh.uvs.iter_mut() {
                    uv.y = 1.0 - uv.y;
                }
            }
            let mesh = transform_mesh(mesh, to_world, flip);
            within_range(&p, "mesh", mesh_bounds(&mesh))?;
            ctx.builder.mesh(mesh, material, emission);
        }
        other => {
            return Err(el.error(format!(
                "unknown shape type \"{other}\" (known: {})",
                SHAPES.join(", ")
            )));
        }
    }
    ctx.finish(&p)?;
    Ok(())
}

/// `<emitter type="area">` inside a shape.
fn area_emitter<'a>(ctx: &mut Context<'a>, el: &'a Element) -> Result<Emission, XmlError> {
    let ty = el.required("type")?;
    if ty != "area" {
        return Err(el.error(format!(
            "only an area emitter can be nested in a shape, not \"{ty}\""
        )));
    }
    let p = Props::new(el)?;
    // Mitsuba 3 takes any texture as `radiance`; lightlab takes a bitmap (nested or by
    // ref), decoded as for reflectances.
    let emission = match p.texture("radiance") {
        Some(t) => {
            let t = ctx.resolve(t, &["texture"])?;
            Emission::textured(load_bitmap(t, ctx)?)
        }
        None => Emission::new(p.emission("radiance", Spectrum::ONE)?),
    };
    ctx.finish(&p)?;
    Ok(emission)
}

/// Refuses a shape that is not finite or reaches beyond ±[`MAX_MAGNITUDE`] in world
/// space: the range lightlab accepts for a file's numbers, which nested transforms
/// multiply. Products of larger coordinates can overflow f32 (a sphere's intersection
/// then gives NaN distances, which block every ray). Located at `to_world` (at the shape
/// when it has none).
fn within_range(p: &Props, what: &str, bounds: Aabb) -> Result<(), XmlError> {
    let finite = bounds.min.is_finite() && bounds.max.is_finite();
    let reach = bounds.min.abs().max(bounds.max.abs()).max_element();
    if finite && reach <= MAX_MAGNITUDE {
        return Ok(());
    }
    let extent = if finite {
        format!("reaches {reach:e}")
    } else {
        "is not finite".to_string()
    };
    Err(p.error_at(
        "to_world",
        format!(
            "the {what} {extent} in world space; lightlab accepts coordinates within \
             ±{MAX_MAGNITUDE:e} (products of larger ones can overflow f32): scale the scene \
             down"
        ),
    ))
}

/// The box around a mesh's vertices; NaN where a vertex is not finite (the box's own
/// fold would pass over a NaN).
fn mesh_bounds(mesh: &Mesh) -> Aabb {
    if mesh.positions.iter().all(|q| q.is_finite()) {
        Aabb::from_points(&mesh.positions)
    } else {
        Aabb {
            min: Vec3::NAN,
            max: Vec3::NAN,
        }
    }
}

/// The scale s when `m` = s · rotation.
fn uniform_scale(m: Mat3) -> Option<f32> {
    let s = m.x_axis.length();
    let cols = [m.x_axis, m.y_axis, m.z_axis];
    let ok = cols.iter().all(|c| (c.length() - s).abs() <= TOLERANCE * s)
        && cols[0].dot(cols[1]).abs() <= TOLERANCE * s * s
        && cols[0].dot(cols[2]).abs() <= TOLERANCE * s * s
        && cols[1].dot(cols[2]).abs() <= TOLERANCE * s * s;
    ok.then_some(s)
}

/// Applies `to_world` (positions; normals by the inverse transpose) and `flip_normals`
/// (reversed winding and negated normals).
fn transform_mesh(mut mesh: Mesh, to_world: Mat4, flip: bool) -> Mesh {
    let normal_matrix = Mat3::from_mat4(to_world).inverse().transpose();
    for p in mesh.positions.iter_mut() {
        *p = to_world.transform_point3(*p);
    }
    let sign = if flip { -1.0 } else { 1.0 };
    for n in mesh.normals.iter_mut() {
        *n = (normal_matrix * *n).normalize_or_zero() * sign;
    }
    if flip {
        for t in mesh.indices.iter_mut() {
            t.swap(1, 2);
        }
    }
    mesh
}

/// Mitsuba's `cube`: [−1, 1]³ as 12 triangles with outward faces.
fn cube() -> Mesh {
    let mut mesh = Mesh::default();
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let n = Vec3::from_array(std::array::from_fn(|i| if i == axis { sign } else { 0.0 }));
            let u = Vec3::from_array(std::array::from_fn(|i| (i == (axis + 1) % 3) as u8 as f32));
            let v = n.cross(u);
            let base = mesh.positions.len() as u32;
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                mesh.positions.push(n + a * u + b * v);
            }
            // u × v = n, so the winding (0, 1, 2) faces outward.
            mesh.indices.push([base, base + 1, base + 2]);
            mesh.indices.push([base, base + 2, base + 3]);
        }
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_faces_point_outward() {
        let m = cube();
        assert_eq!(m.indices.len(), 12);
        for t in &m.indices {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            let n = (b - a).cross(c - a);
            let centre = (a + b + c) / 3.0;
            assert!(n.dot(centre) > 0.0);
        }
    }

    /// Rectangles and disks have Mitsuba's texture coordinates and normals when flipped
    /// (flip_normals) or mirrored (a negative scale), as Mitsuba 3.9's ray_intersect
    /// reports for the same rays.
    #[test]
    fn rectangles_and_disks_keep_mitsubas_uv_and_normal_when_flipped_or_mirrored() {
        let hit = |shape: &str, children: &str| {
            let text = format!(
                r#"<scene version="3.0.0"><sensor type="perspective"><float name="fov" value="40"/></sensor>
                   <shape type="{shape}">{children}</shape></scene>"#
            );
            let scene = crate::scene::xml::load_str(&text, &[])
                .expect("loads")
                .scene;
            let ray = crate::geometry::Ray::new(glam::Vec3::new(0.5, -0.25, 3.0), -glam::Vec3::Z);
            let hit = scene.geometry.intersect(&ray, f32::INFINITY).expect("hit");
            (scene.geometry.texture_uv(&hit), hit.ng)
        };
        let at = |children: &str| hit("rectangle", children);
        let (uv, ng) = at("");
        assert!((uv - glam::Vec2::new(0.75, 0.375)).length() < 1e-5, "{uv}");
        assert!((ng - glam::Vec3::Z).length() < 1e-5);
        let (uv_flip, ng_flip) = at(r#"<boolean name="flip_normals" value="true"/>"#);
        assert!((uv_flip - uv).length() < 1e-5, "{uv_flip}");
        assert!((ng_flip + ng).length() < 1e-5, "{ng_flip}");
        // Mirrored in x: u runs the other way and the normal, dp/du × dp/dv, turns to
        // −z, as Mitsuba 3.9 reports for the same ray; flip_normals turns it back.
        let mirror = r#"<transform name="to_world"><scale x="-1"/></transform>"#;
        let (uv_m, ng_m) = at(mirror);
        assert!(
            (uv_m - glam::Vec2::new(0.25, 0.375)).length() < 1e-5,
            "{uv_m}"
        );
        assert!((ng_m + glam::Vec3::Z).length() < 1e-5, "{ng_m}");
        let flip = r#"<boolean name="flip_normals" value="true"/>"#;
        let (uv_mf, ng_mf) = at(&format!("{flip}{mirror}"));
        assert!((uv_mf - uv_m).length() < 1e-5 && (ng_mf - glam::Vec3::Z).length() < 1e-5);
        // Disks: uv = (r/R, φ/2π) with φ from local x towards local y (Mitsuba 3.9 gives
        // (0.559017, 0.926208) here, and v = 0.573792 when mirrored in x).
        let (uv_d, _) = hit("disk", "");
        assert!(
            (uv_d - glam::Vec2::new(0.559_017, 0.926_208)).length() < 1e-5,
            "{uv_d}"
        );
        let (uv_dm, ng_dm) = hit("disk", mirror);
        assert!(
            (uv_dm - glam::Vec2::new(0.559_017, 0.573_792)).length() < 1e-5,
            "{uv_dm}"
        );
        assert!((ng_dm - glam::Vec3::Z).length() < 1e-5, "{ng_dm}");
        let (uv_df, ng_df) = hit("disk", flip);
        assert!((uv_df - uv_d).length() < 1e-5 && (ng_df + glam::Vec3::Z).length() < 1e-5);
        // Spheres: uv in the sphere's own axes, which its to_world turns (Mitsuba 3.9:
        // (0.926208, 0.188821) unrotated, (0.692291, 0.282183) rotated).
        let (uv_s, _) = hit("sphere", "");
        assert!(
            (uv_s - glam::Vec2::new(0.926_208, 0.188_821)).length() < 1e-5,
            "{uv_s}"
        );
        let turn = r#"<transform name="to_world"><rotate y="1" angle="70"/><rotate x="1" angle="-40"/></transform>"#;
        let (uv_sr, ng_sr) = hit("sphere", turn);
        assert!(
            (uv_sr - glam::Vec2::new(0.692_291, 0.282_183)).length() < 1e-5,
            "{uv_sr}"
        );
        assert!((ng_sr - glam::Vec3::new(0.5, -0.25, 0.829_156)).length() < 1e-5);
    }
}
