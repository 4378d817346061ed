//! Emitter plugins: `area` and `directionalarea` (attached to a shape), `point`, `spot`,
//! `directional`, `constant`, `envmap`, `projector`, `sunsky`, and steradian's own `luminaire` (a
//! photometric file) and `ciesky` (CIE standard skies).

use steradian::emitter::{
    cie_sky, from_photometric, AreaLight, ConstantEnvironment, DirectionalLight, Emitter,
    EnvironmentMap, Luminaire, LuminousOpening, PointLight, Projector, SkyLevel, SkyModel,
    SpotLight, Sun,
};
use steradian::geometry::Transform;
use steradian::photometry::{parse_eulumdat, parse_ies, IntensityTable};
use steradian::{Spectrum, Vec3};

use super::{at, at_filename, at_param, check_non_negative, lookup, required_string, Plugins};
use crate::error::LoadError;
use crate::tree::PluginNode;

/// The emitter of shape number `shape`: `area`, or `directionalarea`, which emits only
/// along the surface normal. No camera or surface path can connect to such a light (a
/// direction has zero probability of being exactly the normal), so Mitsuba's `path` and
/// `direct` integrators never see its light and neither does steradian: its parameters are
/// checked, a warning says so, and no emitter is added (`None`).
pub(crate) fn build_area(
    b: &super::Builder,
    node: &PluginNode,
    shape: u32,
    geometry: &steradian::shape::Shape,
) -> Result<Option<Emitter>, LoadError> {
    if node.plugin_type == "luminaire" {
        return build_luminous_opening(b, node, shape, geometry).map(Some);
    }
    if node.plugin_type != "area" && node.plugin_type != "directionalarea" {
        return Err(LoadError::at(
            &node.pos,
            format!(
                "a shape can only carry an 'area' or 'directionalarea' emitter, not '{}'",
                node.plugin_type
            ),
        ));
    }
    let radiance = match photometric_strength(node, "radiance", &[("luminance", "cd/m²", 1.0)])? {
        Some(v) => steradian::texture::Texture::Constant(v),
        None => super::textures::emitter_texture_param(
            b,
            node,
            "radiance",
            Some(AreaLight::DEFAULT_RADIANCE),
        )?,
    };
    if let steradian::texture::Texture::Constant(v) = radiance {
        check_non_negative(node, "radiance", v)?;
    }
    accept_emitter_medium(node)?;
    if node.plugin_type == "directionalarea" && node.props.contains("to_world") {
        return Err(at(node)(
            "'to_world' is not allowed: the emitter takes its shape's transform".into(),
        ));
    }
    node.check_all_used()?;
    if node.plugin_type == "directionalarea" {
        b.warn(crate::error::LoadWarning::at(
            &node.pos,
            format!(
                "{}: emits only along the surface normal, which no camera or surface path \
                 can reach (as in Mitsuba's path tracer): it adds no light to this render",
                node.desc()
            ),
        ));
        return Ok(None);
    }
    Ok(Some(Emitter::Area(AreaLight::new(shape, radiance))))
}

/// A light's strength given in one of steradian's photometric parameters `(name, unit name,
/// factor)` with an optional `color` (default white): the radiometric value of value × factor
/// (`steradian::emitter::from_photometric`, the one place the units are converted). `None`
/// where none is given, and then `color` is not read (so it is an unused-parameter error).
/// Giving one together with Mitsuba's radiometric parameter `radiometric`, or two of them, is
/// an error.
fn photometric_strength(
    node: &PluginNode,
    radiometric: &str,
    photometric: &[(&str, &str, f32)],
) -> Result<Option<Spectrum>, LoadError> {
    let p = &node.props;
    let given: Vec<&(&str, &str, f32)> =
        photometric.iter().filter(|(name, _, _)| p.contains(name)).collect();
    let &[&(name, unit, factor)] = given.as_slice() else {
        if given.len() > 1 {
            return Err(at(node)(format!(
                "give only one of {}",
                given.iter().map(|(n, _, _)| format!("'{n}'")).collect::<Vec<_>>().join(", ")
            )));
        }
        return Ok(None);
    };
    let prop_err = |msg: String| {
        LoadError::at(p.position(name).unwrap_or(&node.pos), format!("{}: {msg}", node.desc()))
    };
    if p.contains(radiometric) {
        return Err(prop_err(format!(
            "give either '{radiometric}' (radiometric) or '{name}' ({unit}), not both"
        )));
    }
    let value = p.get_float(name)?.expect("present");
    let color = p.get_spectrum("color")?.unwrap_or(Spectrum::ONE);
    from_photometric(value * factor, color).map(Some).map_err(|e| prop_err(format!("{name} {e}")))
}

