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
//! Not representable, and refused with a message: textures (material or emission),
//! two-sided emitters, and render settings a Mitsuba file cannot hold. `phong` is
//! Mitsuba 0.6's plugin: lightlab reads it, Mitsuba 3 does not (the export says so).

mod materials;
mod ply;
mod shapes;
mod text;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::Mat4;

use super::Scene;
use crate::bsdf::Material;
use crate::geometry::{NO_LIGHT, Primitive, Shape};
use crate::image::Filter;
use crate::image::output::write_atomically;
use crate::light::Light;
use crate::light::environment::EnvironmentSource;
use crate::math::Spectrum;
use crate::sampling::SamplerKind;
use crate::settings::{MisHeuristic, RenderPatch};
use materials::bsdf;
use shapes::{mesh_shape, pfm_bytes, shape};
use text::{comment, float, integer, matrix, point, rgb};

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
/// expressed; each file is written whole or not at all.
pub fn export(scene: &Scene, xml: &Path) -> Result<Exported, String> {
    let stem = xml
        .file_stem()
        .and_then(|s| s.to_str())
        .ok_or_else(|| format!("{}: not a file name", xml.display()))?
        .to_owned();
    let dir = xml.parent().unwrap_or(Path::new("")).to_path_buf();
    let plan = Plan::new(scene, &stem)?;
    let mut files = Vec::new();
    for (name, bytes) in &plan.side_files {
        let path = dir.join(name);
        write_atomically(&path, |tmp| {
            std::fs::write(tmp, bytes).map_err(|e| e.to_string())
        })
        .map_err(|e| format!("{}: {e}", path.display()))?;
        files.push(path);
    }
    write_atomically(xml, |tmp| {
        std::fs::write(tmp, &plan.xml).map_err(|e| e.to_string())
    })
    .map_err(|e| format!("{}: {e}", xml.display()))?;
    files.push(xml.to_path_buf());
    Ok(Exported {
        files,
        notes: plan.notes,
    })
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
        refuse_unrepresentable(scene)?;
        let mut plan = Plan {
            xml: String::new(),
            side_files: Vec::new(),
            notes: Vec::new(),
        };
        let prims = scene.geometry.primitives_as_added();
        let used = used_materials(scene, &prims);
        if used
            .iter()
            .any(|&m| matches!(scene.materials[m], Material::Phong(_)))
        {
            plan.notes.push(
                "`phong` is Mitsuba 0.6's plugin: lightlab reads it, Mitsuba 3 does not".into(),
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
                        let _ = writeln!(x, "        <string name=\"filename\" value=\"{file}\"/>");
                        float(x, 2, "scale", scale);
                        matrix(x, 2, &Mat4::from_mat3(to_world));
                        x.push_str("    </emitter>\n");
                        plan.side_files.push((file, pfm_bytes(image)));
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

/// Refuses what a Mitsuba 3 file (as lightlab reads it) cannot say.
fn refuse_unrepresentable(scene: &Scene) -> Result<(), String> {
    if scene.textures.iter().any(Option::is_some) {
        return Err("textured materials cannot be exported (their bitmaps are not kept)".into());
    }
    for light in &scene.lights {
        let (textured, two_sided) = match light {
            Light::Area(a) => (a.texture.is_some(), a.two_sided),
            Light::Polygon(p) => (false, p.two_sided),
            _ => (false, false),
        };
        if textured {
            return Err("textured emitters cannot be exported (their bitmaps are not kept)".into());
        }
        if two_sided {
            return Err(
                "a two-sided emitter has no Mitsuba 3 form (area emitters emit from the \
                        front only)"
                    .into(),
            );
        }
    }
    Ok(())
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
            Some(_) => {
                return Err(format!(
                    "mesh {} has triangles of different materials or emission, which one \
                     Mitsuba shape cannot hold",
                    tri.mesh
                ));
            }
        }
    }
    Ok(items)
}

/// `<integrator type="direct">` with the sample counts the scene asks for.
fn integrator(x: &mut String, requested: &RenderPatch) -> Result<(), String> {
    let rest = RenderPatch {
        sampler: None,
        seed: None,
        mis: None,
        light_samples: None,
        bsdf_samples: None,
        ..requested.clone()
    };
    if rest != RenderPatch::default() {
        return Err(format!(
            "the scene asks for render settings a Mitsuba file cannot hold: {rest}"
        ));
    }
    if requested.mis.is_some_and(|h| h != MisHeuristic::Power) {
        return Err(format!(
            "the scene asks for --mis {}; Mitsuba's `direct` integrator has the power heuristic \
             only",
            requested.mis.map_or("", |h| h.name())
        ));
    }
    let counts = [
        ("emitter_samples", requested.light_samples),
        ("bsdf_samples", requested.bsdf_samples),
    ];
    if counts.iter().all(|(_, n)| n.is_none()) {
        x.push_str("    <integrator type=\"direct\"/>\n");
        return Ok(());
    }
    x.push_str("    <integrator type=\"direct\">\n");
    for (name, n) in counts {
        if let Some(n) = n {
            integer(x, 2, name, n);
        }
    }
    x.push_str("    </integrator>\n");
    Ok(())
}

/// The perspective sensor with its sampler and film; what Mitsuba 3 would read
/// differently goes to `notes`.
fn sensor(x: &mut String, scene: &Scene, notes: &mut Vec<String>) -> Result<(), String> {
    let camera = &scene.camera;
    x.push_str("    <sensor type=\"perspective\">\n");
    float(x, 2, "fov", camera.fov_x_degrees());
    let _ = writeln!(x, "        <string name=\"fov_axis\" value=\"x\"/>");
    float(x, 2, "near_clip", camera.near_clip);
    matrix(x, 2, &Mat4::from(camera.to_world()));
    // Unset, lightlab's default sampler (Sobol) renders a built-in scene; `ldsampler` is
    // the name the loader reads as Sobol and Mitsuba's own low-discrepancy sampler.
    let sampler = match scene.requested.sampler.unwrap_or(SamplerKind::Sobol) {
        SamplerKind::Independent => "independent",
        SamplerKind::Stratified => "stratified",
        SamplerKind::Sobol => "ldsampler",
    };
    let _ = writeln!(x, "        <sampler type=\"{sampler}\">");
    integer(x, 3, "sample_count", scene.spp);
    if let Some(seed) = scene.requested.seed {
        let seed = u32::try_from(seed).map_err(|_| format!("seed {seed} is above 2^32 − 1"))?;
        integer(x, 3, "seed", seed);
    }
    x.push_str("        </sampler>\n");
    x.push_str("        <film type=\"hdrfilm\">\n");
    integer(x, 3, "width", camera.width);
    integer(x, 3, "height", camera.height);
    match scene.filter {
        // Mitsuba 3's box is the one-pixel box and takes no radius.
        Filter::Box { radius: 0.5 } => {
            x.push_str("            <rfilter type=\"box\"/>\n");
        }
        Filter::Box { radius } => {
            notes.push(format!(
                "the box filter of radius {radius}: Mitsuba 3's box has radius 0.5 only"
            ));
            rfilter(x, "box", "radius", radius);
        }
        Filter::Tent { radius } => rfilter(x, "tent", "radius", radius),
        Filter::Gaussian { stddev } => rfilter(x, "gaussian", "stddev", stddev),
    }
    x.push_str("        </film>\n");
    x.push_str("    </sensor>\n");
    Ok(())
}

/// `<rfilter type="name">` with one parameter.
fn rfilter(x: &mut String, name: &str, param: &str, value: f32) {
    let _ = writeln!(x, "            <rfilter type=\"{name}\">");
    float(x, 4, param, value);
    x.push_str("            </rfilter>\n");
}
