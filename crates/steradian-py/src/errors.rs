//! Rust errors as Python exceptions.

use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use steradian::render::RenderError;
use steradian_mitsuba::LoadError;

pyo3::create_exception!(
    steradian,
    SceneError,
    PyValueError,
    "A scene that cannot be loaded: malformed XML, an unknown plugin or parameter, a missing \
     file. `str(e)` is the loader's message, `file:line:col: error: problem`; the attributes \
     `file`, `line`, `column` (None when the error has no position) and `message` give its parts."
);

/// A [`SceneError`] carrying the loader's message and position.
pub fn scene_error(py: Python<'_>, e: &LoadError) -> PyErr {
    let err = SceneError::new_err(e.to_string());
    let value = err.value(py);
    let (file, line, column) = match &e.pos {
        Some(p) => (Some(p.file.display().to_string()), Some(p.line), Some(p.col)),
        None => (None, None, None),
    };
    // setting attributes on a fresh exception instance cannot fail short of memory exhaustion
    let _ = value.setattr("file", file);
    let _ = value.setattr("line", line);
    let _ = value.setattr("column", column);
    let _ = value.setattr("message", &e.message);
    err
}

/// Render errors: a bad sensor choice is the caller's mistake (ValueError), failing to start
/// threads is not.
pub fn render_error(e: RenderError) -> PyErr {
    match e {
        RenderError::ThreadPool(_) => PyRuntimeError::new_err(e.to_string()),
        RenderError::NoSensor
        | RenderError::BadSensor(_)
        | RenderError::NotACamera
        | RenderError::NotLight
        | RenderError::ParticlesNeedPinhole
        | RenderError::BadOption { .. }
        | RenderError::BadRange { .. }
        | RenderError::Resume(_) => PyValueError::new_err(e.to_string()),
    }
}

/// EXR input/output errors (unreadable, corrupt or unwritable files).
pub fn exr_error(message: String) -> PyErr {
    PyOSError::new_err(message)
}
