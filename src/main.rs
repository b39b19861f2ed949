//! The `lightlab` command line; everything lives in the library.

fn main() {
    // Rust ignores SIGPIPE, so printing into a closed pipe (`lightlab diff … | head`)
    // would panic; restore the default so the process ends quietly like other Unix tools.
    #[cfg(unix)]
    // SAFETY: called first thing in main, before any thread exists; SIG_DFL is a valid
    // disposition for SIGPIPE.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    std::process::exit(lightlab::cli::main());
}
