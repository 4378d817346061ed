//! Sensor plugins (`perspective`, `thinlens`, `orthographic`, `batch`, meters, `distant`, and
//! steradian's own `workplane`) with their film (`hdrfilm`), reconstruction
//! filter (`box`, `tent`, `gaussian`, `mitchell`, `catmullrom`, `lanczos`) and sampler (`independent`, `stratified`,
//! `multijitter`, `orthogonal`, `ldsampler`). Every sensor also takes Mitsuba's `shutter_open`
//! and `shutter_close`, which change nothing (see [`shutter`]); `hdrfilm` takes `compensate`,
//! which its f64 sums make moot, and `banner`, which Mitsuba 3.9.1 accepts and ignores.

use glam::{UVec2, Vec2};
use steradian::emitter::horizontal_illuminance;
use steradian::film::{
    BoxFilter, CatmullRomFilter, ComponentFormat, Film, FilmWindow, GaussianFilter, LanczosFilter,
    MitchellFilter, PixelFormat, ReconstructionFilter, SampleBorder, TentFilter,
};
use steradian::geometry::Transform;
use steradian::sampling::{Sampler, SamplerKind};
use steradian::sensor::{
    Batch, Distant, DistantTarget, IrradianceMeter, Orthographic, Perspective, RadianceMeter,
    Sensor, SensorKind, ThinLens, Workplane, WorkplaneMode, WorkplaneUnit,
};

use super::field_of_view::field_of_view;
use super::{at, at_param, choice, geometry, lookup, Builder, Plugins};
use crate::error::{LoadError, LoadWarning};
use crate::tree::{ObjectTag, PluginNode};

fn single_child(node: &PluginNode, tag: ObjectTag) -> Result<Option<&PluginNode>, LoadError> {
    let c = node.children_of(tag);
    if c.len() > 1 {
        return Err(LoadError::at(
            c[1].pos(),
            format!("{} has more than one <{}>", node.desc(), tag.name()),
        ));
    }
    Ok(c.first().map(|c| &*c.node))
}

fn positive_int(node: &PluginNode, name: &str, default: i64) -> Result<u32, LoadError> {
    let v = node.props.get_int(name)?.unwrap_or(default);
    if v < 1 || v > u32::MAX as i64 {
        return Err(LoadError::at(
            node.props.position(name).unwrap_or(&node.pos),
            format!("{}: '{name}' must be a positive integer, got {v}", node.desc()),
        ));
    }
    Ok(v as u32)
}

/// Builds one reconstruction filter from its node.
type BuildFilter = fn(&PluginNode) -> Result<ReconstructionFilter, LoadError>;

/// Every reconstruction filter plugin, by Mitsuba `type`.
pub(super) const FILTERS: &Plugins<BuildFilter> = &[
    ("box", box_filter),
    ("tent", tent_filter),
    ("gaussian", gaussian_filter),
    ("mitchell", mitchell_filter),
    ("catmullrom", catmullrom_filter),
    ("lanczos", lanczos_filter),
];

pub(super) fn build_filter(node: &PluginNode) -> Result<ReconstructionFilter, LoadError> {
    let f = lookup(FILTERS, node)?(node)?;
    node.check_all_used()?;
    Ok(f)
}

fn box_filter(_: &PluginNode) -> Result<ReconstructionFilter, LoadError> {
    Ok(BoxFilter::new().into())
}

fn tent_filter(node: &PluginNode) -> Result<ReconstructionFilter, LoadError> {
    let radius = node.props.get_float("radius")?.unwrap_or(TentFilter::DEFAULT_RADIUS);
    Ok(TentFilter::new(radius).map_err(at(node))?.into())
}

fn gaussian_filter(node: &PluginNode) -> Result<ReconstructionFilter, LoadError> {
    let stddev = node.props.get_float("stddev")?.unwrap_or(GaussianFilter::DEFAULT_STDDEV);
    Ok(GaussianFilter::new(stddev).map_err(at(node))?.into())
}

fn mitchell_filter(node: &PluginNode) -> Result<ReconstructionFilter, LoadError> {
    let b = node.props.get_float("B")?.unwrap_or(MitchellFilter::DEFAULT_B);
    let c = node.props.get_float("C")?.unwrap_or(MitchellFilter::DEFAULT_C);
    Ok(MitchellFilter::new(b, c).map_err(at(node))?.into())
}

