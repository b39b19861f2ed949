//! Errors of lab experiments: a scene or strategy that cannot be made, bad input, or a
//! file that could not be written.

use crate::image::io::ImageError;
use crate::scene::SceneError;
use crate::settings::SettingsError;

/// Why an experiment could not run.
#[derive(Debug, thiserror::Error)]
pub enum LabError {
    /// The scene does not load.
    #[error("{error}")]
    Scene {
        /// The scene as given.
        spec: String,
        /// The loader's error.
        error: SceneError,
    },
    /// A strategy's settings do not fit the scene or each other.
    #[error("strategy \"{label}\" (`{flags}`): {error}")]
    Strategy {
        /// The strategy's label.
        label: String,
        /// Its flags.
        flags: String,
        /// What is wrong.
        error: SettingsError,
    },
    /// Bad input (sizes that do not match, an empty list, ...).
    #[error("{0}")]
    Input(String),
    /// An image or report file could not be read or written.
    #[error(transparent)]
    Io(#[from] ImageError),
}
