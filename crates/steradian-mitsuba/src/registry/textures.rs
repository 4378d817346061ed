//! Texture plugins: `bitmap`, `checkerboard`, `mesh_attribute` and `rawconstant` (see `steradian::texture` for their
//! parameters), and [`texture_param`], which reads a parameter that Mitsuba accepts as a
//! value or as a nested `<texture>`.

use steradian::texture::{
    read_image, Bitmap, Checkerboard, FilterType, MeshAttribute, Texture, UvTransform, WrapMode,
    VOLUME_TEXTURE_DEFAULT,
};
use steradian::Spectrum;

use super::{
    at, at_filename, check_non_negative, choice, lookup, required_string, AttributeSource, Builder,
    Plugins,
};
use crate::error::{LoadError, LoadWarning};
use crate::properties::PropertyValue;
use crate::tree::{ObjectTag, PluginNode};

/// A parameter given as a value (`<rgb>`, `<spectrum>`, `<float>`) or as a nested
/// `<texture name="...">` (or a `<ref>` to one); `default` (uniform) when absent, or an error
/// naming the parameter when `default` is `None`.
pub(crate) fn texture_param(
    b: &Builder,
    node: &PluginNode,
    name: &str,
    default: Option<f32>,
) -> Result<Texture, LoadError> {
    if let Some(child) = node.child(name) {
        if child.node.tag != ObjectTag::Texture {
            return Err(LoadError::at(
                child.pos(),
                format!(
                    "{}: '{name}' must be a texture or a value, got {}",
                    node.desc(),
                    child.node.desc()
                ),
            ));
        }
        return build(b, &child.node);
    }
    match (node.props.get_spectrum(name)?, default) {
        (Some(v), _) => Ok(Texture::Constant(v)),
        (None, Some(d)) => Ok(Texture::Constant(Spectrum::splat(d))),
        (None, None) => Err(LoadError::at(
            &node.pos,
            format!("{}: missing parameter '{name}' (a value or a <texture>)", node.desc()),
        )),
    }
}

/// A parameter read as one number at each point (Mitsuba's `eval_1`: a roughness, a weight,
/// an opacity): a [`texture_param`] that must have a scalar reading, as Mitsuba requires (a
/// 3-channel `mesh_attribute` has none).
pub(crate) fn scalar_param(
    b: &Builder,
    node: &PluginNode,
    name: &str,
    default: Option<f32>,
) -> Result<Texture, LoadError> {
    let t = texture_param(b, node, name, default)?;
    check_scalar(node, name, &t)?;
    Ok(t)
}

/// Refuses texture `t` of parameter `name` when it has no scalar reading ([`scalar_param`]).
pub(crate) fn check_scalar(node: &PluginNode, name: &str, t: &Texture) -> Result<(), LoadError> {
    if let Some(attribute) = t.scalar_reading_refused() {
        let pos = node.child(name).map(|c| c.pos()).unwrap_or(&node.pos);
        return Err(LoadError::at(
            pos,
            format!(
                "{}: '{name}' is a single number, but mesh attribute \"{attribute}\" has 3 \
                 channels (Mitsuba refuses it too; use a 1-channel attribute)",
                node.desc()
            ),
        ));
    }
    Ok(())
}

/// An albedo-like parameter (a reflectance or transmittance, a fraction of the light): a
/// [`texture_param`] whose constant value must be finite and non-negative in every channel
/// (an error at the property), and is warned about above 1, where the surface would create
/// energy. Textures are taken as they are.
pub(crate) fn albedo_param(
    b: &Builder,
    node: &PluginNode,
    name: &str,
    default: Option<f32>,
) -> Result<Texture, LoadError> {
    let t = texture_param(b, node, name, default)?;
    if let Texture::Constant(v) = &t {
        check_non_negative(node, name, *v)?;
        if v.max_element() > 1.0 {
            let pos = node.props.position(name).or_else(|| node.child(name).map(|c| c.pos()));
            b.warn(LoadWarning::at(
                pos.unwrap_or(&node.pos),
                format!(
                    "{}: '{name}' {v} is above 1: the surface returns more light than it receives",
                    node.desc()
                ),
            ));
        }
    }
    Ok(t)
}