fn catmullrom_filter(_: &PluginNode) -> Result<ReconstructionFilter, LoadError> {
    Ok(CatmullRomFilter::new().into())
}

fn lanczos_filter(node: &PluginNode) -> Result<ReconstructionFilter, LoadError> {
    let lobes = node.props.get_int("lobes")?.unwrap_or(LanczosFilter::DEFAULT_LOBES);
    Ok(LanczosFilter::new(lobes).map_err(at(node))?.into())
}

/// Builds one film from its node.
type BuildFilm = fn(&PluginNode) -> Result<Film, LoadError>;

/// Every film plugin, by Mitsuba `type`.
pub(super) const FILMS: &Plugins<BuildFilm> = &[("hdrfilm", hdrfilm)];

pub(super) fn build_film(node: &PluginNode) -> Result<Film, LoadError> {
    let film = lookup(FILMS, node)?(node)?;
    node.check_all_used()?;
    Ok(film)
}

fn hdrfilm(node: &PluginNode) -> Result<Film, LoadError> {
    let p = &node.props;
    let width = positive_int(node, "width", Film::DEFAULT_WIDTH as i64)?;
    let height = positive_int(node, "height", Film::DEFAULT_HEIGHT as i64)?;
    let filter = match single_child(node, ObjectTag::RFilter)? {
        Some(f) => build_filter(f)?,
        None => ReconstructionFilter::default(),
    };
    if let Some(f) = p.get_string("file_format")? {
        if f != "openexr" && f != "exr" {
            return Err(LoadError::at(
                p.position("file_format").unwrap(),
                format!("hdrfilm: file_format '{f}' is not supported (steradian writes OpenEXR)"),
            ));
        }
    }
    let pixel_format = match p.get_string("pixel_format")? {
        Some(f) => PixelFormat::parse(&f).map_err(|m| {
            LoadError::at(p.position("pixel_format").unwrap(), format!("hdrfilm: {m}"))
        })?,
        None => PixelFormat::default(),
    };
    let component_format = match p.get_string("component_format")? {
        Some(f) => ComponentFormat::parse(&f).map_err(|m| {
            LoadError::at(p.position("component_format").unwrap(), format!("hdrfilm: {m}"))
        })?,
        None => ComponentFormat::default(),
    };
    // Kahan-compensated sums in Mitsuba's f32 film; steradian's sums are f64 anyway
    p.get_bool("compensate")?;
    // Mitsuba 0.6's film banner: Mitsuba 3.9.1 still accepts the flag (scenes written for
    // Mitsuba 0.6 and 2 carry it) and draws nothing; neither does steradian
    p.get_bool("banner")?;
    let sample_border = match p.get_bool("sample_border")? {
        Some(true) => SampleBorder::WithMargin,
        Some(false) | None => SampleBorder::FilmOnly,
    };
    // the crop window (Mitsuba's defaults: the whole film)
    let crop_int = |name: &str, default: u32, range: std::ops::RangeInclusive<u32>| {
        let v = p.get_int(name)?.unwrap_or(default as i64);
        if v < *range.start() as i64 || v > *range.end() as i64 {
            return Err(LoadError::at(
                p.position(name).unwrap_or(&node.pos),
                format!(
                    "hdrfilm: {name} = {v} leaves the {width}×{height} film (it must lie in {}..={})",
                    range.start(),
                    range.end()
                ),
            ));
        }
        Ok(v as u32)
    };
    let ox = crop_int("crop_offset_x", 0, 0..=width - 1)?;
    let oy = crop_int("crop_offset_y", 0, 0..=height - 1)?;
    let cw = crop_int("crop_width", width - ox, 1..=width - ox)?;
    let ch = crop_int("crop_height", height - oy, 1..=height - oy)?;
    let core_err = |m: String| {
        // The core's message already says "hdrfilm: ".
        LoadError::at(
            &node.pos,
            format!("{}: {}", node.desc(), m.strip_prefix("hdrfilm: ").unwrap_or(&m)),
        )
    };
    let mut film = Film::new(cw, ch, filter).map_err(core_err)?;
    if (ox, oy, cw, ch) != (0, 0, width, height) {
        film = film.with_crop(UVec2::new(ox, oy), UVec2::new(width, height)).map_err(core_err)?;
    }
    film.component_format = component_format;
    film.sample_border = sample_border;
    film.pixel_format = pixel_format;
    Ok(film)
}

