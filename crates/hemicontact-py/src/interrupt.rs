//! Long computations with the GIL released and Ctrl-C honoured: the work runs on a worker
//! thread while the calling thread, without the GIL, waits for it in slices of 50 ms; between
//! slices it takes the GIL to let Python run its signal handlers. A `KeyboardInterrupt`
//! raises the worker's stop flag, waits for it to stop (within one Newton step) and is
//! raised to the caller, leaving the interpreter usable. Python callables called by the
//! worker take the GIL themselves.

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Condvar, Mutex, PoisonError};
use std::time::Duration;

/// Runs `work` with a stop flag on a worker thread; see the module documentation.
///
/// # Errors
/// The `KeyboardInterrupt` (or other exception) of a signal handler, or a `RuntimeError` if
/// the worker panicked.
pub fn run<T: Send>(py: Python<'_>, work: impl FnOnce(&AtomicBool) -> T + Send) -> PyResult<T> {
    let stop = AtomicBool::new(false);
    let finished = (Mutex::new(false), Condvar::new());
    std::thread::scope(|scope| {
        let (stop, finished) = (&stop, &finished);
        let worker = scope.spawn(move || {
            let out = work(stop);
            *finished.0.lock().unwrap_or_else(PoisonError::into_inner) = true;
            finished.1.notify_all();
            out
        });
        let join = |worker: std::thread::ScopedJoinHandle<'_, T>| {
            worker
                .join()
                .map_err(|_| PyRuntimeError::new_err("internal error: the solver thread panicked"))
        };
        loop {
            let done = py.detach(|| {
                let guard = finished.0.lock().unwrap_or_else(PoisonError::into_inner);
                let (guard, _) = finished
                    .1
                    .wait_timeout_while(guard, Duration::from_millis(50), |done| !*done)
                    .unwrap_or_else(PoisonError::into_inner);
                *guard
            });
            if done {
                return py.detach(|| join(worker));
            }
            if let Err(signal) = py.check_signals() {
                stop.store(true, Ordering::Relaxed);
                // The worker stops within one Newton step; its result is dropped.
                let _ = py.detach(|| join(worker));
                return Err(signal);
            }
        }
    })
}
