//! A scene written out as a Mitsuba 3 XML file (`lightlab export`), so that a built-in
//! scene can be rendered by Mitsuba 3 — the oracle the XML loader is checked against —
//! and compared with lightlab on the same file.
//!
//! What is written is what the loader (`super::xml`) reads back into the same scene: the
//! sensor with its `to_world` matrix, field of view, film, filter and sampler; every
//! material that a shape uses (`diffuse`, `phong`, `conductor`, `roughconductor`,
//! `plastic`, `roughplastic`, inside `twosided` where the scene has it); rectangles,
//! spheres and disks as Mitsuba's shapes with a `to_world` (or a centre and radius);
//! meshes as PLY files beside the XML file; area, point, constant and environment-map
//! emitters (the map as a PFM file beside it). Numbers are written with the shortest
//! decimal that reads back to the same `f32`, so files and meshes keep their values
//! exactly; shapes given by a transform come back within a few ulps.
//!
//! Numbers below 1e-9 in magnitude (rounding residues such as cos 90° in a rotation) are
//! written as 0: the loader refuses such magnitudes.
//!
//! Not representable, and refused with a message: textures (material or emission),
//! two-sided emitters, meshes whose triangles differ in material or emission, and render
//! settings a Mitsuba file cannot hold. Written with a note (in the file and in
//! [`Exported::notes`]): `phong`, Mitsuba 0.6's plugin, and a box filter of a radius other
//! than 0.5, which lightlab reads and Mitsuba 3 refuses ([`UNREADABLE`]); a sample count that
//! Mitsuba 3's sampler rounds up; a polygon light, written as the mesh of its
//! triangulation (read back, one light per triangle: the same emission, sampled
//! triangle by triangle). Mitsuba's `ldsampler`, the name under which lightlab's Sobol
//! sampler is written, is biased where the integrand is steep in both the film position
//! and the light sample (BENCHMARKS.md, session 20): compare against Mitsuba's
//! `independent` sampler there.

mod materials;
mod ply;
mod sensor;
mod shapes;
mod text;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::Mat4;

use super::Scene;
use crate::bsdf::Material;
use crate::geometry::{NO_LIGHT, Primitive, Shape};
use crate::image::io::pfm_bytes;
use crate::image::output::write_all_atomically;
use crate::light::Light;
use crate::light::environment::EnvironmentSource;
use crate::math::Spectrum;
use materials::bsdf;
use sensor::{integrator, sensor};
use shapes::{mesh_shape, shape};
use text::{comment, escape, float, matrix, point, rgb};

/// How a note that Mitsuba 3 will refuse the file begins.
pub const UNREADABLE: &str = "Mitsuba 3 will not read this file: ";

/// What an export wrote, and what a reader should know about it.
#[derive(Debug)]
pub struct Exported {
    /// Every file written: the meshes and the environment map first, the XML file last.
    pub files: Vec<PathBuf>,
    /// Things Mitsuba 3 will not read as lightlab does (each also a comment in the file).
    pub notes: Vec<String>,
}

/// Writes `scene` as the Mitsuba 3 XML file `xml` (its meshes and environment map as
/// files beside it, named after it). Nothing is written when the scene cannot be
/// expressed; the files are written to temporaries first and renamed into place, the
/// XML file last, only when all of them are whole ([`write_all_atomically`]).
pub fn export(scene: &Scene, xml: &Path) -> Result<Exported, String> {
    check_output(xml)?;
    let stem = xml
        .file_stem()
        .and_then(|s| s.to_str())
        .ok_or_else(|| format!("{}: not a file name", xml.display()))?
        .to_owned();
    let dir = xml.parent().unwrap_or(Path::new("")).to_path_buf();
    let plan = Plan::new(scene, &stem)?;
    let mut files: Vec<(PathBuf, &[u8])> = plan
        .side_files
        .iter()
        .map(|(name, bytes)| (dir.join(name), bytes.as_slice()))
        .collect();
    files.push((xml.to_path_buf(), plan.xml.as_bytes()));
    write_all_atomically(&files)?;
    Ok(Exported {
        files: files.into_iter().map(|(path, _)| path).collect(),
        notes: plan.notes,
    })
}

