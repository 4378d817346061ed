//! `Scene`, `Measurement`, `load_file`, `load_string`.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use std::time::Duration;

use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict};
use steradian::render::{
    image_error, render, Checkpoint, GridReading, Job, PixelQuantity, RenderError, RenderOptions,
    RenderOutput, RenderSums, SampleAllocation,
};
use steradian::sensor::{Quantity, SensorKind};

use crate::array::{to_array, to_channels_array, to_f64_array};
use crate::errors::{render_error, scene_error};
use crate::interrupt::run_interruptible;
use crate::sums::Sums;

/// `**defaults` as the loader's `-D name=value` pairs: booleans as `true`/`false`, anything
/// else as `str(value)`.
fn defines(defaults: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, String)>> {
    let Some(d) = defaults else { return Ok(Vec::new()) };
    d.iter()
        .map(|(k, v)| {
            let value = if let Ok(b) = v.downcast::<PyBool>() {
                if b.is_true() { "true" } else { "false" }.to_string()
            } else {
                v.str()?.to_string()
            };
            Ok((k.extract::<String>()?, value))
        })
        .collect()
}

/// Loads a Mitsuba 3 XML scene file. Keyword arguments override the file's `<default>`s (as
/// `-D name=value` does on the command line), e.g. `load_file("scene.xml", spp=64)`.
/// Relative file names in the scene (meshes, includes) resolve against the scene's folder.
/// Raises `SceneError` with the file, line and column of the problem.
#[pyfunction]
#[pyo3(signature = (path, **defaults))]
pub fn load_file(
    py: Python<'_>,
    path: PathBuf,
    defaults: Option<&Bound<'_, PyDict>>,
) -> PyResult<Scene> {
    let defines = defines(defaults)?;
    let scene = py
        .allow_threads(|| steradian_mitsuba::load_file(&path, &defines))
        .map_err(|e| scene_error(py, &e))?;
    warn_all(py, &scene)?;
    Ok(Scene { inner: Arc::new(scene), name: path.display().to_string(), defines, source: None })
}

/// Loads a scene from a Mitsuba 3 XML string. Keyword arguments override its `<default>`s.
/// Relative file names in it resolve against the current directory; error messages call it
/// `<string>`. Raises `SceneError`.
#[pyfunction]
#[pyo3(signature = (xml, /, **defaults))]
pub fn load_string(
    py: Python<'_>,
    xml: &str,
    defaults: Option<&Bound<'_, PyDict>>,
) -> PyResult<Scene> {
    let defines = defines(defaults)?;
    let scene = py
        .allow_threads(|| {
            steradian_mitsuba::load_string(xml, Path::new("<string>"), Path::new("."), &defines)
        })
        .map_err(|e| scene_error(py, &e))?;
    warn_all(py, &scene)?;
    let source = Some(xml.to_string());
    Ok(Scene { inner: Arc::new(scene), name: "<string>".into(), defines, source })
}

/// Issues the loader's warnings as Python `UserWarning`s (one each, with its location).
fn warn_all(py: Python<'_>, job: &Job) -> PyResult<()> {
    for w in &job.warnings {
        let text = std::ffi::CString::new(w.as_str()).unwrap_or_default();
        PyErr::warn(py, &py.get_type::<pyo3::exceptions::PyUserWarning>(), &text, 1)?;
    }
    Ok(())
}

/// `time_limit=` in seconds: positive and finite, or None.
fn time_limit_arg(seconds: Option<f64>) -> PyResult<Option<Duration>> {
    match seconds {
        None => Ok(None),
        Some(t) if t.is_finite() && t > 0.0 => Ok(Some(Duration::from_secs_f64(t))),
        Some(t) => Err(PyValueError::new_err(format!(
            "time_limit must be a positive number of seconds, not {t}"
        ))),
    }
}

fn pixel_quantity(name: &str) -> PyResult<PixelQuantity> {
    PixelQuantity::from_name(name).ok_or_else(|| {
        PyValueError::new_err(format!(
            "quantity must be 'radiance', 'irradiance' or 'illuminance', not '{name}'"
        ))
    })
}

