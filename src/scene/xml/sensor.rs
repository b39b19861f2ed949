//! The sensor (`perspective` camera, `hdrfilm` with its reconstruction filter, the
//! sampler) and the integrator, mapped to lightlab's camera and render settings with
//! Mitsuba 3's names and defaults.

use glam::Affine3A;

use super::XmlError;
use super::build::Context;
use super::props::Props;
use super::tree::Element;
use crate::image::Filter;
use crate::scene::Camera;
use crate::settings::MAX_PIXELS;
use crate::settings::{MisHeuristic, MisSettings, SamplerKind};

/// `hdrfilm`'s format properties and their values in Mitsuba 3 (hdrfilm.cpp), the
/// default first.
const FILM_FORMATS: [(&str, &[&str]); 3] = [
    (
        "pixel_format",
        &["rgb", "rgba", "luminance", "luminance_alpha", "xyz", "xyza"],
    ),
    ("component_format", &["float16", "float32", "uint32"]),
    ("file_format", &["openexr", "exr", "rgbe", "hdr", "pfm"]),
];

/// What the `<sensor>` sets up.
pub struct SensorSetup {
    pub camera: Camera,
    pub spp: u32,
    pub filter: Filter,
    pub sampler: SamplerKind,
    pub seed: u64,
}

/// `<sensor type="perspective">` with its film and sampler.
pub fn build_sensor<'a>(ctx: &mut Context<'a>, el: &'a Element) -> Result<SensorSetup, XmlError> {
    let ty = el.required("type")?;
    if ty != "perspective" {
        return Err(el.error(format!(
            "sensor type \"{ty}\" is not supported (known: perspective)"
        )));
    }
    let p = Props::new(el)?;
    let to_world = p.transform("to_world")?;
    let fov = p.float("fov", 0.0)?;
    if !p.has("fov") {
        return Err(el.error("missing <float name=\"fov\">"));
    }
    if !(fov > 0.0 && fov < 180.0) {
        return Err(p.error_at("fov", format!("fov must be in (0, 180) degrees, not {fov}")));
    }
    let axis = p.string("fov_axis", "x")?;
    let near_clip = p.float("near_clip", 0.01)?;
    let far_clip = p.float("far_clip", 1e4)?;
    if !(near_clip > 0.0 && far_clip > near_clip) {
        return Err(el.error("need 0 < near_clip < far_clip"));
    }
    let mut width = 768;
    let mut height = 576;
    let mut filter = Filter::GAUSSIAN;
    let mut spp = 4;
    let mut sampler = SamplerKind::Independent;
    let mut seed = 0;
    for c in p.nested() {
        let c = ctx.resolve(c, &["film", "sampler"])?;
        if c.tag == "film" {
            (width, height, filter) = build_film(ctx, c)?;
        } else {
            (sampler, spp, seed) = build_sampler(ctx, c)?;
        }
    }
    let (w, h) = (width as f32, height as f32);
    let tan_half = (0.5 * fov.to_radians()).tan();
    // Mitsuba converts the field of view to the x axis (perspective.cpp, parse_fov).
    let tan_x = match axis.as_str() {
        "x" => tan_half,
        "y" => tan_half * w / h,
        "diagonal" => tan_half * w / (w * w + h * h).sqrt(),
        "smaller" if w > h => tan_half * w / h,
        "smaller" => tan_half,
        "larger" if w < h => tan_half * w / h,
        "larger" => tan_half,
        other => {
            return Err(p.error_at(
                "fov_axis",
                format!("unknown fov_axis \"{other}\" (known: x, y, diagonal, smaller, larger)"),
            ));
        }
    };
    let m = Affine3A::from_mat4(to_world);
    if m.matrix3.determinant().abs() < 1e-12 {
        return Err(p.error_at("to_world", "sensor to_world is singular"));
    }
    let mut camera = Camera::new(m, 2.0 * tan_x.atan().to_degrees(), width, height);
    camera.near_clip = near_clip;
    ctx.finish(&p)?;
    Ok(SensorSetup {
        camera,
        spp,
        filter,
        sampler,
        seed,
    })
}