/// Checks, before any work, that `xml` names a `.xml` file in a folder that exists.
pub fn check_output(xml: &Path) -> Result<(), String> {
    let ext = xml.extension().and_then(|e| e.to_str());
    if !ext.is_some_and(|e| e.eq_ignore_ascii_case("xml")) {
        return Err(format!(
            "{}: the export is a Mitsuba XML file: give a .xml path",
            xml.display()
        ));
    }
    match xml.parent().filter(|p| !p.as_os_str().is_empty()) {
        Some(folder) if !folder.is_dir() => Err(format!(
            "{}: folder {} does not exist",
            xml.display(),
            folder.display()
        )),
        _ => Ok(()),
    }
}

/// The XML text and the side files (name beside the XML file, contents), made before
/// anything is written.
struct Plan {
    xml: String,
    side_files: Vec<(String, Vec<u8>)>,
    notes: Vec<String>,
}

impl Plan {
    fn new(scene: &Scene, stem: &str) -> Result<Plan, String> {
        let prims = scene.geometry.primitives_as_added();
        refuse_unrepresentable(scene, &prims)?;
        let mut plan = Plan {
            xml: String::new(),
            side_files: Vec::new(),
            notes: Vec::new(),
        };
        let used = used_materials(scene, &prims);
        if used
            .iter()
            .any(|&m| matches!(scene.materials[m], Material::Phong(_)))
        {
            plan.notes.push(format!(
                "{UNREADABLE}`phong` is Mitsuba 0.6's plugin (lightlab reads it)"
            ));
        }
        if scene.lights.iter().any(|l| matches!(l, Light::Polygon(_))) {
            plan.notes.push(
                "each polygon light is written as the mesh of its triangulation: read back, \
                 one light per triangle (the same emission, sampled triangle by triangle)"
                    .into(),
            );
        }
        let x = &mut plan.xml;
        x.push_str("<scene version=\"3.0.0\">\n");
        integrator(x, &scene.requested)?;
        sensor(x, scene, &mut plan.notes)?;
        for &m in &used {
            bsdf(
                x,
                &format!("material-{m}"),
                &scene.materials[m],
                scene.is_two_sided(m as u32),
            );
        }
        let mut meshes = 0;
        for item in shapes_in_order(scene, &prims)? {
            match item {
                Item::Analytic(prim, emission) => shape(x, &prim, emission),
                Item::Mesh(index, material, emission) => {
                    let mesh = &scene.geometry.meshes[index];
                    let file = format!("{stem}_mesh{meshes}.ply");
                    mesh_shape(x, &file, mesh, material, emission);
                    plan.side_files.push((file, ply::ply_bytes(mesh)));
                    meshes += 1;
                }
            }
        }
        for light in &scene.lights {
            match light {
                Light::Point(p) => {
                    x.push_str("    <emitter type=\"point\">\n");
                    point(x, 2, "position", p.position);
                    rgb(x, 2, "intensity", p.intensity);
                    x.push_str("    </emitter>\n");
                }
                Light::Environment(env) => match env.source() {
                    EnvironmentSource::Constant(l) => {
                        x.push_str("    <emitter type=\"constant\">\n");
                        rgb(x, 2, "radiance", l);
                        x.push_str("    </emitter>\n");
                    }
                    EnvironmentSource::Map {
                        image,
                        scale,
                        to_world,
                    } => {
                        let file = format!("{stem}_envmap.pfm");
                        x.push_str("    <emitter type=\"envmap\">\n");
                        let _ = writeln!(
                            x,
                            "        <string name=\"filename\" value=\"{}\"/>",
                            escape(&file)
                        );
                        float(x, 2, "scale", scale);
                        matrix(x, 2, &Mat4::from_mat3(to_world));
                        x.push_str("    </emitter>\n");
                        plan.side_files.push((
                            file,
                            pfm_bytes(image.width as u32, image.height as u32, &image.texels),
                        ));
                    }
                },
                Light::Area(_) | Light::Polygon(_) => {}
            }
        }
        x.push_str("</scene>\n");
        let mut head = String::from("<?xml version=\"1.0\" encoding=\"utf-8\"?>\n");
        let _ = writeln!(
            head,
            "<!-- {} as written by lightlab export. -->",
            comment(&scene.name)
        );
        for note in &plan.notes {
            let _ = writeln!(head, "<!-- Note: {}. -->", comment(note));
        }
        plan.xml.insert_str(0, &head);
        Ok(plan)
    }
}