/// A loaded scene: geometry, materials, lights, sensors and integrator. Immutable; safe to
/// share between threads.
#[pyclass(frozen, module = "steradian._steradian")]
pub struct Scene {
    inner: Arc<Job>,
    name: String,
    /// The `<default>` overrides it was loaded with, and its XML when given as a string: what
    /// a checkpoint's scene digest covers beside the files.
    defines: Vec<(String, String)>,
    source: Option<String>,
}

/// A sensor given as its index or its `id`.
#[derive(FromPyObject)]
enum SensorArg {
    Index(i64),
    Id(String),
}

impl Scene {
    fn sensor(&self, sensor: Option<SensorArg>) -> PyResult<usize> {
        let n = self.inner.scene.sensors.len();
        match sensor {
            None => Ok(0),
            Some(SensorArg::Id(id)) => {
                self.inner.scene.find_sensor(&id).map_err(PyValueError::new_err)
            }
            Some(SensorArg::Index(i)) => match usize::try_from(i) {
                Ok(i) if i < n => Ok(i),
                _ => Err(PyValueError::new_err(format!(
                    "sensor index {i} out of range: the scene has {n} sensor(s)"
                ))),
            },
        }
    }

    /// The render behind `render` and `render_result` (see `render` for the parameters).
    #[allow(clippy::too_many_arguments)]
    fn render_output(
        &self,
        py: Python<'_>,
        spp: Option<u32>,
        seed: Option<u64>,
        sensor: Option<SensorArg>,
        quantity: &str,
        threads: Option<usize>,
        progress: Option<Py<PyAny>>,
        checkpoint: Option<PathBuf>,
        checkpoint_interval: f64,
        time_limit: Option<f64>,
        target_error: Option<f64>,
        allocation: &str,
    ) -> PyResult<RenderOutput> {
        let time_limit = time_limit_arg(time_limit)?;
        let pixel_quantity = pixel_quantity(quantity)?;
        let allocation = match allocation {
            "auto" => SampleAllocation::Auto,
            "adaptive" => SampleAllocation::Adaptive,
            "uniform" => SampleAllocation::Uniform,
            other => {
                return Err(PyValueError::new_err(format!(
                    "allocation must be 'auto', 'adaptive' or 'uniform', not {other:?}"
                )))
            }
        };
        let sensor = self.sensor(sensor)?;
        let scene = &*self.inner;
        if !(checkpoint_interval.is_finite() && checkpoint_interval >= 0.0) {
            return Err(PyValueError::new_err("checkpoint_interval must be at least 0 seconds"));
        }
        let (resume, scene_digest) = match &checkpoint {
            Some(path) => {
                let resume = if path.exists() {
                    Some(Checkpoint::read(path).map_err(PyValueError::new_err)?)
                } else {
                    None
                };
                let digest =
                    steradian_mitsuba::scene_digest(scene, &self.defines, self.source.as_deref())
                        .map_err(PyOSError::new_err)?;
                (resume, digest)
            }
            None => (None, 0),
        };
        let interval = Duration::from_secs_f64(checkpoint_interval);
        let writer = checkpoint.as_ref().map(|p| Checkpoint::new(p, interval));
        // a failed save leaves the previous checkpoint; the render goes on
        let save = |sums: &RenderSums| {
            if let Some(w) = &writer {
                w.maybe_save(sums);
            }
        };
        run_interruptible(py, progress, |cancel, report| {
            let opts = RenderOptions {
                spp,
                seed,
                sampler: None,
                threads,
                sensor: Some(sensor),
                cancel: Some(cancel),
                progress: Some(report),
                quantity: pixel_quantity,
                resume,
                on_pass: writer.as_ref().map(|_| &save as &(dyn Fn(&RenderSums) + Sync)),
                scene_digest,
                time_limit,
                target_error,
                allocation,
                ..Default::default()
            };
            let out = render(scene, &opts).map_err(|e| match (e, &checkpoint) {
                (RenderError::Resume(e), Some(path)) => PyValueError::new_err(format!(
                    "cannot resume from {}: the checkpoint {e}",
                    path.display()
                )),
                (e, _) => render_error(e),
            })?;
            if let Some(w) = &writer {
                if out.interrupted && !out.target_reached {
                    w.save(&out.sums).map_err(PyOSError::new_err)?;
                } else {
                    // the image holds every sample: the checkpoint has done its work
                    w.remove();
                }
            }
            Ok::<_, PyErr>(out)
        })?
    }

