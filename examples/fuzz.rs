//! Fuzzes lightlab's scene, mesh and image loaders (see `tests/common/fuzz.rs` for the
//! mutations and what counts as a finding).
//!
//! `cargo run --release --example fuzz -- --minutes 30 [--seed S] [--limit SECS]`
//!
//! A supervisor runs workers in child processes, so that a crash the process cannot
//! catch (an abort, a stack overflow) is still recorded: each worker names its current
//! case in `target/fuzz/pending` before running it. Every finding is copied to
//! `tests/bad_inputs/fuzz/` and becomes a row of `tests/bad_inputs/cases.tsv` that
//! expects a clean exit 2 (scenes are rendered, meshes wrapped in a scene, images
//! given to `diff`).

#[path = "../tests/common/fuzz.rs"]
mod fuzz;

use std::collections::HashSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use fuzz::{Kind, Outcome, Rng, Seed};

/// Exit code of a worker that left a hung thread behind and must be replaced.
const EXIT_HUNG: i32 = 3;

struct Options {
    minutes: f64,
    seed: u64,
    limit: Duration,
    /// Set in worker processes: stop at this Unix time.
    worker_until: Option<u64>,
}

fn parse_options() -> Result<Options, String> {
    let mut o = Options {
        minutes: 1.0,
        seed: 1,
        limit: Duration::from_secs(10),
        worker_until: None,
    };
    let args: Vec<String> = std::env::args().skip(1).collect();
    for pair in args.chunks(2) {
        let value = pair.get(1).ok_or(format!("{} needs a value", pair[0]))?;
        let bad = |_: std::num::ParseFloatError| format!("{} {value}: not a number", pair[0]);
        let whole = |v: f64| v as u64;
        match pair[0].as_str() {
            "--minutes" => o.minutes = value.parse().map_err(bad)?,
            "--seed" => o.seed = whole(value.parse().map_err(bad)?),
            "--limit" => o.limit = Duration::from_secs_f64(value.parse().map_err(bad)?),
            "--worker-until" => o.worker_until = Some(whole(value.parse().map_err(bad)?)),
            other => return Err(format!("unknown option {other}")),
        }
    }
    if !(o.minutes >= 0.0 && o.minutes < 1e6) {
        return Err("--minutes must be in 0..1e6".into());
    }
    Ok(o)
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn now() -> u64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs())
}

fn main() {
    let options = match parse_options() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    match options.worker_until {
        Some(until) => std::process::exit(worker(&options, until)),
        None => supervise(&options),
    }
}

/// Restarts workers until the time is up; records the pending case of a worker that died.
fn supervise(o: &Options) {
    let until = now() + (o.minutes * 60.0) as u64;
    let pending = root().join("target/fuzz/pending");
    let (mut executions, mut findings, mut seed) = (0u64, 0u64, o.seed);
    let exe = std::env::current_exe().unwrap_or_else(|_| PathBuf::from("fuzz"));
    loop {
        let _ = std::fs::remove_file(&pending);
        let out = Command::new(&exe)
            .args([
                "--seed",
                &seed.to_string(),
                "--worker-until",
                &until.to_string(),
            ])
            .args(["--limit", &o.limit.as_secs_f64().to_string()])
            .output();
        let Ok(out) = out else {
            eprintln!("error: cannot start a worker");
            std::process::exit(1);
        };
        let stdout = String::from_utf8_lossy(&out.stdout);
        for line in stdout.lines() {
            if let Some(rest) = line.strip_prefix("executions ") {
                let mut it = rest.split(" findings ");
                executions += it.next().and_then(|v| v.parse().ok()).unwrap_or(0);
                findings += it.next().and_then(|v| v.parse().ok()).unwrap_or(0);
            }
        }
        let code = out.status.code();
        if code != Some(0) && code != Some(EXIT_HUNG) {
            // The worker died inside a case: the pending file names it.
            if let Ok(text) = std::fs::read_to_string(&pending)
                && let Some((kind, path)) = text.split_once('\t')
            {
                let kind = match kind {
                    "Scene" => Kind::Scene,
                    "Mesh" => Kind::Mesh,
                    _ => Kind::Image,
                };
                let msg = format!("process died ({:?})", out.status);
                record(kind, Path::new(path), &Outcome::Panic(msg));
                findings += 1;
            }
        }
        if now() >= until {
            break;
        }
        seed += 1000;
    }
    println!("fuzz: {executions} executions, {findings} findings");
}

