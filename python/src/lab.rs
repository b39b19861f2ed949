//! The laboratory from Python: `diff` (the CLI's metrics), `warp` (a named warp's
//! samples and pdf values), tev packets for any image, and `compare` / `converge`
//! (their tables as lists of dicts, their reports written to a folder).

use std::path::PathBuf;

use lightlab::image::metrics::compare as metrics;
use lightlab::image::tev;
use lightlab::lab::budget::{Budget, time_budget};
use lightlab::lab::compare::{CompareConfig, run_compare};
use lightlab::lab::converge::{ConvergeConfig, run_converge};
use lightlab::lab::experiment::ReferenceSource;
use lightlab::lab::strategy::Strategy;
use lightlab::math::Spectrum;
use lightlab::sampling::{Rng32, registry};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

use crate::{interrupt, settings};

fn value_error(e: impl ToString) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// Pixels of an H×W×3 float32 array.
fn pixels(name: &str, a: &PyReadonlyArrayDyn<'_, f32>) -> PyResult<(Vec<usize>, Vec<Spectrum>)> {
    let shape = a.shape().to_vec();
    if shape.len() != 3 || shape[2] != 3 {
        return Err(value_error(format!(
            "{name} has shape {shape:?}, not (H, W, 3)"
        )));
    }
    let data: Vec<f32> = a.as_array().iter().copied().collect();
    let rgb = data.chunks_exact(3).map(Spectrum::from_slice).collect();
    Ok((shape, rgb))
}

/// The CLI's `diff` metrics of `image` against `reference` (with the variance of each
/// pixel's mean of either, when given) as a dict.
#[pyfunction]
#[pyo3(signature = (image, reference, variance = None, reference_variance = None))]
pub fn diff<'py>(
    py: Python<'py>,
    image: PyReadonlyArrayDyn<'py, f32>,
    reference: PyReadonlyArrayDyn<'py, f32>,
    variance: Option<PyReadonlyArrayDyn<'py, f32>>,
    reference_variance: Option<PyReadonlyArrayDyn<'py, f32>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (shape, v) = pixels("image", &image)?;
    let mut arrays = vec![("reference", pixels("reference", &reference)?)];
    if let Some(a) = &variance {
        arrays.push(("variance", pixels("variance", a)?));
    }
    if let Some(a) = &reference_variance {
        arrays.push(("reference_variance", pixels("reference_variance", a)?));
    }
    for (name, (s, _)) in &arrays {
        if *s != shape {
            return Err(value_error(format!(
                "{name} has shape {s:?} but image has {shape:?}"
            )));
        }
    }
    let find = |n: &str| {
        arrays
            .iter()
            .find(|(k, _)| *k == n)
            .map(|(_, (_, p))| p.as_slice())
    };
    let r = find("reference").unwrap_or_default();
    let e = metrics(&v, find("variance"), r, find("reference_variance"));
    let d = PyDict::new(py);
    d.set_item("mse", e.mse)?;
    d.set_item("relmse", e.rel_mse)?;
    d.set_item("relative_bias", e.relative_bias)?;
    d.set_item("bias_std_error", e.bias_std_error)?;
    d.set_item("bias_z", e.bias_z())?;
    d.set_item("nan_pixels", e.nan_pixels)?;
    d.set_item("inf_pixels", e.inf_pixels)?;
    Ok(d)
}

/// `n` samples of warp `name` (see `lightlab warp --list`) from stream `seed`: an n×3
/// array of values (2D domains use the first two columns) and the n pdf values the warp
/// claims, in its domain's measure.
#[pyfunction]
pub fn warp<'py>(
    py: Python<'py>,
    name: &str,
    n: usize,
    seed: u64,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyArray1<f32>>)> {
    let entry = registry::find(name).map_err(value_error)?;
    let mut rng = Rng32::new(seed);
    let (mut values, mut pdfs) = (Vec::with_capacity(3 * n), Vec::with_capacity(n));
    for _ in 0..n {
        let (v, pdf) = entry.sample(&mut rng);
        values.extend(v.to_array());
        pdfs.push(pdf);
    }
    let values = PyArray1::from_vec(py, values).reshape([n, 3])?.into_any();
    Ok((values, PyArray1::from_vec(py, pdfs)))
}

/// tev's `CreateImage` and `UpdateImageV3` packets for an H×W×3 image called `name`.
#[pyfunction]
pub fn tev_packets<'py>(
    py: Python<'py>,
    name: &str,
    image: PyReadonlyArrayDyn<'py, f32>,
) -> PyResult<(Bound<'py, PyBytes>, Bound<'py, PyBytes>)> {
    let (shape, rgb) = pixels("image", &image)?;
    let (w, h) = (shape[1] as u32, shape[0] as u32);
    Ok((
        PyBytes::new(py, &tev::create_image_packet(name, w, h)),
        PyBytes::new(py, &tev::update_image_packet(name, w, h, rgb.into_iter())),
    ))
}

/// Parses each strategy (`label:flags` or a preset).
fn parse_strategies(list: &[String]) -> PyResult<Vec<Strategy>> {
    if list.is_empty() {
        return Err(value_error("strategies: give at least one"));
    }
    list.iter()
        .map(|s| Strategy::parse(s).map_err(value_error))
        .collect()
}

