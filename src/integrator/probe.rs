//! What an estimator did at one shading point, sample by sample, for `lightlab probe`:
//! every direction it drew, with the technique's density, the MIS weight and the term it
//! added to the estimate. The estimators record into a [`Probe`] when one is given, so the
//! report shows the code that renders, not a copy of it.

use std::cell::RefCell;

use glam::Vec3;

use crate::math::Spectrum;

/// One sample drawn by an estimator.
#[derive(Clone, Debug, PartialEq)]
pub struct ProbeSample {
    /// Which estimator sample (0-based) drew it.
    pub sample: u32,
    /// The technique: `light`, `ris`, `bsdf`, or a directional estimator's name.
    pub technique: &'static str,
    /// The direction drawn (world space, unit), if the technique produced one.
    pub w_in: Option<Vec3>,
    /// The technique's density of `w_in` per steradian (for light sampling, selection
    /// probability times the light's own density); for a delta light or lobe, its
    /// discrete probability.
    pub pdf: f32,
    /// The MIS weight (1 outside MIS and for delta samples).
    pub mis_weight: f32,
    /// The term this sample added to the estimate.
    pub contribution: Spectrum,
    /// The light reached or sampled, if any (index in the scene's lights).
    pub light: Option<usize>,
    /// The point on the light, for samples that have one.
    pub light_point: Option<Vec3>,
    /// True when a shadow ray found the light sample blocked.
    pub occluded: bool,
}

/// Collects the samples of one shading point.
#[derive(Debug, Default)]
pub struct Probe {
    samples: RefCell<Vec<ProbeSample>>,
    current: RefCell<u32>,
}

impl Probe {
    /// An empty probe.
    pub fn new() -> Probe {
        Probe::default()
    }

    /// Marks the start of estimator sample `s`: later records carry that index.
    pub fn start_sample(&self, s: u32) {
        *self.current.borrow_mut() = s;
    }

    /// Records a sample (its `sample` field is set to the current estimator sample).
    pub fn record(&self, mut sample: ProbeSample) {
        sample.sample = *self.current.borrow();
        self.samples.borrow_mut().push(sample);
    }

    /// The samples recorded so far.
    pub fn samples(&self) -> Vec<ProbeSample> {
        self.samples.borrow().clone()
    }
}

/// A record of a sample that produced no direction (nothing selected, nothing sampled).
pub fn no_direction(technique: &'static str) -> ProbeSample {
    ProbeSample {
        sample: 0,
        technique,
        w_in: None,
        pdf: 0.0,
        mis_weight: 0.0,
        contribution: Spectrum::ZERO,
        light: None,
        light_point: None,
        occluded: false,
    }
}
