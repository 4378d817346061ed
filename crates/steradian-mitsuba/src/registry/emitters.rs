//! Emitter plugins: `area` (attached to a shape), `point`, `spot`, `directional`,
//! `constant`, `envmap`.

use steradian::emitter::{
    AreaLight, ConstantEnvironment, DirectionalLight, Emitter, EnvironmentMap, PointLight,
    SpotLight,
};
use steradian::geometry::Transform;
use steradian::{Spectrum, Vec3};

use super::{at, at_property, unknown_type};
use crate::error::LoadError;
use crate::xml::PluginNode;

const STANDALONE: &[&str] = &["point", "spot", "directional", "constant", "envmap"];

/// The `area` emitter of shape number `shape`.
pub(crate) fn build_area(
    b: &super::Builder,
    node: &PluginNode,
    shape: u32,
) -> Result<Emitter, LoadError> {
    if node.plugin_type != "area" {
        return Err(LoadError::at(
            &node.pos,
            format!("a shape can only carry an 'area' emitter, not '{}'", node.plugin_type),
        ));
    }
    let radiance = super::textures::texture_param(b, node, "radiance", Some(1.0))?;
    if let steradian::texture::Texture::Constant(v) = radiance {
        check_non_negative(node, "radiance", v)?;
    }
    node.check_all_used()?;
    Ok(Emitter::Area(AreaLight::new(shape, radiance)))
}

fn check_non_negative(node: &PluginNode, name: &str, v: Spectrum) -> Result<(), LoadError> {
    if !v.is_finite() || v.min_element() < 0.0 {
        let pos = node.props.position(name).unwrap_or(&node.pos);
        return Err(LoadError::at(
            pos,
            format!("{}: '{name}' must be finite and non-negative, got {v}", node.desc()),
        ));
    }
    Ok(())
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

/// The `envmap` emitter (parameters and defaults: `steradian::emitter::EnvironmentMap`).
fn build_envmap(b: &super::Builder, node: &PluginNode) -> Result<Emitter, LoadError> {
    let p = &node.props;
    let Some(filename) = p.get_string("filename")? else {
        return Err(LoadError::at(
            &node.pos,
            format!("{}: missing parameter 'filename' (a lat-long image)", node.desc()),
        ));
    };
    let scale = p.get_float("scale")?.unwrap_or(EnvironmentMap::DEFAULT_SCALE);
    let mis_compensation =
        p.get_bool("mis_compensation")?.unwrap_or(EnvironmentMap::DEFAULT_MIS_COMPENSATION);
    let to_world = p.get_transform("to_world")?.unwrap_or_default();
    let at_file = |msg: String| {
        LoadError::at(
            p.position("filename").unwrap_or(&node.pos),
            format!("{}: {msg}", node.desc()),
        )
    };
    let image =
        steradian::texture::read_image(&b.resolve_path(node, &filename)).map_err(at_file)?;
    let env = EnvironmentMap::new(&filename, image, scale, &to_world, mis_compensation).map_err(
        |msg| {
            if msg.starts_with("scale") {
                at_property(node, &["scale"])(msg)
            } else if msg.starts_with("to_world") {
                at_property(node, &["to_world"])(msg)
            } else {
                at_file(msg)
            }
        },
    )?;
    Ok(Emitter::EnvMap(env))
}

/// An emitter declared at the scene level.
pub(crate) fn build_standalone(
    b: &super::Builder,
    node: &PluginNode,
) -> Result<Emitter, LoadError> {
    let p = &node.props;
    let emitter = match node.plugin_type.as_str() {
        "point" => {
            let intensity = p.get_spectrum("intensity")?.unwrap_or(Spectrum::ONE);
            check_non_negative(node, "intensity", intensity)?;
            let to_world = position_or_to_world(node)?;
            Emitter::Point(PointLight::new(to_world.point(Vec3::ZERO), intensity))
        }
        "spot" => {
            let intensity = p.get_spectrum("intensity")?.unwrap_or(Spectrum::ONE);
            check_non_negative(node, "intensity", intensity)?;
            let cutoff = p.get_float("cutoff_angle")?.unwrap_or(20.0);
            let beam = p.get_float("beam_width")?.unwrap_or(cutoff * 0.75);
            // Checked here in the user's degrees (the core's check, in radians, would echo
            // 30° back as 30.000002°).
            let prop_err = |name: &str, msg: String| {
                LoadError::at(
                    p.position(name).unwrap_or(&node.pos),
                    format!("{}: {msg}", node.desc()),
                )
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
            Emitter::Spot(
                SpotLight::new(&to_world, intensity, cutoff.to_radians(), beam.to_radians())
                    .map_err(at_property(node, &["beam_width", "cutoff_angle"]))?,
            )
        }
        "directional" => {
            let irradiance = p.get_spectrum("irradiance")?.unwrap_or(Spectrum::ONE);
            check_non_negative(node, "irradiance", irradiance)?;
            let direction = match (p.get_vector("direction")?, p.get_transform("to_world")?) {
                (Some(_), Some(_)) => {
                    return Err(LoadError::at(
                        &node.pos,
                        format!("{}: give only one of 'direction' and 'to_world'", node.desc()),
                    ))
                }
                (Some(d), None) => d,
                (None, Some(t)) => t.vector(Vec3::Z),
                (None, None) => Vec3::Z,
            };
            Emitter::Directional(DirectionalLight::new(direction, irradiance).map_err(at(node))?)
        }
        "constant" => {
            let radiance = p.get_spectrum("radiance")?.unwrap_or(Spectrum::ONE);
            check_non_negative(node, "radiance", radiance)?;
            Emitter::Constant(ConstantEnvironment::new(radiance))
        }
        "envmap" => build_envmap(b, node)?,
        "area" => {
            return Err(LoadError::at(
                &node.pos,
                "an 'area' emitter must be nested inside the <shape> that emits",
            ));
        }
        _ => return Err(unknown_type(node, STANDALONE)),
    };
    node.check_all_used()?;
    Ok(emitter)
}