/// Reads one sampler's own parameters (not `sample_count` and `seed`) from its node.
type BuildSampler = fn(&Builder, &PluginNode) -> Result<SamplerKind, LoadError>;

/// Every sampler plugin, by Mitsuba `type`. Every Mitsuba sampler type promises the same
/// expectation and differs only in noise; steradian draws Owen-scrambled Sobol points for all
/// of them (unbiased, and lower error than any of them). `--sampler independent` restores
/// i.i.d. numbers.
pub(super) const SAMPLERS: &Plugins<BuildSampler> = &[
    ("independent", sobol),
    ("stratified", jittered),
    ("multijitter", jittered),
    ("orthogonal", orthogonal),
    ("ldsampler", sobol),
];

pub(super) fn build_sampler(b: &Builder, node: &PluginNode) -> Result<Sampler, LoadError> {
    let kind = lookup(SAMPLERS, node)?(b, node)?;
    let sample_count = positive_int(node, "sample_count", Sampler::DEFAULT_SAMPLE_COUNT as i64)?;
    let seed = node.props.get_int("seed")?.unwrap_or(Sampler::DEFAULT_SEED as i64);
    if seed < 0 {
        return Err(LoadError::at(
            node.props.position("seed").unwrap(),
            "seed must be non-negative",
        ));
    }
    node.check_all_used()?;
    Ok(Sampler { kind, sample_count, seed: seed as u64 })
}

/// `independent` and `ldsampler`: no parameters of their own.
fn sobol(_: &Builder, _: &PluginNode) -> Result<SamplerKind, LoadError> {
    Ok(SamplerKind::Sobol)
}

/// `jitter` of `stratified`, `multijitter` and `orthogonal` (default true). Mitsuba's
/// `jitter = false` puts each sample at its stratum's centre, which biases the image;
/// steradian draws its own randomised points for every sampler type anyway, so the flag is
/// accepted (scenes exported by the Blender add-on set it) and ignored, with a warning.
fn jitter(b: &Builder, node: &PluginNode) -> Result<(), LoadError> {
    if node.props.get_bool("jitter")? == Some(false) {
        let pos = node.props.position("jitter").unwrap_or(&node.pos);
        b.warn(LoadWarning::at(
            pos,
            format!(
                "{}: jitter = false is ignored: steradian's samples are always randomised \
                 (Owen-scrambled Sobol points), so the image stays unbiased where Mitsuba's \
                 would sit at the strata's centres",
                node.desc()
            ),
        ));
    }
    Ok(())
}

/// `stratified` and `multijitter`: `jitter` (see [`jitter`]).
fn jittered(b: &Builder, node: &PluginNode) -> Result<SamplerKind, LoadError> {
    jitter(b, node)?;
    Ok(SamplerKind::Sobol)
}

fn orthogonal(b: &Builder, node: &PluginNode) -> Result<SamplerKind, LoadError> {
    if let Some(s) = node.props.get_int("strength")? {
        if s != 2 {
            return Err(LoadError::at(
                node.props.position("strength").unwrap(),
                "orthogonal: only strength 2 is supported",
            ));
        }
    }
    jitter(b, node)?;
    Ok(SamplerKind::Sobol)
}

/// Builds one sensor's kind from its node, given its film and, for a sensor declared inside
/// a shape, that shape's index.
type BuildSensor = fn(&Builder, &PluginNode, &Film, Option<u32>) -> Result<SensorKind, LoadError>;

/// Every sensor plugin, by Mitsuba `type`.
pub(super) const SENSORS: &Plugins<BuildSensor> = &[
    ("perspective", perspective),
    ("thinlens", thinlens),
    ("orthographic", orthographic_sensor),
    ("radiancemeter", radiancemeter),
    ("irradiancemeter", irradiancemeter),
    ("batch", batch),
    ("distant", distant),
    ("workplane", workplane),
];

/// The cells of a `workplane` along x and y.
fn workplane_cells(node: &PluginNode) -> Result<(u32, u32), LoadError> {
    let d = Workplane::DEFAULT_CELLS as i64;
    Ok((positive_int(node, "nx", d)?, positive_int(node, "ny", d)?))
}

