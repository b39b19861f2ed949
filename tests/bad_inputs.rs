//! Hostile inputs through the built binary: every row of `tests/bad_inputs/cases.tsv`
//! (written by `make_cases.py`, plus the fuzzer's findings) runs `lightlab` and checks
//! its exit code, the place its error names (file:line:col or a flag), the words of the
//! message, and that it neither panics, hangs nor leaves an output file behind; a case
//! that succeeds must write the file its `-o` names, and its images must read back whole
//! and finite. Large and binary inputs are generated here into `$GEN`.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use flate2::Compression;
use flate2::write::ZlibEncoder;
use lightlab::image::Film;
use lightlab::image::io::{read_image, write_film, write_film_with_metadata};
use lightlab::math::Spectrum;

/// Longest a case may run.
const LIMIT: Duration = Duration::from_secs(60);

/// A small film with two samples per pixel (or all zero).
fn film(side: u32, zero: bool) -> Film {
    let mut film = Film::new(side, side);
    for (i, p) in film.pixels.iter_mut().enumerate() {
        for k in 0..2 {
            let v = if zero { 0.0 } else { 0.1 + (i + k) as f32 };
            p.add(Spectrum::splat(v));
        }
    }
    film
}

/// `exr` with its data and display windows replaced by [0, w−1] × [0, h−1].
fn with_window(exr: &[u8], w: i32, h: i32) -> Vec<u8> {
    let mut out = exr.to_vec();
    for name in [&b"dataWindow\0box2i\0"[..], &b"displayWindow\0box2i\0"[..]] {
        let Some(at) = out.windows(name.len()).position(|s| s == name) else {
            panic!("no window attribute")
        };
        let at = at + name.len() + 4;
        for (k, v) in [0, 0, w - 1, h - 1].iter().enumerate() {
            out[at + 4 * k..at + 4 * k + 4].copy_from_slice(&v.to_le_bytes());
        }
    }
    out
}

/// A PNG declaring `w` × `h` (8-bit RGB) with an empty IDAT: chunks with their CRCs.
fn png_header(w: u32, h: u32) -> Vec<u8> {
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut ihdr = w.to_be_bytes().to_vec();
    ihdr.extend(h.to_be_bytes());
    ihdr.extend([8, 2, 0, 0, 0]);
    for (tag, data) in [
        (b"IHDR", ihdr),
        (b"IDAT", Vec::new()),
        (b"IEND", Vec::new()),
    ] {
        let mut chunk = tag.to_vec();
        chunk.extend(&data);
        let mut crc = flate2::Crc::new();
        crc.update(&chunk);
        out.extend((data.len() as u32).to_be_bytes());
        out.extend(chunk);
        out.extend(crc.sum().to_be_bytes());
    }
    out
}

/// A serialized mesh (version 4) whose stream declares `nv` vertices and `nt` triangles.
fn serialized(nv: u64, nt: u64) -> Vec<u8> {
    let mut body = 0u32.to_le_bytes().to_vec();
    body.extend(b"m\0");
    body.extend(nv.to_le_bytes());
    body.extend(nt.to_le_bytes());
    body.extend([0u8; 64]);
    let mut z = ZlibEncoder::new(Vec::new(), Compression::default());
    z.write_all(&body).expect("in memory");
    let mut out = vec![0x1C, 0x04, 4, 0];
    out.extend(z.finish().expect("in memory"));
    out
}

