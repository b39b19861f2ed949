//! Built-in scenes: each is a figure the lecture draws, so students can reproduce it.

mod assignment;
mod materials;

use super::{Scene, SceneError};

/// A built-in scene: its name, what it shows, and its builder.
pub struct Builtin {
    /// Name after `builtin:`.
    pub name: &'static str,
    /// One line on what the scene shows.
    pub description: &'static str,
    /// Builds the scene.
    pub build: fn() -> Result<Scene, SceneError>,
}

/// Every built-in scene; the first is the default scene.
pub const BUILTINS: &[Builtin] = &[
    Builtin {
        name: "assignment",
        description: "one small area light over diffuse and Phong (n = 10, 100, 1000) spheres: hemisphere vs BRDF vs light sampling",
        build: assignment::build,
    },
    Builtin {
        name: "materials",
        description: "smooth and rough conductors and plastics (Mitsuba 3's models) under one area light",
        build: materials::build,
    },
];

/// The scene `render` draws when none is given.
pub const DEFAULT_SCENE: &str = "builtin:assignment";

/// Builds the built-in scene `name`.
pub fn build(name: &str) -> Result<Scene, SceneError> {
    match BUILTINS.iter().find(|b| b.name == name) {
        Some(b) => (b.build)(),
        None => {
            let known: Vec<_> = BUILTINS.iter().map(|b| b.name).collect();
            Err(SceneError::new(
                format!("builtin:{name}"),
                None,
                format!("unknown built-in scene (known: {})", known.join(", ")),
            ))
        }
    }
}
