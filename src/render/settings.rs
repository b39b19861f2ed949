//! Everything that describes a render besides the scene, complete and validated: built
//! once per render from the defaults and the [`RenderPatch`] layers over them.

use crate::image::Filter;
use crate::light::{check_sampling, sampling_summary};
use crate::scene::{Camera, Scene};
use crate::settings::{
    DEFAULT_RIS_CANDIDATES, DEFAULT_RIS_RADIUS, EstimatorKind, LightSampling, LightSelect,
    LightStrategy, MAX_PIXELS, MisHeuristic, MisSettings, Pass, RenderPatch, SamplerKind,
    SettingsError, Switch,
};

/// A complete description of how to render a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    /// Direct-lighting estimator.
    pub estimator: EstimatorKind,
    /// Heuristic and sample counts of the `mis` estimator.
    pub mis: MisSettings,
    /// Sampling strategy of area lights.
    pub light_sampling: LightSampling,
    /// Light selection.
    pub light_select: LightSelect,
    /// Candidates per light sample when `light_select` is `ris`.
    pub ris_candidates: u32,
    /// Neighbouring pixels whose reservoirs each `ris` light sample reuses (0: none).
    pub ris_spatial: u32,
    /// Radius in pixels of the disk those neighbours come from.
    pub ris_radius: u32,
    /// Random number source.
    pub sampler: SamplerKind,
    /// Samples per pixel (of the whole render, over all passes).
    pub spp: u32,
    /// Seed of every random stream.
    pub seed: u64,
    /// Image size override.
    pub resolution: Option<(u32, u32)>,
    /// Which share of the samples to render.
    pub pass: Pass,
    /// Index of every pixel's first sample (0 for a render of its own): a timed render's
    /// later rounds continue the sampler's sequence from the samples already taken, so
    /// that N samples in rounds are the same points as N in one render.
    pub first_sample: u32,
    /// Pixel reconstruction filter (the one-pixel box unless a scene file asks).
    pub filter: Filter,
    /// MIS compensation of environment-map sampling (Karlík et al. 2019); allowed only
    /// with the `mis` estimator, where it stays unbiased, and on there unless
    /// `--no-envmap-compensation` says otherwise.
    pub envmap_compensation: bool,
    /// Horizon rejection of area-light samples before the shadow ray (default on).
    pub horizon_rejection: bool,
    /// The f32 fast paths of light sampling (default on; off for the f64 reference).
    pub fast_paths: bool,
}

impl RenderSettings {
    /// The defaults for `scene`: MIS (one light and one BSDF sample, power heuristic,
    /// environment maps sampled with MIS compensation) with the best light sampling per
    /// shape, light-BVH selection and the Sobol sampler at the
    /// scene's spp, and the scene's filter, with the scene file's requests laid over them.
    pub fn for_scene(scene: &Scene) -> RenderSettings {
        Self::build(scene, &[]).expect("a scene's own requests are valid")
    }

