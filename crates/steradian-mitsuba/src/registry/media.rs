//! Medium, volume and phase-function plugins: `homogeneous`, `heterogeneous`; `gridvolume`,
//! `constvolume`; `isotropic`, `hg`, `rayleigh`, `blendphase`. Their manuals are the core
//! library's files (`steradian::medium`, `steradian::phase`).
//!
//! A medium is declared inside the shape that bounds it (`<medium name="interior" ...>`, or
//! `exterior`), inside the sensor that sits in it (`name="medium"`), or at scene level with an
//! `id` and referenced (`<ref name="interior" id="fog"/>`); a referenced medium is built once
//! and shared.

use std::sync::Arc;

use steradian::geometry::Transform;
use steradian::medium::{
    GridVolume, Heterogeneous, Homogeneous, Medium, Volume, VolumeData, VolumeFilter, VolumeWrap,
};
use steradian::phase::{
    BlendPhase, HenyeyGreenstein, Isotropic, PhaseFunction, Rayleigh, TabulatedPhase,
};
use steradian::Spectrum;

use super::{at, at_filename, at_param, choice, lookup, required_string, Builder, Plugins};
use crate::error::LoadError;
use crate::tree::{Child, ObjectTag, PluginNode};

type BuildMedium = fn(&Builder, &PluginNode) -> Result<Medium, LoadError>;

/// Every medium plugin, by Mitsuba `type`.
pub(super) const MEDIA: &Plugins<BuildMedium> =
    &[("homogeneous", homogeneous), ("heterogeneous", heterogeneous)];

type BuildVolume = fn(&Builder, &PluginNode) -> Result<Volume, LoadError>;

/// Every volume plugin, by Mitsuba `type`.
pub(super) const VOLUMES: &Plugins<BuildVolume> =
    &[("gridvolume", gridvolume), ("constvolume", constvolume)];

type BuildPhase = fn(&PluginNode) -> Result<PhaseFunction, LoadError>;

/// Every phase-function plugin, by Mitsuba `type`.
pub(super) const PHASES: &Plugins<BuildPhase> = &[
    ("isotropic", isotropic),
    ("hg", hg),
    ("rayleigh", rayleigh),
    ("tabphase", tabphase),
    ("blendphase", blendphase),
];

/// Builds one medium from its node.
pub(super) fn build(b: &Builder, node: &PluginNode) -> Result<Medium, LoadError> {
    if node.tag != ObjectTag::Medium {
        return Err(LoadError::at(&node.pos, format!("{} is not a <medium>", node.desc())));
    }
    let medium = lookup(MEDIA, node)?(b, node)?;
    node.check_all_used()?;
    Ok(medium)
}

/// The phase function nested in a medium: at most one, `isotropic` by default.
fn nested_phase(node: &PluginNode) -> Result<PhaseFunction, LoadError> {
    let children = node.children_of(ObjectTag::Phase);
    match children.as_slice() {
        [] => Ok(PhaseFunction::Isotropic(Isotropic)),
        [one] => build_phase(&one.node),
        [_, second, ..] => Err(LoadError::at(
            second.pos(),
            format!("{} has more than one phase function", node.desc()),
        )),
    }
}

fn build_phase(node: &PluginNode) -> Result<PhaseFunction, LoadError> {
    let phase = lookup(PHASES, node)?(node)?;
    node.check_all_used()?;
    Ok(phase)
}

/// `homogeneous` (`steradian::medium::Homogeneous`): `sigma_t`, `albedo`, `scale`,
/// `sample_emitters`, a nested phase function.
fn homogeneous(b: &Builder, node: &PluginNode) -> Result<Medium, LoadError> {
    let sigma_t = constant_param(b, node, "sigma_t", Homogeneous::DEFAULT_SIGMA_T)?;
    let albedo = constant_param(b, node, "albedo", Homogeneous::DEFAULT_ALBEDO)?;
    let (scale, sample_emitters, phase) =
        shared_parameters(node, Homogeneous::DEFAULT_SCALE, Homogeneous::DEFAULT_SAMPLE_EMITTERS)?;
    let m =
        Homogeneous::new(sigma_t, albedo, scale, phase, sample_emitters).map_err(at_param(node))?;
    Ok(Medium::Homogeneous(m))
}

