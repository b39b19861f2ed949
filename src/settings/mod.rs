//! The strategy vocabulary: every choice a render can make, as typed values with one
//! command-line name each (DESIGN: "strategies are data").
//!
//! This module sits below every other layer that talks about strategies (`light`,
//! `integrator`, `scene`, `render`, `lab`, `cli`) and depends on none of them: a scene
//! names the settings it asks for, a lab strategy is a label and a [`RenderPatch`], and the
//! command line parses into the same patch. `render::RenderSettings` is the complete,
//! validated result of layering patches over the defaults.

mod pass;
mod patch;

pub use pass::{Pass, SampleBlock};
pub use patch::{MAX_MIS_SAMPLES, MAX_PIXELS, MAX_SIDE, RenderPatch, SettingsError};

named_enum! {
    /// The direct-lighting strategy, by CLI name.
    pub enum EstimatorKind: "estimator" {
        /// Uniform directions by (z, φ), weight 2π.
        Hemisphere => "hemisphere",
        /// Uniform directions by rejection from the cube [-1, 1]³.
        HemisphereRejection => "hemisphere-rejection",
        /// Cosine-weighted directions (Malley's method).
        Cosine => "cosine",
        /// The BSDF's own `sample`.
        Bsdf => "bsdf",
        /// A point on a light (area form), one shadow ray.
        Light => "light",
        /// Light and BSDF sampling combined by multiple importance sampling.
        Mis => "mis",
        /// Lecture only, deliberately biased: uniform (θ, φ) weighted by 2π as if the
        /// directions were uniform ("1st try: polar coordinates … biased result, more
        /// samples towards the poles"); the true density is 1/(π² sin θ).
        HemisphereThetaPhi => "hemisphere-theta-phi",
    }
}

impl EstimatorKind {
    /// Whether the estimator converges to the right answer (all but the lecture's
    /// deliberately biased `hemisphere-theta-phi`).
    pub fn is_unbiased(self) -> bool {
        self != EstimatorKind::HemisphereThetaPhi
    }

    /// Every unbiased estimator, in CLI order: what tests and benchmarks run.
    pub fn unbiased() -> impl Iterator<Item = EstimatorKind> {
        EstimatorKind::ALL.into_iter().filter(|k| k.is_unbiased())
    }
}

named_enum! {
    /// A setting that is on or off (`--horizon-rejection on|off`).
    pub enum Switch: "switch" {
        /// On.
        On => "on",
        /// Off.
        Off => "off",
    }
}

named_enum! {
    /// How the `mis` estimator combines light and BSDF sampling.
    pub enum MisHeuristic: "MIS heuristic" {
        /// Multi-sample model, balance heuristic.
        Balance => "balance",
        /// Multi-sample model, power heuristic with β = 2.
        Power => "power",
        /// One-sample model: pick light or BSDF sampling at random, weight by the balance
        /// heuristic.
        OneSample => "one-sample",
        /// Multi-sample model, optimal weights (Kondapaneni et al. 2019): the balance
        /// heuristic plus a per-pixel control variate from earlier rounds' samples.
        Optimal => "optimal",
    }
}

named_enum! {
    /// How an area light draws its samples. Named as on the command line. A render
    /// refuses a strategy that one of the scene's shapes lacks (`light::check_sampling`);
    /// `best` resolves per shape (`LightSampling::resolve` in the `light` module).
    pub enum LightSampling: "light sampling" {
        /// Uniform over the shape's area (lecture p₁ = 1/A), with horizon rejection before
        /// the shadow ray.
        Area => "area",
        /// Spheres: uniform over the cap visible from the shading point (lecture p₂).
        VisibleArea => "visible-area",
        /// Uniform in the solid angle the shape subtends: cone (sphere, lecture p₃),
        /// spherical rectangle (Ureña et al. 2013), spherical triangle (Arvo 1995),
        /// spherical triangles of a polygon's triangulation.
        SolidAngle => "solid-angle",
        /// Spheres: ∝ cos θx·cos θy/d² (lecture p₄), i.e. ∝ cos θx in solid angle.
        Geometric => "geometric",
        /// Rectangles, triangles and polygons: solid-angle sampling after a bilinear warp
        /// of the square weighted by cos θ at the corners (Hart et al. 2020), ≈ ∝ cos θx.
        SolidAngleCos => "solid-angle-cos",
        /// Rectangles, triangles and polygons: exactly ∝ cos θx over the part above the
        /// horizon (projected solid angle; after Peters 2021), so an unoccluded constant
        /// emitter over a Lambertian receiver gives every sample the same value.
        ProjectedSolidAngle => "projected-solid-angle",
        /// Per shape, the strategy of lowest measured relMSE × time (solid angle on most
        /// shapes; area on disks, small triangles and textured rectangles and disks;
        /// `LightSampling::resolve`).
        Best => "best",
    }
}