/// `<film type="hdrfilm">`: size and reconstruction filter.
fn build_film<'a>(ctx: &mut Context<'a>, el: &'a Element) -> Result<(u32, u32, Filter), XmlError> {
    let ty = el.required("type")?;
    if ty != "hdrfilm" {
        return Err(el.error(format!(
            "film type \"{ty}\" is not supported (known: hdrfilm)"
        )));
    }
    let p = Props::new(el)?;
    let width = p.count("width", 768, 32768)?;
    let height = p.count("height", 576, 32768)?;
    if width == 0 || height == 0 || width as u64 * height as u64 > MAX_PIXELS {
        return Err(el.error(format!(
            "image size {width}x{height} is out of range (1 to {MAX_PIXELS} pixels)"
        )));
    }
    // Checked against Mitsuba 3's hdrfilm values, then ignored: lightlab writes the
    // format that `-o` names.
    for (name, known) in FILM_FORMATS {
        let v = p.string(name, known[0])?;
        if !known.contains(&v.as_str()) {
            return Err(p.error_at(
                name,
                format!("unknown {name} \"{v}\" (known: {})", known.join(", ")),
            ));
        }
    }
    let mut filter = Filter::GAUSSIAN;
    for c in p.nested() {
        let c = ctx.resolve(c, &["rfilter"])?;
        let ty = c.required("type")?;
        let fp = Props::new(c)?;
        filter = match ty {
            "box" => Filter::Box {
                radius: fp.float("radius", 0.5)?,
            },
            "tent" => Filter::Tent {
                radius: fp.float("radius", 1.0)?,
            },
            "gaussian" => Filter::Gaussian {
                stddev: fp.float("stddev", 0.5)?,
            },
            other => {
                return Err(c.error(format!(
                    "unknown rfilter \"{other}\" (known: box, tent, gaussian)"
                )));
            }
        };
        filter.validate().map_err(|e| c.error(e))?;
        ctx.finish(&fp)?;
    }
    ctx.finish(&p)?;
    Ok((width, height, filter))
}

/// `<sampler>`: Mitsuba's samplers mapped to ours (`multijitter` → stratified,
/// `ldsampler` → sobol), `sample_count` and `seed`.
fn build_sampler<'a>(
    ctx: &mut Context<'a>,
    el: &'a Element,
) -> Result<(SamplerKind, u32, u64), XmlError> {
    let ty = el.required("type")?;
    let kind = match ty {
        "independent" => SamplerKind::Independent,
        "stratified" | "multijitter" => SamplerKind::Stratified,
        "ldsampler" => SamplerKind::Sobol,
        other => {
            return Err(el.error(format!(
                "unknown sampler \"{other}\" (known: independent, stratified, multijitter, ldsampler)"
            )));
        }
    };
    let p = Props::new(el)?;
    let spp = p.count("sample_count", 4, 1 << 20)?;
    if spp == 0 {
        return Err(p.error_at("sample_count", "sample_count must be at least 1"));
    }
    let seed = p.count("seed", 0, u32::MAX)? as u64;
    p.ignore("jitter");
    ctx.finish(&p)?;
    Ok((kind, spp, seed))
}

/// `<integrator>`: `direct` (power heuristic with `emitter_samples` light and
/// `bsdf_samples` BSDF samples, as Mitsuba 3's direct.cpp) or `path` with
/// `max_depth` 2, which is the same estimator with one sample of each.
pub fn build_integrator<'a>(
    ctx: &mut Context<'a>,
    el: &'a Element,
) -> Result<MisSettings, XmlError> {
    let ty = el.required("type")?;
    let p = Props::new(el)?;
    let mis = match ty {
        "direct" => {
            let shading = p.count("shading_samples", 1, 1024)?;
            if p.has("shading_samples") && (p.has("emitter_samples") || p.has("bsdf_samples")) {
                return Err(
                    el.error("give shading_samples or emitter_samples/bsdf_samples, not both")
                );
            }
            let light_samples = p.count("emitter_samples", shading, 1024)?;
            let bsdf_samples = p.count("bsdf_samples", shading, 1024)?;
            // Mitsuba 3 takes 0 as "skip this strategy"; lightlab's MIS estimator takes at
            // least one sample of each (the render settings refuse 0).
            for (name, n) in [
                ("shading_samples", shading),
                ("emitter_samples", light_samples),
                ("bsdf_samples", bsdf_samples),
            ] {
                if n == 0 {
                    return Err(p.error_at(
                        name,
                        format!(
                            "{name} 0 is not supported: lightlab's MIS takes at least one \
                             sample of each strategy (--estimator light or bsdf uses one alone)"
                        ),
                    ));
                }
            }
            MisSettings {
                heuristic: MisHeuristic::Power,
                light_samples,
                bsdf_samples,
                diffuse_bsdf_samples: None,
            }
        }
        "path" => {
            let depth = p.int("max_depth", -1)?;
            if depth != 2 {
                return Err(p.error_at(
                    "max_depth",
                    format!(
                        "path with max_depth {depth} is not supported: lightlab renders direct \
                     light only (max_depth 2)"
                    ),
                ));
            }
            p.ignore("rr_depth");
            MisSettings::default()
        }
        other => {
            return Err(el.error(format!(
                "integrator \"{other}\" is not supported (known: direct, path with max_depth 2)"
            )));
        }
    };
    if p.bool("hide_emitters", false)? {
        return Err(p.error_at("hide_emitters", "hide_emitters is not supported"));
    }
    ctx.finish(&p)?;
    Ok(mis)
}