/// A light's strength: one of steradian's photometric parameters ([`photometric_strength`]),
/// else Mitsuba's radiometric spectrum `radiometric` (`default` in each channel where it is
/// not given), checked finite and non-negative.
fn strength(
    node: &PluginNode,
    radiometric: &str,
    default: f32,
    photometric: &[(&str, &str, f32)],
) -> Result<Spectrum, LoadError> {
    let v = match photometric_strength(node, radiometric, photometric)? {
        Some(v) => v,
        None => node.props.get_spectrum(radiometric)?.unwrap_or(Spectrum::splat(default)),
    };
    check_non_negative(node, radiometric, v)?;
    Ok(v)
}

/// A position given either as `position` or as the translation of `to_world`, not both.
fn position_or_to_world(node: &PluginNode) -> Result<Transform, LoadError> {
    let p = &node.props;
    match (p.get_point("position")?, p.get_transform("to_world")?) {
        (Some(_), Some(_)) => Err(LoadError::at(
            &node.pos,
            format!("{}: give only one of 'position' and 'to_world'", node.desc()),
        )),
        (Some(pos), None) => Ok(Transform::translate(pos)),
        (None, Some(t)) => Ok(t),
        (None, None) => Ok(Transform::IDENTITY),
    }
}

/// Builds one emitter declared at the scene level from its node.
type BuildEmitter = fn(&super::Builder, &PluginNode) -> Result<Emitter, LoadError>;

/// Every emitter plugin declared at the scene level, by Mitsuba `type`. (`area` is the one
/// emitter a shape carries: [`build_area`].)
pub(super) const EMITTERS: &Plugins<BuildEmitter> = &[
    ("point", point),
    ("spot", spot),
    ("directional", directional),
    ("constant", constant),
    ("envmap", build_envmap),
    ("projector", projector),
    ("luminaire", build_luminaire),
    ("ciesky", build_ciesky),
    ("sun", sun),
    ("sunsky", build_sunsky),
];