/// Writes the generated inputs into `dir`.
fn generate(dir: &Path, scenes: &Path) {
    // Parts as `render` writes them: scene hash, settings and sample blocks in the header.
    let part = |name: &str, size: u32, hash: &str, settings: &str, samples: &str| {
        let meta: Vec<(String, String)> = [
            ("lightlab.scene", "builtin:test"),
            ("lightlab.scene_hash", hash),
            ("lightlab.settings", settings),
            ("lightlab.samples", samples),
        ]
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect();
        write_film_with_metadata(&film(size, false), &dir.join(name), 0.0, &meta).expect("write")
    };
    let (h, s) = ("00000000000000aa", "--estimator light");
    part("ok4.exr", 4, h, s, "0:0..4");
    part("ok8.exr", 8, h, s, "0:4..8");
    part("pass2.exr", 4, h, s, "0:4..8");
    part("overlap.exr", 4, h, s, "0:2..6");
    part("other-seed.exr", 4, h, s, "1:0..4");
    part("other-scene.exr", 4, "00000000000000bb", s, "0:4..8");
    part("other-settings.exr", 4, h, "--estimator mis", "0:4..8");
    part("bad-blocks.exr", 4, h, s, "0:4..eight");
    part("self-overlap.exr", 4, h, s, "0:4..8 0:6..7");
    write_film(&film(4, false), &dir.join("no-provenance.exr"), 0.0).expect("write");
    write_film(&film(4, true), &dir.join("zero4.exr"), 0.0).expect("write");
    write_film(&film(4, false), &dir.join("ok4.pfm"), 0.0).expect("write");
    let ok = std::fs::read(dir.join("ok4.exr")).expect("read");
    let binary_ply = |n: u32| {
        let mut d = format!(
            "ply\nformat binary_little_endian 1.0\nelement vertex {n}\nproperty float x\n\
             property float y\nproperty float z\nend_header\n"
        )
        .into_bytes();
        d.extend([0u8; 30]);
        d
    };
    let original = std::fs::read(scenes.join("meshes/shapes.serialized")).expect("read");
    let files: Vec<(&str, Vec<u8>)> = vec![
        (
            "huge-window.exr",
            with_window(&ok, 1_000_000_000, 1_000_000_000),
        ),
        ("big-window.exr", with_window(&ok, 9999, 9999)),
        ("wide-window.exr", with_window(&ok, 1_000_000_000, 1)),
        ("truncated.exr", ok[..ok.len() / 2].to_vec()),
        ("huge.png", png_header(100_000, 100_000)),
        ("big.png", png_header(60_000, 60_000)),
        (
            "huge.hdr",
            b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1000000000 +X 1000000000\n\0\0\0\0".to_vec(),
        ),
        (
            "huge.pfm",
            b"PF\n1000000000 1000000000\n-1.0\n\0\0\0\0".to_vec(),
        ),
        ("short.pfm", b"PF\n4 4\n-1.0\n\0\0\0\0\0\0\0\0\0\0".to_vec()),
        ("zero-size.pfm", b"PF\n0 4\n-1.0\n".to_vec()),
        ("zero-scale.pfm", b"Pf\n1 1\n0\n\0\0\0\0".to_vec()),
        ("huge.serialized", serialized(1 << 40, 1 << 40)),
        ("truncated.serialized", original[..24].to_vec()),
        ("huge-binary.ply", binary_ply(4_000_000_000)),
        ("truncated-binary.ply", binary_ply(3)),
        // A scene whose path is beyond Latin-1: its EXR header holds the path.
        (
            "日本.xml",
            std::fs::read(scenes.join("cbox_diffuse.xml")).expect("read"),
        ),
    ];
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes).expect("write");
    }
}

/// One row of the manifest.
struct Case {
    name: String,
    args: Vec<String>,
    code: i32,
    place: Option<String>,
    words: Vec<String>,
}

fn parse(manifest: &str, inputs: &Path, generated: &Path, out: &Path) -> Vec<Case> {
    let dirs = |s: &str| {
        s.replace("$IN", &inputs.display().to_string())
            .replace("$GEN", &generated.display().to_string())
            .replace("$OUT", &out.display().to_string())
    };
    let field = |s: &str| (s != "-").then(|| s.to_owned());
    manifest
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|line| {
            let f: Vec<&str> = line.split('\t').collect();
            assert!(f.len() >= 5, "bad manifest row: {line}");
            Case {
                name: f[0].to_owned(),
                args: f[1].split(' ').map(dirs).collect(),
                code: f[2]
                    .parse()
                    .unwrap_or_else(|_| panic!("bad exit code: {line}")),
                place: field(f[3]),
                words: field(f[4])
                    .map_or(Vec::new(), |w| w.split(';').map(str::to_owned).collect()),
            }
        })
        .collect()
}

