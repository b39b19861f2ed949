//! The `lightlab` command line; everything lives in the library.

fn main() {
    std::process::exit(lightlab::cli::main());
}