/// `heterogeneous` (`steradian::medium::Heterogeneous`): `sigma_t` and `albedo` (each a
/// nested `<volume>` or a value, which Mitsuba makes a `constvolume` over the unit cube),
/// `scale`, `sample_emitters`, a nested phase function.
fn heterogeneous(b: &Builder, node: &PluginNode) -> Result<Medium, LoadError> {
    let sigma_t = volume_param(b, node, "sigma_t", Heterogeneous::DEFAULT_SIGMA_T)?;
    let albedo = volume_param(b, node, "albedo", Heterogeneous::DEFAULT_ALBEDO)?;
    let (scale, sample_emitters, phase) = shared_parameters(
        node,
        Heterogeneous::DEFAULT_SCALE,
        Heterogeneous::DEFAULT_SAMPLE_EMITTERS,
    )?;
    let m = Heterogeneous::new(sigma_t, albedo, scale, phase, sample_emitters).map_err(|e| {
        // a volume's error points at the volume
        match node.child(e.param) {
            Some(c) => LoadError::at(c.pos(), format!("{}: {e}", node.desc())),
            None => at_param(node)(e),
        }
    })?;
    // every <volume> child must fill a slot
    if let Some(c) = node
        .children_of(ObjectTag::Volume)
        .into_iter()
        .find(|c| !matches!(c.name.as_deref(), Some("sigma_t" | "albedo")))
    {
        return Err(LoadError::at(
            c.pos(),
            format!(
                "{}: a volume in {} must be named \"sigma_t\" or \"albedo\"",
                c.node.desc(),
                node.desc()
            ),
        ));
    }
    Ok(Medium::Heterogeneous(Box::new(m)))
}

/// A homogeneous medium's `sigma_t` or `albedo`: a value, or (as Mitsuba also takes it) a
/// nested `constvolume`, whose value is used; any other volume is an error at it (the medium
/// is the same everywhere).
fn constant_param(
    b: &Builder,
    node: &PluginNode,
    name: &str,
    default: f32,
) -> Result<Spectrum, LoadError> {
    let only_constant = |c: &Child| {
        if c.node.plugin_type == "constvolume" {
            return Ok(());
        }
        Err(LoadError::at(
            c.pos(),
            format!(
                "{}: a homogeneous medium's '{name}' is a value or a `constvolume`, not {} (use `heterogeneous`)",
                node.desc(),
                c.node.desc()
            ),
        ))
    };
    match nested_volume(b, node, name, only_constant)? {
        None => Ok(node.props.get_spectrum(name)?.unwrap_or(Spectrum::splat(default))),
        Some(Volume { data: VolumeData::Const(v), .. }) => Ok(v),
        Some(_) => {
            Err(LoadError::at(&node.pos, format!("{}: '{name}' must be a constant", node.desc())))
        }
    }
}

/// What both media read besides their coefficients: `scale` and `sample_emitters` (with the
/// plugin's defaults), the nested phase function, and Mitsuba's `has_spectral_extinction` (a
/// boolean, default true), read and without effect: steradian's free flights are unbiased
/// either way (spectral MIS, `steradian::medium`), and a grey σ_t is recognised from its values.
fn shared_parameters(
    node: &PluginNode,
    default_scale: f32,
    default_sample_emitters: bool,
) -> Result<(f32, bool, PhaseFunction), LoadError> {
    let p = &node.props;
    let scale = p.get_float("scale")?.unwrap_or(default_scale);
    let sample_emitters = p.get_bool("sample_emitters")?.unwrap_or(default_sample_emitters);
    let phase = nested_phase(node)?;
    p.get_bool("has_spectral_extinction")?;
    Ok((scale, sample_emitters, phase))
}

/// The volume a medium gives for parameter `name` as a nested `<volume name="...">` (or a
/// `<ref>` to one), built, or `None`; `accept` may refuse its type first. A parameter given
/// both as a value and as a volume is an error at the volume.
fn nested_volume(
    b: &Builder,
    node: &PluginNode,
    name: &str,
    accept: impl Fn(&Child) -> Result<(), LoadError>,
) -> Result<Option<Volume>, LoadError> {
    let nested = node
        .children
        .iter()
        .find(|c| c.node.tag == ObjectTag::Volume && c.name.as_deref() == Some(name));
    let Some(c) = nested else { return Ok(None) };
    accept(c)?;
    if node.props.contains(name) {
        return Err(LoadError::at(
            c.pos(),
            format!("{}: '{name}' is given twice (a value and a volume)", node.desc()),
        ));
    }
    c.mark_used();
    let volume = lookup(VOLUMES, &c.node)?(b, &c.node)?;
    c.node.check_all_used()?;
    Ok(Some(volume))
}

/// A medium's volume parameter: a nested `<volume name="...">` (or a `<ref>` to one), else a
/// value (float, rgb or spectrum), else `default`, the last two as Mitsuba's `constvolume`
/// over the unit cube.
pub(super) fn volume_param(
    b: &Builder,
    node: &PluginNode,
    name: &str,
    default: f32,
) -> Result<Volume, LoadError> {
    if let Some(volume) = nested_volume(b, node, name, |_| Ok(()))? {
        return Ok(volume);
    }
    let v = node.props.get_spectrum(name)?.unwrap_or(Spectrum::splat(default));
    Ok(Volume::constant(v))
}

