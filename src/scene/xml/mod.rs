//! Mitsuba XML scenes (Mitsuba 3's format, and 0.5/0.6 files upgraded as Mitsuba 3 does):
//! `tree` parses text into located elements (includes, defaults, `$name` substitution,
//! version upgrade), `props` reads typed properties, `build` resolves ids and refs and
//! turns plugins (with `sensor`, `shapes` and `bitmap`) into a [`Scene`] through the [`SceneBuilder`](super::SceneBuilder), and
//! `shapes` builds the geometry. Every error names the file, line, column and element.

mod bitmap;
mod build;
mod digest;
mod microfacet;
mod props;
mod sensor;
mod shapes;
mod tree;

use std::path::Path;

pub use tree::MAX_INCLUDE_DEPTH;

use super::{Scene, SceneError};
use tree::Loc;

/// Errors of the XML loader are scene errors with a location.
pub(crate) type XmlError = SceneError;

impl SceneError {
    /// An error at an element's location.
    pub(crate) fn at(loc: &Loc, message: impl Into<String>) -> SceneError {
        SceneError::new(loc.file.to_string(), Some((loc.line, loc.col)), message)
    }

    /// An error about a whole file.
    pub(crate) fn file(name: &str, message: impl Into<String>) -> SceneError {
        SceneError::new(name, None, message)
    }
}

/// A loaded scene and the warnings the loader found (unused `-D` definitions; with
/// [`LoadOptions::lenient`], unused and duplicated properties), each located.
#[derive(Debug)]
pub struct Loaded {
    /// The scene.
    pub scene: Scene,
    /// Located warnings.
    pub warnings: Vec<String>,
}

/// How strictly the loader reads a file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// Unused (misspelt) and duplicated properties become warnings instead of errors,
    /// for files written for older or more lenient loaders. Mitsuba 3 refuses both
    /// (`Properties::mark_queried` check in its XML parser), and so does the default.
    pub lenient: bool,
}

/// Loads the Mitsuba XML file at `path`; `defines` are `-D name=value` pairs that
/// override the file's `<default>`s.
pub fn load(path: &Path, defines: &[(String, String)]) -> Result<Loaded, SceneError> {
    load_with_options(path, defines, LoadOptions::default())
}

/// [`load`] with [`LoadOptions`].
pub fn load_with_options(
    path: &Path,
    defines: &[(String, String)],
    options: LoadOptions,
) -> Result<Loaded, SceneError> {
    let mut warnings = Vec::new();
    let root = tree::parse_file(path, defines, &mut warnings)?;
    let mut scene = build::build(&root, path, options, &mut warnings)?;
    scene.content_hash = digest::digest(&root);
    Ok(Loaded { scene, warnings })
}

/// Loads a scene from XML text (for tests and fuzzing); relative paths resolve
/// against the current directory. The text is written to a temporary file first, so
/// errors name that file.
pub fn load_str(text: &str, defines: &[(String, String)]) -> Result<Loaded, SceneError> {
    use std::sync::atomic::{AtomicU64, Ordering};
    static N: AtomicU64 = AtomicU64::new(0);
    let path = std::env::temp_dir().join(format!(
        "lightlab-xml-{}-{}.xml",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    std::fs::write(&path, text)
        .map_err(|e| SceneError::file(&path.display().to_string(), e.to_string()))?;
    let result = load(&path, defines);
    let _ = std::fs::remove_file(&path);
    result
}
