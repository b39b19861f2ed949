//! `lightlab scenes`: the built-in scenes, one per line (name, then what it shows).

use super::CliError;
use crate::scene::builtin::BUILTINS;

/// Runs `scenes`.
pub fn run() -> Result<(), CliError> {
    for b in BUILTINS {
        println!("builtin:{:<20} {}", b.name, b.description);
    }
    Ok(())
}
