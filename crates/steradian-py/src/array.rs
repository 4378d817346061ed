//! Images to and from NumPy arrays of shape (H, W, 3), float32, through NumPy's Python API
//! (no compiled NumPy dependency): one copy each way.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyBytes};
use steradian::film::Image;

/// A float32 array (H, W, 3) holding a copy of `image` (row 0 = top).
pub fn to_array<'py>(py: Python<'py>, image: &Image) -> PyResult<Bound<'py, PyAny>> {
    let buffer = PyByteArray::new_with(py, image.data.len() * 4, |bytes| {
        for (b, v) in bytes.chunks_exact_mut(4).zip(&image.data) {
            b.copy_from_slice(&v.to_ne_bytes());
        }
        Ok(())
    })?;
    let np = py.import("numpy")?;
    let flat = np.call_method1("frombuffer", (buffer, np.getattr("float32")?))?;
    flat.call_method1("reshape", ((image.height as usize, image.width as usize, 3usize),))
}

/// An image from any array-like of shape (H, W, 3), converted to float32.
pub fn from_array(py: Python<'_>, obj: &Bound<'_, PyAny>) -> PyResult<Image> {
    let np = py.import("numpy")?;
    let arr = np.call_method1("ascontiguousarray", (obj, np.getattr("float32")?))?;
    let shape: Vec<usize> = arr.getattr("shape")?.extract()?;
    let [h, w, 3] = shape[..] else {
        return Err(PyValueError::new_err(format!(
            "an image must have shape (H, W, 3), got {shape:?}"
        )));
    };
    let (Ok(w32), Ok(h32)) = (u32::try_from(w), u32::try_from(h)) else {
        return Err(PyValueError::new_err(format!("image {w}x{h} is too large")));
    };
    let bytes = arr.call_method0("tobytes")?;
    let bytes = bytes.downcast::<PyBytes>()?.as_bytes();
    let data =
        bytes.chunks_exact(4).map(|b| f32::from_ne_bytes([b[0], b[1], b[2], b[3]])).collect();
    Image::from_data(w32, h32, data).map_err(PyValueError::new_err)
}
