//! Scenes loaded once and reused across renders: `lightlab.load_scene(path, **defines)`.

use std::path::PathBuf;
use std::sync::Arc;

use lightlab::scene::{self, Scene};
use pyo3::prelude::*;

use crate::SceneError;

/// A loaded scene (a Mitsuba XML file with its `-D` definitions, or `builtin:NAME`).
#[pyclass(name = "Scene", module = "lightlab._lightlab", frozen)]
pub struct PyScene {
    /// The scene.
    pub scene: Arc<Scene>,
    /// The spec it came from, with its definitions (`file.xml?a=1&b=2`), so lab runs that
    /// load the scene themselves see the same one.
    pub spec: String,
}

#[pymethods]
impl PyScene {
    /// The scene's name.
    #[getter]
    fn name(&self) -> String {
        self.scene.name.clone()
    }

    /// The spec (path or `builtin:NAME`, with definitions as `?name=value&...`).
    #[getter]
    fn spec(&self) -> String {
        self.spec.clone()
    }

    /// (width, height) of the scene's own camera.
    #[getter]
    fn size(&self) -> (u32, u32) {
        (self.scene.camera.width, self.scene.camera.height)
    }

    /// Writes the scene as a Mitsuba 3 XML file at `path` (meshes and environment map
    /// beside it; `lightlab export`), GIL released. Returns (the files written, notes on
    /// what Mitsuba 3 refuses or reads otherwise); a scene the format cannot hold raises
    /// `SceneError` naming what.
    fn export(&self, py: Python<'_>, path: PathBuf) -> PyResult<(Vec<PathBuf>, Vec<String>)> {
        let scene = Arc::clone(&self.scene);
        let written = py.detach(move || scene::export::export(&scene, &path));
        let exported =
            written.map_err(|e| SceneError::new_err(format!("{}: {e}", self.scene.name)))?;
        Ok((exported.files, exported.notes))
    }

    fn __repr__(&self) -> String {
        format!("lightlab.Scene({:?})", self.spec)
    }
}

/// Loads `spec` with `defines` (the command line's `-D name=value`), GIL released. A
/// scene that does not load raises `SceneError` (a `ValueError`) with `file:line:col`.
#[pyfunction]
#[pyo3(signature = (spec, defines = Vec::new()))]
pub fn load_scene(
    py: Python<'_>,
    spec: String,
    defines: Vec<(String, String)>,
) -> PyResult<PyScene> {
    let loaded = py.detach(|| scene::load_with(&spec, &defines));
    let scene = loaded.map_err(|e| SceneError::new_err(e.to_string()))?;
    let spec = if defines.is_empty() {
        spec
    } else {
        let query: Vec<String> = defines.iter().map(|(k, v)| format!("{k}={v}")).collect();
        format!("{spec}?{}", query.join("&"))
    };
    Ok(PyScene {
        scene: Arc::new(scene),
        spec,
    })
}