/// Runs one case; returns what is wrong with its outcome, if anything.
fn check(case: &Case, out: &Path) -> Option<String> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_lightlab"))
        .args(&case.args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start lightlab");
    let start = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > LIMIT {
            let _ = child.kill();
            return Some(format!("still running after {LIMIT:?}"));
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let output = child.wait_with_output().expect("output");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    let mut wrong = Vec::new();
    if output.status.code() != Some(case.code) {
        wrong.push(format!(
            "exit {:?}, not {}",
            output.status.code(),
            case.code
        ));
    }
    if text.contains("panicked") || text.contains("RUST_BACKTRACE") {
        wrong.push("panicked".into());
    }
    for w in case.place.iter().chain(&case.words) {
        if !text.contains(w.as_str()) {
            wrong.push(format!("lacks \"{w}\""));
        }
    }
    // A failing run writes nothing, not even a temporary file.
    let left: Vec<_> = std::fs::read_dir(out).expect("out dir").flatten().collect();
    if case.code != 0 && !left.is_empty() {
        wrong.push(format!("left {:?}", left[0].file_name()));
    }
    if case.code == 0 {
        // The image it was asked for must be there (`-o PATH`), and every image read back.
        let asked = case
            .args
            .iter()
            .position(|a| a == "-o")
            .and_then(|i| case.args.get(i + 1));
        if let Some(path) = asked.filter(|p| !Path::new(p).exists()) {
            wrong.push(format!("wrote no {path}"));
        }
        wrong.extend(left.iter().filter_map(|f| unreadable(case, &f.path())));
    }
    for f in left {
        let _ = std::fs::remove_file(f.path());
    }
    (!wrong.is_empty()).then(|| format!("{}: {}\n{text}", case.name, wrong.join(", ")))
}

/// What is wrong with an image a successful run wrote, if anything: it must read back
/// whole with every value finite (its variances too), and an EXR of `render` given a
/// scene file must name the scene as it was given (`lightlab.scene`, a path beyond
/// Latin-1 included).
fn unreadable(case: &Case, path: &Path) -> Option<String> {
    let name = path.file_name()?.to_string_lossy().into_owned();
    let image = match read_image(path) {
        Ok(image) => image,
        Err(e) => return Some(format!("wrote {name}, which does not read back: {e}")),
    };
    let pixels = image.width as usize * image.height as usize;
    let variance = image.variance.as_deref().unwrap_or_default();
    let mut values = image.rgb.iter().chain(variance);
    if image.rgb.len() != pixels || values.any(|c| !c.is_finite()) {
        return Some(format!("wrote {name} with missing or non-finite values"));
    }
    let exr = path.extension().is_some_and(|e| e == "exr");
    let scene = case
        .args
        .get(1)
        .filter(|a| !a.starts_with('-') && !a.starts_with("builtin:"));
    if exr && case.args.first().is_some_and(|a| a == "render") {
        let scene = scene?;
        let named = |(k, v): &(String, String)| k == "lightlab.scene" && v == scene;
        if !image.metadata.iter().any(named) {
            return Some(format!("{name} does not name its scene {scene}"));
        }
    }
    None
}

#[test]
fn bad_inputs_exit_2_with_the_place_named() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests");
    let inputs = root.join("bad_inputs");
    let scratch = std::env::temp_dir().join(format!("lightlab-bad-{}", std::process::id()));
    let (generated, out) = (scratch.join("gen"), scratch.join("out"));
    std::fs::create_dir_all(&generated).expect("mkdir");
    std::fs::create_dir_all(&out).expect("mkdir");
    generate(&generated, &root.join("scenes"));
    let manifest = std::fs::read_to_string(inputs.join("cases.tsv")).expect("manifest");
    let cases = parse(&manifest, &inputs, &generated, &out);
    assert!(cases.len() >= 150, "only {} cases", cases.len());
    let failures: Vec<String> = cases.iter().filter_map(|c| check(c, &out)).collect();
    let _ = std::fs::remove_dir_all(&scratch);
    assert!(
        failures.is_empty(),
        "{} of {} cases failed:\n\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}
