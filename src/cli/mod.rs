//! Command-line subcommands, one file each. The binary wires them into its clap parser.

pub mod warp;
