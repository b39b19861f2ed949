//! `render` and `merge`, and the `Result` they return: the image and the variance of
//! each pixel's mean as numpy arrays, the canonical flags, a PNG preview for notebooks,
//! and pickling (exact film statistics) so results cross processes.

use std::time::Duration;

use lightlab::image::Film;
use lightlab::image::io::to_srgb8;
use lightlab::image::tev::TevDisplay;
use lightlab::lab::merge::overlapping;
use lightlab::lab::reference::estimate_error;
use lightlab::render::{Control, RenderOutput, RenderSettings, render as render_scene};
use lightlab::settings::{Pass, RenderPatch};
use numpy::{PyArray1, PyArray3, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyTuple};

use crate::scene::PyScene;
use crate::state::{Rendered, decode, encode};
use crate::{interrupt, settings};

/// A render, or a merge of several.
#[pyclass(name = "Result", module = "lightlab._lightlab", frozen)]
pub struct PyRender(pub Rendered);

/// H×W×3 float32 array of one value per pixel of `film`.
fn array<'py>(
    py: Python<'py>,
    film: &Film,
    value: impl Fn(&lightlab::image::PixelStats) -> [f32; 3],
) -> PyResult<Bound<'py, PyArray3<f32>>> {
    let data: Vec<f32> = film.pixels.iter().flat_map(value).collect();
    PyArray1::from_vec(py, data).reshape([film.height as usize, film.width as usize, 3])
}

#[pymethods]
impl PyRender {
    /// The image (mean of each pixel), float32 H×W×3, linear RGB.
    #[getter]
    fn image<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        array(py, &self.0.out.film, |p| p.mean.to_array())
    }

    /// The variance of each pixel's mean, float32 H×W×3.
    #[getter]
    fn variance<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        array(py, &self.0.out.film, |p| p.variance_of_mean().to_array())
    }

    /// Samples per pixel rendered.
    #[getter]
    fn spp(&self) -> u32 {
        self.0.out.spp
    }

    /// Seconds spent rendering (summed over merged parts).
    #[getter]
    fn time(&self) -> f64 {
        self.0.out.time.as_secs_f64()
    }

    /// The canonical flags (`--estimator mis ... --spp 64 --seed 0`).
    #[getter]
    fn settings(&self) -> String {
        self.0.settings.clone()
    }

    /// 0-based pass index (0 for a whole render).
    #[getter]
    fn pass_index(&self) -> u32 {
        self.0.pass.index
    }

    /// Number of passes the render was split into (1 for a whole render).
    #[getter]
    fn pass_count(&self) -> u32 {
        self.0.pass.count
    }

    /// Samples whose radiance was not finite (scored as zero).
    #[getter]
    fn invalid_samples(&self) -> u64 {
        self.0.out.invalid_samples
    }

    /// Shadow rays traced (light and MIS estimators).
    #[getter]
    fn shadow_rays(&self) -> u64 {
        self.0.out.shadow_rays
    }

    /// True when a stop request ended the render early.
    #[getter]
    fn stopped(&self) -> bool {
        self.0.out.stopped
    }

    /// The relative error a reference is held to (`lightlab reference`): the larger of
    /// the image mean's relative standard error and the 90th percentile of the pixels'.
    #[getter]
    fn rel_error(&self) -> f64 {
        estimate_error(&self.0.out.film).worst()
    }

    /// The scene's name.
    #[getter]
    fn scene(&self) -> String {
        self.0.scene.clone()
    }

    /// An sRGB PNG of the image (exposure 0), which notebooks show.
    fn _repr_png_<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let film = &self.0.out.film;
        let rgb: Vec<u8> = film
            .pixels
            .iter()
            .flat_map(|p| to_srgb8(p.mean, 1.0))
            .collect();
        let mut png = Vec::new();
        let encoder = image::codecs::png::PngEncoder::new(&mut png);
        image::ImageEncoder::write_image(
            encoder,
            &rgb,
            film.width,
            film.height,
            image::ExtendedColorType::Rgb8,
        )
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        Ok(PyBytes::new(py, &png))
    }

    /// Pickles as the exact film statistics (`_result_from_state(bytes)`).
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let rebuild = py
            .import("lightlab._lightlab")?
            .getattr("_result_from_state")?;
        let state = PyBytes::new(py, &encode(&self.0));
        PyTuple::new(py, [rebuild, PyTuple::new(py, [state])?.into_any()])
    }

    fn __repr__(&self) -> String {
        let f = &self.0.out.film;
        format!(
            "lightlab.Result({}: {}x{}, {} spp, {:.3} s, {})",
            self.0.scene,
            f.width,
            f.height,
            self.0.out.spp,
            self.0.out.time.as_secs_f64(),
            self.0.settings
        )
    }
}

