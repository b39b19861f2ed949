//! Python keywords to the settings patch: keyword `x_y` is flag `--x-y`, and its value is
//! read by `RenderPatch::set`, so the flags are listed once, in the library.

use lightlab::settings::{Pass, RenderPatch};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// The switches that take no value on the command line: compensation on and off, both
/// the keyword `envmap_compensation` (True or False) in Python.
const ENVMAP_COMPENSATION: &str = "envmap-compensation";
const NO_ENVMAP_COMPENSATION: &str = "no-envmap-compensation";

/// The keywords a render accepts: every value flag (`pass` as `pass_index` and
/// `pass_count`) and the envmap-compensation switch, in canonical order.
pub fn keywords() -> Vec<String> {
    let mut all: Vec<String> = Vec::new();
    for (flag, _) in RenderPatch::VALUE_FLAGS {
        if *flag == "pass" {
            all.extend(["pass_index".into(), "pass_count".into()]);
        } else {
            all.push(flag.replace('-', "_"));
        }
    }
    all.push(ENVMAP_COMPENSATION.replace('-', "_"));
    all
}

/// The patch of `(keyword, value)` pairs, values as text (Python's `str`). A wrong
/// keyword or value is a `ValueError` naming it and what is accepted.
pub fn patch(pairs: &[(String, String)]) -> PyResult<RenderPatch> {
    let mut patch = RenderPatch::default();
    let (mut pass_index, mut pass_count) = (None, None);
    for (keyword, value) in pairs {
        let bad = |message: String| PyValueError::new_err(format!("{keyword}={value}: {message}"));
        match keyword.as_str() {
            "pass_index" => pass_index = Some(parse_u32(value).map_err(bad)?),
            "pass_count" => pass_count = Some(parse_u32(value).map_err(bad)?),
            "envmap_compensation" => {
                patch.envmap_compensation = Some(parse_switch(value).map_err(bad)?)
            }
            _ => {
                let flag = keyword.replace('_', "-");
                if keyword.contains('-') || !keywords().contains(keyword) {
                    return Err(PyValueError::new_err(format!(
                        "unknown setting `{keyword}` (accepted: {})",
                        keywords().join(", ")
                    )));
                }
                patch.set(&flag, value).map_err(|e| bad(e.to_string()))?;
            }
        }
    }
    patch.pass = pass(pass_index, pass_count)?;
    Ok(patch)
}

/// The keywords that give `patch` (its canonical flags, `x-y` as `x_y`, the pass as
/// `pass_index` and `pass_count`).
pub fn keywords_of(patch: &RenderPatch) -> Vec<(String, String)> {
    let mut pairs = Vec::new();
    let text = patch.to_string();
    let mut words = text.split_whitespace();
    while let Some(word) = words.next() {
        let name = word.trim_start_matches('-');
        if name == ENVMAP_COMPENSATION || name == NO_ENVMAP_COMPENSATION {
            let on = if name == ENVMAP_COMPENSATION {
                "True"
            } else {
                "False"
            };
            pairs.push((ENVMAP_COMPENSATION.replace('-', "_"), on.to_string()));
        } else if let Some(value) = words.next() {
            pairs.push((name.replace('-', "_"), value.to_string()));
        }
    }
    if let Some(p) = patch.pass {
        pairs.retain(|(k, _)| k != "pass");
        pairs.push(("pass_index".into(), p.index.to_string()));
        pairs.push(("pass_count".into(), p.count.to_string()));
    }
    pairs
}

/// `pass_index` (0-based, as Python's `range`) of `pass_count`.
fn pass(index: Option<u32>, count: Option<u32>) -> PyResult<Option<Pass>> {
    match (index, count) {
        (None, None) => Ok(None),
        (Some(index), Some(count)) if count >= 1 && index < count => {
            Ok(Some(Pass { index, count }))
        }
        (Some(i), Some(n)) => Err(PyValueError::new_err(format!(
            "pass_index={i}, pass_count={n}: need 0 <= pass_index < pass_count"
        ))),
        _ => Err(PyValueError::new_err(
            "pass_index and pass_count go together (pass_index=i, pass_count=n, 0 <= i < n)",
        )),
    }
}

fn parse_u32(value: &str) -> Result<u32, String> {
    value
        .trim()
        .parse()
        .map_err(|_| "expected a whole number".to_string())
}

fn parse_switch(value: &str) -> Result<bool, String> {
    match value.trim() {
        "True" | "true" | "1" => Ok(true),
        "False" | "false" | "0" => Ok(false),
        _ => Err("expected True or False".into()),
    }
}
