//! Images: the film that accumulates samples (count, mean, running variance), file
//! input/output (EXR with variance, PNG, PFM) with size limits on input, error metrics
//! against a reference, and a live view in the tev viewer.

pub mod film;
pub mod filter;
pub mod io;
pub mod limits;
pub mod metrics;
pub mod output;
pub mod tev;

pub use film::{Film, PixelStats};
pub use filter::Filter;
