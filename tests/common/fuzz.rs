//! A structure-aware fuzzer of lightlab's loaders, on the stable toolchain: every scene
//! in `tests/scenes/`, its meshes and its images are mutated (byte flips, truncation,
//! element and attribute swaps, deletions and copies, `<ref>` insertions, number
//! extremes such as 1e38, -0, NaN and huge counts) and fed to the library in-process:
//! scene load plus an 8×8 1-spp render, the mesh loaders, the image readers. A case is
//! a finding when it panics, hangs past a time limit, or renders non-finite radiance
//! from a scene the loader accepted. Shared by `examples/fuzz.rs` (long runs) and
//! `tests/fuzz_short.rs` (a short deterministic run).

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::mpsc;
use std::time::Duration;

use lightlab::image::io::read_image;
use lightlab::image::limits::open_image;
use lightlab::render::{self, Control, RenderSettings};
use lightlab::scene::{mesh_io, xml};

/// The kinds of input, by the loader that reads them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A Mitsuba XML scene.
    Scene,
    /// A mesh: OBJ, PLY or serialized (by extension).
    Mesh,
    /// An image: EXR, PNG, JPEG, HDR or PFM (by extension).
    Image,
}

/// An input to mutate: its file (which gives the kind and the extension) and bytes.
pub struct Seed {
    /// Where it came from.
    pub path: PathBuf,
    /// Which loader reads it.
    pub kind: Kind,
    /// Its bytes.
    pub bytes: Vec<u8>,
}

/// What one case did.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    /// Loaded (and rendered) cleanly.
    Accepted,
    /// Refused with an error message.
    Refused,
    /// A panic, with its message: a finding.
    Panic(String),
    /// Still running after the time limit: a finding.
    Hang,
    /// An accepted scene whose render had non-finite samples: a finding.
    NonFinite(u64),
}

impl Outcome {
    /// True for the outcomes that are bugs.
    pub fn is_finding(&self) -> bool {
        matches!(
            self,
            Outcome::Panic(_) | Outcome::Hang | Outcome::NonFinite(_)
        )
    }
}

/// SplitMix64 (Steele et al. 2014): a tiny deterministic generator.
pub struct Rng(pub u64);