/// A strategy (`label:flags` or a preset) as (label, render keywords).
#[pyfunction]
pub fn strategy_settings(text: &str) -> PyResult<(String, Vec<(String, String)>)> {
    let s = Strategy::parse(text).map_err(value_error)?;
    Ok((s.label, settings::keywords_of(&s.patch)))
}

fn reference_source(file: Option<PathBuf>, spp: u32) -> PyResult<ReferenceSource> {
    if spp == 0 {
        return Err(value_error("reference_spp=0: need at least 1"));
    }
    Ok(match file {
        Some(p) => ReferenceSource::File(p),
        None => ReferenceSource::Render {
            strategy: Strategy::new("default", Default::default()),
            spp,
        },
    })
}

/// `lightlab compare`: renders each strategy at `spp` (or for `time` seconds), measures
/// it against the reference and writes the report into `output`; returns one dict per
/// strategy.
#[pyfunction]
#[pyo3(signature = (scene, strategies, output, spp = None, time = None, reference = None, reference_spp = 1024, flags = Vec::new(), threads = None))]
#[allow(clippy::too_many_arguments)] // one argument per keyword of the Python call
pub fn compare<'py>(
    py: Python<'py>,
    scene: String,
    strategies: Vec<String>,
    output: PathBuf,
    spp: Option<u32>,
    time: Option<f64>,
    reference: Option<PathBuf>,
    reference_spp: u32,
    flags: Vec<(String, String)>,
    threads: Option<usize>,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let budget = match (spp, time) {
        (Some(0), _) => return Err(value_error("spp=0: need at least 1")),
        (Some(n), None) => Budget::Spp(n),
        (None, Some(t)) => {
            Budget::Time(time_budget(t).map_err(|e| value_error(format!("time {e}")))?)
        }
        _ => return Err(value_error("give spp=N or time=SECONDS (one of them)")),
    };
    let config = CompareConfig {
        scene,
        strategies: parse_strategies(&strategies)?,
        budget,
        base: settings::patch(&flags)?,
        reference: reference_source(reference, reference_spp)?,
        insets: vec![],
        title: None,
        notes: vec![],
        links: vec![],
    };
    let results = interrupt::run(py, threads, |stop| {
        run_compare(&config, &output, stop, &|_| {})
    })?
    .map_err(value_error)?;
    results
        .iter()
        .map(|r| {
            let d = PyDict::new(py);
            d.set_item("label", &r.label)?;
            d.set_item("flags", &r.flags)?;
            d.set_item("spp", r.spp)?;
            d.set_item("time", r.time.as_secs_f64())?;
            d.set_item("mse", r.error.mse)?;
            d.set_item("relmse", r.error.rel_mse)?;
            d.set_item("relative_bias", r.error.relative_bias)?;
            d.set_item("bias_std_error", r.error.bias_std_error)?;
            d.set_item("efficiency", r.efficiency)?;
            d.set_item("relative_efficiency", r.relative_efficiency)?;
            d.set_item("invalid_samples", r.invalid_samples)?;
            Ok(d)
        })
        .collect()
}

/// `lightlab converge`: relMSE against spp and time for each strategy (powers of two up
/// to `max_spp`, `seeds` seeds per point), report written into `output`; returns one
/// dict per (strategy, spp).
#[pyfunction]
#[pyo3(signature = (scene, strategies, output, max_spp, seeds = 1, reference = None, reference_spp = 1024, flags = Vec::new(), threads = None))]
#[allow(clippy::too_many_arguments)] // one argument per keyword of the Python call
pub fn converge<'py>(
    py: Python<'py>,
    scene: String,
    strategies: Vec<String>,
    output: PathBuf,
    max_spp: u32,
    seeds: u32,
    reference: Option<PathBuf>,
    reference_spp: u32,
    flags: Vec<(String, String)>,
    threads: Option<usize>,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    if max_spp == 0 || seeds == 0 {
        return Err(value_error("max_spp and seeds must be at least 1"));
    }
    let config = ConvergeConfig {
        scene,
        strategies: parse_strategies(&strategies)?,
        max_spp,
        seeds,
        base: settings::patch(&flags)?,
        reference: reference_source(reference, reference_spp)?,
        title: None,
    };
    let series = interrupt::run(py, threads, |stop| {
        run_converge(&config, &output, stop, &|_| {})
    })?
    .map_err(value_error)?;
    let mut rows = Vec::new();
    for s in &series {
        for p in &s.points {
            let d = PyDict::new(py);
            d.set_item("label", &s.label)?;
            d.set_item("spp", p.spp)?;
            d.set_item("time", p.time)?;
            d.set_item("relmse", p.rel_mse)?;
            d.set_item("relmse_min", p.rel_mse_min)?;
            d.set_item("relmse_max", p.rel_mse_max)?;
            d.set_item("slope_spp", s.slope_spp)?;
            d.set_item("slope_time", s.slope_time)?;
            rows.push(d);
        }
    }
    Ok(rows)
}