/// steradian's `workplane` (parameters and defaults: `steradian::sensor::Workplane`).
fn workplane(
    b: &Builder,
    node: &PluginNode,
    film: &Film,
    shape: Option<u32>,
) -> Result<SensorKind, LoadError> {
    not_in_shape(node, shape)?;
    let p = &node.props;
    let (nx, ny) = workplane_cells(node)?;
    if (film.width, film.height) != (nx, ny) {
        return Err(LoadError::at(
            &node.pos,
            format!(
                "{}: the film must be nx x ny = {nx}x{ny} pixels (one per cell), got {}x{}",
                node.desc(),
                film.width,
                film.height
            ),
        ));
    }
    let mode = choice(
        node,
        "mode",
        Workplane::DEFAULT_MODE,
        &[("point", WorkplaneMode::Point), ("cell", WorkplaneMode::Cell)],
    )?;
    // the daylight factor's outdoor illuminance comes from the scene's sky, known once the
    // whole scene is built: `resolve_daylight_factors` fills it in (NaN until then)
    let unresolved = WorkplaneUnit::DaylightFactor { outdoor_lux: f64::NAN };
    let unit = choice(
        node,
        "quantity",
        Workplane::DEFAULT_UNIT,
        &[
            ("illuminance", WorkplaneUnit::Illuminance),
            ("irradiance", WorkplaneUnit::Irradiance),
            ("daylight_factor", unresolved),
        ],
    )?;
    if matches!(unit, WorkplaneUnit::DaylightFactor { .. }) {
        b.daylight_planes.borrow_mut().push((node.pos.clone(), node.desc()));
    }
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let mut w = Workplane::new(to_world, nx, ny, mode, unit).map_err(at_param(node))?;
    w.batch = positive_int(node, "batch", Workplane::DEFAULT_BATCH as i64)?;
    if w.batch > steradian::render::MAX_BATCH {
        return Err(LoadError::at(
            p.position("batch").unwrap_or(&node.pos),
            format!("{}: 'batch' must be at most {}", node.desc(), steradian::render::MAX_BATCH),
        ));
    }
    Ok(SensorKind::Workplane(w))
}

/// Gives every work plane that reports the daylight factor the outdoor illuminance of the
/// scene's `ciesky` (E_out, `steradian::emitter::horizontal_illuminance`); an error, at the
/// first such plane, when the scene has no `ciesky` or it is black.
pub(crate) fn resolve_daylight_factors(b: &mut Builder) -> Result<(), LoadError> {
    let planes = b.daylight_planes.borrow();
    let Some((pos, desc)) = planes.first() else { return Ok(()) };
    let outdoor_lux = match b.sky.get() {
        Some((model, level)) => horizontal_illuminance(model, level),
        None => {
            return Err(LoadError::at(
                pos,
                format!(
                    "{desc}: the daylight factor needs the scene's sky: add a <emitter \
                     type=\"ciesky\"> (E_out is its unobstructed horizontal illuminance)"
                ),
            ))
        }
    };
    if !(outdoor_lux > 0.0 && outdoor_lux.is_finite()) {
        return Err(LoadError::at(
            pos,
            format!("{desc}: the daylight factor needs a sky brighter than 0 lx"),
        ));
    }
    // E_in would hold the direct sun, which the daylight factor leaves out by definition
    if b.desc.emitters.iter().any(|e| matches!(e, steradian::emitter::Emitter::Sun(_))) {
        return Err(LoadError::at(
            pos,
            format!(
                "{desc}: the daylight factor is defined under the sky alone: remove the scene's \
                 `sun` (or measure illuminance)"
            ),
        ));
    }
    drop(planes);
    for sensor in &mut b.desc.sensors {
        if let SensorKind::Workplane(w) = &mut sensor.kind {
            if let WorkplaneUnit::DaylightFactor { .. } = w.unit {
                w.unit = WorkplaneUnit::DaylightFactor { outdoor_lux };
            }
        }
    }
    Ok(())
}

