//! Output files written whole or not at all: each goes to a hidden temporary sibling
//! (`.NAME.tmp-PID`) renamed into place; temporaries that a killed run left behind are
//! removed by the next run that writes the same output. [`check_output`] lets a command
//! refuse an unwritable path before any work.

use std::fs;
use std::path::{Path, PathBuf};

/// Checks, before any work, that `path` names a file with one of `formats`'
/// extensions (lower case, no dot) in a folder that exists.
pub fn check_output(path: &Path, formats: &[&str]) -> Result<(), String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if ext.is_empty() {
        return Err(format!("{}: has no extension", path.display()));
    }
    if !formats.contains(&ext.as_str()) {
        let known: Vec<String> = formats.iter().map(|f| format!(".{f}")).collect();
        return Err(format!(
            "{}: unknown image format \".{ext}\" (known: {})",
            path.display(),
            known.join(", ")
        ));
    }
    if path.file_name().is_none() {
        return Err(format!("{}: not a file path", path.display()));
    }
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !folder.is_dir() {
        return Err(format!(
            "{}: the folder {} does not exist",
            path.display(),
            folder.display()
        ));
    }
    Ok(())
}

/// The temporary sibling of `path` that process `pid` writes.
fn temporary(path: &Path, file_name: &str, pid: u32) -> PathBuf {
    path.with_file_name(format!(".{file_name}.tmp-{pid}"))
}

/// Whether process `pid` still runs; unknown (true) without `/proc`.
fn alive(pid: u32) -> bool {
    let proc = Path::new("/proc");
    !proc.join("self").exists() || proc.join(pid.to_string()).exists()
}

/// Removes temporaries of `path` left by processes that no longer run.
fn remove_stale(path: &Path, file_name: &str) {
    let prefix = format!(".{file_name}.tmp-");
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let Ok(entries) = fs::read_dir(folder) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let pid = name
            .strip_prefix(&prefix)
            .and_then(|p| p.parse::<u32>().ok());
        if let Some(pid) = pid
            && pid != std::process::id()
            && !alive(pid)
        {
            let _ = fs::remove_file(entry.path());
        }
    }
}

/// Writes `path` through a temporary sibling renamed into place; `write` writes the
/// temporary. Stale temporaries of the same output are removed first.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), String> {
    let file_name = path
        .file_name()
        .ok_or("not a file path")?
        .to_string_lossy()
        .into_owned();
    remove_stale(path, &file_name);
    let tmp = temporary(path, &file_name, std::process::id());
    if let Err(e) = write(&tmp) {
        let _ = fs::remove_file(&tmp);
        return Err(e);
    }
    fs::rename(&tmp, path).map_err(|e| {
        let _ = fs::remove_file(&tmp);
        e.to_string()
    })
}

/// Writes several files that belong together (a scene file and the files it names):
/// each to its temporary sibling (stale temporaries removed first), then all renamed into
/// place in order, the last one last. When a write fails, the temporaries are removed and
/// nothing is replaced; when a rename fails, the files renamed before it may already be
/// new, but the later ones (the last included) are still the old ones.
pub fn write_all_atomically(files: &[(PathBuf, &[u8])]) -> Result<(), String> {
    let pid = std::process::id();
    let mut named = Vec::with_capacity(files.len());
    for (path, bytes) in files {
        let file_name = path
            .file_name()
            .ok_or_else(|| format!("{}: not a file path", path.display()))?
            .to_string_lossy()
            .into_owned();
        remove_stale(path, &file_name);
        named.push((path, temporary(path, &file_name, pid), *bytes));
    }
    let written = named.iter().try_for_each(|(path, tmp, bytes)| {
        fs::write(tmp, bytes).map_err(|e| format!("{}: {e}", path.display()))
    });
    let renamed = written.and_then(|()| {
        named.iter().try_for_each(|(path, tmp, _)| {
            fs::rename(tmp, path).map_err(|e| format!("{}: {e}", path.display()))
        })
    });
    if renamed.is_err() {
        for (_, tmp, _) in &named {
            let _ = fs::remove_file(tmp);
        }
    }
    renamed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stale_temporaries_go_and_bad_paths_are_refused() {
        let dir = std::env::temp_dir().join(format!("lightlab-output-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let out = dir.join("o.pfm");
        // u32::MAX is no running process.
        let stale = temporary(&out, "o.pfm", u32::MAX);
        fs::write(&stale, b"half").unwrap();
        write_atomically(&out, |tmp| fs::write(tmp, b"x").map_err(|e| e.to_string())).unwrap();
        assert!(!stale.exists() && out.exists());
        assert!(check_output(&out, &["pfm"]).is_ok());
        assert!(check_output(&dir.join("o.bmp"), &["pfm"]).is_err());
        assert!(check_output(&dir.join("none/o.pfm"), &["pfm"]).is_err());
        let _ = fs::remove_dir_all(dir);
    }
}
