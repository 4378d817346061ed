//! Sensor plugins (`perspective`, `thinlens`, `orthographic`, meters) with their film (`hdrfilm`), reconstruction
//! filter (`box`, `tent`, `gaussian`) and sampler (`independent`, `stratified`,
//! `multijitter`, `orthogonal`, `ldsampler`).

use steradian::film::{
    BoxFilter, ComponentFormat, Film, GaussianFilter, ReconstructionFilter, TentFilter,
};
use steradian::sampling::{Sampler, SamplerKind};
use steradian::sensor::{
    FieldOfView, FovAxis, IrradianceMeter, Orthographic, Perspective, RadianceMeter, Sensor,
    SensorKind, ThinLens,
};

use super::{at, at_property, unknown_type};
use crate::error::LoadError;
use crate::xml::{ObjectTag, PluginNode};

const KNOWN: &[&str] =
    &["perspective", "thinlens", "orthographic", "radiancemeter", "irradiancemeter"];

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

fn build_filter(node: &PluginNode) -> Result<ReconstructionFilter, LoadError> {
    let f: ReconstructionFilter = match node.plugin_type.as_str() {
        "box" => BoxFilter::new().into(),
        "tent" => {
            TentFilter::new(node.props.get_float("radius")?.unwrap_or(TentFilter::DEFAULT_RADIUS))
                .map_err(at(node))?
                .into()
        }
        "gaussian" => GaussianFilter::new(
            node.props.get_float("stddev")?.unwrap_or(GaussianFilter::DEFAULT_STDDEV),
        )
        .map_err(at(node))?
        .into(),
        _ => return Err(unknown_type(node, &["box", "tent", "gaussian"])),
    };
    node.check_all_used()?;
    Ok(f)
}

fn build_film(node: &PluginNode) -> Result<Film, LoadError> {
    if node.plugin_type != "hdrfilm" {
        return Err(unknown_type(node, &["hdrfilm"]));
    }
    let p = &node.props;
    let width = positive_int(node, "width", 768)?;
    let height = positive_int(node, "height", 576)?;
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
    if let Some(f) = p.get_string("pixel_format")? {
        if f != "rgb" {
            return Err(LoadError::at(
                p.position("pixel_format").unwrap(),
                format!("hdrfilm: pixel_format '{f}' is not supported yet (only 'rgb')"),
            ));
        }
    }
    let component_format = match p.get_string("component_format")? {
        Some(f) => ComponentFormat::parse(&f).map_err(|m| {
            LoadError::at(p.position("component_format").unwrap(), format!("hdrfilm: {m}"))
        })?,
        None => ComponentFormat::Float16,
    };
    if p.get_bool("sample_border")? == Some(true) {
        return Err(LoadError::at(
            p.position("sample_border").unwrap(),
            "hdrfilm: sample_border = true is not supported yet",
        ));
    }
    // The core's message already says "hdrfilm: ".
    let mut film = Film::new(width, height, filter).map_err(|m| {
        LoadError::at(
            &node.pos,
            format!("{}: {}", node.desc(), m.strip_prefix("hdrfilm: ").unwrap_or(&m)),
        )
    })?;
    film.component_format = component_format;
    node.check_all_used()?;
    Ok(film)
}

/// Every Mitsuba sampler type promises the same expectation and differs only in noise;
/// steradian draws Owen-scrambled Sobol points for all of them (unbiased, and lower error
/// than any of them). `--sampler independent` restores i.i.d. numbers.
fn build_sampler(node: &PluginNode) -> Result<Sampler, LoadError> {
    let kind = match node.plugin_type.as_str() {
        "independent" => SamplerKind::Sobol,
        "stratified" | "multijitter" => {
            if node.props.get_bool("jitter")? == Some(false) {
                return Err(LoadError::at(
                    node.props.position("jitter").unwrap(),
                    format!("{}: jitter = false (biased) is not supported", node.desc()),
                ));
            }
            SamplerKind::Sobol
        }
        "orthogonal" => {
            if let Some(s) = node.props.get_int("strength")? {
                if s != 2 {
                    return Err(LoadError::at(
                        node.props.position("strength").unwrap(),
                        "orthogonal: only strength 2 is supported",
                    ));
                }
            }
            if node.props.get_bool("jitter")? == Some(false) {
                return Err(LoadError::at(
                    node.props.position("jitter").unwrap(),
                    "orthogonal: jitter = false (biased) is not supported",
                ));
            }
            SamplerKind::Sobol
        }
        "ldsampler" => SamplerKind::Sobol,
        _ => {
            return Err(unknown_type(
                node,
                &["independent", "stratified", "multijitter", "orthogonal", "ldsampler"],
            ))
        }
    };
    let sample_count = positive_int(node, "sample_count", 4)?;
    let seed = node.props.get_int("seed")?.unwrap_or(0);
    if seed < 0 {
        return Err(LoadError::at(
            node.props.position("seed").unwrap(),
            "seed must be non-negative",
        ));
    }
    node.check_all_used()?;
    Ok(Sampler { kind, sample_count, seed: seed as u64 })
}

fn parse_focal_length(node: &PluginNode, s: &str) -> Result<f32, LoadError> {
    let num = s.trim().strip_suffix("mm").unwrap_or(s.trim());
    num.trim().parse::<f32>().ok().filter(|v| *v > 0.0 && v.is_finite()).ok_or_else(|| {
        LoadError::at(
            node.props.position("focal_length").unwrap_or(&node.pos),
            format!("focal_length must look like '50mm', got '{s}'"),
        )
    })
}