/// `to_uv` as the affine map of texture coordinates.
fn to_uv(node: &PluginNode) -> Result<UvTransform, LoadError> {
    Ok(node
        .props
        .get_transform("to_uv")?
        .map_or(UvTransform::IDENTITY, |t| UvTransform::from_mat4(&t.m)))
}

/// Builds one texture from its node.
type BuildTexture = fn(&Builder, &PluginNode) -> Result<Texture, LoadError>;

/// Every texture plugin, by Mitsuba `type`.
pub(super) const TEXTURES: &Plugins<BuildTexture> = &[
    ("bitmap", bitmap),
    ("checkerboard", checkerboard),
    ("mesh_attribute", mesh_attribute),
    ("rawconstant", rawconstant),
    ("volume", volume),
];

/// `volume`: a nested `<volume name="volume">` (0.75 everywhere without one; a value is
/// refused, as Mitsuba 3.9.1 refuses it) looked up at the surface point's world position: a
/// 3-D texture for BSDF parameters (steradian's emitters evaluate textures by uv alone and
/// refuse it).
fn volume(b: &Builder, node: &PluginNode) -> Result<Texture, LoadError> {
    if let Some(pos) = node.props.position("volume") {
        return Err(LoadError::at(
            pos,
            format!("{}: 'volume' must be a nested <volume>, not a value", node.desc()),
        ));
    }
    let v = super::media::volume_param(b, node, "volume", VOLUME_TEXTURE_DEFAULT)?;
    Ok(Texture::Volume(std::sync::Arc::new(v)))
}

/// [`texture_param`] for an emitter, whose textures are looked up by uv alone: a `volume`
/// texture (which needs the world position) is refused by name.
pub(crate) fn emitter_texture_param(
    b: &Builder,
    node: &PluginNode,
    name: &str,
    default: Option<f32>,
) -> Result<Texture, LoadError> {
    let t = texture_param(b, node, name, default)?;
    if t.reads_position() {
        let pos = node.child(name).map(|c| c.pos()).unwrap_or(&node.pos);
        return Err(LoadError::at(
            pos,
            format!(
                "{}: a 'volume' texture for '{name}' is not supported on emitters",
                node.desc()
            ),
        ));
    }
    Ok(t)
}

/// Builds a `<texture>` node.
pub(crate) fn build(b: &Builder, node: &PluginNode) -> Result<Texture, LoadError> {
    let texture = lookup(TEXTURES, node)?(b, node)?;
    node.check_all_used()?;
    Ok(texture)
}

/// `rawconstant`: Mitsuba 3's constant that skips spectral conversion. Its `value` (required) is
/// a `<float>` (all channels) or a 3-vector (`<vector>` or `<point>`; `<rgb>` is refused, as
/// Mitsuba refuses it). steradian renders in RGB, where Mitsuba's RGB variants use the value as
/// given too, so it is a constant texture.
fn rawconstant(_: &Builder, node: &PluginNode) -> Result<Texture, LoadError> {
    let p = &node.props;
    let value = match p.get("value") {
        None => return Err(at(node)("missing parameter 'value' (a float or a 3-vector)".into())),
        Some(PropertyValue::Float(f)) => Spectrum::splat(*f as f32),
        Some(PropertyValue::Vector(v) | PropertyValue::Point(v)) => Spectrum::from(*v),
        Some(other) => {
            let pos = p.position("value").unwrap_or(&node.pos);
            return Err(LoadError::at(
                pos,
                format!(
                    "{}: 'value' must be a float or a 3-vector (<vector>), got {}",
                    node.desc(),
                    other.type_name()
                ),
            ));
        }
    };
    Ok(Texture::Constant(value))
}

