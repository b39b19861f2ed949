//! Ctrl-C during `render`: the rounds done are written, the EXR header says the image is
//! partial, and the exit code is 130 (128 + SIGINT); a temporary file that a killed run
//! left beside the output is removed by the next run writing that output.
#![cfg(unix)]

use std::process::Command;
use std::time::Duration;

use lightlab::image::io::read_image;

#[test]
fn interrupted_render_writes_a_partial_image_and_exits_130() {
    let dir = std::env::temp_dir().join(format!("lightlab-interrupt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("o.exr");
    // A leftover of a killed run (u32::MAX is no running process).
    let stale = dir.join(format!(".o.exr.tmp-{}", u32::MAX));
    std::fs::write(&stale, b"half an image").unwrap();
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/scenes/cbox_diffuse.xml");
    let mut child = Command::new(env!("CARGO_BIN_EXE_lightlab"))
        .args(["render", scene, "--spp", "20000", "--threads", "1", "-o"])
        .arg(&out)
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(700));
    // SAFETY: kill(2) with a child's pid and SIGINT has no memory effects.
    assert_eq!(unsafe { libc::kill(child.id() as i32, libc::SIGINT) }, 0);
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130));
    let image = read_image(&out).unwrap();
    let partial = image.metadata.iter().find(|(k, _)| k == "lightlab.partial");
    assert!(
        partial.is_some_and(|(_, v)| v.contains("of 20000 spp")),
        "{:?}",
        image.metadata
    );
    assert!(image.spp.is_some_and(|s| s < 20000), "{:?}", image.spp);
    assert!(!stale.exists(), "the stale temporary file is still there");
    let _ = std::fs::remove_dir_all(&dir);
}