/// Mitsuba's `sunsky` (parameters and defaults: `steradian::emitter::SunSky`).
fn build_sunsky(b: &super::Builder, node: &PluginNode) -> Result<Emitter, LoadError> {
    use steradian::emitter::{LocationTime, SunModel, SunPosition, SunSky, SunSkyParams};
    use steradian::param::ParamError;
    let p = &node.props;
    const WHEN: [&str; 9] =
        ["latitude", "longitude", "timezone", "year", "month", "day", "hour", "minute", "second"];
    let sun = match p.get_vector("sun_direction")? {
        Some(d) => {
            if let Some(&name) = WHEN.iter().find(|n| p.contains(n)) {
                return Err(at_param(node)(ParamError::new(
                    name,
                    format!(
                        "'{name}' cannot be given with 'sun_direction' (the sun is either placed \
                         by direction or by location and time)"
                    ),
                )));
            }
            SunPosition::Direction(d)
        }
        None => {
            let d = LocationTime::default();
            let int = |name: &'static str, default: i32| -> Result<i32, LoadError> {
                match p.get_int(name)? {
                    None => Ok(default),
                    Some(v) => i32::try_from(v).map_err(|_| {
                        at_param(node)(ParamError::new(name, format!("{name} {v} is out of range")))
                    }),
                }
            };
            let float = |name: &str, default: f32| -> Result<f32, LoadError> {
                Ok(p.get_float(name)?.unwrap_or(default))
            };
            SunPosition::At(LocationTime {
                latitude: float("latitude", d.latitude)?,
                longitude: float("longitude", d.longitude)?,
                timezone: float("timezone", d.timezone)?,
                year: int("year", d.year)?,
                month: int("month", d.month)?,
                day: int("day", d.day)?,
                hour: float("hour", d.hour)?,
                minute: float("minute", d.minute)?,
                second: float("second", d.second)?,
            })
        }
    };
    let defaults = SunSkyParams::default();
    let params = SunSkyParams {
        sun,
        turbidity: p.get_float("turbidity")?.unwrap_or(defaults.turbidity),
        albedo: p.get_spectrum("albedo")?.unwrap_or(defaults.albedo),
        sun_scale: p.get_float("sun_scale")?.unwrap_or(defaults.sun_scale),
        sky_scale: p.get_float("sky_scale")?.unwrap_or(defaults.sky_scale),
        sun_aperture: p.get_float("sun_aperture")?.unwrap_or(defaults.sun_aperture),
        model: match p.get_bool("complex_sun")? {
            Some(true) => SunModel::LimbDarkened,
            _ => SunModel::Uniform,
        },
    };
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let sky = SunSky::new(&params, &to_world).map_err(at_param(node))?;
    if !sky.sun_is_up() {
        b.warn(crate::error::LoadWarning::at(
            &node.pos,
            format!(
                "{}: the sun is below the horizon at this time and place: the sky is black (as in \
                 Mitsuba)",
                node.desc()
            ),
        ));
    }
    Ok(Emitter::SunSky(Box::new(sky)))
}

/// steradian's `ciesky` (parameters and defaults: `steradian::emitter::cie_sky`).
fn build_ciesky(b: &super::Builder, node: &PluginNode) -> Result<Emitter, LoadError> {
    let p = &node.props;
    let err = |name: &str, msg: String| {
        LoadError::at(p.position(name).unwrap_or(&node.pos), format!("{}: {msg}", node.desc()))
    };
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let sky = p.get_string("sky")?.unwrap_or_else(|| "overcast".into());
    let model = if sky == "overcast" {
        SkyModel::Overcast
    } else {
        let kind: u8 = sky.parse().ok().filter(|k| (1..=15).contains(k)).ok_or_else(|| {
            err(
                "sky",
                format!("'sky' must be 'overcast' or a CIE general sky type 1 to 15, got '{sky}'"),
            )
        })?;
        let Some(sun) = p.get_vector("sun_direction")? else {
            return Err(err(
                "sky",
                format!("the CIE general sky of type {kind} needs 'sun_direction'"),
            ));
        };
        if !(sun.is_finite() && sun.length() > 0.0) {
            return Err(err("sun_direction", "sun_direction must be a non-zero vector".into()));
        }
        // the sky frame's sun: world direction through the inverse of to_world
        let local = to_world.inverse().vector(sun).normalize();
        SkyModel::General { kind, sun: local }
    };
    let level =
        match (p.get_float("zenith_luminance")?, p.get_float("horizontal_illuminance")?) {
            (Some(l), None) => SkyLevel::ZenithLuminance(l as f64),
            (None, Some(e)) => SkyLevel::HorizontalIlluminance(e as f64),
            _ => return Err(err(
                "zenith_luminance",
                "give exactly one of 'zenith_luminance' (cd/m²) and 'horizontal_illuminance' (lx)"
                    .into(),
            )),
        };
    let env = cie_sky(model, level, &to_world).map_err(at_param(node))?;
    b.sky.set(Some((model, level)));
    Ok(Emitter::EnvMap(env))
}