fn bitmap(b: &Builder, node: &PluginNode) -> Result<Texture, LoadError> {
    let p = &node.props;
    let filename = required_string(node, "filename", "")?;
    let filter = choice(
        node,
        "filter_type",
        FilterType::default(),
        &[("bilinear", FilterType::Bilinear), ("nearest", FilterType::Nearest)],
    )?;
    let wrap = choice(
        node,
        "wrap_mode",
        WrapMode::default(),
        &[("repeat", WrapMode::Repeat), ("mirror", WrapMode::Mirror), ("clamp", WrapMode::Clamp)],
    )?;
    let raw = p.get_bool("raw")?.unwrap_or(Bitmap::DEFAULT_RAW);
    // storage precision and CUDA texture hardware: no effect on steradian's results
    choice(node, "format", (), &[("auto", ()), ("variant", ()), ("fp16", ())])?;
    p.get_bool("accel")?;
    let to_uv = to_uv(node)?;
    let path = b.resolve_path(node, &filename);
    let at_file = at_filename::<String>(node);
    let image = read_image(&path).map_err(&at_file)?;
    Ok(Texture::Bitmap(Bitmap::new(&filename, image, raw, filter, wrap, to_uv).map_err(at_file)?))
}

/// `mesh_attribute` (see `steradian::texture::MeshAttribute`): an attribute of the PLY mesh
/// whose BSDF holds the texture, found by `name` among the file's attributes.
fn mesh_attribute(b: &Builder, node: &PluginNode) -> Result<Texture, LoadError> {
    let p = &node.props;
    let Some(name) = p.get_string("name")? else {
        return Err(at(node)("missing parameter 'name' (e.g. \"vertex_color\")".into()));
    };
    let at_name = |msg: String| {
        LoadError::at(p.position("name").unwrap_or(&node.pos), format!("{}: {msg}", node.desc()))
    };
    // Mitsuba's test: the name contains one of the prefixes
    if !name.contains("vertex_") && !name.contains("face_") {
        return Err(at_name(format!(
            "invalid attribute name \"{name}\": it must start with \"vertex_\" or \"face_\""
        )));
    }
    let scale = p.get_float("scale")?.unwrap_or(MeshAttribute::DEFAULT_SCALE);
    if !scale.is_finite() {
        return Err(LoadError::at(
            p.position("scale").unwrap_or(&node.pos),
            format!("{}: 'scale' must be finite, got {scale}", node.desc()),
        ));
    }
    let source = b.mesh_attributes.borrow();
    let attributes = match &*source {
        AttributeSource::Mesh(a) => a,
        AttributeSource::Deferred => {
            // a scene-level BSDF or texture: rebuilt, with its mesh, by each shape using it
            b.read_mesh_attribute.set(true);
            return Ok(Texture::Constant(Spectrum::splat(0.0)));
        }
        AttributeSource::None => {
            return Err(at(node)(format!(
                "attribute \"{name}\": no mesh attributes here; a mesh_attribute texture reads \
                 the attributes of the mesh whose BSDF holds it (not an emitter's or a sensor's)"
            )));
        }
    };
    if attributes.list.is_empty() {
        return Err(at_name(format!("the mesh has no attributes, so none named \"{name}\"")));
    }
    let Some(data) = attributes.list.iter().find(|a| a.name == name) else {
        let names: Vec<String> =
            attributes.list.iter().map(|a| format!("\"{}\"", a.name)).collect();
        return Err(at_name(format!(
            "the mesh has no attribute \"{name}\"; it has {}",
            names.join(", ")
        )));
    };
    let texture = MeshAttribute::new(data, attributes.indices.clone(), scale).map_err(at_name)?;
    b.read_mesh_attribute.set(true);
    Ok(Texture::MeshAttribute(texture))
}

fn checkerboard(b: &Builder, node: &PluginNode) -> Result<Texture, LoadError> {
    let color0 = texture_param(b, node, "color0", Some(Checkerboard::DEFAULT_COLOR0))?;
    let color1 = texture_param(b, node, "color1", Some(Checkerboard::DEFAULT_COLOR1))?;
    Ok(Texture::Checkerboard(Checkerboard::new(color0, color1, to_uv(node)?)))
}
