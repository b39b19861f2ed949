//! The XML loader on bad input: located errors with the element named, and no panic on
//! malformed XML, mutated scenes or random bytes.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;

use lightlab::scene::SceneError;
use lightlab::scene::xml::{self, LoadOptions, Loaded};

fn load(text: &str) -> Result<Loaded, SceneError> {
    xml::load_str(text, &[])
}

const SENSOR: &str = r#"<sensor type="perspective"><float name="fov" value="40"/>
<film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>"#;

fn scene(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{SENSOR}\n{body}\n</scene>")
}

#[test]
fn errors_name_line_column_and_element() {
    // (scene text, (line, column), words the message must contain)
    let cases: &[(String, (u32, u32), &[&str])] = &[
        (
            scene(r#"<shape type="sphere"><bsdf type="foo"/></shape>"#),
            (4, 22),
            &[
                "<bsdf type=\"foo\">",
                "unknown BSDF type \"foo\"",
                "known: diffuse",
            ],
        ),
        (
            scene(r#"<shape type="teapot"/>"#),
            (4, 1),
            &["unknown shape type \"teapot\""],
        ),
        (
            scene(r#"<shape type="obj"><string name="filename" value="missing.obj"/></shape>"#),
            (4, 19),
            &["missing.obj"],
        ),
        (
            scene(r#"<shape type="sphere"><float name="radius" value="nan"/></shape>"#),
            (4, 22),
            &["not a finite number"],
        ),
        (
            scene(r#"<shape type="sphere"><ref id="nothing"/></shape>"#),
            (4, 22),
            &["no element has id \"nothing\""],
        ),
        (
            scene(r#"<emitter type="envmap"/>"#),
            (4, 1),
            &["missing <string name=\"filename\">"],
        ),
        (
            scene(r#"<emitter type="spot"/>"#),
            (4, 1),
            &["not supported"],
        ),
        (
            scene(r#"<integrator type="path"><integer name="max_depth" value="5"/></integrator>"#),
            (4, 25),
            &["max_depth 5"],
        ),
        (
            scene(r#"<shape type="sphere"><float name="radius" value="$r"/></shape>"#),
            (4, 22),
            &["undefined parameter $r"],
        ),
        (
            scene(r#"<shape type="sphere" id="a"/><shape type="sphere" id="a"/>"#),
            (4, 30),
            &["id \"a\" is used twice"],
        ),
        (
            scene(r#"<include filename="nowhere.xml"/>"#),
            (4, 1),
            &["cannot read scene file", "nowhere.xml"],
        ),
        (
            "<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n</scene>".to_string(),
            (3, 1),
            &["malformed XML"],
        ),
        ("<scene>\n</scene>".to_string(), (1, 1), &["version"]),
    ];
    for (text, (line, col), words) in cases {
        let e = match load(text) {
            Ok(_) => panic!("accepted:\n{text}"),
            Err(e) => e,
        };
        let msg = e.to_string();
        assert_eq!(e.location, Some((*line, *col)), "{msg}");
        for w in *words {
            assert!(msg.contains(w), "\"{msg}\" lacks \"{w}\"");
        }
    }
}

#[test]
fn defaults_defines_and_warnings() {
    let text = format!(
        "<scene version=\"3.0.0\"><default name=\"r\" value=\"2\"/><default name=\"rr\" value=\"9\"/>\n{SENSOR}\n\
         <shape type=\"sphere\"><float name=\"radius\" value=\"$rr\"/><float name=\"bogus\" value=\"1\"/></shape></scene>"
    );
    // An unused property is an error, as in Mitsuba 3, and a warning when lenient.
    let e = load(&text).unwrap_err();
    assert!(e.to_string().contains("bogus"), "{e}");
    assert_eq!(e.location.map(|l| l.0), Some(4));
    let path = std::env::temp_dir().join(format!("lightlab-lenient-{}.xml", std::process::id()));
    std::fs::write(&path, &text).unwrap();
    let lenient = LoadOptions { lenient: true };
    let loaded = xml::load_with_options(&path, &[], lenient).unwrap();
    // `$rr` is substituted before `$r` (longest first).
    let bounds = loaded.scene.geometry.bounds();
    assert!((bounds.max.x - 9.0).abs() < 1e-3, "{bounds:?}");
    assert_eq!(loaded.warnings.len(), 1, "{:?}", loaded.warnings);
    assert!(loaded.warnings[0].contains("bogus") && loaded.warnings[0].contains(":4:"));
    let defines = [("rr".into(), "0.5".into())];
    let defined = xml::load_with_options(&path, &defines, lenient).unwrap();
    assert!((defined.scene.geometry.bounds().max.x - 0.5).abs() < 1e-3);
    let _ = std::fs::remove_file(&path);
}

#[test]
fn deep_nesting_and_huge_films_are_errors() {
    let deep = format!(
        "<scene version=\"3.0.0\">{}{}</scene>",
        "<shape type=\"sphere\">".repeat(100_000),
        "</shape>".repeat(100_000)
    );
    let e = load(&deep).unwrap_err();
    assert!(e.to_string().contains("nested deeper"), "{e}");
    let huge = SENSOR.replace("value=\"8\"", "value=\"30000\"");
    let e = load(&format!("<scene version=\"3.0.0\">{huge}</scene>")).unwrap_err();
    assert!(e.to_string().contains("out of range"), "{e}");
}

#[test]
fn include_cycles_stop_at_the_depth_limit() {
    let dir = std::env::temp_dir().join(format!("lightlab-include-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("self.xml");
    std::fs::write(
        &path,
        "<scene version=\"3.0.0\">\n  <include filename=\"self.xml\"/>\n</scene>",
    )
    .unwrap();
    let e = xml::load(&path, &[]).unwrap_err();
    assert!(e.to_string().contains("deeper than"), "{e}");
    assert_eq!(e.location, Some((2, 3)));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A tiny deterministic generator (SplitMix64) for the fuzz cases.
fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

#[test]
fn garbage_and_mutated_scenes_never_panic() {
    let scenes = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/scenes");
    let originals: Vec<String> = [
        "cbox_diffuse",
        "path_include",
        "legacy_v06",
        "mesh_ply_serialized",
    ]
    .iter()
    .map(|n| std::fs::read_to_string(scenes.join(format!("{n}.xml"))).unwrap())
    .collect();
    let tokens = [
        "<",
        ">",
        "\"",
        "/>",
        "nan",
        "-1",
        "1e40",
        "$x",
        "<ref id=\"q\"/>",
        "0",
        "",
        "&",
        "type=\"box\"",
    ];
    let mut state = 7u64;
    let mut errors = 0;
    for i in 0..600 {
        let text = if i % 5 == 0 {
            // Random printable bytes.
            (0..(splitmix(&mut state) % 300))
                .map(|_| (32 + splitmix(&mut state) % 95) as u8 as char)
                .collect()
        } else {
            let mut t = originals[i % originals.len()].clone();
            for _ in 0..1 + splitmix(&mut state) % 3 {
                let mut at = (splitmix(&mut state) as usize) % t.len();
                while !t.is_char_boundary(at) {
                    at -= 1;
                }
                let cut = ((splitmix(&mut state) % 6) as usize).min(t.len() - at);
                let mut end = at + cut;
                while !t.is_char_boundary(end) {
                    end += 1;
                }
                let tok = tokens[(splitmix(&mut state) as usize) % tokens.len()];
                t.replace_range(at..end, tok);
            }
            t
        };
        // Mutated scenes refer to meshes by relative path: load them from their folder.
        let path = scenes.join(format!(".fuzz-{}-{i}.xml", std::process::id()));
        std::fs::write(&path, &text).unwrap();
        let result = catch_unwind(AssertUnwindSafe(|| xml::load(&path, &[])));
        let _ = std::fs::remove_file(&path);
        match result {
            Ok(Ok(_)) => {}
            Ok(Err(e)) => {
                errors += 1;
                assert!(!e.to_string().is_empty());
            }
            Err(_) => panic!("the loader panicked on:\n{text}"),
        }
    }
    // Most mutations must break the scene; the test fails if they never reach the loader.
    assert!(errors > 200, "only {errors} of 600 inputs were rejected");
}

#[test]
fn mitsuba_06_phong_maps_to_ours_and_bad_microfacet_parameters_are_errors() {
    let text = format!(
        "<scene version=\"0.6.0\">\n{SENSOR}\n<shape type=\"sphere\"><bsdf type=\"phong\">\
         <float name=\"exponent\" value=\"80\"/><rgb name=\"diffuseReflectance\" value=\"0.1 0.2 0.3\"/>\
         </bsdf></shape></scene>"
    );
    let scene = load(&text).expect("phong scene").scene;
    match &scene.materials[0] {
        lightlab::bsdf::Material::Phong(p) => {
            assert_eq!(p.exponent, 80.0);
            assert_eq!(p.kd, glam::Vec3::new(0.1, 0.2, 0.3));
            assert_eq!(p.ks, glam::Vec3::splat(0.2)); // Mitsuba 0.6's default
        }
        other => panic!("phong became {other:?}"),
    }
    let e = load(&scene_text_with(
        "<bsdf type=\"roughplastic\"><string name=\"distribution\" value=\"phong\"/></bsdf>",
    ))
    .unwrap_err();
    assert!(
        e.to_string().contains("unknown microfacet distribution"),
        "{e}"
    );
    let e = load(&scene_text_with(
        "<bsdf type=\"conductor\"><string name=\"material\" value=\"Unobtainium\"/></bsdf>",
    ))
    .unwrap_err();
    assert!(e.to_string().contains("Unobtainium"), "{e}");
}

fn scene_text_with(bsdf: &str) -> String {
    scene(&format!("<shape type=\"sphere\">{bsdf}</shape>"))
}

#[test]
fn legacy_look_at_is_upgraded() {
    let sensor = r#"<sensor type="perspective"><float name="fov" value="40"/>
<transform name="toWorld"><lookAt origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
<film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>"#;
    let loaded = load(&format!("<scene version=\"0.5.0\">{sensor}</scene>")).expect("0.5 scene");
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    // The camera sits at z = 5 looking at the origin.
    let ray = loaded.scene.camera.ray(glam::Vec2::new(4.0, 4.0));
    assert!(
        (ray.d - glam::Vec3::new(0.0, 0.0, -1.0)).length() < 1e-3,
        "{:?}",
        ray.d
    );
}

#[test]
fn definitions_ride_in_the_scene_name() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/scenes/cbox_diffuse.xml");
    let spec = format!("{}?spp=5", path.display());
    assert_eq!(lightlab::scene::load(&spec).expect("scene").spp, 5);
    assert!(lightlab::scene::load(&format!("{}?spp", path.display())).is_err());
}