    /// The settings for `scene`: the defaults, then the scene file's requests, then each
    /// of `layers` in order (for instance the command line, a lab strategy, an
    /// experiment's budget); a later layer wins field by field. Checks what a layer alone
    /// cannot: the image size in pixels, compensation only with `mis`, and a light
    /// sampling strategy every emitting shape of the scene has (no silent fallback).
    pub fn build(scene: &Scene, layers: &[&RenderPatch]) -> Result<RenderSettings, SettingsError> {
        let p = layers
            .iter()
            .fold(scene.requested.clone(), |acc, layer| acc.then(layer));
        p.validate()?;
        let defaults = MisSettings::default();
        let estimator = p.estimator.unwrap_or(EstimatorKind::Mis);
        let s = RenderSettings {
            estimator,
            mis: MisSettings {
                heuristic: p.mis.unwrap_or(defaults.heuristic),
                light_samples: p.light_samples.unwrap_or(defaults.light_samples),
                bsdf_samples: p.bsdf_samples.unwrap_or(defaults.bsdf_samples),
                diffuse_bsdf_samples: p.diffuse_bsdf_samples,
            },
            light_sampling: p.light_sampling.unwrap_or(LightSampling::Best),
            light_select: p.light_select.unwrap_or(LightSelect::Bvh),
            ris_candidates: p.ris_candidates.unwrap_or(DEFAULT_RIS_CANDIDATES),
            ris_spatial: p.ris_spatial.unwrap_or(0),
            ris_radius: p.ris_radius.unwrap_or(DEFAULT_RIS_RADIUS),
            sampler: p.sampler.unwrap_or(SamplerKind::Sobol),
            spp: p.spp.unwrap_or(scene.spp),
            seed: p.seed.unwrap_or(0),
            resolution: resolution(&scene.camera, p.width, p.height),
            pass: p.pass.unwrap_or(Pass::WHOLE),
            first_sample: 0,
            filter: scene.filter,
            envmap_compensation: p
                .envmap_compensation
                .unwrap_or(estimator == EstimatorKind::Mis),
            horizon_rejection: p.horizon_rejection != Some(Switch::Off),
            fast_paths: p.fast_paths != Some(Switch::Off),
        };
        if s.envmap_compensation && s.estimator != EstimatorKind::Mis {
            return Err(SettingsError::Conflict(format!(
                "--envmap-compensation is unbiased only with --estimator mis, not {}",
                s.estimator
            )));
        }
        if s.estimator == EstimatorKind::Mis
            && s.mis.heuristic == MisHeuristic::Optimal
            && s.light_select == LightSelect::Ris
        {
            return Err(SettingsError::Conflict(
                "--mis optimal does not combine with --light-select ris (a resampled light \
                 sample has no density for the control variate)"
                    .into(),
            ));
        }
        if s.estimator == EstimatorKind::Mis
            && s.mis.heuristic == MisHeuristic::Optimal
            && s.mis.diffuse_bsdf_samples.is_some()
        {
            return Err(SettingsError::Conflict(
                "--diffuse-bsdf-samples does not combine with --mis optimal (its control \
                 variate needs both techniques at every shading point)"
                    .into(),
            ));
        }
        if s.ris_spatial > 0 && (s.light_select != LightSelect::Ris || !s.samples_lights()) {
            return Err(SettingsError::Conflict(format!(
                "--ris-spatial reuses the reservoirs of --light-select ris under --estimator \
                 light or mis, not --light-select {} --estimator {}",
                s.light_select, s.estimator
            )));
        }
        if s.samples_lights() {
            check_sampling(&scene.lights, s.light_sampling)
                .map_err(|e| SettingsError::Conflict(e.to_string()))?;
        }
        if let Some((w, h)) = s.resolution
            && (w == 0 || h == 0 || w as u64 * h as u64 > MAX_PIXELS)
        {
            return Err(SettingsError::Conflict(format!(
                "--width {w} --height {h}: image size is out of range (1 to {MAX_PIXELS} pixels)"
            )));
        }
        Ok(s)
    }

    /// Whether the estimator samples lights (`light`, `mis`): only then does the light
    /// sampling strategy run.
    pub fn samples_lights(&self) -> bool {
        matches!(self.estimator, EstimatorKind::Light | EstimatorKind::Mis)
    }

    /// Per light type, which strategy runs (`lights: 1 rectangle (solid-angle)`), or how
    /// the estimator finds lights when it samples none.
    pub fn lights_summary(&self, scene: &Scene) -> String {
        if self.samples_lights() {
            let summary = sampling_summary(&scene.lights, Some(self.light_sampling));
            let strategy = self.light_strategy();
            let silent = scene
                .lights
                .iter()
                .filter(|l| l.draws_no_samples(strategy))
                .count();
            match silent {
                0 => format!("lights: {summary}"),
                1 => format!(
                    "lights: {summary}; under MIS compensation the uniform environment draws \
                     no light samples (the BSDF samples light it)"
                ),
                n => format!(
                    "lights: {summary}; under MIS compensation the {n} uniform environments \
                     draw no light samples (the BSDF samples light them)"
                ),
            }
        } else {
            let summary = sampling_summary(&scene.lights, None);
            format!(
                "lights: {summary} (not sampled: {} directions find them)",
                self.estimator
            )
        }
    }

    /// The camera with the resolution override applied.
    pub fn camera(&self, scene: &Scene) -> Camera {
        match self.resolution {
            Some((w, h)) => scene.camera.with_resolution(w, h),
            None => scene.camera.clone(),
        }
    }

    /// How lights are sampled: the per-shape strategy, and MIS compensation of the
    /// environment, which only the `mis` estimator uses.
    pub fn light_strategy(&self) -> LightStrategy {
        LightStrategy {
            sampling: self.light_sampling,
            env_compensation: self.envmap_compensation && self.estimator == EstimatorKind::Mis,
            horizon_rejection: self.horizon_rejection,
            fast_paths: self.fast_paths,
        }
    }