    /// Renders sensor `sensor` as `measure` and `measure_grid` read it: (spp, seed, sensor,
    /// threads), interruptible, with a time limit, a target error and Sobol batches.
    fn render_meter(
        &self,
        py: Python<'_>,
        (spp, seed, sensor, threads): (Option<u32>, Option<u64>, usize, Option<usize>),
        progress: Option<Py<PyAny>>,
        (time_limit, target_error, batch): (Option<f64>, Option<f64>, Option<u32>),
    ) -> PyResult<RenderOutput> {
        let time_limit = time_limit_arg(time_limit)?;
        let scene = &*self.inner;
        run_interruptible(py, progress, |cancel, report| {
            let opts = RenderOptions {
                spp,
                seed,
                threads,
                sensor: Some(sensor),
                cancel: Some(cancel),
                progress: Some(report),
                time_limit,
                target_error,
                batch,
                ..Default::default()
            };
            render(scene, &opts)
        })?
        .map_err(render_error)
    }
}

#[pymethods]
impl Scene {
    /// Renders a sensor and returns its image as a float32 array of shape (H, W, 3), linear
    /// RGB in physical units: radiance in W/(m²·sr) for cameras, the meter's quantity for
    /// meters.
    ///
    /// - `spp`: samples per pixel (default: the scene's sampler's `sample_count`).
    /// - `seed`: the sampler's seed, 0 by default as in Mitsuba's `mi.render`; `None` keeps
    ///   the scene sampler's seed. The same scene, spp and seed give the same image, bit for
    ///   bit, whatever the thread count, and the same image as the `steradian render` command.
    /// - `sensor`: index or `id` of the sensor (default: the first).
    /// - `quantity`: `"radiance"` (what the sensor measures), `"irradiance"` (W/m² on the
    ///   surface each camera pixel sees) or `"illuminance"` (lux = 683 lm/W × luminance of the
    ///   irradiance).
    /// - `threads`: worker threads (default: all cores).
    /// - `progress`: called as `progress(samples_done, samples_total)` on the calling thread
    ///   while rendering; an exception it raises stops the render and propagates.
    ///
    /// - `time_limit`: seconds after which the render ends: the image holds the whole passes
    ///   finished by then (about half the work done or more); with `checkpoint`, a later call
    ///   goes on. `measure` takes it too.
    /// - `target_error`: stop once 95 % of the pixels are within this fraction of their value
    ///   at 95 % confidence, a pixel's value counting at least 1 % of the image's mean; `spp`
    ///   is then the most samples taken (default 1048576). `measure` takes it too, per reading.
    /// - `allocation`: how the samples are spread over the pixels: `"auto"` (the default: a
    ///   short pilot, then adaptive sampling where it predicts at least 1.4× lower relative
    ///   variance), `"adaptive"` or `"uniform"`; `spp` is the mean per pixel of an adaptive
    ///   render. The same image bit for bit as `steradian render --allocation`.
    /// - `checkpoint`: a file that keeps the finished passes' sums (written atomically every
    ///   `checkpoint_interval` seconds and when the render is stopped); a render given a
    ///   checkpoint that exists continues from it, and returns the uninterrupted render's image
    ///   bit for bit. A checkpoint of another scene, spp, seed, sensor or resolution raises
    ///   ValueError. The file is deleted when the render completes.
    ///
    /// With a `moment` or `aov` integrator, or a film whose `pixel_format` has alpha
    /// (`rgba`), a radiance render of a camera returns shape (H, W, 3 + k): R, G, B, the
    /// integrator's layers, then `A`; their names are `channel_names()`. (The colour stays
    /// R, G, B whatever the `pixel_format`: luminance and XYZ are for the files.)
    ///
    /// The GIL is released while rendering. Ctrl-C stops the render and raises
    /// `KeyboardInterrupt`.
    #[pyo3(
        signature = (spp=None, seed=Some(0), sensor=None, *, quantity="radiance", threads=None, progress=None, checkpoint=None, checkpoint_interval=60.0, time_limit=None, target_error=None, allocation="auto"),
        text_signature = "(self, /, spp=None, seed=0, sensor=None, *, quantity='radiance', threads=None, progress=None, checkpoint=None, checkpoint_interval=60.0, time_limit=None, target_error=None, allocation='auto')"
    )]
    #[allow(clippy::too_many_arguments)]
    fn render<'py>(
        &self,
        py: Python<'py>,
        spp: Option<u32>,
        seed: Option<u64>,
        sensor: Option<SensorArg>,
        quantity: &str,
        threads: Option<usize>,
        progress: Option<Py<PyAny>>,
        checkpoint: Option<PathBuf>,
        checkpoint_interval: f64,
        time_limit: Option<f64>,
        target_error: Option<f64>,
        allocation: &str,
    ) -> PyResult<Bound<'py, PyAny>> {
        let out = self.render_output(
            py,
            spp,
            seed,
            sensor,
            quantity,
            threads,
            progress,
            checkpoint,
            checkpoint_interval,
            time_limit,
            target_error,
            allocation,
        )?;
        to_channels_array(py, &out.image(), &out.aov_images())
    }

    /// Renders as `render` does (the same parameters, the same image bit for bit) and returns
    /// a `RenderResult`: the image with each pixel's standard error, the samples spent, the
    /// error reached and the work done, what `steradian render` prints in its summary.
    #[pyo3(
        signature = (spp=None, seed=Some(0), sensor=None, *, quantity="radiance", threads=None, progress=None, checkpoint=None, checkpoint_interval=60.0, time_limit=None, target_error=None, allocation="auto"),
        text_signature = "(self, /, spp=None, seed=0, sensor=None, *, quantity='radiance', threads=None, progress=None, checkpoint=None, checkpoint_interval=60.0, time_limit=None, target_error=None, allocation='auto')"
    )]
    #[allow(clippy::too_many_arguments)]
    fn render_result(
        &self,
        py: Python<'_>,
        spp: Option<u32>,
        seed: Option<u64>,
        sensor: Option<SensorArg>,
        quantity: &str,
        threads: Option<usize>,
        progress: Option<Py<PyAny>>,
        checkpoint: Option<PathBuf>,
        checkpoint_interval: f64,
        time_limit: Option<f64>,
        target_error: Option<f64>,
        allocation: &str,
    ) -> PyResult<RenderResult> {
        let out = self.render_output(
            py,
            spp,
            seed,
            sensor,
            quantity,
            threads,
            progress,
            checkpoint,
            checkpoint_interval,
            time_limit,
            target_error,
            allocation,
        )?;
        RenderResult::new(py, &out)
    }

    /// Reads a sensor: its value per RGB channel with the standard error of that value, in the
    /// sensor's unit. For a meter (`radiancemeter`, `irradiancemeter`) this is its one pixel;
    /// for a camera the image mean. Meters use independent random numbers, so the error is
    /// a proper standard error. Same options as `render`; `seed=None` keeps the scene's seed.
    /// `target_error=E` stops once the reading is within E of its value at 95 % confidence
    /// (1.96 standard errors) in every channel, `spp` then being the most samples taken. `batch=N` (meters)
    /// makes each sample the mean of N Sobol points under a scramble of its own: the error
    /// stays a proper standard error and falls far faster; `spp` counts these samples.
    #[pyo3(
        signature = (spp=None, seed=Some(0), sensor=None, *, threads=None, progress=None, time_limit=None, target_error=None, batch=None),
        text_signature = "(self, /, spp=None, seed=0, sensor=None, *, threads=None, progress=None, time_limit=None, target_error=None, batch=None)"
    )]
    fn measure(
        &self,
        py: Python<'_>,
        spp: Option<u32>,
        seed: Option<u64>,
        sensor: Option<SensorArg>,
        threads: Option<usize>,
        progress: Option<Py<PyAny>>,
        time_limit: Option<f64>,
        target_error: Option<f64>,
        batch: Option<u32>,
    ) -> PyResult<Measurement> {
        let sensor = self.sensor(sensor)?;
        let out = self.render_meter(
            py,
            (spp, seed, sensor, threads),
            progress,
            (time_limit, target_error, batch),
        )?;
        let quantity = self.inner.scene.sensors[sensor].quantity();
        let m = steradian::render::Measurement::from_render(&out, sensor, quantity);
        Ok(Measurement { inner: m })
    }

    /// Reads a `workplane` sensor's grid: a dict with `values` and `stderr` (float64 arrays
    /// of shape (ny, nx), row 0 the plan's top row), `unit` (`"lx"`, `"W/m^2"`, or `"%"` for
    /// a daylight factor), `spp`, and `stats`: `avg`, `min`, `max`, `u0` (min/avg) and
    /// `min_max` (min/max), each a `(value, stderr)` tuple, and `target_reached`. Same options as `measure` (a target
    /// error applies to every cell).
    #[pyo3(
        signature = (spp=None, seed=Some(0), sensor=None, *, threads=None, progress=None, time_limit=None, target_error=None, batch=None),
        text_signature = "(self, /, spp=None, seed=0, sensor=None, *, threads=None, progress=None, time_limit=None, target_error=None, batch=None)"
    )]
    #[allow(clippy::too_many_arguments)]
    fn measure_grid<'py>(
        &self,
        py: Python<'py>,
        spp: Option<u32>,
        seed: Option<u64>,
        sensor: Option<SensorArg>,
        threads: Option<usize>,
        progress: Option<Py<PyAny>>,
        time_limit: Option<f64>,
        target_error: Option<f64>,
        batch: Option<u32>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let sensor = self.sensor(sensor)?;
        let SensorKind::Workplane(w) = &self.inner.scene.sensors[sensor].kind else {
            return Err(PyValueError::new_err("measure_grid reads a 'workplane' sensor"));
        };
        let unit = w.unit;
        let out = self.render_meter(
            py,
            (spp, seed, sensor, threads),
            progress,
            (time_limit, target_error, batch),
        )?;
        let g = GridReading::from_render(&out, unit);
        let d = PyDict::new(py);
        d.set_item("values", to_f64_array(py, &g.values, &[g.ny, g.nx])?)?;
        d.set_item("stderr", to_f64_array(py, &g.stderr, &[g.ny, g.nx])?)?;
        d.set_item("unit", g.unit)?;
        d.set_item("spp", out.spp)?;
        d.set_item("target_reached", out.target_reached)?;
        let stats = PyDict::new(py);
        let s = g.stats;
        for (name, e) in
            [("avg", s.avg), ("min", s.min), ("max", s.max), ("u0", s.u0), ("min_max", s.min_max)]
        {
            stats.set_item(name, (e.value, e.stderr))?;
        }
        d.set_item("stats", stats)?;
        Ok(d)
    }

    /// What a render will do, without rendering: a dict with `spp`, `seed`, `width`,
    /// `height`, `pass_bounds` (the samples per pixel at which its passes end, from 0 to
    /// `spp`: `render_range` ranges start and end on them) and `branches` (`path`'s branch
    /// count, chosen by its pilot, which this runs, when the scene leaves it open; None for
    /// other integrators). Same options as `render`.
    #[pyo3(
        signature = (spp=None, seed=Some(0), sensor=None, *, quantity="radiance", threads=None),
        text_signature = "(self, /, spp=None, seed=0, sensor=None, *, quantity='radiance', threads=None)"
    )]
    fn plan<'py>(
        &self,
        py: Python<'py>,
        spp: Option<u32>,
        seed: Option<u64>,
        sensor: Option<SensorArg>,
        quantity: &str,
        threads: Option<usize>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let quantity = pixel_quantity(quantity)?;
        let sensor = self.sensor(sensor)?;
        let scene = &*self.inner;
        let opts = RenderOptions {
            spp,
            seed,
            threads,
            sensor: Some(sensor),
            quantity,
            ..Default::default()
        };
        let plan =
            py.allow_threads(|| steradian::render::plan(scene, &opts)).map_err(render_error)?;
        let d = PyDict::new(py);
        let h = &plan.header;
        d.set_item("spp", h.spp)?;
        d.set_item("seed", h.seed)?;
        d.set_item("width", h.width)?;
        d.set_item("height", h.height)?;
        d.set_item("pass_bounds", plan.pass_bounds)?;
        d.set_item("branches", (h.branches > 0).then_some(h.branches))?;
        Ok(d)
    }

    /// Renders samples `first .. first + count` of every pixel of a render of `spp` samples
    /// and returns their raw sums (`Sums`), not an image. `first` and `first + count` must be
    /// pass boundaries (`plan()["pass_bounds"]`). Sums of consecutive ranges, joined in range
    /// order with `Sums.append`, hold bit for bit what one render of all of them holds, on any
    /// machine: this is how distributed renders and resumed renders add up.
    ///
    /// - `branches`: `path`'s branch count (give `plan()["branches"]`, so that every range
    ///   renders the same paths without running the pilot again); None runs the pilot.
    /// - `resume`: sums to continue (`first` must be where they end); the result holds both.
    /// - `scene_digest`: a number recorded in the sums' header and compared when sums are
    ///   joined or resumed (e.g. a digest of the scene's files), 0 by default.
    /// - the other options as in `render`.
    #[pyo3(
        signature = (first, count, spp=None, seed=Some(0), sensor=None, *, quantity="radiance", branches=None, resume=None, scene_digest=0, threads=None, progress=None),
        text_signature = "(self, /, first, count, spp=None, seed=0, sensor=None, *, quantity='radiance', branches=None, resume=None, scene_digest=0, threads=None, progress=None)"
    )]
    fn render_range(
        &self,
        py: Python<'_>,
        first: u32,
        count: u32,
        spp: Option<u32>,
        seed: Option<u64>,
        sensor: Option<SensorArg>,
        quantity: &str,
        branches: Option<u32>,
        resume: Option<PyRef<'_, Sums>>,
        scene_digest: u64,
        threads: Option<usize>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Sums> {
        let quantity = pixel_quantity(quantity)?;
        let sensor = self.sensor(sensor)?;
        let scene = &*self.inner;
        let end = first
            .checked_add(count)
            .ok_or_else(|| PyValueError::new_err("first + count overflows"))?;
        let resume = resume.map(|r| r.inner.clone());
        let out = run_interruptible(py, progress, |cancel, report| {
            let opts = RenderOptions {
                spp,
                seed,
                threads,
                sensor: Some(sensor),
                cancel: Some(cancel),
                progress: Some(report),
                quantity,
                range: Some((first, end)),
                branches,
                resume,
                scene_digest,
                ..Default::default()
            };
            render(scene, &opts)
        })?
        .map_err(render_error)?;
        Ok(Sums { inner: out.sums })
    }

    /// The image of `sums` (a prefix of a render of this scene, or any range) as `render`
    /// returns it: (H, W, 3) float32, or (H, W, 3 + k) with the `moment`/`aov` layers.
    fn develop<'py>(&self, py: Python<'py>, sums: PyRef<'_, Sums>) -> PyResult<Bound<'py, PyAny>> {
        let s = &sums.inner;
        let sensor = self.inner.scene.sensors.get(s.header.sensor as usize);
        let layers = match sensor {
            Some(sn) if s.header.aov_layers > 0 => self.inner.camera_layers(sn),
            _ => Vec::new(),
        };
        if layers.len() != s.header.aov_layers as usize {
            return Err(PyValueError::new_err(format!(
                "the sums hold {} AOV layers, this scene's integrator writes {}",
                s.header.aov_layers,
                layers.len()
            )));
        }
        let film = s.film();
        let aovs: Vec<_> =
            layers.into_iter().enumerate().map(|(k, l)| (l, film.develop_aov(k))).collect();
        to_channels_array(py, &s.image(), &aovs)
    }

    /// The files the scene was read from (the scene file, its includes, meshes, images), in
    /// the order first read; empty for `load_string` scenes without files.
    #[getter]
    fn files(&self) -> Vec<String> {
        self.inner.inputs.iter().map(|p| p.display().to_string()).collect()
    }

    /// The `id` of each sensor, in scene order (`""` for a sensor without one).
    #[getter]
    fn sensor_ids(&self) -> Vec<String> {
        self.inner.scene.sensors.iter().map(|s| s.id.clone()).collect()
    }

    /// The channel names of a radiance render of a sensor (index or id; default the first):
    /// `["R", "G", "B"]`, followed for a camera under `moment` or `aov` by each layer's
    /// channels (`"pp.X"`, `"m2_pp.X"`, `"dd.T"`, ...) and for an `rgba` film by `"A"`, in the
    /// order `render` returns them.
    #[pyo3(signature = (sensor=None))]
    fn channel_names(&self, sensor: Option<SensorArg>) -> PyResult<Vec<String>> {
        let i = self.sensor(sensor)?;
        let mut names: Vec<String> = ["R", "G", "B"].map(String::from).to_vec();
        if let Some(s) = self.inner.scene.sensors.get(i) {
            for l in self.inner.camera_layers(s) {
                names.extend(l.channel_names());
            }
        }
        Ok(names)
    }

    /// The film size (width, height) in pixels of a sensor (index or id; default the first).
    #[pyo3(signature = (sensor=None))]
    fn film_size(&self, sensor: Option<SensorArg>) -> PyResult<(u32, u32)> {
        let i = self.sensor(sensor)?;
        let f = &self
            .inner
            .scene
            .sensors
            .get(i)
            .ok_or_else(|| PyValueError::new_err("the scene has no sensor"))?
            .film;
        Ok((f.width, f.height))
    }

    fn __repr__(&self) -> String {
        let s = &self.inner.scene;
        format!(
            "<steradian.Scene {}: {} shapes, {} emitters, {} sensors>",
            self.name,
            s.shapes.len(),
            s.emitters.len(),
            s.sensors.len()
        )
    }
}

