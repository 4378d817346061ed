//! Images to and from NumPy arrays of shape (H, W, 3) (and (H, W, 3 + k) with AOV layers),
//! float32, through NumPy's Python API (no compiled NumPy dependency): one copy each way.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyBytes, PyTuple};
use steradian::film::{AovLayer, Image};

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

/// A float32 array (H, W, 3 + k) of `image`'s R, G, B followed by each AOV layer's channels
/// (Mitsuba's `mi.render` layout for `moment` and `aov`; just R, G, B without layers).
pub fn to_channels_array<'py>(
    py: Python<'py>,
    image: &Image,
    layers: &[(AovLayer, Image)],
) -> PyResult<Bound<'py, PyAny>> {
    let n = 3 + layers.iter().map(|(l, _)| l.channels.len()).sum::<usize>();
    let pixels = image.width as usize * image.height as usize;
    let mut values = Vec::with_capacity(pixels * n);
    for i in 0..pixels {
        values.extend_from_slice(&image.data[3 * i..3 * i + 3]);
        for (l, img) in layers {
            values.extend_from_slice(&img.data[3 * i..3 * i + l.channels.len()]);
        }
    }
    let buffer = PyByteArray::new_with(py, values.len() * 4, |bytes| {
        for (b, v) in bytes.chunks_exact_mut(4).zip(&values) {
            b.copy_from_slice(&v.to_ne_bytes());
        }
        Ok(())
    })?;
    let np = py.import("numpy")?;
    let flat = np.call_method1("frombuffer", (buffer, np.getattr("float32")?))?;
    flat.call_method1("reshape", ((image.height as usize, image.width as usize, n),))
}

/// A float64 array of `shape` holding a copy of `values` (one copy, as `to_array`).
pub fn to_f64_array<'py>(
    py: Python<'py>,
    values: &[f64],
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    let buffer = PyByteArray::new_with(py, values.len() * 8, |bytes| {
        for (b, v) in bytes.chunks_exact_mut(8).zip(values) {
            b.copy_from_slice(&v.to_ne_bytes());
        }
        Ok(())
    })?;
    let np = py.import("numpy")?;
    let flat = np.call_method1("frombuffer", (buffer, np.getattr("float64")?))?;
    flat.call_method1("reshape", (PyTuple::new(py, shape)?,))
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
