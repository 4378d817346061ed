//! `steradian._steradian`: the Python extension module.
//!
//! Bindings only. Scenes are loaded by `steradian-mitsuba`, rendered and measured by the same
//! driver the `steradian` command uses (`steradian::render::{render, measure}`) with the
//! same defaults, so an image from Python equals the command's EXR bit for bit. This crate
//! converts arguments and results, releases the GIL while rendering, turns Ctrl-C into
//! `KeyboardInterrupt` and forwards progress to a Python callback.
//!
//! The public Python API is `python/steradian/__init__.py`; its types are in
//! `python/steradian/_steradian.pyi`.

mod array;
mod errors;
mod interrupt;
mod radiometry;
mod scene;
mod sums;

use std::path::PathBuf;

use pyo3::prelude::*;

use crate::array::{from_array, to_array};
use crate::errors::{exr_error, SceneError};

/// Writes `image`, an array-like of shape (H, W, 3) (converted to float32), as an OpenEXR file
/// with float32 channels R, G, B (linear values, e.g. radiance in W/(m²·sr)).
#[pyfunction]
#[pyo3(signature = (path, image))]
fn write_exr(py: Python<'_>, path: PathBuf, image: &Bound<'_, PyAny>) -> PyResult<()> {
    let image = from_array(py, image)?;
    py.allow_threads(|| steradian::film::write_exr(&path, &image)).map_err(exr_error)
}

/// Writes `image`, an array-like of shape (H, W, 3), as an 8-bit sRGB PNG preview (values
/// clamped to [0, 1] after the sRGB transfer curve), as `steradian render` writes its PNG.
#[pyfunction]
#[pyo3(signature = (path, image))]
fn write_png(py: Python<'_>, path: PathBuf, image: &Bound<'_, PyAny>) -> PyResult<()> {
    let image = from_array(py, image)?;
    py.allow_threads(|| steradian::film::write_png(&path, &image, 1.0)).map_err(exr_error)
}

/// Reads the R, G, B channels of an OpenEXR file (float16, float32 or uint32 samples, any
/// compression) as a float32 array of shape (H, W, 3), top row first.
#[pyfunction]
#[pyo3(signature = (path))]
fn read_exr(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyAny>> {
    let image = py.allow_threads(|| steradian::film::read_exr(&path)).map_err(exr_error)?;
    to_array(py, &image)
}

#[pymodule]
fn _steradian(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.setattr("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<scene::Measurement>()?;
    m.add_class::<scene::RenderResult>()?;
    m.add_class::<sums::Sums>()?;
    m.add_function(wrap_pyfunction!(scene::load_file, m)?)?;
    m.add_function(wrap_pyfunction!(scene::load_string, m)?)?;
    m.add_function(wrap_pyfunction!(write_exr, m)?)?;
    m.add_function(wrap_pyfunction!(read_exr, m)?)?;
    m.add_function(wrap_pyfunction!(write_png, m)?)?;
    let radiometry = PyModule::new(py, "radiometry")?;
    radiometry::register(&radiometry)?;
    m.add_submodule(&radiometry)?;
    // make `import steradian._steradian.radiometry` (and the package's `steradian.radiometry`)
    // resolvable: a submodule made here is otherwise only an attribute
    py.import("sys")?
        .getattr("modules")?
        .set_item("steradian._steradian.radiometry", &radiometry)?;
    Ok(())
}
