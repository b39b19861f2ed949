//! 1D variance.
