//! Errors of lab experiments: a scene or strategy this build cannot make, bad input, or
//! a file that could not be written.

use crate::image::io::ImageError;
use crate::lab::strategy::StrategyError;
use crate::scene::SceneError;

/// Why an experiment could not run.
#[derive(Debug, thiserror::Error)]
pub enum LabError {
    /// The scene does not load (for a built-in: not built yet, or a typo).
    #[error("{error}")]
    Scene {
        /// The scene as given.
        spec: String,
        /// The loader's error.
        error: SceneError,
    },
    /// A strategy's flags do not parse in this build.
    #[error("strategy \"{label}\" (`{flags}`): {error}")]
    Strategy {
        /// The strategy's label.
        label: String,
        /// Its flags.
        flags: String,
        /// What the parser said.
        error: StrategyError,
    },
    /// Bad input (sizes that do not match, an empty list, ...).
    #[error("{0}")]
    Input(String),
    /// An image or report file could not be read or written.
    #[error(transparent)]
    Io(#[from] ImageError),
}

impl LabError {
    /// What is missing, when the error is a scene or strategy this build lacks:
    /// "scene `builtin:veach-mis`", "estimator `mis`".
    pub fn missing(&self) -> Option<String> {
        match self {
            LabError::Scene { spec, .. } => Some(format!("scene `{spec}`")),
            LabError::Strategy { error, .. } => Some(error.missing()),
            _ => None,
        }
    }
}