/// `gridvolume` (`steradian::medium::GridVolume`).
fn gridvolume(b: &Builder, node: &PluginNode) -> Result<Volume, LoadError> {
    let p = &node.props;
    let file = required_string(node, "filename", " (a Mitsuba .vol file)")?;
    let path = b.resolve_path(node, &file);
    let mut grid = GridVolume::read(&path).map_err(at_filename(node))?;
    grid.filter = choice(
        node,
        "filter_type",
        VolumeFilter::default(),
        &[("trilinear", VolumeFilter::Trilinear), ("nearest", VolumeFilter::Nearest)],
    )?;
    grid.wrap = choice(
        node,
        "wrap_mode",
        VolumeWrap::default(),
        &[
            ("clamp", VolumeWrap::Clamp),
            ("repeat", VolumeWrap::Repeat),
            ("mirror", VolumeWrap::Mirror),
        ],
    )?;
    if let Some(max) = p.get_float("max_value")? {
        grid.set_max(max).map_err(|m| {
            LoadError::at(
                p.position("max_value").unwrap_or(&node.pos),
                format!("{}: {m}", node.desc()),
            )
        })?;
    }
    // RGB rendering reads the values as they are, raw or not
    let _raw = p.get_bool("raw")?;
    let mut to_world = p.get_transform("to_world")?.unwrap_or_default();
    if p.get_bool("use_grid_bbox")?.unwrap_or(false) {
        let (lo, hi) = grid.bbox;
        let fit = Transform::scale(hi - lo)
            .map(|s| s.then(&Transform::translate(lo)))
            .map_err(|e| at(node)(format!("the file's bounding box is degenerate: {e}")))?;
        to_world = fit.then(&to_world);
    }
    Ok(Volume::new(VolumeData::Grid(Arc::new(grid)), to_world))
}

/// `constvolume`: `value` (spectrum, default 1) over the unit cube that `to_world` places.
fn constvolume(_: &Builder, node: &PluginNode) -> Result<Volume, LoadError> {
    let p = &node.props;
    let value = p.get_spectrum("value")?.unwrap_or(Spectrum::ONE);
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    Ok(Volume::new(VolumeData::Const(value), to_world))
}

/// `isotropic` (no parameters).
fn isotropic(_: &PluginNode) -> Result<PhaseFunction, LoadError> {
    Ok(PhaseFunction::Isotropic(Isotropic))
}

/// `hg`: `g`.
fn hg(node: &PluginNode) -> Result<PhaseFunction, LoadError> {
    let g = node.props.get_float("g")?.unwrap_or(HenyeyGreenstein::DEFAULT_G);
    Ok(PhaseFunction::HenyeyGreenstein(HenyeyGreenstein::new(g).map_err(at_param(node))?))
}

/// `rayleigh` (no parameters).
fn rayleigh(_: &PluginNode) -> Result<PhaseFunction, LoadError> {
    Ok(PhaseFunction::Rayleigh(Rayleigh))
}

/// `tabphase`: `values`, a string of numbers separated by commas or spaces (Mitsuba's).
fn tabphase(node: &PluginNode) -> Result<PhaseFunction, LoadError> {
    let p = &node.props;
    let text = p.get_string("values")?.ok_or_else(|| {
        LoadError::at(&node.pos, format!("{}: missing 'values' (a list of numbers)", node.desc()))
    })?;
    let pos = p.position("values").unwrap_or(&node.pos);
    let values = text
        .split([',', ' '])
        .filter(|w| !w.is_empty())
        .map(|w| {
            w.trim().parse::<f32>().map_err(|_| {
                LoadError::at(pos, format!("{}: '{w}' in 'values' is not a number", node.desc()))
            })
        })
        .collect::<Result<Vec<f32>, LoadError>>()?;
    let table = TabulatedPhase::new(&values).map_err(at_param(node))?;
    Ok(PhaseFunction::Tabulated(table))
}

/// `blendphase`: `weight` and two nested phase functions, ordered as Mitsuba orders them (by
/// their names when named, else in document order).
fn blendphase(node: &PluginNode) -> Result<PhaseFunction, LoadError> {
    let weight = node.props.get_float("weight")?.unwrap_or(BlendPhase::DEFAULT_WEIGHT);
    let mut children = node.children_of(ObjectTag::Phase);
    if children.len() != 2 {
        return Err(LoadError::at(
            &node.pos,
            format!(
                "{}: needs exactly two nested phase functions, got {}",
                node.desc(),
                children.len()
            ),
        ));
    }
    if children.iter().all(|c| c.name.is_some()) {
        children.sort_by(|a, b| a.name.cmp(&b.name));
    }
    let first = build_phase(&children[0].node)?;
    let second = build_phase(&children[1].node)?;
    let blend = BlendPhase::new(weight, first, second).map_err(at_param(node))?;
    Ok(PhaseFunction::Blend(Box::new(blend)))
}