/// Builds a sensor; `shape` is the enclosing shape for an `irradiancemeter`.
pub(crate) fn build(node: &PluginNode, shape: Option<u32>) -> Result<Sensor, LoadError> {
    if !KNOWN.contains(&node.plugin_type.as_str()) {
        return Err(unknown_type(node, KNOWN));
    }
    let p = &node.props;
    let film = match single_child(node, ObjectTag::Film)? {
        Some(f) => build_film(f)?,
        None => Film::new(768, 576, ReconstructionFilter::default()).map_err(at(node))?,
    };
    let sampler = match single_child(node, ObjectTag::Sampler)? {
        Some(s) => build_sampler(s)?,
        None => Sampler::default(),
    };
    let id = node.id.clone().unwrap_or_default();
    let meter_film = |film: &Film| -> Result<(), LoadError> {
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
    };
    match (node.plugin_type.as_str(), shape) {
        ("irradiancemeter", None) => {
            return Err(LoadError::at(
                &node.pos,
                "an irradiancemeter must be declared inside the <shape> it measures",
            ));
        }
        ("irradiancemeter", Some(shape)) => {
            meter_film(&film)?;
            node.check_all_used()?;
            return Ok(Sensor {
                kind: SensorKind::IrradianceMeter(IrradianceMeter { shape }),
                film,
                sampler,
                id,
            });
        }
        (_, Some(_)) => {
            return Err(LoadError::at(
                &node.pos,
                format!(
                    "only an irradiancemeter can be declared inside a shape, not {}",
                    node.desc()
                ),
            ));
        }
        ("radiancemeter", None) => {
            meter_film(&film)?;
            let meter = match (
                p.get_transform("to_world")?,
                p.get_point("origin")?,
                p.get_vector("direction")?,
            ) {
                (Some(t), None, None) => RadianceMeter::from_transform(&t),
                (None, Some(o), Some(d)) => RadianceMeter::new(o, d),
                (None, None, None) => RadianceMeter::from_transform(&Default::default()),
                (Some(_), _, _) => return Err(LoadError::at(
                    &node.pos,
                    "radiancemeter: give either 'to_world' or 'origin' and 'direction', not both",
                )),
                _ => {
                    return Err(LoadError::at(
                        &node.pos,
                        "radiancemeter: 'origin' and 'direction' go together",
                    ))
                }
            }
            .map_err(at(node))?;
            node.check_all_used()?;
            return Ok(Sensor { kind: SensorKind::RadianceMeter(meter), film, sampler, id });
        }
        ("orthographic", None) => {
            let kind = SensorKind::Orthographic(orthographic(node, &film)?);
            node.check_all_used()?;
            return Ok(Sensor { kind, film, sampler, id });
        }
        _ => {}
    }
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let fov = match (p.get_float("fov")?, p.get_string("focal_length")?) {
        (Some(_), Some(_)) => {
            return Err(LoadError::at(
                &node.pos,
                format!("{}: give only one of 'fov' and 'focal_length'", node.desc()),
            ))
        }
        (Some(degrees), None) => {
            let axis = match p.get_string("fov_axis")? {
                Some(a) => FovAxis::parse(&a).ok_or_else(|| {
                    LoadError::at(
                        p.position("fov_axis").unwrap(),
                        format!("fov_axis must be x, y, diagonal, smaller or larger, got '{a}'"),
                    )
                })?,
                None => FovAxis::X,
            };
            FieldOfView::Angle { degrees, axis }
        }
        (None, fl) => {
            if p.contains("fov_axis") {
                p.get_string("fov_axis")?;
                return Err(LoadError::at(
                    p.position("fov_axis").unwrap(),
                    "fov_axis only applies together with 'fov'",
                ));
            }
            FieldOfView::FocalLength {
                mm: match fl {
                    Some(s) => parse_focal_length(node, &s)?,
                    None => 50.0,
                },
            }
        }
    };
    let x_fov =
        fov.x_fov(film.width, film.height).map_err(at_property(node, &["fov", "focal_length"]))?;
    let aspect = film.width as f32 / film.height as f32;
    let near = p.get_float("near_clip")?.unwrap_or(0.01);
    let far = p.get_float("far_clip")?.unwrap_or(1e4);
    let focus = p.get_float("focus_distance")?.unwrap_or(far);
    let lens_err = at_property(
        node,
        &["to_world", "near_clip", "far_clip", "aperture_radius", "focus_distance"],
    );
    let kind = match node.plugin_type.as_str() {
        "perspective" => SensorKind::Perspective(
            Perspective::new(to_world, x_fov, aspect, near, far).map_err(lens_err)?,
        ),
        "thinlens" => {
            let aperture = p.get_float("aperture_radius")?.ok_or_else(|| {
                LoadError::at(&node.pos, format!("{}: missing 'aperture_radius'", node.desc()))
            })?;
            SensorKind::ThinLens(
                ThinLens::new(to_world, x_fov, aspect, near, far, aperture, focus)
                    .map_err(lens_err)?,
            )
        }
        _ => unreachable!("checked above"),
    };
    node.check_all_used()?;
    Ok(Sensor { kind, film, sampler, id })
}

/// `orthographic` (core: sensor/orthographic.rs): no field of view; `to_world` may scale.
fn orthographic(node: &PluginNode, film: &Film) -> Result<Orthographic, LoadError> {
    use steradian::sensor::orthographic::{DEFAULT_FAR_CLIP, DEFAULT_NEAR_CLIP};
    let p = &node.props;
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let near = p.get_float("near_clip")?.unwrap_or(DEFAULT_NEAR_CLIP);
    let far = p.get_float("far_clip")?.unwrap_or(DEFAULT_FAR_CLIP);
    let aspect = film.width as f32 / film.height as f32;
    Orthographic::new(to_world, aspect, near, far)
        .map_err(at_property(node, &["to_world", "near_clip", "far_clip"]))
}