/// Builds a sensor; `shape` is the enclosing shape for an `irradiancemeter`.
pub(crate) fn build(
    b: &Builder,
    node: &PluginNode,
    shape: Option<u32>,
) -> Result<Sensor, LoadError> {
    let build_kind = lookup(SENSORS, node)?;
    let film = match single_child(node, ObjectTag::Film)? {
        Some(f) => build_film(f)?,
        // a work plane's film is its grid
        None if node.plugin_type == "workplane" => {
            let (nx, ny) = workplane_cells(node)?;
            Film::new(nx, ny, ReconstructionFilter::Box(BoxFilter)).map_err(at(node))?
        }
        None => {
            Film::new(Film::DEFAULT_WIDTH, Film::DEFAULT_HEIGHT, ReconstructionFilter::default())
                .map_err(at(node))?
        }
    };
    let sampler = match single_child(node, ObjectTag::Sampler)? {
        Some(s) => build_sampler(b, s)?,
        None => Sampler::default(),
    };
    let kind = build_kind(b, node, &film, shape)?;
    shutter(node)?;
    node.check_all_used()?;
    Ok(Sensor { kind, film, sampler, id: node.id.clone().unwrap_or_default() })
}

/// Every Mitsuba sensor's `shutter_open` and `shutter_close` (s, default 0 and 0): checked as
/// Mitsuba checks them (finite, open ≤ close) and otherwise without effect: nothing a scene
/// file describes moves (Mitsuba 3 has no animated transforms in XML either), so a sample's
/// time changes no ray.
fn shutter(node: &PluginNode) -> Result<(), LoadError> {
    let p = &node.props;
    let open = p.get_float("shutter_open")?.unwrap_or(0.0);
    let close = p.get_float("shutter_close")?.unwrap_or(0.0);
    if !(open.is_finite() && close.is_finite() && open <= close) {
        return Err(LoadError::at(
            p.position("shutter_close").or(p.position("shutter_open")).unwrap_or(&node.pos),
            format!(
                "{}: the shutter must open (shutter_open = {open}) no later than it closes (shutter_close = {close})",
                node.desc()
            ),
        ));
    }
    Ok(())
}

/// Only an `irradiancemeter` may be declared inside a shape.
fn not_in_shape(node: &PluginNode, shape: Option<u32>) -> Result<(), LoadError> {
    match shape {
        None => Ok(()),
        Some(_) => Err(LoadError::at(
            &node.pos,
            format!("only an irradiancemeter can be declared inside a shape, not {}", node.desc()),
        )),
    }
}

/// A meter measures one value: its film must be 1x1.
fn meter_film(node: &PluginNode, film: &Film) -> Result<(), LoadError> {
    if (film.width, film.height) != (1, 1) {
        return Err(LoadError::at(
            &node.pos,
            format!(
                "{}: a meter needs a 1x1 film, got {}x{}",
                node.desc(),
                film.width,
                film.height
            ),
        ));
    }
    Ok(())
}

fn irradiancemeter(
    _: &Builder,
    node: &PluginNode,
    film: &Film,
    shape: Option<u32>,
) -> Result<SensorKind, LoadError> {
    let Some(shape) = shape else {
        return Err(LoadError::at(
            &node.pos,
            "an irradiancemeter must be declared inside the <shape> it measures",
        ));
    };
    meter_film(node, film)?;
    Ok(SensorKind::IrradianceMeter(IrradianceMeter { shape }))
}

fn radiancemeter(
    _: &Builder,
    node: &PluginNode,
    film: &Film,
    shape: Option<u32>,
) -> Result<SensorKind, LoadError> {
    not_in_shape(node, shape)?;
    meter_film(node, film)?;
    let p = &node.props;
    let meter =
        match (p.get_transform("to_world")?, p.get_point("origin")?, p.get_vector("direction")?) {
            (Some(t), None, None) => RadianceMeter::from_transform(&t),
            (None, Some(o), Some(d)) => RadianceMeter::new(o, d),
            (None, None, None) => RadianceMeter::from_transform(&Default::default()),
            (Some(_), _, _) => {
                return Err(LoadError::at(
                    &node.pos,
                    "radiancemeter: give either 'to_world' or 'origin' and 'direction', not both",
                ))
            }
            _ => {
                return Err(LoadError::at(
                    &node.pos,
                    "radiancemeter: 'origin' and 'direction' go together",
                ))
            }
        }
        .map_err(at(node))?;
    Ok(SensorKind::RadianceMeter(meter))
}

/// The parameters `perspective` and `thinlens` share.
struct Projective {
    to_world: Transform,
    /// Radians.
    x_fov: f32,
    /// Film width / height.
    aspect: f32,
    near_clip: f32,
    far_clip: f32,
    focus_distance: f32,
}