/// A finished render (`Scene.render_result`): the image, each pixel's standard error and
/// what the render spent and reached.
#[pyclass(frozen, module = "steradian._steradian")]
pub struct RenderResult {
    /// The image, as `Scene.render` returns it: float32, shape (H, W, 3) (or 3 + k with AOV
    /// layers), in the sensor's unit.
    #[pyo3(get)]
    image: Py<PyAny>,
    /// Each pixel's standard error of the mean, float32, shape (H, W, 3), same unit.
    #[pyo3(get)]
    stderr: Py<PyAny>,
    /// Samples per pixel in the image (the mean per pixel of an adaptive render); with
    /// `target_error`, where the render stopped.
    #[pyo3(get)]
    spp: u32,
    /// Samples in the image, all pixels.
    #[pyo3(get)]
    samples: u64,
    /// Ray queries (closest hits and shadow rays) made by this call's passes.
    #[pyo3(get)]
    rays: u64,
    /// Seconds the render took (pilots included; loading not).
    #[pyo3(get)]
    elapsed: f64,
    /// The relative error that 95 % of the pixels have reached at 95 % confidence (1.96
    /// standard errors over the pixel's value, a value counting at least 1 % of the image's
    /// mean): `target_error`'s rule, which the render met when this is at most its target.
    #[pyo3(get)]
    error_reached: f64,
    /// Whether the render stopped because it reached its `target_error`.
    #[pyo3(get)]
    target_reached: bool,
    /// Whether the render ended before its samples or its target error (a time limit, or
    /// stopped).
    #[pyo3(get)]
    interrupted: bool,
    /// NaN/Inf samples dropped (never averaged in).
    #[pyo3(get)]
    dropped_samples: u64,
    /// `path`'s branches per camera sample; `None` for other integrators.
    #[pyo3(get)]
    branches: Option<u32>,
    /// Whether the samples were spread by adaptive sampling (`allocation`).
    #[pyo3(get)]
    adaptive: bool,
}

