//! The sensor (camera, sampler, film, filter) and the integrator of an export, as
//! Mitsuba 3's `perspective`, `hdrfilm` and `direct` read them.

use std::fmt::Write as _;

use glam::Mat4;

use super::UNREADABLE;
use super::text::{float, integer, matrix};
use crate::image::Filter;
use crate::sampling::SamplerKind;
use crate::scene::Scene;
use crate::settings::{MisHeuristic, RenderPatch};

/// `<integrator type="direct">` with the sample counts the scene asks for.
pub fn integrator(x: &mut String, requested: &RenderPatch) -> Result<(), String> {
    let rest = RenderPatch {
        sampler: None,
        seed: None,
        mis: None,
        light_samples: None,
        bsdf_samples: None,
        ..requested.clone()
    };
    if rest != RenderPatch::default() {
        return Err(format!(
            "the scene asks for render settings a Mitsuba file cannot hold: {rest}"
        ));
    }
    if requested.mis.is_some_and(|h| h != MisHeuristic::Power) {
        return Err(format!(
            "the scene asks for --mis {}; Mitsuba's `direct` integrator has the power heuristic \
             only",
            requested.mis.map_or("", |h| h.name())
        ));
    }
    let counts = [
        ("emitter_samples", requested.light_samples),
        ("bsdf_samples", requested.bsdf_samples),
    ];
    if counts.iter().all(|(_, n)| n.is_none()) {
        x.push_str("    <integrator type=\"direct\"/>\n");
        return Ok(());
    }
    x.push_str("    <integrator type=\"direct\">\n");
    for (name, n) in counts {
        if let Some(n) = n {
            integer(x, 2, name, n);
        }
    }
    x.push_str("    </integrator>\n");
    Ok(())
}

/// The perspective sensor with its sampler and film; what Mitsuba 3 would read
/// differently goes to `notes`.
pub fn sensor(x: &mut String, scene: &Scene, notes: &mut Vec<String>) -> Result<(), String> {
    let camera = &scene.camera;
    x.push_str("    <sensor type=\"perspective\">\n");
    float(x, 2, "fov", camera.fov_x_degrees());
    let _ = writeln!(x, "        <string name=\"fov_axis\" value=\"x\"/>");
    float(x, 2, "near_clip", camera.near_clip);
    matrix(x, 2, &Mat4::from(camera.to_world()));
    // Unset, lightlab's default sampler (Sobol) renders a built-in scene; `ldsampler` is
    // the name the loader reads as Sobol and Mitsuba's own low-discrepancy sampler.
    let sampler = match scene.requested.sampler.unwrap_or(SamplerKind::Sobol) {
        SamplerKind::Independent => "independent",
        SamplerKind::Stratified => "stratified",
        SamplerKind::Sobol => "ldsampler",
    };
    let _ = writeln!(x, "        <sampler type=\"{sampler}\">");
    integer(x, 3, "sample_count", scene.spp);
    let n = scene.spp;
    let rounded = mitsuba_sample_count(sampler, n);
    if rounded != n {
        notes.push(format!(
            "Mitsuba 3's {sampler} renders the {n} samples per pixel as {rounded}"
        ));
    }
    if let Some(seed) = scene.requested.seed {
        let seed = u32::try_from(seed).map_err(|_| format!("seed {seed} is above 2^32 − 1"))?;
        integer(x, 3, "seed", seed);
    }
    x.push_str("        </sampler>\n");
    x.push_str("        <film type=\"hdrfilm\">\n");
    integer(x, 3, "width", camera.width);
    integer(x, 3, "height", camera.height);
    match scene.filter {
        // Mitsuba 3's box is the one-pixel box and takes no radius.
        Filter::Box { radius: 0.5 } => {
            x.push_str("            <rfilter type=\"box\"/>\n");
        }
        Filter::Box { radius } => {
            notes.push(format!(
                "{UNREADABLE}its box filter takes no radius (radius {radius} here, which \
                 lightlab reads)"
            ));
            rfilter(x, "box", "radius", radius);
        }
        Filter::Tent { radius } => rfilter(x, "tent", "radius", radius),
        Filter::Gaussian { stddev } => rfilter(x, "gaussian", "stddev", stddev),
    }
    x.push_str("        </film>\n");
    x.push_str("    </sensor>\n");
    Ok(())
}

/// The sample count Mitsuba 3's `sampler` renders when asked for `n`: `ldsampler` keeps
/// the square of a power of two, at least 4 (its `set_sample_count`: res = 2, then the
/// next power of two above res while res² < n); `stratified` the square of ⌈√n⌉.
fn mitsuba_sample_count(sampler: &str, n: u32) -> u32 {
    let n = u64::from(n);
    let rounded = match sampler {
        "ldsampler" => {
            let mut res = 2u64;
            while res * res < n {
                res = (res + 1).next_power_of_two();
            }
            res * res
        }
        "stratified" => {
            let mut res = (n as f64).sqrt() as u64;
            while res * res < n {
                res += 1;
            }
            res * res
        }
        _ => n,
    };
    u32::try_from(rounded).unwrap_or(u32::MAX)
}

/// `<rfilter type="name">` with one parameter.
fn rfilter(x: &mut String, name: &str, param: &str, value: f32) {
    let _ = writeln!(x, "            <rfilter type=\"{name}\">");
    float(x, 4, param, value);
    x.push_str("            </rfilter>\n");
}

#[cfg(test)]
mod tests {
    use super::mitsuba_sample_count;

    #[test]
    fn mitsuba_rounds_sample_counts_as_its_samplers_do() {
        let ld = [
            (1, 4),
            (2, 4),
            (4, 4),
            (8, 16),
            (16, 16),
            (49, 64),
            (128, 256),
            (8192, 16384),
        ];
        for (n, m) in ld {
            assert_eq!(mitsuba_sample_count("ldsampler", n), m, "ldsampler {n}");
        }
        for (n, m) in [(1, 1), (2, 4), (9, 9), (10, 16), (49, 49), (50, 64)] {
            assert_eq!(mitsuba_sample_count("stratified", n), m, "stratified {n}");
        }
        assert_eq!(mitsuba_sample_count("independent", 7), 7);
    }
}
