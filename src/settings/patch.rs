//! A typed patch of render settings: every field optional, so the command line, a scene
//! file, a lab strategy and an experiment's budget each say only what they change, and
//! patches layer in order (later wins). The flag names are the command-line contract of
//! `crate::names::flag`; [`RenderPatch`]'s `Display` writes the canonical flags and its
//! `FromStr` reads them back, with no command-line library involved.

use std::fmt;
use std::str::FromStr;

use super::{
    EstimatorKind, LightSampling, LightSelect, MAX_RIS_CANDIDATES, MAX_RIS_RADIUS, MAX_RIS_SPATIAL,
    MisHeuristic, Pass, SamplerKind, Switch,
};
use crate::names::flag;

/// The most samples per estimate the `mis` estimator takes per strategy.
pub const MAX_MIS_SAMPLES: u32 = 1024;
/// The longest image side a render accepts.
pub const MAX_SIDE: u32 = 32768;
/// The most pixels a render accepts (8192²): the film keeps about 40 bytes per pixel.
pub const MAX_PIXELS: u64 = 1 << 26;

/// Why a patch or a set of settings is rejected. Always names the flag it is about.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SettingsError {
    /// A flag this build does not have.
    #[error("unknown flag `--{0}` (known: {known})", known = known_flags())]
    UnknownFlag(String),
    /// A flag's value does not parse or is out of range.
    #[error("--{flag} {value}: {message}")]
    BadValue {
        /// The flag, without `--`.
        flag: String,
        /// The value as given.
        value: String,
        /// What is wrong with it.
        message: String,
    },
    /// A flag that takes a value was the last word.
    #[error("--{0} needs a value")]
    MissingValue(String),
    /// Settings that do not fit together (the message names the flags).
    #[error("{0}")]
    Conflict(String),
}

impl SettingsError {
    fn bad(flag: &str, value: impl ToString, message: impl ToString) -> SettingsError {
        SettingsError::BadValue {
            flag: flag.to_string(),
            value: value.to_string(),
            message: message.to_string(),
        }
    }
}