/// steradian's `luminaire` (parameters and defaults: `steradian::emitter::Luminaire`).
/// A `luminaire` nested in a flat shape (`steradian::emitter::LuminousOpening`): the
/// luminaire's parameters, `to_world` a rotation of its photometric frame.
fn build_luminous_opening(
    b: &super::Builder,
    node: &PluginNode,
    shape: u32,
    geometry: &steradian::shape::Shape,
) -> Result<Emitter, LoadError> {
    use steradian::shape::Shape;
    if !matches!(geometry, Shape::Rectangle(_) | Shape::Disk(_)) {
        return Err(LoadError::at(
            &node.pos,
            format!(
                "{}: a luminaire's luminous opening must be flat: nest it in a `rectangle` or a `disk`",
                node.desc()
            ),
        ));
    }
    let luminaire = read_luminaire(b, node)?;
    let p = &node.props;
    if luminaire.position != Vec3::ZERO {
        return Err(LoadError::at(
            p.position("to_world").or(p.position("position")).unwrap_or(&node.pos),
            format!("{}: in a shape, to_world only turns the photometric frame (the shape places the opening): no translation", node.desc()),
        ));
    }
    let opening =
        LuminousOpening::new(shape, geometry.surface_area(), luminaire).map_err(at(node))?;
    node.check_all_used()?;
    Ok(Emitter::LuminousOpening(opening))
}

/// The intensity table of a `luminaire`'s photometric file (`filename`, `.ies` or `.ldt`).
fn read_intensity_table(
    b: &super::Builder,
    node: &PluginNode,
) -> Result<IntensityTable, LoadError> {
    let p = &node.props;
    let filename = required_string(node, "filename", " (an .ies or .ldt file)")?;
    let at_file = |msg: String| {
        LoadError::at(
            p.position("filename").unwrap_or(&node.pos),
            format!("{}: \"{filename}\": {msg}", node.desc()),
        )
    };
    let extension = std::path::Path::new(&filename)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let parse = match extension.as_deref() {
        Some("ies") => parse_ies,
        Some("ldt") => parse_eulumdat,
        _ => return Err(at_file("a photometric file must end in .ies or .ldt".into())),
    };
    let path = b.resolve_path(node, &filename);
    let bytes = std::fs::read(&path).map_err(|e| at_file(format!("cannot read it: {e}")))?;
    // photometric files are often Latin-1: their text fields do not matter, their numbers are ASCII
    let text = String::from_utf8_lossy(&bytes);
    let photometry = parse(&text).map_err(|e| at_file(e.to_string()))?;
    IntensityTable::new(&photometry).map_err(at_file)
}

fn build_luminaire(b: &super::Builder, node: &PluginNode) -> Result<Emitter, LoadError> {
    read_luminaire(b, node).map(Emitter::Luminaire)
}

/// A `luminaire`'s parameters (`steradian::emitter::Luminaire`), at the scene level or in a
/// shape.
fn read_luminaire(b: &super::Builder, node: &PluginNode) -> Result<Luminaire, LoadError> {
    let p = &node.props;
    let table = read_intensity_table(b, node)?;
    let scale = p.get_float("scale")?.unwrap_or(Luminaire::DEFAULT_SCALE);
    let color = p.get_spectrum("color")?.unwrap_or(Spectrum::splat(Luminaire::DEFAULT_COLOR));
    let to_world = position_or_to_world(node)?;
    Luminaire::new(&to_world, table, scale, color).map_err(at_param(node))
}

/// The `envmap` emitter (parameters and defaults: `steradian::emitter::EnvironmentMap`).
fn build_envmap(b: &super::Builder, node: &PluginNode) -> Result<Emitter, LoadError> {
    let p = &node.props;
    let filename = required_string(node, "filename", " (a lat-long image)")?;
    let scale = p.get_float("scale")?.unwrap_or(EnvironmentMap::DEFAULT_SCALE);
    let mis_compensation = p.get_bool("mis_compensation")?.unwrap_or(
        if b.integrator_type.as_deref() == Some("path") {
            EnvironmentMap::DEFAULT_MIS_COMPENSATION_UNDER_PATH
        } else {
            EnvironmentMap::DEFAULT_MIS_COMPENSATION
        },
    );
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let image = steradian::texture::read_image(&b.resolve_path(node, &filename))
        .map_err(at_filename(node))?;
    let env = EnvironmentMap::new(&filename, image, scale, &to_world, mis_compensation)
        .map_err(at_param(node))?;
    Ok(Emitter::EnvMap(env))
}

