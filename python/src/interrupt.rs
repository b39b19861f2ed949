//! Long work with the GIL released that Ctrl-C still stops: the work runs on its own
//! thread while the calling thread wakes every few milliseconds, takes the GIL and runs
//! Python's signal handlers (`PyErr_CheckSignals`). A `KeyboardInterrupt` raises the
//! work's stop flag, waits for the work to end its round (so no thread outlives the
//! call) and is raised to the caller.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// How often the waiting thread looks at Python's signals.
const POLL: Duration = Duration::from_millis(10);

/// Runs `work(stop)` on a rayon pool of `threads` workers (all cores when `None`).
pub fn run<T: Send>(
    py: Python<'_>,
    threads: Option<usize>,
    work: impl FnOnce(&AtomicBool) -> T + Send,
) -> PyResult<T> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start worker threads: {e}")))?;
    let stop = AtomicBool::new(false);
    let finished = AtomicBool::new(false);
    let mut interrupted = None;
    let out = std::thread::scope(|scope| {
        let worker = scope.spawn(|| {
            let out = pool.install(|| work(&stop));
            finished.store(true, Ordering::Release);
            out
        });
        while !finished.load(Ordering::Acquire) {
            py.detach(|| {
                for _ in 0..5 {
                    if finished.load(Ordering::Acquire) {
                        break;
                    }
                    std::thread::sleep(POLL);
                }
            });
            if interrupted.is_none()
                && let Err(e) = py.check_signals()
            {
                stop.store(true, Ordering::Relaxed);
                interrupted = Some(e);
            }
        }
        worker.join()
    });
    if let Some(e) = interrupted {
        return Err(e);
    }
    out.map_err(|_| PyRuntimeError::new_err("the render panicked (a bug: please report it)"))
}
