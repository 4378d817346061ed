//! `Sums`: a render's raw per-pixel sums (`steradian::render::RenderSums`) in Python.

use std::path::PathBuf;

use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};
use steradian::render::{PixelQuantity, RenderSums};

use crate::array::{to_array, to_f64_array};

/// The raw sums of samples `first .. end` of every pixel of a render (`Scene.render_range`):
/// per pixel Σw·L, Σw, Σw·L² and Σw² in float64, and the count of dropped NaN/Inf samples.
/// Sums of consecutive ranges of one render, joined in range order with `append`, equal bit
/// for bit what one process rendering all of them holds. Picklable (as `to_bytes()`), so they
/// travel between processes and machines; `save`/`load` keep them in a file atomically.
#[pyclass(module = "steradian._steradian")]
pub struct Sums {
    pub inner: RenderSums,
}

fn sums_error(e: steradian::render::SumsError) -> PyErr {
    PyValueError::new_err(format!("the sums {e}"))
}

#[pymethods]
impl Sums {
    /// The first sample per pixel of the range.
    #[getter]
    fn first(&self) -> u32 {
        self.inner.first()
    }

    /// One past the last sample per pixel of the range.
    #[getter]
    fn end(&self) -> u32 {
        self.inner.end()
    }

    /// Samples per pixel of the whole render the range belongs to.
    #[getter]
    fn spp(&self) -> u32 {
        self.inner.header.spp
    }

    #[getter]
    fn seed(&self) -> u64 {
        self.inner.header.seed
    }

    /// `path`'s branch count, None for other integrators.
    #[getter]
    fn branches(&self) -> Option<u32> {
        let b = self.inner.header.branches;
        (b > 0).then_some(b)
    }

    /// (width, height) in pixels.
    #[getter]
    fn size(&self) -> (u32, u32) {
        (self.inner.header.width, self.inner.header.height)
    }

    /// Index of the sensor rendered.
    #[getter]
    fn sensor(&self) -> u32 {
        self.inner.header.sensor
    }

    /// `"radiance"`, `"irradiance"` or `"illuminance"`.
    #[getter]
    fn quantity(&self) -> &'static str {
        match self.inner.header.quantity {
            PixelQuantity::Sensor => "radiance",
            PixelQuantity::SurfaceIrradiance => "irradiance",
            PixelQuantity::SurfaceIlluminance => "illuminance",
        }
    }

    /// The number the caller recorded (`render_range(scene_digest=...)`).
    #[getter]
    fn scene_digest(&self) -> u64 {
        self.inner.header.scene_digest
    }

    /// NaN/Inf samples dropped in the range.
    #[getter]
    fn dropped_samples(&self) -> u64 {
        self.inner.film().dropped()
    }

    /// Whether the range starts at sample 0 (its image is the render's so far).
    #[getter]
    fn is_prefix(&self) -> bool {
        self.inner.is_prefix()
    }

    /// Whether the sums hold every sample of the render.
    #[getter]
    fn is_complete(&self) -> bool {
        self.inner.is_complete()
    }

    /// Joins the range that follows (same render, starting at `end`), in place.
    fn append(&mut self, py: Python<'_>, next: PyRef<'_, Sums>) -> PyResult<()> {
        let next = next.inner.clone();
        py.allow_threads(|| self.inner.append(next)).map_err(sums_error)
    }

    /// The sums as float64 arrays: `wl` (H, W, 3) = Σw·L, `w` (H, W) = Σw, `wl2` (H, W, 3) =
    /// Σw·L², `w2` (H, W) = Σw² (in the film's unit: irradiance for illuminance maps).
    fn arrays<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (w, h) = (self.inner.header.width as usize, self.inner.header.height as usize);
        let (px, _) = self.inner.film().sums();
        let d = PyDict::new(py);
        let rgb = |f: &dyn Fn(&steradian::film::PixelAccum) -> [f64; 3]| {
            px.iter().flat_map(f).collect::<Vec<f64>>()
        };
        let one = |f: &dyn Fn(&steradian::film::PixelAccum) -> f64| {
            px.iter().map(f).collect::<Vec<f64>>()
        };
        d.set_item("wl", to_f64_array(py, &rgb(&|p| p.wl), &[h, w, 3])?)?;
        d.set_item("w", to_f64_array(py, &one(&|p| p.w), &[h, w])?)?;
        d.set_item("wl2", to_f64_array(py, &rgb(&|p| p.wl2), &[h, w, 3])?)?;
        d.set_item("w2", to_f64_array(py, &one(&|p| p.w2), &[h, w])?)?;
        Ok(d)
    }

    /// The range's image, float32 (H, W, 3), as `Scene.render` returns it for a render of
    /// these samples (without `moment`/`aov` layers: `Scene.develop` adds them).
    fn image<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_array(py, &self.inner.image())
    }

    /// The standard error of each pixel of `image()`, float32 (H, W, 3).
    fn stderr<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_array(py, &self.inner.stderr_image())
    }

    /// The sums as bytes (steradian's sums record; read back by `Sums.from_bytes`).
    fn to_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &self.inner.to_bytes())
    }

    /// Sums from `to_bytes()`'s record; ValueError for a damaged record or one made by another
    /// steradian version.
    #[staticmethod]
    fn from_bytes(data: &[u8]) -> PyResult<Sums> {
        RenderSums::from_bytes(data).map(|inner| Sums { inner }).map_err(sums_error)
    }

    /// Writes the sums to `path` atomically (a temporary file renamed over it).
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        py.allow_threads(|| self.inner.save(&path))
            .map_err(|e| PyOSError::new_err(format!("cannot write {}: {e}", path.display())))
    }

    /// Sums that `save` wrote.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Sums> {
        py.allow_threads(|| RenderSums::load(&path))
            .map(|inner| Sums { inner })
            .map_err(PyValueError::new_err)
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let from_bytes = py.get_type::<Sums>().getattr("from_bytes")?;
        let bytes = slf.borrow().to_bytes(py);
        PyTuple::new(py, [from_bytes.into_any(), PyTuple::new(py, [bytes])?.into_any()])
    }

    fn __repr__(&self) -> String {
        let h = &self.inner.header;
        format!(
            "<steradian.Sums samples {}..{} of {} spp, {}x{}, seed {}>",
            self.inner.first(),
            self.inner.end(),
            h.spp,
            h.width,
            h.height,
            h.seed
        )
    }
}