impl Rng {
    /// The next 64 random bits.
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in 0..n (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    /// One item of a non-empty slice.
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// Numbers at the edges: float extremes, signed zero, NaN, counts past every type.
const NUMBERS: [&str; 16] = [
    "1e38",
    "-1e38",
    "-0",
    "NaN",
    "inf",
    "-1",
    "0",
    "1e-45",
    "4294967295",
    "4294967296",
    "2147483648",
    "99999999999999999999",
    "1e400",
    "0x10",
    "",
    "1,2,3,4",
];

/// Attribute names a mutation may rename an attribute to.
const ATTRIBUTES: [&str; 4] = ["name", "id", "value", "type"];

/// Element names a mutation may rename a tag to.
const TAGS: [&str; 12] = [
    "float",
    "integer",
    "string",
    "rgb",
    "ref",
    "bsdf",
    "emitter",
    "shape",
    "texture",
    "sensor",
    "film",
    "transform",
];

/// The seeds: every file in `tests/scenes/` (XML), its meshes and its images.
pub fn seeds(root: &Path) -> Vec<Seed> {
    let mut out = Vec::new();
    for dir in ["", "meshes", "textures", "common"] {
        let Ok(entries) = std::fs::read_dir(root.join(dir)) else {
            continue;
        };
        let mut paths: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
        paths.sort();
        for path in paths {
            let ext = extension(&path);
            let kind = match ext.as_str() {
                "xml" => Kind::Scene,
                "obj" | "ply" | "serialized" => Kind::Mesh,
                "exr" | "png" | "jpg" | "hdr" | "pfm" => Kind::Image,
                _ => continue,
            };
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
            if name.is_some_and(|n| n.starts_with('.')) {
                continue;
            }
            if let Ok(bytes) = std::fs::read(&path) {
                out.push(Seed { path, kind, bytes });
            }
        }
    }
    out
}

/// The lower-case extension of `path`.
pub fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// One to three mutations of `seed`: structural on XML that still parses, byte-level
/// otherwise.
pub fn mutate(seed: &Seed, rng: &mut Rng) -> Vec<u8> {
    let mut bytes = seed.bytes.clone();
    for _ in 0..1 + rng.below(3) {
        let structural = match std::str::from_utf8(&bytes) {
            Ok(text) if seed.kind == Kind::Scene && rng.below(5) > 0 => mutate_xml(text, rng),
            Ok(text) if seed.kind != Kind::Image && rng.below(2) == 0 => mutate_numbers(text, rng),
            _ => None,
        };
        bytes = structural.map_or_else(|| mutate_bytes(bytes, rng), String::into_bytes);
    }
    bytes
}

/// Structure-aware XML mutations by roxmltree's source ranges; None if `text` does not
/// parse.
fn mutate_xml(text: &str, rng: &mut Rng) -> Option<String> {
    let doc = roxmltree::Document::parse(text).ok()?;
    let elements: Vec<roxmltree::Node> = doc.descendants().filter(|n| n.is_element()).collect();
    let attrs: Vec<roxmltree::Attribute> = elements.iter().flat_map(|e| e.attributes()).collect();
    let ids: Vec<&str> = elements.iter().filter_map(|e| e.attribute("id")).collect();
    let a = rng.pick(&elements).range();
    let b = rng.pick(&elements).range();
    let splice = |range: std::ops::Range<usize>, with: &str| {
        format!("{}{with}{}", &text[..range.start], &text[range.end..])
    };
    Some(match rng.below(8) {
        // An attribute value to a number extreme (or another attribute's value).
        0 | 1 if !attrs.is_empty() => {
            let at = rng.pick(&attrs).range_value();
            let v = match rng.below(4) {
                0 => rng.pick(&attrs).value().to_owned(),
                _ => rng.pick(&NUMBERS).to_string(),
            };
            splice(at, &v)
        }
        // An attribute deleted, or renamed.
        2 if !attrs.is_empty() => {
            let attr = rng.pick(&attrs);
            let name: &&str = rng.pick(&ATTRIBUTES);
            match rng.below(2) {
                0 => splice(attr.range(), ""),
                _ => splice(attr.range_qname(), name),
            }
        }
        // An element deleted.
        3 if a.start > 0 => splice(a, ""),
        // An element copied next to, or into, another.
        4 => {
            let copy = text[a.clone()].to_owned();
            let at = if rng.below(2) == 0 { b.start } else { b.end };
            format!("{}{copy}{}", &text[..at], &text[at..])
        }
        // Two disjoint elements swapped.
        5 if a.end <= b.start => format!(
            "{}{}{}{}{}",
            &text[..a.start],
            &text[b.clone()],
            &text[a.end..b.start],
            &text[a.clone()],
            &text[b.end..]
        ),
        // A tag renamed (start and end tags alike).
        6 => {
            let e = rng.pick(&elements);
            let old = e.tag_name().name();
            let new = rng.pick(&TAGS);
            let r = e.range();
            let inner = text[r.clone()]
                .replacen(&format!("<{old}"), &format!("<{new}"), 1)
                .replace(&format!("</{old}>"), &format!("</{new}>"));
            splice(r, &inner)
        }
        // A `<ref>` to an existing id inserted into an element (cycles, wrong kinds).
        _ if !ids.is_empty() => {
            let e = rng.pick(&elements);
            let at = e.range().end;
            let close = text[..at].rfind("</").filter(|&p| p > e.range().start)?;
            let r = format!("<ref id=\"{}\"/>", rng.pick(&ids));
            format!("{}{r}{}", &text[..close], &text[close..])
        }
        _ => return None,
    })
}

/// A numeric token of a text format (OBJ, PLY header or body) replaced by an extreme.
fn mutate_numbers(text: &str, rng: &mut Rng) -> Option<String> {
    let tokens: Vec<(usize, &str)> = text
        .split_ascii_whitespace()
        .map(|t| (t.as_ptr() as usize - text.as_ptr() as usize, t))
        .filter(|(_, t)| t.parse::<f64>().is_ok())
        .collect();
    if tokens.is_empty() {
        return None;
    }
    let (at, t) = *rng.pick(&tokens);
    let with = rng.pick(&NUMBERS[..13]);
    Some(format!("{}{with}{}", &text[..at], &text[at + t.len()..]))
}

/// Byte flips, truncation, copied runs and 4-byte number extremes.
fn mutate_bytes(mut bytes: Vec<u8>, rng: &mut Rng) -> Vec<u8> {
    if bytes.is_empty() {
        return vec![rng.next() as u8];
    }
    let at = rng.below(bytes.len());
    match rng.below(5) {
        0 => bytes[at] = rng.next() as u8,
        1 => bytes.truncate(at),
        2 => {
            let end = (at + 1 + rng.below(64)).min(bytes.len());
            let run = bytes[at..end].to_vec();
            let to = rng.below(bytes.len());
            bytes.splice(to..to, run);
        }
        3 => bytes[at] ^= 1 << rng.below(8),
        _ => {
            let words: [u32; 7] = [
                f32::MAX.to_bits(),
                f32::NAN.to_bits(),
                (-0.0f32).to_bits(),
                f32::INFINITY.to_bits(),
                u32::MAX,
                i32::MAX as u32,
                1 << 30,
            ];
            let w = rng.pick(&words).to_le_bytes();
            for (k, b) in w.iter().enumerate() {
                if let Some(x) = bytes.get_mut(at + k) {
                    *x = *b;
                }
            }
        }
    }
    bytes
}

/// Loads `path` with the loader of `kind`; scenes are also rendered at 8×8, 1 spp.
pub fn load(kind: Kind, path: &Path) -> Outcome {
    let refused = |ok: bool| {
        if ok {
            Outcome::Accepted
        } else {
            Outcome::Refused
        }
    };
    match kind {
        Kind::Scene => match xml::load(path, &[]) {
            Ok(loaded) => render_tiny(&loaded.scene),
            Err(_) => Outcome::Refused,
        },
        Kind::Mesh => {
            let ok = match extension(path).as_str() {
                "obj" => mesh_io::load_obj(path).is_ok(),
                "ply" => mesh_io::load_ply(path).is_ok(),
                _ => mesh_io::load_serialized(path, 0).is_ok(),
            };
            // A mesh that loads is also rendered, lit by the sky and glowing itself.
            let scene = path.with_extension("mesh.xml");
            let text = format!(
                "<scene version=\"3.0.0\"><sensor type=\"perspective\"><float name=\"fov\" \
                 value=\"60\"/></sensor><emitter type=\"constant\"/><shape type=\"{}\">\
                 <string name=\"filename\" value=\"{}\"/><emitter type=\"area\"/></shape></scene>",
                extension(path),
                path.display()
            );
            if !ok || std::fs::write(&scene, text).is_err() {
                return refused(ok);
            }
            let outcome = load(Kind::Scene, &scene);
            let _ = std::fs::remove_file(&scene);
            outcome
        }
        Kind::Image if extension(path) == "jpg" => refused(open_image(path).is_ok()),
        Kind::Image => refused(read_image(path).is_ok()),
    }
}

/// An 8×8 render at 1 spp; non-finite samples are a finding.
fn render_tiny(scene: &lightlab::scene::Scene) -> Outcome {
    let mut settings = RenderSettings::for_scene(scene);
    settings.resolution = Some((8, 8));
    settings.spp = 1;
    let stop = AtomicBool::new(false);
    let control = Control {
        progress: &|_, _| {},
        stop: &stop,
        frame: None,
    };
    let out = render::render(scene, &settings, &control);
    match out.invalid_samples {
        0 => Outcome::Accepted,
        n => Outcome::NonFinite(n),
    }
}

/// Runs [`load`] in a worker thread, catching panics; a case still running after
/// `limit` is a hang (its thread is left behind).
pub fn run_case(kind: Kind, path: &Path, limit: Duration) -> Outcome {
    let (tx, rx) = mpsc::channel();
    let owned = path.to_path_buf();
    let spawned = std::thread::Builder::new()
        .stack_size(8 << 20)
        .spawn(move || {
            let result = catch_unwind(AssertUnwindSafe(|| load(kind, &owned)));
            let _ = tx.send(result.unwrap_or_else(|p| {
                let msg = p
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| p.downcast_ref::<String>().cloned())
                    .unwrap_or_default();
                Outcome::Panic(msg)
            }));
        });
    if spawned.is_err() {
        return Outcome::Refused;
    }
    rx.recv_timeout(limit).unwrap_or(Outcome::Hang)
}

/// Where a mutated case is written: scenes beside the originals (their relative paths
/// to meshes, textures and includes must resolve), other files in `scratch`.
pub fn case_path(seed: &Seed, scratch: &Path, n: u64) -> PathBuf {
    let name = format!(".fuzz-{}-{n}.{}", std::process::id(), extension(&seed.path));
    match seed.kind {
        Kind::Scene => seed.path.with_file_name(name),
        _ => scratch.join(name),
    }
}
