//! Tabulated and generic distributions: the lecture's "stacked rectangles" (a 1D
//! piecewise-constant pdf, sampled through its CDF), its 2D marginal–conditional form,
//! Vose's alias table, rejection sampling under a bound, and numerical inversion of a
//! monotone CDF.
//!
//! Zero-weight bins are never chosen. A table whose weights are all zero falls back to
//! the uniform distribution (documented on each type); negative or non-finite weights
//! are an error.

pub mod alias;
pub mod inversion;
pub mod marginal_conditional;
pub mod piecewise_constant;
pub mod rejection;

pub use alias::AliasTable;
pub use inversion::sample_by_inversion;
pub use marginal_conditional::PiecewiseConstant2D;
pub use piecewise_constant::PiecewiseConstant1D;
pub use rejection::RejectionSampler;

/// Why a table of weights cannot become a distribution.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DistributionError {
    /// No weights at all.
    #[error("a distribution needs at least one weight")]
    Empty,
    /// A weight is negative, NaN or infinite.
    #[error("weight {index} is {value}: weights must be finite and non-negative")]
    BadWeight {
        /// Position of the offending weight.
        index: usize,
        /// Its value.
        value: f32,
    },
    /// `width × height` does not match the number of weights.
    #[error("{len} weights do not form a {width}×{height} table")]
    Shape {
        /// Number of weights given.
        len: usize,
        /// Requested columns.
        width: usize,
        /// Requested rows.
        height: usize,
    },
}

/// Checks that `weights` is non-empty, finite and non-negative.
pub(crate) fn check_weights(weights: &[f32]) -> Result<(), DistributionError> {
    if weights.is_empty() {
        return Err(DistributionError::Empty);
    }
    match weights.iter().position(|w| !(w.is_finite() && *w >= 0.0)) {
        Some(index) => Err(DistributionError::BadWeight {
            index,
            value: weights[index],
        }),
        None => Ok(()),
    }
}