/// The projective parameters for `film`, the field of view read against `fov_film`'s size
/// (the film itself, except in a `batch`).
fn projective(node: &PluginNode, film: &Film, fov_film: &Film) -> Result<Projective, LoadError> {
    let p = &node.props;
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let fov = field_of_view(node)?;
    // the full frame, of which a cropped film renders a window
    let (fov_size, size) = (fov_film.window().full_size(), film.window().full_size());
    let x_fov = fov.x_fov(fov_size.x, fov_size.y).map_err(at_param(node))?;
    let aspect = size.x as f32 / size.y as f32;
    let near_clip = p.get_float("near_clip")?.unwrap_or(Perspective::DEFAULT_NEAR_CLIP);
    let far_clip = p.get_float("far_clip")?.unwrap_or(Perspective::DEFAULT_FAR_CLIP);
    let focus_distance = p.get_float("focus_distance")?.unwrap_or(far_clip);
    Ok(Projective { to_world, x_fov, aspect, near_clip, far_clip, focus_distance })
}

fn perspective(
    _: &Builder,
    node: &PluginNode,
    film: &Film,
    shape: Option<u32>,
) -> Result<SensorKind, LoadError> {
    not_in_shape(node, shape)?;
    perspective_camera(node, film, film)
}

fn perspective_camera(
    node: &PluginNode,
    film: &Film,
    fov_film: &Film,
) -> Result<SensorKind, LoadError> {
    let c = projective(node, film, fov_film)?;
    let p = &node.props;
    let offset = Vec2::new(
        p.get_float("principal_point_offset_x")?.unwrap_or(0.0),
        p.get_float("principal_point_offset_y")?.unwrap_or(0.0),
    );
    let camera = Perspective::new(c.to_world, c.x_fov, c.aspect, c.near_clip, c.far_clip)
        .and_then(|camera| camera.with_principal_point_offset(offset))
        .map_err(at_param(node))?;
    Ok(SensorKind::Perspective(camera))
}

fn thinlens(
    _: &Builder,
    node: &PluginNode,
    film: &Film,
    shape: Option<u32>,
) -> Result<SensorKind, LoadError> {
    not_in_shape(node, shape)?;
    thinlens_camera(node, film, film)
}

fn thinlens_camera(
    node: &PluginNode,
    film: &Film,
    fov_film: &Film,
) -> Result<SensorKind, LoadError> {
    let c = projective(node, film, fov_film)?;
    let aperture = node.props.get_float("aperture_radius")?.ok_or_else(|| {
        LoadError::at(&node.pos, format!("{}: missing 'aperture_radius'", node.desc()))
    })?;
    let camera = ThinLens::new(
        c.to_world,
        c.x_fov,
        c.aspect,
        c.near_clip,
        c.far_clip,
        aperture,
        c.focus_distance,
    )
    .map_err(at_param(node))?;
    Ok(SensorKind::ThinLens(camera))
}

fn orthographic_sensor(
    _: &Builder,
    node: &PluginNode,
    film: &Film,
    shape: Option<u32>,
) -> Result<SensorKind, LoadError> {
    not_in_shape(node, shape)?;
    Ok(SensorKind::Orthographic(orthographic(node, film)?))
}

/// `orthographic` (core: sensor/orthographic.rs): no field of view; `to_world` may scale.
fn orthographic(node: &PluginNode, film: &Film) -> Result<Orthographic, LoadError> {
    use steradian::sensor::orthographic::{DEFAULT_FAR_CLIP, DEFAULT_NEAR_CLIP};
    let p = &node.props;
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let near = p.get_float("near_clip")?.unwrap_or(DEFAULT_NEAR_CLIP);
    let far = p.get_float("far_clip")?.unwrap_or(DEFAULT_FAR_CLIP);
    let size = film.window().full_size();
    let aspect = size.x as f32 / size.y as f32;
    Orthographic::new(to_world, aspect, near, far).map_err(at_param(node))
}