/// Refuses what a Mitsuba 3 file (as lightlab reads it) cannot say, naming the shape (by
/// where it is) or the material (`material-N`, the id the export would give it).
fn refuse_unrepresentable(scene: &Scene, prims: &[Primitive]) -> Result<(), String> {
    if let Some(m) = used_materials(scene, prims)
        .into_iter()
        .find(|&m| scene.texture(m as u32).is_some())
    {
        return Err(format!(
            "material-{m} is textured, and textures cannot be exported (their bitmaps are \
             not kept)"
        ));
    }
    for p in prims {
        let (textured, two_sided) = match scene.lights.get(p.light as usize) {
            Some(Light::Area(a)) => (a.texture.is_some(), a.two_sided),
            Some(Light::Polygon(l)) => (false, l.two_sided),
            _ => (false, false),
        };
        let shape = describe(scene, p);
        if textured {
            return Err(format!(
                "{shape} is a textured emitter, and textures cannot be exported (their \
                 bitmaps are not kept)"
            ));
        }
        if two_sided {
            return Err(format!(
                "{shape} emits from both sides, which has no Mitsuba 3 form (area \
                 emitters emit from the front only)"
            ));
        }
    }
    Ok(())
}

/// A primitive's shape, named by where it is.
fn describe(scene: &Scene, p: &Primitive) -> String {
    match &p.shape {
        Shape::Sphere(s) => format!("the sphere centred at {}", s.center),
        Shape::Rectangle(r) => format!("the rectangle with corner {}", r.o),
        Shape::Disk(d) => format!("the disk centred at {}", d.center),
        Shape::Triangle(t) => match scene.lights.get(p.light as usize) {
            Some(Light::Polygon(_)) => format!("the polygon light with a vertex at {}", t.p0),
            _ => format!("the mesh with a vertex at {}", t.p0),
        },
    }
}

/// The materials that some primitive uses, in index order.
fn used_materials(scene: &Scene, prims: &[Primitive]) -> Vec<usize> {
    let mut used = vec![false; scene.materials.len()];
    for p in prims {
        used[p.material as usize] = true;
    }
    (0..used.len()).filter(|&m| used[m]).collect()
}

/// A shape to write: an analytic one with its emitted radiance, or a whole mesh (its
/// index) with the material and radiance all its triangles share.
enum Item {
    Analytic(Primitive, Option<Spectrum>),
    Mesh(usize, u32, Option<Spectrum>),
}

/// The shapes in the order they were added (a mesh where its first triangle was).
fn shapes_in_order(scene: &Scene, prims: &[Primitive]) -> Result<Vec<Item>, String> {
    let radiance = |p: &Primitive| match scene.lights.get(p.light as usize) {
        _ if p.light == NO_LIGHT => None,
        Some(Light::Area(a)) => Some(a.radiance),
        Some(Light::Polygon(l)) => Some(l.radiance),
        _ => None,
    };
    let mut seen: Vec<Option<(u32, Option<Spectrum>)>> = vec![None; scene.geometry.meshes.len()];
    let mut items = Vec::new();
    for p in prims {
        let Shape::Triangle(tri) = &p.shape else {
            items.push(Item::Analytic(*p, radiance(p)));
            continue;
        };
        let this = (p.material, radiance(p));
        match seen[tri.mesh as usize] {
            None => {
                seen[tri.mesh as usize] = Some(this);
                items.push(Item::Mesh(tri.mesh as usize, this.0, this.1));
            }
            Some(first) if first == this => {}
            Some((material, emission)) => {
                let what = if material != this.0 {
                    format!("materials (material-{material} and material-{})", this.0)
                } else {
                    format!("emission ({emission:?} and {:?})", this.1)
                };
                return Err(format!(
                    "{} has triangles of different {what}, which one Mitsuba shape cannot hold",
                    describe(scene, p)
                ));
            }
        }
    }
    Ok(items)
}
