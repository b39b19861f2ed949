//! `lightlab._lightlab`: the Python bindings of lightlab (issue 16). They sit beside the
//! command line, on the library: settings travel as the command line's flags into
//! `RenderPatch::set`, renders run on the library's thread pool with the GIL released,
//! and the pure-Python package `lightlab` wraps these functions with keyword arguments.

mod interrupt;
mod lab;
mod result;
mod scene;
mod settings;
mod state;

use pyo3::prelude::*;

pyo3::create_exception!(
    _lightlab,
    SceneError,
    pyo3::exceptions::PyValueError,
    "A scene that does not load; the message names `file:line:col`."
);

#[pymodule]
fn _lightlab(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add("SETTINGS", settings::keywords())?;
    m.add_class::<scene::PyScene>()?;
    m.add_class::<result::PyRender>()?;
    m.add_function(wrap_pyfunction!(scene::load_scene, m)?)?;
    m.add_function(wrap_pyfunction!(result::render, m)?)?;
    m.add_function(wrap_pyfunction!(result::merge, m)?)?;
    m.add_function(wrap_pyfunction!(result::result_from_state, m)?)?;
    m.add_function(wrap_pyfunction!(lab::diff, m)?)?;
    m.add_function(wrap_pyfunction!(lab::warp, m)?)?;
    m.add_function(wrap_pyfunction!(lab::compare, m)?)?;
    m.add_function(wrap_pyfunction!(lab::converge, m)?)?;
    m.add_function(wrap_pyfunction!(lab::strategy_settings, m)?)?;
    m.add_function(wrap_pyfunction!(lab::tev_packets, m)?)?;
    Ok(())
}