/// An emitter declared at the scene level.
pub(crate) fn build_standalone(
    b: &super::Builder,
    node: &PluginNode,
) -> Result<Emitter, LoadError> {
    if node.plugin_type == "area" {
        return Err(LoadError::at(
            &node.pos,
            "an 'area' emitter must be nested inside the <shape> that emits (or declared with an id and referenced from it)",
        ));
    }
    let emitter = lookup(EMITTERS, node)?(b, node)?;
    accept_emitter_medium(node)?;
    node.check_all_used()?;
    Ok(emitter)
}

/// The medium an emitter may name (`<medium>` or `<ref>` nested in it), as Mitsuba 3 lets
/// every endpoint name the medium it sits in: accepted, one at most, and not used. Mitsuba
/// 3.9.1's `volpath` and `volpathmis` attenuate a light's contribution by the media along
/// the path from the scattering point, whatever medium the emitter names, and steradian
/// does the same (checked against Mitsuba: a point light in fog named in the light and the
/// sensor, `scripts/mitsuba_diff/probes.py` `point_in_medium`).
fn accept_emitter_medium(node: &PluginNode) -> Result<(), LoadError> {
    let media = node.children_of(crate::tree::ObjectTag::Medium);
    match media.get(1) {
        Some(second) => Err(LoadError::at(
            second.pos(),
            format!("{}: only one medium can be named per emitter", node.desc()),
        )),
        None => Ok(()),
    }
}

fn point(_b: &super::Builder, node: &PluginNode) -> Result<Emitter, LoadError> {
    let photometric = [
        ("luminous_intensity", "cd", 1.0),
        // isotropic: I = Φ/4π
        ("luminous_flux", "lm", 1.0 / (4.0 * std::f32::consts::PI)),
    ];
    let intensity = strength(node, "intensity", PointLight::DEFAULT_INTENSITY, &photometric)?;
    let to_world = position_or_to_world(node)?;
    Ok(Emitter::Point(PointLight::new(to_world.point(Vec3::ZERO), intensity)))
}

fn spot(b: &super::Builder, node: &PluginNode) -> Result<Emitter, LoadError> {
    let p = &node.props;
    let cd = [("luminous_intensity", "cd", 1.0)];
    let intensity = strength(node, "intensity", SpotLight::DEFAULT_INTENSITY, &cd)?;
    let cutoff = p.get_float("cutoff_angle")?.unwrap_or(SpotLight::DEFAULT_CUTOFF_ANGLE);
    let beam = p.get_float("beam_width")?.unwrap_or(cutoff * SpotLight::DEFAULT_BEAM_WIDTH_RATIO);
    // Checked here in the user's degrees (the core's check, in radians, would echo
    // 30° back as 30.000002°).
    let prop_err = |name: &str, msg: String| {
        LoadError::at(p.position(name).unwrap_or(&node.pos), format!("{}: {msg}", node.desc()))
    };
    if !(cutoff > 0.0 && cutoff <= 180.0) {
        return Err(prop_err(
            "cutoff_angle",
            format!("cutoff_angle must lie in (0°, 180°], got {cutoff}°"),
        ));
    }
    if !(beam > 0.0 && beam <= cutoff) {
        let name = if p.contains("beam_width") { "beam_width" } else { "cutoff_angle" };
        return Err(prop_err(
            name,
            format!("beam_width must lie in (0°, cutoff_angle = {cutoff}°], got {beam}°"),
        ));
    }
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let mut spot = SpotLight::new(&to_world, intensity, cutoff.to_radians(), beam.to_radians())
        .map_err(at_param(node))?;
    if node.children.iter().any(|c| c.name.as_deref() == Some("texture")) {
        spot = spot.with_texture(
            &to_world,
            super::textures::emitter_texture_param(b, node, "texture", None)?,
        );
    }
    Ok(Emitter::Spot(spot))
}