    /// Every setting as a patch: laid over any scene it gives these settings back (the
    /// resolution only when overridden, the pass only when partial).
    pub fn patch(&self) -> RenderPatch {
        RenderPatch {
            estimator: Some(self.estimator),
            mis: Some(self.mis.heuristic),
            light_samples: Some(self.mis.light_samples),
            bsdf_samples: Some(self.mis.bsdf_samples),
            diffuse_bsdf_samples: self.mis.diffuse_bsdf_samples,
            light_sampling: Some(self.light_sampling),
            light_select: Some(self.light_select),
            ris_candidates: (self.light_select == LightSelect::Ris).then_some(self.ris_candidates),
            ris_spatial: (self.ris_spatial > 0).then_some(self.ris_spatial),
            ris_radius: (self.ris_spatial > 0).then_some(self.ris_radius),
            sampler: Some(self.sampler),
            spp: Some(self.spp),
            seed: Some(self.seed),
            width: self.resolution.map(|r| r.0),
            height: self.resolution.map(|r| r.1),
            pass: (self.pass != Pass::WHOLE).then_some(self.pass),
            // The value in effect (only `mis` uses it), unset where it is what the
            // estimator implies: on with `mis`, off otherwise.
            envmap_compensation: (self.estimator == EstimatorKind::Mis
                && !self.envmap_compensation)
                .then_some(false),
            horizon_rejection: (!self.horizon_rejection).then_some(Switch::Off),
            fast_paths: (!self.fast_paths).then_some(Switch::Off),
        }
    }
}