/// Declares [`RenderPatch`] from one table of (field, type, flag, help): the struct, its
/// flag list, the setter by flag name, layering and the canonical flags.
macro_rules! render_patch {
    ($( #[doc = $doc:literal] $field:ident : $ty:ty = $flag:path ),+ $(,)?) => {
        /// Render settings that a layer (scene, command line, strategy, budget) changes;
        /// `None` keeps what the layers below say.
        #[derive(Clone, Debug, Default, PartialEq, Eq)]
        pub struct RenderPatch {
            $( #[doc = $doc] pub $field: Option<$ty>, )+
            /// MIS compensation of environment-map sampling (Karlík et al. 2019): the
            /// switches `--envmap-compensation` (true) and `--no-envmap-compensation`
            /// (false) on the command line; unset, it is on exactly with `mis`.
            pub envmap_compensation: Option<bool>,
        }

        impl RenderPatch {
            /// Every flag that takes a value, as (name without `--`, help), in canonical
            /// order.
            pub const VALUE_FLAGS: &'static [(&'static str, &'static str)] =
                &[$(($flag, $doc.trim_ascii())),+];

            /// Sets the field of flag `name` (without `--`) from its command-line text.
            pub fn set(&mut self, name: &str, value: &str) -> Result<(), SettingsError> {
                $(
                    if name == $flag {
                        let v = value
                            .trim()
                            .parse::<$ty>()
                            .map_err(|e| SettingsError::bad(name, value, e))?;
                        self.$field = Some(v);
                        return self.validate();
                    }
                )+
                if name == flag::ENVMAP_COMPENSATION || name == flag::NO_ENVMAP_COMPENSATION {
                    return Err(SettingsError::bad(name, value, "is a switch and takes no value"));
                }
                Err(SettingsError::UnknownFlag(name.to_string()))
            }

            /// This patch with `later`'s fields laid over it.
            pub fn then(&self, later: &RenderPatch) -> RenderPatch {
                RenderPatch {
                    $( $field: later.$field.or(self.$field), )+
                    envmap_compensation: later.envmap_compensation.or(self.envmap_compensation),
                }
            }
        }

        impl fmt::Display for RenderPatch {
            /// The canonical flags, in table order, switches last (`--estimator light
            /// --spp 16`).
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                let mut words: Vec<String> = Vec::new();
                $( if let Some(v) = &self.$field { words.push(format!("--{} {v}", $flag)); } )+
                match self.envmap_compensation {
                    Some(true) => words.push(format!("--{}", flag::ENVMAP_COMPENSATION)),
                    Some(false) => words.push(format!("--{}", flag::NO_ENVMAP_COMPENSATION)),
                    None => {}
                }
                f.write_str(&words.join(" "))
            }
        }
    };
}

render_patch! {
    /// Direct-lighting estimator: hemisphere, hemisphere-rejection, cosine, bsdf, light, mis.
    estimator: EstimatorKind = flag::ESTIMATOR,
    /// MIS weighting: balance, power (β = 2), one-sample (balance, one strategy per sample), optimal (Kondapaneni et al. 2019: balance plus a per-pixel control variate; not with `--light-select ris`).
    mis: MisHeuristic = flag::MIS,
    /// Light samples per estimate of the `mis` estimator (1 to 1024).
    light_samples: u32 = flag::LIGHT_SAMPLES,
    /// BSDF samples per estimate of the `mis` estimator (1 to 1024).
    bsdf_samples: u32 = flag::BSDF_SAMPLES,
    /// BSDF samples of the `mis` estimator at Lambertian shading points (0 to 1024; default: --bsdf-samples); 0 leaves them to light samples alone (not in scenes with a sky; not with --mis optimal).
    diffuse_bsdf_samples: u32 = flag::DIFFUSE_BSDF_SAMPLES,
    /// Area-light sampling: area, visible-area, solid-angle, geometric, solid-angle-cos, projected-solid-angle, best (per shape).
    light_sampling: LightSampling = flag::LIGHT_SAMPLING,
    /// Light selection among many lights: uniform, power, adaptive, bvh, ris.
    light_select: LightSelect = flag::LIGHT_SELECT,
    /// Candidates per light sample of `--light-select ris` (1 to 64, default 2).
    ris_candidates: u32 = flag::RIS_CANDIDATES,
    /// Spatial reuse of `--light-select ris` reservoirs: K neighbouring pixels per sample (0 = off, up to 32; Bitterli et al. 2020, neighbours combined with pairwise MIS weights; estimators light and mis).
    ris_spatial: u32 = flag::RIS_SPATIAL,
    /// Radius in pixels of the disk `--ris-spatial` draws its neighbours from (1 to 256, default 10).
    ris_radius: u32 = flag::RIS_RADIUS,
    /// Sampler: independent, stratified, sobol.
    sampler: SamplerKind = flag::SAMPLER,
    /// Samples per pixel (default: the scene's).
    spp: u32 = flag::SPP,
    /// Seed of every random stream.
    seed: u64 = flag::SEED,
    /// Image width (height follows the scene's aspect unless given).
    width: u32 = flag::WIDTH,
    /// Image height (width follows the scene's aspect unless given).
    height: u32 = flag::HEIGHT,
    /// Render only pass I of N of the samples (`2/8`).
    pass: Pass = flag::PASS,
    /// Area lights: reject samples below the horizon before the shadow ray: on (default), off.
    horizon_rejection: Switch = flag::HORIZON_REJECTION,
    /// The renderer's f32 fast paths for light sampling: on (default), off (the readable f64 implementations they are tested against).
    fast_paths: Switch = flag::FAST_PATHS,
}

/// The known flags, for error messages.
fn known_flags() -> String {
    let mut all: Vec<String> = RenderPatch::VALUE_FLAGS
        .iter()
        .map(|(f, _)| format!("--{f}"))
        .collect();
    all.push(format!("--{}", flag::ENVMAP_COMPENSATION));
    all.push(format!("--{}", flag::NO_ENVMAP_COMPENSATION));
    all.join(", ")
}

impl RenderPatch {
    /// A patch that sets only the spp (an experiment's equal-spp budget).
    pub fn spp(spp: u32) -> RenderPatch {
        RenderPatch {
            spp: Some(spp),
            ..Default::default()
        }
    }

    /// True when no field is set.
    pub fn is_empty(&self) -> bool {
        *self == RenderPatch::default()
    }

    /// Checks each set field's range on its own (combinations are checked when the
    /// settings are resolved).
    pub fn validate(&self) -> Result<(), SettingsError> {
        let ranges = [
            (flag::LIGHT_SAMPLES, self.light_samples, 1, MAX_MIS_SAMPLES),
            (flag::BSDF_SAMPLES, self.bsdf_samples, 1, MAX_MIS_SAMPLES),
            (
                flag::DIFFUSE_BSDF_SAMPLES,
                self.diffuse_bsdf_samples,
                0,
                MAX_MIS_SAMPLES,
            ),
            (
                flag::RIS_CANDIDATES,
                self.ris_candidates,
                1,
                MAX_RIS_CANDIDATES,
            ),
            (flag::RIS_SPATIAL, self.ris_spatial, 0, MAX_RIS_SPATIAL),
            (flag::RIS_RADIUS, self.ris_radius, 1, MAX_RIS_RADIUS),
            (flag::SPP, self.spp, 1, u32::MAX),
            (flag::WIDTH, self.width, 1, MAX_SIDE),
            (flag::HEIGHT, self.height, 1, MAX_SIDE),
        ];
        for (name, value, lo, hi) in ranges {
            if let Some(v) = value
                && !(lo..=hi).contains(&v)
            {
                let range = if hi == u32::MAX {
                    format!("must be at least {lo}")
                } else {
                    format!("must be in {lo}..={hi}")
                };
                return Err(SettingsError::bad(name, v, range));
            }
        }
        Ok(())
    }
}

impl FromStr for RenderPatch {
    type Err = SettingsError;

    /// Reads flags as on the command line (`--estimator light --spp=16
    /// --envmap-compensation`); a flag given twice keeps its last value.
    fn from_str(text: &str) -> Result<RenderPatch, SettingsError> {
        let mut patch = RenderPatch::default();
        let mut words = text.split_whitespace();
        while let Some(word) = words.next() {
            let Some(name) = word.strip_prefix("--") else {
                return Err(SettingsError::Conflict(format!(
                    "expected a flag (--NAME), not \"{word}\""
                )));
            };
            let (name, inline) = match name.split_once('=') {
                Some((n, v)) => (n, Some(v)),
                None => (name, None),
            };
            if name == flag::ENVMAP_COMPENSATION || name == flag::NO_ENVMAP_COMPENSATION {
                if let Some(v) = inline {
                    return Err(SettingsError::bad(
                        name,
                        v,
                        "is a switch and takes no value",
                    ));
                }
                patch.envmap_compensation = Some(name == flag::ENVMAP_COMPENSATION);
                continue;
            }
            if !RenderPatch::VALUE_FLAGS.iter().any(|(f, _)| *f == name) {
                return Err(SettingsError::UnknownFlag(name.to_string()));
            }
            let value = match inline {
                Some(v) => v,
                None => words
                    .next()
                    .ok_or_else(|| SettingsError::MissingValue(name.to_string()))?,
            };
            patch.set(name, value)?;
        }
        Ok(patch)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flags_round_trip_in_canonical_order() {
        let text =
            "--spp 16 --estimator light --envmap-compensation --pass 2/8 --light-sampling=area";
        let patch: RenderPatch = text.parse().unwrap();
        assert_eq!(patch.spp, Some(16));
        assert_eq!(patch.pass, Some(Pass { index: 1, count: 8 }));
        let canonical = patch.to_string();
        assert_eq!(
            canonical,
            "--estimator light --light-sampling area --spp 16 --pass 2/8 --envmap-compensation"
        );
        assert_eq!(canonical.parse::<RenderPatch>().unwrap(), patch);
        assert_eq!("".parse::<RenderPatch>().unwrap(), RenderPatch::default());
        // The opposite switch: the last one given wins, and it prints back.
        let off: RenderPatch = "--envmap-compensation --no-envmap-compensation"
            .parse()
            .unwrap();
        assert_eq!(off.envmap_compensation, Some(false));
        assert_eq!(off.to_string(), "--no-envmap-compensation");
    }

    #[test]
    fn later_layers_win_field_by_field() {
        let base: RenderPatch = "--width 64 --seed 3".parse().unwrap();
        let strategy: RenderPatch = "--estimator cosine --seed 5".parse().unwrap();
        let both = base.then(&strategy);
        assert_eq!((both.width, both.seed), (Some(64), Some(5)));
        assert_eq!(both.estimator, Some(EstimatorKind::Cosine));
        assert_eq!(base.then(&RenderPatch::default()), base);
    }

    #[test]
    fn errors_name_the_flag() {
        let cases = [
            ("--spp -1", "--spp -1"),
            ("--spp 0", "--spp 0: must be at least 1"),
            ("--seed -1", "--seed -1"),
            ("--estimator nope", "unknown estimator \"nope\""),
            (
                "--light-samples 2000",
                "--light-samples 2000: must be in 1..=1024",
            ),
            (
                "--diffuse-bsdf-samples 1025",
                "--diffuse-bsdf-samples 1025: must be in 0..=1024",
            ),
            ("--width 0", "--width 0"),
            ("--no-such 3", "unknown flag `--no-such`"),
            ("--spp", "--spp needs a value"),
            ("--envmap-compensation=1", "--envmap-compensation 1"),
            ("--no-envmap-compensation=1", "--no-envmap-compensation 1"),
            ("spp 3", "expected a flag"),
        ];
        for (text, words) in cases {
            let e = text.parse::<RenderPatch>().unwrap_err().to_string();
            assert!(e.contains(words), "{text}: {e}");
        }
    }
}