fn directional(_b: &super::Builder, node: &PluginNode) -> Result<Emitter, LoadError> {
    let p = &node.props;
    let lx = [("illuminance", "lx", 1.0)];
    let irradiance = strength(node, "irradiance", DirectionalLight::DEFAULT_IRRADIANCE, &lx)?;
    let direction = match (p.get_vector("direction")?, p.get_transform("to_world")?) {
        (Some(_), Some(_)) => {
            return Err(LoadError::at(
                &node.pos,
                format!("{}: give only one of 'direction' and 'to_world'", node.desc()),
            ))
        }
        (Some(d), None) => d,
        (None, Some(t)) => t.vector(Vec3::Z),
        (None, None) => DirectionalLight::DEFAULT_DIRECTION,
    };
    Ok(Emitter::Directional(DirectionalLight::new(direction, irradiance).map_err(at(node))?))
}

/// steradian's own `sun` (`steradian::emitter::Sun`): `sun_direction` (required), `irradiance`
/// or `illuminance` (with `color`), `angular_radius` in degrees.
fn sun(_b: &super::Builder, node: &PluginNode) -> Result<Emitter, LoadError> {
    let p = &node.props;
    let lx = [("illuminance", "lx", 1.0)];
    let irradiance = strength(node, "irradiance", Sun::DEFAULT_IRRADIANCE, &lx)?;
    let towards = p.get_vector("sun_direction")?.ok_or_else(|| {
        LoadError::at(
            &node.pos,
            format!("{}: missing parameter 'sun_direction' (towards the sun)", node.desc()),
        )
    })?;
    let radius = p.get_float("angular_radius")?.unwrap_or(Sun::DEFAULT_ANGULAR_RADIUS);
    Sun::new(towards, irradiance, radius).map(Emitter::Sun).map_err(|m| {
        let name = if m.contains("angular_radius") { "angular_radius" } else { "sun_direction" };
        LoadError::at(p.position(name).unwrap_or(&node.pos), format!("{}: {m}", node.desc()))
    })
}

fn constant(_b: &super::Builder, node: &PluginNode) -> Result<Emitter, LoadError> {
    let nits = [("luminance", "cd/m²", 1.0)];
    let radiance = strength(node, "radiance", ConstantEnvironment::DEFAULT_RADIANCE, &nits)?;
    Ok(Emitter::Constant(ConstantEnvironment::new(radiance)))
}

/// `projector`: `irradiance` (required; a value or a texture), `scale`, `to_world`, and the
/// field of view of `perspective` with the image's aspect ratio (1 for a constant).
fn projector(b: &super::Builder, node: &PluginNode) -> Result<Emitter, LoadError> {
    let p = &node.props;
    let irradiance = super::textures::emitter_texture_param(b, node, "irradiance", None)?;
    if let steradian::texture::Texture::Constant(v) = irradiance {
        check_non_negative(node, "irradiance", v)?;
    }
    let scale = p.get_float("scale")?.unwrap_or(Projector::DEFAULT_SCALE);
    check_non_negative(node, "scale", Spectrum::splat(scale))?;
    let (width, height) = match &irradiance {
        steradian::texture::Texture::Bitmap(bm) => bm.resolution(),
        _ => (1, 1),
    };
    let fov = super::field_of_view::field_of_view(node)?;
    let x_fov = fov.x_fov(width as u32, height as u32).map_err(at_param(node))?;
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let aspect = width as f32 / height as f32;
    Ok(Emitter::Projector(Projector::new(&to_world, irradiance, scale, x_fov, aspect)))
}