/// The image size for `width`/`height` overrides: a missing side follows the camera's
/// aspect ratio; `None` keeps the camera's own size.
fn resolution(camera: &Camera, width: Option<u32>, height: Option<u32>) -> Option<(u32, u32)> {
    let (cw, ch) = (camera.width as u64, camera.height as u64);
    let follow = |given: u32, num: u64, den: u64| {
        ((given as u64 * num) / den).clamp(1, u32::MAX as u64) as u32
    };
    match (width, height) {
        (None, None) => None,
        (Some(w), None) => Some((w, follow(w, ch, cw))),
        (None, Some(h)) => Some((follow(h, cw, ch), h)),
        (Some(w), Some(h)) => Some((w, h)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene;

    /// The summary says when MIS compensation leaves a constant sky to the BSDF samples,
    /// and only then.
    #[test]
    fn the_summary_names_a_sky_that_draws_no_light_samples() {
        let scene = scene::load("tests/scenes/constant_env.xml").expect("scene");
        let mis = RenderSettings::for_scene(&scene);
        assert_eq!(mis.estimator, EstimatorKind::Mis);
        let text = mis.lights_summary(&scene);
        assert!(
            text.contains("the uniform environment draws no light samples"),
            "{text}"
        );
        let plain = RenderSettings {
            envmap_compensation: false,
            ..mis.clone()
        };
        assert!(!plain.lights_summary(&scene).contains("draws no"));
        let light = RenderSettings {
            estimator: EstimatorKind::Light,
            envmap_compensation: false,
            ..mis
        };
        assert!(!light.lights_summary(&scene).contains("draws no"));
    }

    #[test]
    fn layers_apply_in_order_and_round_trip() {
        let scene = scene::load("builtin:assignment").unwrap();
        let cli: RenderPatch = "--width 64 --seed 3 --estimator light".parse().unwrap();
        let strategy: RenderPatch = "--estimator cosine".parse().unwrap();
        let s = RenderSettings::build(&scene, &[&cli, &strategy, &RenderPatch::spp(7)]).unwrap();
        assert_eq!((s.estimator, s.seed, s.spp), (EstimatorKind::Cosine, 3, 7));
        let (cw, ch) = (scene.camera.width, scene.camera.height);
        assert_eq!(s.resolution, Some((64, 64 * ch / cw)));
        assert_eq!(RenderSettings::build(&scene, &[&s.patch()]).unwrap(), s);
        assert_eq!(
            RenderSettings::for_scene(&scene).patch().to_string(),
            "--estimator mis --mis power --light-samples 1 --bsdf-samples 1 --light-sampling best \
             --light-select bvh --sampler sobol --spp 16 --seed 0"
                .replace("--spp 16", &format!("--spp {}", scene.spp))
        );
    }

    #[test]
    fn combinations_are_checked() {
        let scene = scene::load("builtin:assignment").unwrap();
        let bad = |text: &str| {
            let p: RenderPatch = text.parse().unwrap();
            RenderSettings::build(&scene, &[&p])
                .unwrap_err()
                .to_string()
        };
        assert!(bad("--envmap-compensation --estimator light").contains("--estimator mis"));
        // Compensation: on by default with mis only, off when asked; the patch gives it back.
        let with = |text: &str| {
            let p: RenderPatch = text.parse().unwrap();
            let s = RenderSettings::build(&scene, &[&p]).unwrap();
            let again = RenderSettings::build(&scene, &[&s.patch()]).unwrap();
            assert_eq!(again.envmap_compensation, s.envmap_compensation, "{text}");
            s.envmap_compensation
        };
        assert!(with("") && with("--estimator mis") && with("--envmap-compensation"));
        assert!(!with("--no-envmap-compensation") && !with("--estimator light"));
        assert!(!with("--estimator bsdf --no-envmap-compensation"));
        // Layers: a later estimator decides the default; an explicit switch stays.
        let layered = |below: &str, above: &str| {
            let (b, a): (RenderPatch, RenderPatch) =
                (below.parse().unwrap(), above.parse().unwrap());
            RenderSettings::build(&scene, &[&b, &a])
                .unwrap()
                .envmap_compensation
        };
        assert!(!layered("--no-envmap-compensation", "--estimator mis"));
        assert!(layered("--estimator light", "--estimator mis"));
        assert!(!layered("--estimator mis", "--estimator light"));
        // Set directly on settings whose estimator does not use it: the patch says what
        // is in effect, and builds again.
        let mut s = RenderSettings::for_scene(&scene);
        s.estimator = EstimatorKind::Light;
        assert!(s.envmap_compensation);
        assert!(RenderSettings::build(&scene, &[&s.patch()]).is_ok());
        let e = bad("--diffuse-bsdf-samples 0 --mis optimal");
        assert!(
            e.contains("--diffuse-bsdf-samples") && e.contains("optimal"),
            "{e}"
        );
        // A Lambertian point's own count: unset by default (the BSDF count), zero
        // allowed, and given back by the patch.
        assert_eq!(
            RenderSettings::for_scene(&scene).mis.diffuse_bsdf_samples,
            None
        );
        let p: RenderPatch = "--diffuse-bsdf-samples 0 --bsdf-samples 2".parse().unwrap();
        let s = RenderSettings::build(&scene, &[&p]).unwrap();
        assert_eq!(
            (s.mis.bsdf_samples, s.mis.diffuse_bsdf_samples),
            (2, Some(0))
        );
        assert!(s.patch().to_string().contains("--diffuse-bsdf-samples 0"));
        assert_eq!(RenderSettings::build(&scene, &[&s.patch()]).unwrap(), s);
        let e = bad("--ris-spatial 4");
        assert!(e.contains("--ris-spatial") && e.contains("bvh"), "{e}");
        let e = bad("--ris-spatial 4 --light-select ris --estimator cosine");
        assert!(e.contains("cosine"), "{e}");
        let range = |text: &str| text.parse::<RenderPatch>().unwrap_err().to_string();
        assert!(range("--ris-spatial 33").contains("0..=32"));
        assert!(range("--ris-radius 0").contains("1..=256"));
        let spatial: RenderPatch = "--light-select ris --ris-spatial 4 --ris-radius 6"
            .parse()
            .unwrap();
        let s = RenderSettings::build(&scene, &[&spatial]).unwrap();
        assert_eq!((s.ris_spatial, s.ris_radius), (4, 6));
        assert_eq!(RenderSettings::build(&scene, &[&s.patch()]).unwrap(), s);
        assert!(bad("--width 32768 --height 32768").contains("--width 32768 --height 32768"));
        // No silent fallback: the assignment's light is a rectangle (issue 18).
        for s in ["geometric", "visible-area"] {
            let e = bad(&format!("--estimator light --light-sampling {s}"));
            assert!(e.contains(s) && e.contains("rectangle"), "{e}");
        }
        let bsdf: RenderPatch = "--estimator bsdf --light-sampling geometric"
            .parse()
            .unwrap();
        assert!(RenderSettings::build(&scene, &[&bsdf]).is_ok());
    }
}