named_enum! {
    /// Light selection strategy, by CLI name.
    pub enum LightSelect: "light selection" {
        /// i = ⌊ξ·n⌋ (lecture solution #1); among the lights that draw samples when some
        /// draw none (a compensated constant sky: an alias table of equal weights).
        Uniform => "uniform",
        /// ∝ emitted power Φ, by an alias table (lecture solution #2).
        Power => "power",
        /// ∝ a per-point contribution estimate with a floor, O(n) (lecture solution #3).
        Adaptive => "adaptive",
        /// A light BVH with importance from distance and orientation bounds, O(log n)
        /// (Conty Estevez & Kulla 2018).
        Bvh => "bvh",
        /// Resampled importance sampling (Talbot et al. 2005): `--ris-candidates` light
        /// samples drawn with the light BVH, one kept ∝ its unshadowed contribution
        /// f·cos·Le.
        Ris => "ris",
    }
}

/// Candidates per light sample of `--light-select ris` when none is given: the best of
/// 2, 4 and 8 at equal time on `shirley-100` and `many-lights?n=1000` (BENCHMARKS.md;
/// one candidate is the `bvh` estimator with a target evaluation more per sample).
pub const DEFAULT_RIS_CANDIDATES: u32 = 2;
/// The most candidates `--light-select ris` draws per light sample.
pub const MAX_RIS_CANDIDATES: u32 = 64;
/// The most neighbouring pixels `--ris-spatial K` reuses reservoirs from.
pub const MAX_RIS_SPATIAL: u32 = 32;
/// Radius in pixels of the disk `--ris-spatial` picks neighbours in when none is given.
pub const DEFAULT_RIS_RADIUS: u32 = 10;
/// The largest `--ris-radius`.
pub const MAX_RIS_RADIUS: u32 = 256;

named_enum! {
    /// Which sampler a render uses; parsed from and shown as its CLI name.
    pub enum SamplerKind: "sampler" {
        /// Independent uniform numbers from PCG32.
        Independent => "independent",
        /// Jittered strata in every dimension, decorrelated across dimensions by permutation.
        Stratified => "stratified",
        /// Owen-scrambled Sobol points (Burley 2020, "Practical Hash-based Owen Scrambling").
        Sobol => "sobol",
    }
}

/// How the `mis` estimator spends and weights its samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MisSettings {
    /// Weighting heuristic or the one-sample model.
    pub heuristic: MisHeuristic,
    /// Light samples per estimate (N).
    pub light_samples: u32,
    /// BSDF samples per estimate (M).
    pub bsdf_samples: u32,
    /// BSDF samples per estimate at shading points whose material is Lambertian, where
    /// light samples alone reach every emitter (some light draws samples, and the scene
    /// has no environment); `None`: `bsdf_samples` there too. Zero leaves such points to
    /// the light samples alone, with weight 1: the light estimator there. Not under
    /// optimal weights.
    pub diffuse_bsdf_samples: Option<u32>,
}

impl Default for MisSettings {
    /// One light and one BSDF sample, power heuristic (Veach's recommendation).
    fn default() -> Self {
        MisSettings {
            heuristic: MisHeuristic::Power,
            light_samples: 1,
            bsdf_samples: 1,
            diffuse_bsdf_samples: None,
        }
    }
}

/// How lights are sampled during one render: the per-shape strategy and whether an
/// environment map samples with MIS compensation. It travels with the estimator to
/// every `Light::sample` and `Light::pdf` call, so a render never copies the scene to
/// change it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightStrategy {
    /// Per-shape strategy name (resolved per shape by the light).
    pub sampling: LightSampling,
    /// MIS compensation of environment-map sampling (Karlík et al. 2019).
    pub env_compensation: bool,
    /// Area lights: drop samples below the shading point's horizon before the shadow ray
    /// (lecture, "lights below the horizon"); off traces the shadow ray first, as the
    /// naive loop does, for the same image.
    pub horizon_rejection: bool,
    /// Sample with the renderer's f32 fast paths where a shape has one (rectangles
    /// under `solid-angle`); off, every light uses the readable f64 implementation the
    /// fast paths are tested against.
    pub fast_paths: bool,
}

impl Default for LightStrategy {
    /// `best` per shape, no compensation.
    fn default() -> Self {
        LightStrategy {
            sampling: LightSampling::Best,
            env_compensation: false,
            horizon_rejection: true,
            fast_paths: true,
        }
    }
}

impl From<LightSampling> for LightStrategy {
    fn from(sampling: LightSampling) -> Self {
        LightStrategy {
            sampling,
            env_compensation: false,
            horizon_rejection: true,
            fast_paths: true,
        }
    }
}