/// Rebuilds a pickled result.
#[pyfunction]
#[pyo3(name = "_result_from_state")]
pub fn result_from_state(state: &[u8]) -> PyResult<PyRender> {
    decode(state).map(PyRender).map_err(PyValueError::new_err)
}

/// Renders `scene` with the keyword settings `flags` on `threads` workers, GIL released;
/// Ctrl-C raises `KeyboardInterrupt`. With `display` (`HOST:PORT`) each round is shown
/// in tev.
#[pyfunction]
#[pyo3(signature = (scene, flags, threads = None, display = None))]
pub fn render(
    py: Python<'_>,
    scene: &PyScene,
    flags: Vec<(String, String)>,
    threads: Option<usize>,
    display: Option<String>,
) -> PyResult<PyRender> {
    let patch = settings::patch(&flags)?;
    let s = RenderSettings::build(&scene.scene, &[&patch])
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    if threads == Some(0) {
        return Err(PyValueError::new_err("threads=0: need at least 1"));
    }
    let scene = &scene.scene;
    let camera = s.camera(scene);
    let out = interrupt::run(py, threads, |stop| {
        let view = display
            .as_deref()
            .and_then(|a| TevDisplay::connect(a, &scene.name, camera.width, camera.height));
        let frame = |film: &Film| {
            if let Some(v) = &view {
                v.send(&scene.name, film);
            }
        };
        // Frames only for a live view: a render without one may take fewer, longer
        // rounds.
        let control = Control {
            progress: &|_, _| {},
            stop,
            frame: view.is_some().then_some(&frame as &(dyn Fn(&Film) + Sync)),
        };
        let out = render_scene(scene, &s, &control);
        if let Some(v) = view {
            v.finish(&scene.name, &out.film);
        }
        out
    })?;
    Ok(PyRender(Rendered {
        out,
        settings: s.patch().to_string(),
        pass: s.pass,
        scene: scene.name.clone(),
    }))
}

/// The flags of `settings` without `--pass`.
fn without_pass(settings: &str) -> String {
    match settings.parse::<RenderPatch>() {
        Ok(mut p) => {
            p.pass = None;
            p.to_string()
        }
        Err(_) => settings.to_string(),
    }
}

/// Merges renders of the same image (passes of one render, or renders with other
/// seeds) by Chan et al.'s pairwise update, as `lightlab merge` does: sample-weighted,
/// variance kept. All passes of one render give that render (up to summation order),
/// except under optimal MIS, where each pass learns its own α: then an unbiased
/// estimate of the same image, not that render's bits.
#[pyfunction]
pub fn merge(results: Vec<PyRef<'_, PyRender>>) -> PyResult<PyRender> {
    let mut parts: Vec<&Rendered> = results.iter().map(|r| &r.0).collect();
    parts.sort_by_key(|r| (r.pass.count, r.pass.index));
    let Some(first) = parts.first() else {
        return Err(PyValueError::new_err("merge needs at least one result"));
    };
    let (w, h) = (first.out.film.width, first.out.film.height);
    let mut total: Option<RenderOutput> = None;
    let mut time = Duration::ZERO;
    for (i, part) in parts.iter().enumerate() {
        let f = &part.out.film;
        if (f.width, f.height) != (w, h) {
            return Err(PyValueError::new_err(format!(
                "cannot merge a {}x{} result into {w}x{h} ones",
                f.width, f.height
            )));
        }
        // The same samples twice (a result given twice, or overlapping passes of one
        // seed) would count them twice.
        let have: Vec<_> = parts[..i]
            .iter()
            .flat_map(|p| p.out.samples.clone())
            .collect();
        if let Some((old, new)) = overlapping(&have, &part.out.samples) {
            return Err(PyValueError::new_err(format!(
                "cannot merge: samples {new} (pass {}) overlap samples {old} of another result \
                 (the same result twice, or passes of different splits of one seed)",
                part.pass
            )));
        }
        time += part.out.time;
        total = Some(RenderOutput::merge(total, part.out.clone()));
    }
    let mut settings: Vec<String> = Vec::new();
    for s in parts.iter().map(|p| without_pass(&p.settings)) {
        if !settings.contains(&s) {
            settings.push(s);
        }
    }
    // One part keeps its pass; several parts are a render of their own (all passes of
    // one render are that render).
    let pass = if parts.len() == 1 {
        first.pass
    } else {
        Pass::WHOLE
    };
    let mut out = total.ok_or_else(|| PyValueError::new_err("merge needs at least one result"))?;
    out.time = time;
    Ok(PyRender(Rendered {
        out,
        settings: if parts.len() == 1 {
            first.settings.clone()
        } else {
            settings.join(" + ")
        },
        pass,
        scene: first.scene.clone(),
    }))
}
