//! `lightlab export`: every built-in scene, and every test scene that has no texture,
//! written as Mitsuba XML and read back is the same scene — the same camera rays, the
//! same shapes in the same order with the same materials and emission, the same lights —
//! and renders the same image (per-block z-test against the original). Textured scenes
//! and bad output paths are refused with a message and exit code 2.

use std::path::{Path, PathBuf};
use std::process::Command;

use glam::Vec2;
use lightlab::bsdf::Material;
use lightlab::geometry::{NO_LIGHT, Shape};
use lightlab::light::Light;
use lightlab::light::environment::EnvironmentSource;
use lightlab::render::RenderSettings;
use lightlab::sampling::SamplerKind;
use lightlab::scene::builtin::BUILTINS;
use lightlab::scene::export::{UNREADABLE, export};
use lightlab::scene::{Scene, load};

mod common;
use common::blocks::{block_z, blocks, render_small, worst};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lightlab-export-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `scene` written to `dir/name.xml` and loaded back.
fn round_trip(scene: &Scene, dir: &Path, name: &str) -> Scene {
    let xml = dir.join(format!("{name}.xml"));
    let exported = export(scene, &xml).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(exported.files.last(), Some(&xml));
    load(xml.to_str().unwrap()).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn close(a: glam::Vec3, b: glam::Vec3, scale: f32) -> bool {
    (a - b).abs().max_element() <= 1e-5 * scale.max(1.0)
}

/// The radiance a primitive's light emits, if it emits.
fn radiance(scene: &Scene, light: u32) -> Option<glam::Vec3> {
    if light == NO_LIGHT {
        return None;
    }
    match &scene.lights[light as usize] {
        Light::Area(a) => Some(a.radiance),
        Light::Polygon(p) => Some(p.radiance),
        _ => None,
    }
}

/// A material's parameters (a smooth plastic has no roughness to compare).
fn describe(m: &Material) -> String {
    match m {
        Material::Plastic(p) => {
            let q = p.params();
            format!(
                "plastic {:?} {:?} {} {} {}",
                q.diffuse_reflectance, q.specular_reflectance, q.int_ior, q.ext_ior, q.nonlinear
            )
        }
        m => format!("{m:?}"),
    }
}

/// Checks that `back` is `scene` up to float rounding of transformed shapes.
fn assert_same_scene(name: &str, scene: &Scene, back: &Scene, sampler: SamplerKind) {
    let (c, d) = (&scene.camera, &back.camera);
    assert_eq!(
        (c.width, c.height, scene.spp),
        (d.width, d.height, back.spp),
        "{name}"
    );
    for p in [
        Vec2::ZERO,
        Vec2::new(17.5, 3.25),
        Vec2::new(c.width as f32, c.height as f32),
    ] {
        let (r, s) = (c.ray(p), d.ray(p));
        assert!(
            close(r.o, s.o, r.o.abs().max_element()) && close(r.d, s.d, 1.0),
            "{name}: ray {p}"
        );
    }
    assert_eq!(scene.filter, back.filter, "{name}");
    assert_eq!(back.requested.sampler, Some(sampler), "{name}");
    // Every setting the scene asks for (seed, MIS sample counts, sampler) resolves alike.
    assert_eq!(
        RenderSettings::for_scene(scene),
        RenderSettings::for_scene(back),
        "{name}: settings"
    );
    let (a, b) = (
        scene.geometry.primitives_as_added(),
        back.geometry.primitives_as_added(),
    );
    assert_eq!(a.len(), b.len(), "{name}: primitive count");
    let bounds = scene.geometry.bounds();
    let scale = (bounds.max - bounds.min).max_element();
    for (i, (p, q)) in a.iter().zip(&b).enumerate() {
        let what = format!("{name}: primitive {i}");
        let (bp, bq) = (p.shape.bounds(), q.shape.bounds());
        assert!(
            close(bp.min, bq.min, scale) && close(bp.max, bq.max, scale),
            "{what}: bounds"
        );
        match (&p.shape, &q.shape) {
            (Shape::Rectangle(r), Shape::Rectangle(s)) => {
                let same = close(r.o, s.o, scale)
                    && close(r.ea, s.ea, scale)
                    && close(r.eb, s.eb, scale)
                    && close(r.normal, s.normal, 1.0);
                assert!(same, "{what}: {r:?} {s:?}");
            }
            (Shape::Sphere(r), Shape::Sphere(s)) => {
                assert!(close(r.center, s.center, scale), "{what}");
                assert!((r.radius - s.radius).abs() <= 1e-6 * r.radius, "{what}");
                let (a, b) = (r.axes, s.axes);
                let axes = close(a.s, b.s, 1.0) && close(a.t, b.t, 1.0) && close(a.n, b.n, 1.0);
                assert!(axes, "{what}: sphere axes {a:?} {b:?}");
            }
            (Shape::Disk(r), Shape::Disk(s)) => {
                let same = close(r.center, s.center, scale)
                    && close(r.normal, s.normal, 1.0)
                    && (r.radius - s.radius).abs() <= 1e-6 * r.radius
                    && close(r.axes[0], s.axes[0], 1.0)
                    && close(r.axes[1], s.axes[1], 1.0);
                assert!(same, "{what}: {r:?} {s:?}");
            }
            (Shape::Triangle(r), Shape::Triangle(s)) => {
                assert_eq!((r.p0, r.e1, r.e2), (s.p0, s.e1, s.e2), "{what}");
                let normal = |scene: &Scene, t: &lightlab::geometry::shape::Triangle| {
                    let mesh = &scene.geometry.meshes[t.mesh as usize];
                    (
                        mesh.shading_normal(t.index, 0.3, 0.3),
                        mesh.uv(t.index, 0.3, 0.3),
                    )
                };
                let ((n, uv), (m, vu)) = (normal(scene, r), normal(back, s));
                let same_normal = match (n, m) {
                    (Some(n), Some(m)) => close(n, m, 0.1),
                    (n, m) => n == m,
                };
                assert!(
                    same_normal && uv == vu,
                    "{what}: shading normal, uv {n:?} {m:?}"
                );
            }
            (x, y) => panic!("{what}: {x:?} read back as {y:?}"),
        }
        let (m, n) = (p.material, q.material);
        assert_eq!(
            describe(&scene.materials[m as usize]),
            describe(&back.materials[n as usize]),
            "{what}: material"
        );
        assert_eq!(scene.is_two_sided(m), back.is_two_sided(n), "{what}: sides");
        assert_eq!(
            radiance(scene, p.light),
            radiance(back, q.light),
            "{what}: emission"
        );
    }
    let others = |s: &Scene| -> Vec<String> {
        s.lights
            .iter()
            .filter_map(|l| match l {
                Light::Point(p) => Some(format!("point {:?} {:?}", p.position, p.intensity)),
                Light::Environment(e) => Some(match e.source() {
                    EnvironmentSource::Constant(l) => format!("constant {l:?}"),
                    EnvironmentSource::Map {
                        image,
                        scale,
                        to_world,
                    } => format!(
                        "map {}x{} {:?} {scale} {:.5?}",
                        image.width, image.height, image.texels, to_world
                    ),
                }),
                _ => None,
            })
            .collect()
    };
    assert_eq!(
        others(scene),
        others(back),
        "{name}: point and environment lights"
    );
}

/// The two scenes render the same image, block by block, within noise.
fn assert_same_image(name: &str, scene: &Scene, back: &Scene) {
    let (a, b) = (
        render_small(scene, 16, 7, |_| {}),
        render_small(back, 16, 7, |_| {}),
    );
    let z = worst(&block_z(&blocks(&b), &blocks(&a)));
    assert!(z.abs() < 4.0, "{name}: worst block z {z}");
}

#[test]
fn every_builtin_scene_reads_back_as_itself() {
    let dir = scratch("builtins");
    for b in BUILTINS {
        let spec = format!("builtin:{}", b.name);
        let scene = load(&spec).unwrap();
        let back = round_trip(&scene, &dir, b.name);
        assert_same_scene(&spec, &scene, &back, SamplerKind::Sobol);
        assert_same_image(&spec, &scene, &back);
    }
    // A polygon light comes back as the mesh of its triangulation, emitting alike.
    let spec = "builtin:sphere-near-plane?emitters=polygon";
    let scene = load(spec).unwrap();
    let notes = export(&scene, &dir.join("polygon.xml")).unwrap().notes;
    assert!(
        notes.iter().any(|n| n.contains("polygon light")),
        "{notes:?}"
    );
    let back = round_trip(&scene, &dir, "polygon");
    assert_same_image(spec, &scene, &back);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Rotations that leave residues below the loader's smallest number (cos 90° · cos 90°),
/// a small rotated disk and rectangle, a sphere with axes of its own, a box filter of
/// radius 1 and 49 samples under `ldsampler`: read back the same, with notes for what
/// Mitsuba 3 reads otherwise.
const AWKWARD: &str = r#"<scene version="3.0.0">
    <integrator type="direct"><integer name="emitter_samples" value="2"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="50"/>
        <transform name="to_world"><lookat origin="0, 2, 4" target="0, 0.3, 0" up="0, 1, 0"/></transform>
        <sampler type="ldsampler"><integer name="sample_count" value="49"/><integer name="seed" value="5"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="48"/><integer name="height" value="32"/>
            <rfilter type="box"><float name="radius" value="1"/></rfilter>
        </film>
    </sensor>
    <shape type="rectangle">
        <transform name="to_world"><rotate x="1" angle="-90"/><scale value="3"/></transform>
    </shape>
    <shape type="disk">
        <transform name="to_world">
            <scale value="0.01"/><rotate x="1" angle="90"/><rotate y="1" angle="90"/>
            <translate y="0.5"/>
        </transform>
    </shape>
    <shape type="rectangle">
        <transform name="to_world">
            <scale value="0.3"/><rotate x="1" angle="90"/><rotate z="1" angle="90"/>
            <translate x="0.7" y="1.2"/>
        </transform>
        <emitter type="area"><rgb name="radiance" value="6, 5, 4"/></emitter>
    </shape>
    <shape type="sphere">
        <float name="radius" value="0.3"/>
        <transform name="to_world"><rotate y="1" angle="37"/><translate x="-0.6" y="0.3"/></transform>
    </shape>
</scene>
"#;

#[test]
fn awkward_numbers_and_settings_read_back_with_notes() {
    let dir = scratch("awkward");
    let file = dir.join("awkward-in.xml");
    std::fs::write(&file, AWKWARD).unwrap();
    let scene = load(file.to_str().unwrap()).unwrap();
    let exported = export(&scene, &dir.join("awkward.xml")).unwrap();
    let notes = exported.notes.join("\n");
    assert!(
        notes.contains(UNREADABLE) && notes.contains("radius 1"),
        "{notes}"
    );
    assert!(
        notes.contains("ldsampler renders the 49 samples per pixel as 64"),
        "{notes}"
    );
    let back = load(dir.join("awkward.xml").to_str().unwrap()).unwrap();
    assert_same_scene("awkward", &scene, &back, SamplerKind::Sobol);
    assert_same_image("awkward", &scene, &back);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn test_scenes_without_textures_read_back_as_themselves() {
    let dir = scratch("files");
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&scenes)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .collect();
    files.sort();
    let mut refused = Vec::new();
    for file in files {
        let name = file.file_stem().unwrap().to_str().unwrap().to_owned();
        let scene = load(file.to_str().unwrap()).unwrap();
        let xml = dir.join(format!("{name}.xml"));
        match export(&scene, &xml) {
            Ok(_) => {
                let back = load(xml.to_str().unwrap()).unwrap();
                let sampler = scene.requested.sampler.unwrap();
                assert_same_scene(&name, &scene, &back, sampler);
                assert_same_image(&name, &scene, &back);
            }
            Err(e) => {
                assert!(e.contains("textured"), "{name}: {e}");
                assert!(!xml.exists(), "{name}: a refused export wrote its file");
                refused.push(name);
            }
        }
    }
    assert_eq!(refused, ["textured_emitter", "textures_bitmap"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_command_refuses_bad_outputs_and_textured_scenes() {
    let dir = scratch("cli");
    let run = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_lightlab"))
            .arg("export")
            .args(args)
            .output()
            .unwrap()
    };
    let out = run(&[
        "builtin:materials",
        "-o",
        dir.join("m.png").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains(".xml path"));
    let missing = dir.join("no/such/folder/m.xml");
    let out = run(&["builtin:materials", "-o", missing.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("does not exist"));
    let textured = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/textures_bitmap.xml");
    let out = run(&[
        textured.to_str().unwrap(),
        "-o",
        dir.join("t.xml").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    let named = err.contains("textures_bitmap.xml: cannot export: material-0 is textured");
    assert!(named, "{err}");
    // A bare file name: written in the working folder, meshes beside it.
    let out = Command::new(env!("CARGO_BIN_EXE_lightlab"))
        .args(["export", "builtin:sphere-near-plane", "-o", "m.xml"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let listed = String::from_utf8_lossy(&out.stdout);
    assert!(
        listed.contains("m_mesh0.ply") && listed.contains("m.xml"),
        "{listed}"
    );
    assert!(dir.join("m_mesh0.ply").exists() && dir.join("m.xml").exists());
    let read = load(dir.join("m.xml").to_str().unwrap());
    assert!(read.is_ok(), "{:?}", read.err());
    // Size, samples and sampler as a render takes them (height from the aspect).
    let sized = dir.join("sized.xml");
    let sized_arg = sized.to_str().unwrap();
    let flags = ["--width", "96", "--spp", "8", "--sampler", "independent"];
    let out = run(&[&["builtin:sphere-near-plane", "-o", sized_arg][..], &flags].concat());
    assert_eq!(out.status.code(), Some(0));
    let back = load(sized_arg).unwrap();
    assert_eq!(
        (back.camera.width, back.camera.height, back.spp),
        (96, 64, 8)
    );
    assert_eq!(back.requested.sampler, Some(SamplerKind::Independent));
    let out = run(&["builtin:materials", "-o", sized_arg, "--width", "0"]);
    assert_eq!(out.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).unwrap();
}