impl RenderResult {
    fn new(py: Python<'_>, out: &RenderOutput) -> PyResult<RenderResult> {
        let image = to_channels_array(py, &out.image(), &out.aov_images())?;
        Ok(RenderResult {
            image: image.unbind(),
            stderr: to_array(py, &out.stderr_image())?.unbind(),
            spp: out.spp,
            samples: out.samples(),
            rays: out.rays,
            elapsed: out.elapsed.as_secs_f64(),
            error_reached: image_error(out.film()),
            target_reached: out.target_reached,
            interrupted: out.interrupted && !out.target_reached,
            dropped_samples: out.dropped_samples,
            branches: out.branches,
            adaptive: out.adaptive.is_some_and(|a| a.adaptive),
        })
    }
}

#[pymethods]
impl RenderResult {
    fn __repr__(&self) -> String {
        format!(
            "RenderResult({} spp, 95 % of the pixels within ±{:.2} %, {:.2} s)",
            self.spp,
            self.error_reached * 100.0,
            self.elapsed
        )
    }
}

/// A sensor reading: `value` and `stderr` (float64 arrays of shape (3,), RGB, in `unit`).
#[pyclass(frozen, module = "steradian._steradian")]
pub struct Measurement {
    inner: steradian::render::Measurement,
}

#[pymethods]
impl Measurement {
    /// The estimate per RGB channel, float64 array of shape (3,), in `unit`.
    #[getter]
    fn value<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_f64_array(py, &self.inner.value, &[3])
    }

    /// The standard error of `value` per channel, float64 array of shape (3,), in `unit`.
    #[getter]
    fn stderr<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_f64_array(py, &self.inner.stderr, &[3])
    }

    /// Whether the measurement stopped because it reached its `target_error`.
    #[getter]
    fn target_reached(&self) -> bool {
        self.inner.target_reached
    }

    /// `"radiance"` or `"irradiance"`.
    #[getter]
    fn quantity(&self) -> &'static str {
        match self.inner.quantity {
            Quantity::Radiance => "radiance",
            Quantity::Irradiance => "irradiance",
        }
    }

    /// `"W/(m²·sr)"` for radiance, `"W/m²"` for irradiance.
    #[getter]
    fn unit(&self) -> &'static str {
        self.inner.unit()
    }

    /// Index of the sensor read.
    #[getter]
    fn sensor(&self) -> usize {
        self.inner.sensor
    }

    /// Samples per pixel taken.
    #[getter]
    fn spp(&self) -> u32 {
        self.inner.spp
    }

    /// NaN/Inf samples dropped (never averaged in).
    #[getter]
    fn dropped_samples(&self) -> u64 {
        self.inner.dropped_samples
    }

    /// Paths continued from each sample's first hit by the `path` integrator (its `branches`,
    /// chosen by a short pilot when the scene leaves it unset); `None` for other integrators.
    #[getter]
    fn branches(&self) -> Option<u32> {
        self.inner.branches
    }

    fn __repr__(&self) -> String {
        let (v, e) = (self.inner.value, self.inner.stderr);
        format!(
            "Measurement({}: [{:.6e} ± {:.2e}, {:.6e} ± {:.2e}, {:.6e} ± {:.2e}] {} at {} spp)",
            self.quantity(),
            v[0],
            e[0],
            v[1],
            e[1],
            v[2],
            e[2],
            self.unit(),
            self.inner.spp
        )
    }
}