/// Runs cases until `until`; prints its counts; exits [`EXIT_HUNG`] after a hang.
fn worker(o: &Options, until: u64) -> i32 {
    std::panic::set_hook(Box::new(|_| {}));
    let seeds: Vec<Seed> = fuzz::seeds(&root().join("tests/scenes"));
    let scratch = root().join("target/fuzz");
    let _ = std::fs::create_dir_all(&scratch);
    let pending = scratch.join("pending");
    let mut rng = Rng(o.seed);
    let mut seen: HashSet<String> = HashSet::new();
    let (mut executions, mut findings, mut code) = (0u64, 0u64, 0);
    let start = Instant::now();
    while now() < until && !seeds.is_empty() {
        let seed = rng.pick(&seeds);
        let path = fuzz::case_path(seed, &scratch, executions);
        let bytes = fuzz::mutate(seed, &mut rng);
        if std::fs::write(&path, &bytes).is_err() {
            break;
        }
        let _ = std::fs::write(&pending, format!("{:?}\t{}", seed.kind, path.display()));
        let outcome = fuzz::run_case(seed.kind, &path, o.limit);
        executions += 1;
        if outcome.is_finding() {
            // One finding per panic message, and per seed file for hangs and NaNs.
            let key = match &outcome {
                Outcome::Panic(m) => m.lines().next().unwrap_or("").to_owned(),
                other => format!("{} {}", seed.path.display(), other == &Outcome::Hang),
            };
            if seen.insert(key) {
                record(seed.kind, &path, &outcome);
                findings += 1;
            }
        }
        let _ = std::fs::remove_file(&path);
        let _ = std::fs::remove_file(&pending);
        if outcome == Outcome::Hang {
            code = EXIT_HUNG;
            break;
        }
    }
    println!("executions {executions} findings {findings}");
    eprintln!(
        "worker {}: {executions} cases in {:.0} s",
        o.seed,
        start.elapsed().as_secs_f64()
    );
    code
}

/// Copies a finding into `tests/bad_inputs/fuzz/` and appends its case row.
fn record(kind: Kind, path: &Path, outcome: &Outcome) {
    let dir = root().join("tests/bad_inputs/fuzz");
    let _ = std::fs::create_dir_all(&dir);
    let Ok(bytes) = std::fs::read(path) else {
        return;
    };
    // FNV-1a of the bytes names the case.
    let hash = bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x100_0000_01b3)
    });
    let ext = fuzz::extension(path);
    let name = format!("{hash:016x}.{ext}");
    let mut bytes = bytes;
    if kind == Kind::Scene {
        // Relative paths pointed into tests/scenes/.
        let text = String::from_utf8_lossy(&bytes).into_owned();
        let fixed = ["meshes/", "textures/", "common/"]
            .iter()
            .fold(text, |t, p| {
                t.replace(&format!("\"{p}"), &format!("\"../../scenes/{p}"))
            });
        bytes = fixed.into_bytes();
    }
    let _ = std::fs::write(dir.join(&name), &bytes);
    let args = match kind {
        Kind::Scene => format!("render $IN/fuzz/{name} --spp 1 -o $OUT/o.exr"),
        Kind::Mesh => {
            let scene = format!("{name}.xml");
            let text = format!(
                "<scene version=\"3.0.0\"><sensor type=\"perspective\"><float name=\"fov\" \
                 value=\"40\"/></sensor><shape type=\"{ext}\"><string name=\"filename\" \
                 value=\"{name}\"/></shape></scene>\n"
            );
            let _ = std::fs::write(dir.join(&scene), text);
            format!("render $IN/fuzz/{scene} --spp 1 --width 8 --height 8 -o $OUT/o.exr")
        }
        Kind::Image => format!("diff $IN/fuzz/{name} $IN/fuzz/{name}"),
    };
    let what = format!("{outcome:?}").replace(['\t', '\n'], " ");
    let row = format!("fuzz-{hash:016x}\t{args}\t2\t-\t-\t# fuzz finding: {what}\n");
    if let Ok(mut f) = std::fs::OpenOptions::new()
        .append(true)
        .create(true)
        .open(root().join("tests/bad_inputs/cases.tsv"))
    {
        let _ = f.write_all(row.as_bytes());
    }
    eprintln!("finding: {name}: {what}");
}
