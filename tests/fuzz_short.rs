//! A short deterministic run of the loader fuzzer (`tests/common/fuzz.rs`): a fixed seed
//! and a fixed number of mutated scenes, meshes and images, none of which may panic,
//! hang or render non-finite radiance. `cargo run --release --example fuzz` runs it long.

#[path = "common/fuzz.rs"]
mod fuzz;

use std::path::PathBuf;
use std::time::Duration;

use fuzz::{Outcome, Rng};

#[test]
fn mutated_inputs_are_refused_cleanly() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let seeds = fuzz::seeds(&root.join("tests/scenes"));
    assert!(seeds.len() >= 20, "{} seeds", seeds.len());
    let scratch = std::env::temp_dir().join(format!("lightlab-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).unwrap();
    let mut rng = Rng(20261122);
    let (mut refused, mut findings) = (0, Vec::new());
    for n in 0..2000 {
        let seed = rng.pick(&seeds);
        let path = fuzz::case_path(seed, &scratch, n);
        let bytes = fuzz::mutate(seed, &mut rng);
        std::fs::write(&path, &bytes).unwrap();
        let outcome = fuzz::run_case(seed.kind, &path, Duration::from_secs(60));
        let _ = std::fs::remove_file(&path);
        match outcome {
            Outcome::Refused => refused += 1,
            o if o.is_finding() => findings.push(format!(
                "{}: {o:?}\n{}",
                seed.path.display(),
                String::from_utf8_lossy(&bytes)
            )),
            _ => {}
        }
    }
    let _ = std::fs::remove_dir_all(&scratch);
    assert!(findings.is_empty(), "{}", findings.join("\n\n"));
    // The mutations must reach the loaders' error paths, not only their happy paths.
    assert!(refused > 500, "only {refused} of 2000 cases were refused");
}