/// `batch`: its nested cameras, each built for its share of the film (width / n × height);
/// the width must be a multiple of their number. Nested meters, batches and films are
/// refused (the batch's film is the one rendered). As in Mitsuba, which builds each camera
/// for a default film (768 × 576) before resizing it, a camera's `fov` is read against that
/// default size (it matters for `fov_axis` other than `x` and for `focal_length`), and the
/// horizontal field of view it gives is kept on the camera's share of the film.
fn batch(
    _: &Builder,
    node: &PluginNode,
    film: &Film,
    shape: Option<u32>,
) -> Result<SensorKind, LoadError> {
    not_in_shape(node, shape)?;
    if let Some(s) = node.children_of(ObjectTag::Shape).first() {
        return Err(LoadError::at(
            s.pos(),
            format!("{}: sensors attached to shapes cannot be batched", node.desc()),
        ));
    }
    let nested = node.children_of(ObjectTag::Sensor);
    if nested.is_empty() {
        return Err(at(node)("needs at least one nested <sensor>".into()));
    }
    let n = nested.len() as u32;
    if film.window() != FilmWindow::whole(film.width, film.height) {
        return Err(at(node)("a batch renders the whole film: crop_* is not supported".into()));
    }
    if film.sample_border == SampleBorder::WithMargin {
        return Err(at(node)("a batch's film cannot sample_border (not supported)".into()));
    }
    if !film.width.is_multiple_of(n) {
        return Err(at(node)(format!(
            "the film's width {} must be a multiple of the number of sensors ({n})",
            film.width
        )));
    }
    let sub = Film::new(film.width / n, film.height, film.filter).map_err(at(node))?;
    let fov_film = Film::default();
    let mut cameras = Vec::with_capacity(nested.len());
    for c in nested {
        let child = &*c.node;
        lookup(SENSORS, child)?;
        if let Some(f) = child.children_of(ObjectTag::Film).first() {
            return Err(LoadError::at(
                f.pos(),
                format!("{}: a batched camera renders into the batch's film", child.desc()),
            ));
        }
        cameras.push(match child.plugin_type.as_str() {
            "perspective" => perspective_camera(child, &sub, &fov_film)?,
            "thinlens" => thinlens_camera(child, &sub, &fov_film)?,
            "orthographic" => SensorKind::Orthographic(orthographic(child, &sub)?),
            _ => {
                return Err(LoadError::at(
                    c.pos(),
                    format!("{}: only cameras can be batched, not {}", node.desc(), child.desc()),
                ))
            }
        });
        child.check_all_used()?;
    }
    Ok(SensorKind::Batch(Batch { cameras }))
}

/// `distant` (core: sensor/distant.rs): a 1x1 film; `to_world` or `direction`, not both;
/// `target` a point or a nested shape (built for its geometry only, not rendered).
fn distant(
    b: &Builder,
    node: &PluginNode,
    film: &Film,
    shape: Option<u32>,
) -> Result<SensorKind, LoadError> {
    not_in_shape(node, shape)?;
    if (film.width, film.height) != (1, 1) {
        return Err(at(node)(format!(
            "supports only a 1x1 film, got {}x{} (Mitsuba 3 refuses it too)",
            film.width, film.height
        )));
    }
    if film.filter.radius() > 0.5 + 1e-4 {
        b.warn(LoadWarning::at(
            &node.pos,
            format!(
                "{}: a reconstruction filter of radius {} is wider than the one pixel (use the default box)",
                node.desc(),
                film.filter.radius()
            ),
        ));
    }
    let p = &node.props;
    let target = match (p.contains("target"), node.child("target")) {
        (true, Some(c)) => {
            return Err(LoadError::at(
                c.pos(),
                format!("{}: 'target' is given twice, as a property and an object", node.desc()),
            ))
        }
        (true, None) => DistantTarget::Point(p.get_point("target")?.unwrap_or_default()),
        (false, Some(c)) if c.node.tag == ObjectTag::Shape => {
            DistantTarget::Shape(Box::new(geometry::build_geometry(b, &c.node)?))
        }
        (false, Some(c)) => {
            return Err(LoadError::at(
                c.pos(),
                format!(
                    "{}: 'target' must be a point or a shape, not {}",
                    node.desc(),
                    c.node.desc()
                ),
            ))
        }
        (false, None) => DistantTarget::BoundingSphere,
    };
    let sensor = match (p.get_transform("to_world")?, p.get_vector("direction")?) {
        (Some(_), Some(_)) => {
            return Err(at(node)(
                "give either 'to_world' or 'direction', not both (Mitsuba 3 refuses both)".into(),
            ))
        }
        (None, Some(d)) => Distant::along(d, target),
        (t, None) => Distant::new(&t.unwrap_or_default(), target),
    };
    Ok(SensorKind::Distant(sensor.map_err(at(node))?))
}
