//! Running a render with the GIL released, stoppable by Ctrl-C, reporting progress.
//!
//! The render runs on a scoped worker thread (which fans out to its own thread pool) while the
//! calling thread, GIL released, waits for it in slices of [`POLL`]. After each slice it takes
//! the GIL back for a moment to run Python's signal handlers (`Python::check_signals`: a
//! SIGINT raises `KeyboardInterrupt` there) and to call the progress callback. An exception
//! from either sets the render driver's cancel flag, the same flag the command's Ctrl-C
//! handler sets, and is raised once the driver has stopped (it checks the flag every pixel
//! row). Progress callbacks therefore run on the calling thread, never on a render thread.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::sync::Mutex;
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use steradian::render::Progress;

/// How often the waiting thread checks for signals and reports progress.
const POLL: Duration = Duration::from_millis(50);

/// Runs `job(cancel, progress)` off the GIL. `job` must pass `cancel` and `progress` on to
/// the render driver (`RenderOptions::cancel`, `RenderOptions::progress`). `callback`, when
/// given, is called as `callback(samples_done, samples_total)`.
pub fn run_interruptible<T, F>(py: Python<'_>, callback: Option<Py<PyAny>>, job: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce(&AtomicBool, &(dyn Fn(Progress) + Sync)) -> T + Send,
{
    let cancel = AtomicBool::new(false);
    // the furthest progress reported by the workers and not yet passed to the callback
    let latest: Mutex<Option<Progress>> = Mutex::new(None);
    let record = |p: Progress| {
        let mut l = latest.lock().unwrap_or_else(|e| e.into_inner());
        // workers report out of order: keep the largest count
        if l.is_none_or(|q| p.samples_done > q.samples_done) {
            *l = Some(p);
        }
    };
    let report = |py: Python<'_>| -> PyResult<()> {
        py.check_signals()?;
        if let Some(cb) = &callback {
            let p = latest.lock().unwrap_or_else(|e| e.into_inner()).take();
            if let Some(p) = p {
                cb.call1(py, (p.samples_done, p.samples_total))?;
            }
        }
        Ok(())
    };
    py.allow_threads(|| {
        std::thread::scope(|s| {
            let (tx, rx) = channel();
            let (cancel, record) = (&cancel, &record);
            s.spawn(move || {
                let _ = tx.send(catch_unwind(AssertUnwindSafe(|| job(cancel, record))));
            });
            let mut failure: Option<PyErr> = None;
            let result = loop {
                match rx.recv_timeout(POLL) {
                    Ok(r) => break r,
                    Err(RecvTimeoutError::Timeout) => {}
                    Err(RecvTimeoutError::Disconnected) => {
                        return Err(PyRuntimeError::new_err(
                            "the render thread ended without a result",
                        ))
                    }
                }
                if failure.is_none() {
                    if let Err(e) = Python::with_gil(report) {
                        cancel.store(true, Ordering::Relaxed);
                        failure = Some(e);
                    }
                }
            };
            if let Some(e) = failure {
                return Err(e);
            }
            let value = result.map_err(|panic| {
                let what = panic
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| panic.downcast_ref::<String>().cloned())
                    .unwrap_or_default();
                PyRuntimeError::new_err(format!("the renderer failed (a bug in steradian): {what}"))
            })?;
            // the last report (100%), and a Ctrl-C that came during the final slice
            Python::with_gil(report)?;
            Ok(value)
        })
    })
}
