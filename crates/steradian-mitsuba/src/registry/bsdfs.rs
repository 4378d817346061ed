//! BSDF plugins: `diffuse`, `twosided`, `conductor`, `roughconductor`, `dielectric`,
//! `thindielectric`, `roughdielectric`, `plastic`, `roughplastic`, `mask`, `blendbsdf`,
//! `bumpmap`, `normalmap`, `null`, `pplastic`, `principled`, `principledthin`, `hair`, `measured`, and steradian's
//! own `phong` and `merl`. Parameters and defaults are Mitsuba 3's (see each plugin's
//! documentation in `steradian::bsdf`). Reflectances and transmittances (`phong`'s too),
//! `mask`'s `opacity`, `blendbsdf`'s `weight` and the principled materials' parameters take a
//! value or a texture; IORs and roughness are values (textures where Mitsuba allows them).

use steradian::bsdf::ior::{conductor_preset, lookup_ior};
use steradian::bsdf::{
    BlendBsdf, Bsdf, BumpMap, Conductor, Dielectric, Diffuse, Hair, HairAbsorption,
    InternalScattering, Mask, MicrofacetDistribution, MicrofacetKind, NormalMap, PPlastic,
    PerturbOptions, Plastic, Principled, PrincipledSamplingRates, PrincipledThin,
    PrincipledThinSamplingRates, RoughConductor, RoughDielectric, RoughPlastic, ThinDielectric,
    TwoSided,
};
use steradian::bsdf::{Measured, MeasuredTables, Merl, MerlTable, Phong};
use steradian::texture::Texture;
use steradian::Spectrum;

use super::textures::{self, albedo_param, scalar_param, texture_param};
use super::{
    at, at_filename, at_param, check_non_negative, lookup, required_string, Builder, Plugins,
};
use crate::error::{LoadError, LoadWarning};
use crate::properties::PropertyValue;
use crate::tree::{ObjectTag, PluginNode};

/// The nested BSDFs of `node` (named or not), built, in document order.
fn nested_bsdfs(b: &Builder, node: &PluginNode) -> Result<Vec<Bsdf>, LoadError> {
    node.children_of(ObjectTag::Bsdf).iter().map(|c| build(b, &c.node)).collect()
}

/// `flip_invalid_normals` and `use_shadowing_function` of `bumpmap` and `normalmap`.
fn perturb_options(node: &PluginNode) -> Result<PerturbOptions, LoadError> {
    let d = PerturbOptions::default();
    Ok(PerturbOptions {
        flip_invalid_normals: node
            .props
            .get_bool("flip_invalid_normals")?
            .unwrap_or(d.flip_invalid_normals),
        use_shadowing_function: node
            .props
            .get_bool("use_shadowing_function")?
            .unwrap_or(d.use_shadowing_function),
    })
}

/// Exactly one nested BSDF.
fn one_nested(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let mut v = nested_bsdfs(b, node)?;
    if v.len() != 1 {
        return Err(at(node)(format!("expects exactly one nested BSDF, got {}", v.len())));
    }
    Ok(v.remove(0))
}

/// An IOR given as a number or as a name from Mitsuba's table (`int_ior`, `ext_ior`).
fn ior(node: &PluginNode, name: &str, default: &str) -> Result<f32, LoadError> {
    let p = &node.props;
    let pos = p.position(name).cloned().unwrap_or_else(|| node.pos.clone());
    let value = match p.get(name) {
        None => lookup_ior(default),
        Some(PropertyValue::Float(f)) => Ok(*f as f32),
        Some(PropertyValue::Int(i)) => Ok(*i as f32),
        Some(PropertyValue::String(s)) => lookup_ior(s),
        Some(v) => {
            Err(format!("property '{name}' must be a float or an IOR name, got {}", v.type_name()))
        }
    };
    let v = value.map_err(|m| LoadError::at(&pos, format!("{}: {m}", node.desc())))?;
    if v.is_nan() || v <= 0.0 || v.is_infinite() {
        return Err(LoadError::at(
            &pos,
            format!("{}: {name} must be positive, got {v}", node.desc()),
        ));
    }
    Ok(v)
}

/// η = int_ior/ext_ior, with the plugin's defaults for the two.
fn relative_ior(node: &PluginNode, int_default: &str, ext_default: &str) -> Result<f32, LoadError> {
    Ok(ior(node, "int_ior", int_default)? / ior(node, "ext_ior", ext_default)?)
}

/// The rough interfaces (`roughdielectric`, `roughplastic`, `pplastic`) need a real one.
fn distinct_iors(node: &PluginNode, eta: f32) -> Result<(), LoadError> {
    if eta == 1.0 {
        return Err(at(node)("the interior and exterior IORs must differ".into()));
    }
    Ok(())
}

/// A constant spectrum parameter with a default.
fn spectrum(node: &PluginNode, name: &str, default: f32) -> Result<Spectrum, LoadError> {
    Ok(node.props.get_spectrum(name)?.unwrap_or(Spectrum::splat(default)))
}

/// Conductor IOR: `material` preset (default `none`: η 0, k 1) or explicit `eta`/`k`.
fn conductor_ior(node: &PluginNode) -> Result<(Spectrum, Spectrum), LoadError> {
    let p = &node.props;
    let material = p.get_string("material")?.unwrap_or_else(|| Conductor::DEFAULT_MATERIAL.into());
    if p.contains("eta") || material == "none" {
        if material != "none" {
            return Err(at(node)("specify either (eta, k) or material, not both".into()));
        }
        let eta = spectrum(node, "eta", Conductor::DEFAULT_ETA)?;
        let k = spectrum(node, "k", Conductor::DEFAULT_K)?;
        check_non_negative(node, "eta", eta)?;
        check_non_negative(node, "k", k)?;
        Ok((eta, k))
    } else {
        conductor_preset(&material).map_err(at(node))
    }
}

/// Spatially varying roughness (α_u, α_v), when given as textures.
type AlphaTextures = Option<(Texture, Texture)>;

/// `distribution`, `alpha` or `alpha_u`/`alpha_v`, `sample_visible`. With `textures`
/// (roughconductor, roughdielectric) the roughness may be a texture, as in Mitsuba;
/// roughplastic takes numbers only (Mitsuba precomputes tables for its α).
fn microfacet(
    b: &Builder,
    node: &PluginNode,
    textures: bool,
) -> Result<(MicrofacetDistribution, AlphaTextures), LoadError> {
    let p = &node.props;
    let kind = match p.get_string("distribution")?.map(|s| s.to_lowercase()).as_deref() {
        None => MicrofacetKind::default(),
        Some("beckmann") => MicrofacetKind::Beckmann,
        Some("ggx") => MicrofacetKind::Ggx,
        Some(other) => {
            return Err(at(node)(format!(
                "invalid distribution \"{other}\", must be \"beckmann\" or \"ggx\""
            )))
        }
    };
    let sample_visible =
        p.get_bool("sample_visible")?.unwrap_or(MicrofacetDistribution::DEFAULT_SAMPLE_VISIBLE);
    let given = |n: &str| {
        p.contains(n) || (textures && node.children.iter().any(|c| c.name.as_deref() == Some(n)))
    };
    let alpha = |n: &str| -> Result<Texture, LoadError> {
        if textures {
            scalar_param(b, node, n, Some(MicrofacetDistribution::DEFAULT_ALPHA))
        } else {
            let alpha = p.get_float(n)?.unwrap_or(MicrofacetDistribution::DEFAULT_ALPHA);
            Ok(Texture::Constant(Spectrum::splat(alpha)))
        }
    };
    let (tu, tv) = if given("alpha_u") || given("alpha_v") {
        if !(given("alpha_u") && given("alpha_v")) {
            return Err(at(node)("both 'alpha_u' and 'alpha_v' must be specified".into()));
        }
        if given("alpha") {
            return Err(at(node)("specify either 'alpha' or 'alpha_u'/'alpha_v', not both".into()));
        }
        (alpha("alpha_u")?, alpha("alpha_v")?)
    } else {
        let a = alpha("alpha")?;
        (a.clone(), a)
    };
    match (&tu, &tv) {
        (Texture::Constant(u), Texture::Constant(v)) => {
            // a constant is read like Mitsuba's eval_1 of it (the channel mean)
            let (au, av) = (u.element_sum() / 3.0, v.element_sum() / 3.0);
            if !(au >= 0.0 && av >= 0.0 && au.is_finite() && av.is_finite()) {
                return Err(at(node)(format!(
                    "roughness must be finite and non-negative, got alpha_u = {au}, alpha_v = {av}"
                )));
            }
            Ok((MicrofacetDistribution::new(kind, au, av, sample_visible), None))
        }
        _ => {
            // α placeholders: the textures give the roughness at each point
            let a = MicrofacetDistribution::DEFAULT_ALPHA;
            Ok((MicrofacetDistribution::new(kind, a, a, sample_visible), Some((tu, tv))))
        }
    }
}

/// Builds one BSDF from its node.
type BuildBsdf = fn(&Builder, &PluginNode) -> Result<Bsdf, LoadError>;

/// Every BSDF plugin, by Mitsuba `type`.
pub(super) const BSDFS: &Plugins<BuildBsdf> = &[
    ("diffuse", diffuse),
    ("twosided", twosided),
    ("conductor", conductor),
    ("roughconductor", roughconductor),
    ("dielectric", dielectric),
    ("thindielectric", thindielectric),
    ("roughdielectric", roughdielectric),
    ("plastic", plastic),
    ("roughplastic", roughplastic),
    ("phong", phong),
    ("merl", merl),
    ("measured", measured),
    ("mask", mask),
    ("blendbsdf", blendbsdf),
    ("bumpmap", bumpmap),
    ("normalmap", normalmap),
    ("null", null),
    ("pplastic", pplastic),
    ("principled", principled),
    ("principledthin", principledthin),
    ("hair", hair),
];

/// Builds a BSDF node (not cached: use `Builder::bsdf_index` for scene BSDFs).
pub(crate) fn build(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let bsdf = lookup(BSDFS, node)?(b, node)?;
    node.check_all_used()?;
    Ok(bsdf)
}

fn diffuse(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    Ok(Bsdf::Diffuse(Diffuse::new(albedo_param(
        b,
        node,
        "reflectance",
        Some(Diffuse::DEFAULT_REFLECTANCE),
    )?)))
}

/// `pplastic` (its unpolarised form): roughness as numbers (anisotropic allowed), IORs,
/// diffuse and specular reflectances (values or textures).
fn pplastic(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let eta = relative_ior(node, PPlastic::DEFAULT_INT_IOR, PPlastic::DEFAULT_EXT_IOR)?;
    distinct_iors(node, eta)?;
    let (d, _) = microfacet(b, node, false)?;
    let diffuse =
        albedo_param(b, node, "diffuse_reflectance", Some(PPlastic::DEFAULT_DIFFUSE_REFLECTANCE))?;
    let specular = albedo_param(
        b,
        node,
        "specular_reflectance",
        Some(PPlastic::DEFAULT_SPECULAR_REFLECTANCE),
    )?;
    Ok(Bsdf::PPlastic(PPlastic::new(d, eta, diffuse, specular)))
}

/// A non-negative weight of a principled material (a value or a texture; constants checked).
fn weight_param(
    b: &Builder,
    node: &PluginNode,
    name: &str,
    default: f32,
) -> Result<Texture, LoadError> {
    let t = scalar_param(b, node, name, Some(default))?;
    if let Texture::Constant(v) = &t {
        check_non_negative(node, name, *v)?;
    }
    Ok(t)
}

/// A finite, non-negative float (a sampling rate), `default` when absent.
fn rate(node: &PluginNode, name: &str, default: f32) -> Result<f32, LoadError> {
    let v = node.props.get_float(name)?.unwrap_or(default);
    check_non_negative(node, name, Spectrum::splat(v))?;
    Ok(v)
}

/// Whether a principled lobe is switched on, Mitsuba's test: the parameter is given, and not
/// as the number 0 (a texture always switches it on).
fn lobe_given(node: &PluginNode, name: &str) -> bool {
    match node.props.get(name) {
        Some(PropertyValue::Float(f)) => *f != 0.0,
        Some(PropertyValue::Int(i)) => *i != 0,
        Some(_) => true,
        None => node.child(name).is_some(),
    }
}

/// `principled`: every weight a value or a texture; `eta` or `specular` (not both) sets the
/// dielectric's IOR, nudged off 1 (η 1.001, specular 0.001) when there is a transmission,
/// as Mitsuba does.
fn principled(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let w = |name| weight_param(b, node, name, Principled::DEFAULT_WEIGHT);
    let mut p = Principled::new();
    p.base_color = albedo_param(b, node, "base_color", Some(Principled::DEFAULT_BASE_COLOR))?;
    p.roughness = weight_param(b, node, "roughness", Principled::DEFAULT_ROUGHNESS)?;
    p.anisotropic = w("anisotropic")?;
    p.metallic = w("metallic")?;
    p.spec_trans = w("spec_trans")?;
    p.spec_tint = w("spec_tint")?;
    p.sheen = w("sheen")?;
    p.sheen_tint = w("sheen_tint")?;
    p.flatness = w("flatness")?;
    p.clearcoat = w("clearcoat")?;
    p.clearcoat_gloss = w("clearcoat_gloss")?;
    let transmits = lobe_given(node, "spec_trans");
    let props = &node.props;
    p.eta = match (props.get_float("eta")?, props.get_float("specular")?) {
        (Some(_), Some(_)) => {
            return Err(at(node)("give either 'eta' or 'specular', not both".into()));
        }
        (Some(eta), None) => {
            if !(eta > 0.0 && eta.is_finite()) {
                return Err(LoadError::at(
                    props.position("eta").unwrap_or(&node.pos),
                    format!("{}: eta must be positive, got {eta}", node.desc()),
                ));
            }
            if transmits && eta == 1.0 {
                1.001
            } else {
                eta
            }
        }
        (None, s) => {
            let s = s.unwrap_or(Principled::DEFAULT_SPECULAR);
            if !(0.0..12.5).contains(&s) {
                return Err(LoadError::at(
                    props.position("specular").unwrap_or(&node.pos),
                    format!("{}: specular must lie in [0, 12.5), got {s}", node.desc()),
                ));
            }
            Principled::eta_from_specular(if transmits && s == 0.0 { 1e-3 } else { s })
        }
    };
    let d = Principled::DEFAULT_SAMPLING_RATES;
    p.rates = PrincipledSamplingRates {
        diffuse: rate(node, "diffuse_reflectance_sampling_rate", d.diffuse)?,
        specular: rate(node, "main_specular_sampling_rate", d.specular)?,
        clearcoat: rate(node, "clearcoat_sampling_rate", d.clearcoat)?,
    };
    Ok(Bsdf::Principled(p))
}

/// `principledthin`: every weight and `eta` a value or a texture.
fn principledthin(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let w = |name| weight_param(b, node, name, PrincipledThin::DEFAULT_WEIGHT);
    let mut p = PrincipledThin::new();
    p.base_color = albedo_param(b, node, "base_color", Some(PrincipledThin::DEFAULT_BASE_COLOR))?;
    p.roughness = weight_param(b, node, "roughness", PrincipledThin::DEFAULT_ROUGHNESS)?;
    p.anisotropic = w("anisotropic")?;
    p.spec_trans = w("spec_trans")?;
    p.eta = weight_param(b, node, "eta", PrincipledThin::DEFAULT_ETA)?;
    p.spec_tint = w("spec_tint")?;
    p.diff_trans = w("diff_trans")?;
    p.sheen = w("sheen")?;
    p.sheen_tint = w("sheen_tint")?;
    p.flatness = w("flatness")?;
    let d = PrincipledThin::DEFAULT_SAMPLING_RATES;
    p.rates = PrincipledThinSamplingRates {
        specular_reflection: rate(
            node,
            "specular_reflectance_sampling_rate",
            d.specular_reflection,
        )?,
        specular_transmission: rate(
            node,
            "specular_transmittance_sampling_rate",
            d.specular_transmission,
        )?,
        diffuse_reflection: rate(node, "diffuse_reflectance_sampling_rate", d.diffuse_reflection)?,
        diffuse_transmission: rate(
            node,
            "diffuse_transmittance_sampling_rate",
            d.diffuse_transmission,
        )?,
    };
    Ok(Bsdf::PrincipledThin(p))
}

/// `null` (no parameters): a surface that lets every ray through unchanged, Mitsuba's
/// `BSDFFlags::Null` lobe alone. It is the fully transparent `mask` (opacity 0; the nested
/// BSDF is never sampled), so it behaves as Mitsuba's `path` treats it: a crossing counts as a
/// bounce, emitters seen through it take full weight, and shadow rays stop at it (`ray_test`
/// finds null surfaces; only `volpath` traces through them).
fn null(_: &Builder, _: &PluginNode) -> Result<Bsdf, LoadError> {
    let black = Bsdf::Diffuse(Diffuse::new(Texture::Constant(Spectrum::ZERO)));
    Ok(Bsdf::Mask(Mask::new(Texture::Constant(Spectrum::ZERO), black)))
}

fn twosided(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let children = node.children_of(ObjectTag::Bsdf);
    let built: Vec<Bsdf> = children.iter().map(|c| build(b, &c.node)).collect::<Result<_, _>>()?;
    if built.iter().any(|b| matches!(b, Bsdf::TwoSided(_))) {
        return Err(LoadError::at(&node.pos, "twosided: a nested twosided BSDF makes no sense"));
    }
    if let Some(c) = built.iter().position(transmits) {
        return Err(LoadError::at(
            children[c].pos(),
            format!(
                "twosided: {} transmits light, and only BSDFs without transmission can be two-sided \
                 (as in Mitsuba 3.9.1; glass, masks and null surfaces are two-sided already)",
                children[c].node.desc()
            ),
        ));
    }
    match <[Bsdf; 1]>::try_from(built.clone()) {
        Ok([one]) => Ok(Bsdf::TwoSided(TwoSided::new(one.clone(), one))),
        Err(_) => match <[Bsdf; 2]>::try_from(built) {
            Ok([front, back]) => Ok(Bsdf::TwoSided(TwoSided::new(front, back))),
            Err(v) => Err(LoadError::at(
                &node.pos,
                format!("twosided: expects one or two nested BSDFs, got {}", v.len()),
            )),
        },
    }
}

/// Whether Mitsuba 3.9.1 gives the BSDF a transmission or null lobe, which its `twosided`
/// refuses: the dielectrics, `mask` and `null`, `principledthin`, `hair`, `principled` with
/// a `spec_trans` that is not 0, and the wrappers of these (checked against Mitsuba).
fn transmits(b: &Bsdf) -> bool {
    match b {
        Bsdf::Dielectric(_)
        | Bsdf::ThinDielectric(_)
        | Bsdf::RoughDielectric(_)
        | Bsdf::Mask(_)
        | Bsdf::PrincipledThin(_)
        | Bsdf::Hair(_) => true,
        Bsdf::Principled(p) => p.spec_trans != Texture::Constant(Spectrum::ZERO),
        Bsdf::BlendBsdf(b) => transmits(&b.bsdf0) || transmits(&b.bsdf1),
        Bsdf::BumpMap(b) => transmits(&b.nested),
        Bsdf::NormalMap(b) => transmits(&b.nested),
        _ => false,
    }
}

fn conductor(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let (eta, k) = conductor_ior(node)?;
    let specular = Some(Conductor::DEFAULT_SPECULAR_REFLECTANCE);
    Ok(Bsdf::Conductor(Conductor::new(
        eta,
        k,
        albedo_param(b, node, "specular_reflectance", specular)?,
    )))
}

fn roughconductor(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let (eta, k) = conductor_ior(node)?;
    let (d, alpha) = microfacet(b, node, true)?;
    let specular = Some(Conductor::DEFAULT_SPECULAR_REFLECTANCE);
    let mut c =
        RoughConductor::new(d, eta, k, albedo_param(b, node, "specular_reflectance", specular)?);
    if let Some((u, v)) = alpha {
        c = c.with_alpha_textures(u, v);
    }
    Ok(Bsdf::RoughConductor(c))
}

/// The relative IOR and the specular reflectance and transmittance of the dielectrics.
fn dielectric_params(b: &Builder, node: &PluginNode) -> Result<(f32, Texture, Texture), LoadError> {
    let eta = relative_ior(node, Dielectric::DEFAULT_INT_IOR, Dielectric::DEFAULT_EXT_IOR)?;
    let r = albedo_param(
        b,
        node,
        "specular_reflectance",
        Some(Dielectric::DEFAULT_SPECULAR_REFLECTANCE),
    )?;
    let t = albedo_param(
        b,
        node,
        "specular_transmittance",
        Some(Dielectric::DEFAULT_SPECULAR_TRANSMITTANCE),
    )?;
    Ok((eta, r, t))
}

fn dielectric(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let (eta, r, t) = dielectric_params(b, node)?;
    Ok(Bsdf::Dielectric(Dielectric::new(eta, r, t)))
}

fn thindielectric(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let (eta, r, t) = dielectric_params(b, node)?;
    Ok(Bsdf::ThinDielectric(ThinDielectric::new(eta, r, t)))
}

fn roughdielectric(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let (eta, r, t) = dielectric_params(b, node)?;
    distinct_iors(node, eta)?;
    let (d, alpha) = microfacet(b, node, true)?;
    let mut rd = RoughDielectric::new(d, eta, r, t);
    if let Some((u, v)) = alpha {
        rd = rd.with_alpha_textures(u, v);
    }
    Ok(Bsdf::RoughDielectric(rd))
}

/// The coating's relative IOR, the diffuse and specular reflectances and the internal
/// scattering model of the plastics.
fn plastic_params(
    b: &Builder,
    node: &PluginNode,
) -> Result<(f32, Texture, Texture, InternalScattering), LoadError> {
    let eta = relative_ior(node, Plastic::DEFAULT_INT_IOR, Plastic::DEFAULT_EXT_IOR)?;
    let diffuse =
        albedo_param(b, node, "diffuse_reflectance", Some(Plastic::DEFAULT_DIFFUSE_REFLECTANCE))?;
    let specular =
        albedo_param(b, node, "specular_reflectance", Some(Plastic::DEFAULT_SPECULAR_REFLECTANCE))?;
    let internal = if node.props.get_bool("nonlinear")?.unwrap_or(Plastic::DEFAULT_NONLINEAR) {
        InternalScattering::Nonlinear
    } else {
        InternalScattering::Linear
    };
    Ok((eta, diffuse, specular, internal))
}

fn plastic(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let (eta, diffuse, specular, internal) = plastic_params(b, node)?;
    Ok(Bsdf::Plastic(Plastic::new(eta, diffuse, specular, internal)))
}

fn roughplastic(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let (eta, diffuse, specular, internal) = plastic_params(b, node)?;
    distinct_iors(node, eta)?;
    let (d, _) = microfacet(b, node, false)?;
    if !d.is_isotropic() {
        return Err(at(node)(
            "roughplastic supports isotropic roughness only (use 'alpha')".into(),
        ));
    }
    Ok(Bsdf::RoughPlastic(RoughPlastic::new(d, eta, diffuse, specular, internal)))
}

fn phong(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let diffuse =
        albedo_param(b, node, "diffuse_reflectance", Some(Phong::DEFAULT_DIFFUSE_REFLECTANCE))?;
    let specular =
        albedo_param(b, node, "specular_reflectance", Some(Phong::DEFAULT_SPECULAR_REFLECTANCE))?;
    let exponent = node.props.get_float("exponent")?.unwrap_or(Phong::DEFAULT_EXPONENT);
    Phong::new(diffuse, specular, exponent).map(Bsdf::Phong).map_err(at_param(node))
}

/// `hair` (core: bsdf/hair.rs): pigments or `sigma_a` (with `scale`), not both.
fn hair(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let p = &node.props;
    let float = |name: &str, default: f32| -> Result<f32, LoadError> {
        Ok(p.get_float(name)?.unwrap_or(default))
    };
    let sigma_given = p.contains("sigma_a") || node.child("sigma_a").is_some();
    let absorption = if sigma_given {
        if let Some(name) = ["eumelanin", "pheomelanin"].into_iter().find(|n| p.contains(n)) {
            return Err(LoadError::at(
                p.position(name).unwrap_or(&node.pos),
                format!("{}: give the pigments or 'sigma_a', not both", node.desc()),
            ));
        }
        let sigma_a = texture_param(b, node, "sigma_a", None)?;
        if let Texture::Constant(v) = &sigma_a {
            check_non_negative(node, "sigma_a", *v)?;
        }
        HairAbsorption::SigmaA { sigma_a, scale: float("scale", Hair::DEFAULT_SCALE)? }
    } else {
        HairAbsorption::Pigments {
            eumelanin: float("eumelanin", Hair::DEFAULT_EUMELANIN)?,
            pheomelanin: float("pheomelanin", Hair::DEFAULT_PHEOMELANIN)?,
        }
    };
    // `scale` applies to `sigma_a`; Mitsuba reads it with the pigments too
    p.get_float("scale")?;
    let eta = relative_ior(node, Hair::DEFAULT_INT_IOR, Hair::DEFAULT_EXT_IOR)?;
    Hair::new(
        absorption,
        eta,
        float("longitudinal_roughness", Hair::DEFAULT_LONGITUDINAL_ROUGHNESS)?,
        float("azimuthal_roughness", Hair::DEFAULT_AZIMUTHAL_ROUGHNESS)?,
        float("scale_tilt", Hair::DEFAULT_SCALE_TILT)?,
    )
    .map(Bsdf::Hair)
    .map_err(at(node))
}

fn merl(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let p = &node.props;
    let file = p
        .get_string("filename")?
        .ok_or_else(|| at(node)("missing 'filename' (the MERL .binary file)".into()))?;
    let table = MerlTable::read(&b.resolve_path(node, &file)).map_err(at_filename(node))?;
    Ok(Bsdf::Merl(Merl::new(table)))
}

fn measured(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let file = required_string(node, "filename", " (the material's RGB .bsdf file)")?;
    let tables = MeasuredTables::read(&b.resolve_path(node, &file)).map_err(at_filename(node))?;
    Ok(Bsdf::Measured(Measured::new(tables)))
}

fn mask(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let opacity = albedo_param(b, node, "opacity", Some(Mask::DEFAULT_OPACITY))?;
    textures::check_scalar(node, "opacity", &opacity)?;
    Ok(Bsdf::Mask(Mask::new(opacity, one_nested(b, node)?)))
}

fn blendbsdf(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let weight = albedo_param(b, node, "weight", None)?;
    textures::check_scalar(node, "weight", &weight)?;
    match <[Bsdf; 2]>::try_from(nested_bsdfs(b, node)?) {
        Ok([b0, b1]) => {
            let blend = BlendBsdf::new(weight, b0, b1);
            let mixed = |x: &Bsdf, y: &Bsdf| x.has_delta_lobe() && y.has_smooth_lobe();
            if mixed(&blend.bsdf0, &blend.bsdf1) || mixed(&blend.bsdf1, &blend.bsdf0) {
                b.warn(LoadWarning::at(
                    &node.pos,
                    format!(
                        "{}: blends a delta lobe (mirror, smooth glass or plastic coating) with a \
                         smooth one; Mitsuba 3.9.1 renders such blends too dark or too bright \
                         (its image is not the weighted sum of the two BSDFs' images); \
                         steradian's is (bsdf/blendbsdf.rs)",
                        node.desc()
                    ),
                ));
            }
            Ok(Bsdf::BlendBsdf(blend))
        }
        Err(v) => Err(at(node)(format!("expects two nested BSDFs, got {}", v.len()))),
    }
}

fn bumpmap(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let textures = node.children_of(ObjectTag::Texture);
    if textures.len() != 1 {
        return Err(at(node)(format!(
            "expects exactly one nested texture (the height), got {}",
            textures.len()
        )));
    }
    let height = textures::build(b, &textures[0].node)?;
    let scale = node.props.get_float("scale")?.unwrap_or(BumpMap::DEFAULT_SCALE);
    if !scale.is_finite() {
        return Err(at(node)(format!("scale must be finite, got {scale}")));
    }
    let nested = one_nested(b, node)?;
    let bump = BumpMap::new(height, scale, nested, perturb_options(node)?)
        .map_err(|m| LoadError::at(textures[0].pos(), format!("{}: {m}", node.desc())))?;
    Ok(Bsdf::BumpMap(bump))
}

fn normalmap(b: &Builder, node: &PluginNode) -> Result<Bsdf, LoadError> {
    let normals = texture_param(b, node, "normalmap", None)?;
    Ok(Bsdf::NormalMap(NormalMap::new(normals, one_nested(b, node)?, perturb_options(node)?)))
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use steradian::bsdf::Bsdf;

    fn load(bsdf_xml: &str) -> Result<Vec<Bsdf>, String> {
        let xml = format!(
            r#"<scene version="3.0.0"><integrator type="path"/><sensor type="perspective"/><shape type="sphere">{bsdf_xml}</shape></scene>"#
        );
        crate::load_string(&xml, Path::new("t.xml"), Path::new("."), &[])
            .map(|s| s.scene.bsdfs.clone())
            .map_err(|e| e.to_string())
    }

    fn one(bsdf_xml: &str) -> Bsdf {
        let v = load(bsdf_xml).unwrap();
        assert_eq!(v.len(), 1);
        v.into_iter().next().unwrap()
    }

    #[test]
    fn principled_parameters() {
        use steradian::bsdf::{Principled, PrincipledThin};
        let Bsdf::Principled(p) = one(r#"<bsdf type="principled"/>"#) else { panic!() };
        assert_eq!(p, Principled::new());
        assert_eq!(p.eta, 1.5);
        let Bsdf::Principled(p) =
            one(r#"<bsdf type="principled"><float name="specular" value="0"/></bsdf>"#)
        else {
            panic!()
        };
        assert_eq!(p.eta, 1.0, "no transmission: specular 0 stays η 1");
        // a transmission moves η and specular off 1 and 0 (to 1.001 and 0.001: η 1.018), as
        // Mitsuba does
        for x in [r#"<float name="eta" value="1"/>"#, r#"<float name="specular" value="0"/>"#] {
            let xml = format!(
                r#"<bsdf type="principled"><float name="spec_trans" value="0.5"/>{x}</bsdf>"#
            );
            let Bsdf::Principled(p) = one(&xml) else { panic!() };
            assert!(p.eta > 1.0 && p.eta < 1.02, "{x}: η {}", p.eta);
        }
        let Bsdf::PrincipledThin(t) = one(r#"<bsdf type="principledthin"/>"#) else { panic!() };
        assert_eq!(t, PrincipledThin::new());
        for bad in [
            r#"<bsdf type="principled"><float name="roughness" value="-0.1"/></bsdf>"#,
            r#"<bsdf type="principled"><float name="specular" value="20"/></bsdf>"#,
            r#"<bsdf type="principled"><float name="clearcoat_sampling_rate" value="-1"/></bsdf>"#,
            r#"<bsdf type="principledthin"><float name="diff_trans" value="-2"/></bsdf>"#,
            r#"<bsdf type="principledthin"><float name="alpha" value="0.2"/></bsdf>"#,
        ] {
            let e = load(bad).unwrap_err();
            assert!(e.contains("t.xml:1:"), "{bad}: {e}");
        }
    }

    #[test]
    fn defaults() {
        match one(r#"<bsdf type="conductor"/>"#) {
            Bsdf::Conductor(c) => assert_eq!(
                (c.ior.eta(), c.ior.k()),
                (steradian::Spectrum::ZERO, steradian::Spectrum::ONE)
            ),
            b => panic!("{b:?}"),
        }
        match one(r#"<bsdf type="roughconductor"/>"#) {
            Bsdf::RoughConductor(c) => {
                let d = c.distribution;
                assert_eq!(
                    (d.kind, d.alpha_u, d.alpha_v, d.sample_visible),
                    (steradian::bsdf::MicrofacetKind::Beckmann, 0.1, 0.1, true)
                );
                assert_eq!(c.ior.k(), steradian::Spectrum::ONE);
            }
            b => panic!("{b:?}"),
        }
        for t in ["dielectric", "thindielectric", "roughdielectric"] {
            let eta = match one(&format!(r#"<bsdf type="{t}"/>"#)) {
                Bsdf::Dielectric(d) => d.eta,
                Bsdf::ThinDielectric(d) => d.eta,
                Bsdf::RoughDielectric(d) => {
                    assert_eq!(d.distribution.kind, steradian::bsdf::MicrofacetKind::Beckmann);
                    d.eta
                }
                b => panic!("{b:?}"),
            };
            assert!((eta - 1.5046 / 1.000277).abs() < 1e-6, "{t}: {eta}");
        }
    }

    #[test]
    fn parameters() {
        match one(
            r#"<bsdf type="roughdielectric"><string name="distribution" value="ggx"/><float name="alpha_u" value="0.2"/><float name="alpha_v" value="0.4"/><string name="int_ior" value="water"/><float name="ext_ior" value="1.0"/><boolean name="sample_visible" value="false"/></bsdf>"#,
        ) {
            Bsdf::RoughDielectric(d) => {
                assert_eq!(
                    (d.distribution.alpha_u, d.distribution.alpha_v, d.distribution.sample_visible),
                    (0.2, 0.4, false)
                );
                assert!((d.eta - 1.333).abs() < 1e-6);
            }
            b => panic!("{b:?}"),
        }
        match one(
            r#"<bsdf type="conductor"><string name="material" value="Au"/><rgb name="specular_reflectance" value="0.5"/></bsdf>"#,
        ) {
            Bsdf::Conductor(c) => {
                assert!(
                    (c.ior.eta().x - 0.14303598).abs() < 1e-6
                        && (c.ior.k().x - 3.982997).abs() < 1e-6
                )
            }
            b => panic!("{b:?}"),
        }
        match one(
            r#"<bsdf type="roughconductor"><rgb name="eta" value="0.2, 0.9, 1.1"/><rgb name="k" value="3.9, 2.4, 2.1"/></bsdf>"#,
        ) {
            Bsdf::RoughConductor(c) => assert_eq!(c.ior.eta().y, 0.9),
            b => panic!("{b:?}"),
        }
    }

    #[test]
    fn errors() {
        let e = load(r#"<bsdf type="dielectric"><string name="int_ior" value="glass"/></bsdf>"#)
            .unwrap_err();
        assert!(e.contains("glass") && e.contains("bk7") && e.contains("diamond"), "{e}");
        let e = load(r#"<bsdf type="roughconductor"><float name="alpha" value="0.1"/><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.2"/></bsdf>"#).unwrap_err();
        assert!(e.contains("alpha"), "{e}");
        let e = load(r#"<bsdf type="roughdielectric"><float name="alpha_u" value="0.1"/></bsdf>"#)
            .unwrap_err();
        assert!(e.contains("alpha_v"), "{e}");
        let e = load(r#"<bsdf type="conductor"><string name="material" value="Xx"/></bsdf>"#)
            .unwrap_err();
        assert!(e.contains("Au") && e.contains("none"), "{e}");
        let e = load(r#"<bsdf type="conductor"><string name="material" value="Au"/><rgb name="eta" value="1"/></bsdf>"#).unwrap_err();
        assert!(e.contains("not both"), "{e}");
        let e = load(
            r#"<bsdf type="roughconductor"><string name="distribution" value="phong"/></bsdf>"#,
        )
        .unwrap_err();
        assert!(e.contains("beckmann"), "{e}");
        let e = load(r#"<bsdf type="roughdielectric"><float name="int_ior" value="1.2"/><float name="ext_ior" value="1.2"/></bsdf>"#).unwrap_err();
        assert!(e.contains("differ"), "{e}");
        let e = load(r#"<bsdf type="dielectric"><float name="alpha" value="0.1"/></bsdf>"#)
            .unwrap_err();
        assert!(e.contains("unreferenced"), "{e}");
    }

    #[test]
    fn plastics() {
        for t in ["plastic", "roughplastic"] {
            let b = one(&format!(r#"<bsdf type="{t}"/>"#));
            let (eta, internal) = match &b {
                Bsdf::Plastic(p) => (p.eta, p.internal),
                Bsdf::RoughPlastic(p) => {
                    let d = p.distribution;
                    assert_eq!(
                        (d.kind, d.alpha_u),
                        (steradian::bsdf::MicrofacetKind::Beckmann, 0.1)
                    );
                    (p.eta, p.internal)
                }
                b => panic!("{b:?}"),
            };
            assert!((eta - 1.49 / 1.000277).abs() < 1e-6, "{t}: {eta}");
            assert_eq!(internal, steradian::bsdf::InternalScattering::Linear);
        }
        match one(
            r#"<bsdf type="roughplastic"><string name="distribution" value="ggx"/><float name="alpha" value="0.3"/><boolean name="nonlinear" value="true"/><rgb name="diffuse_reflectance" value="0.1, 0.2, 0.3"/><float name="int_ior" value="1.6"/></bsdf>"#,
        ) {
            Bsdf::RoughPlastic(p) => {
                assert_eq!(
                    (p.distribution.kind, p.distribution.alpha_u),
                    (steradian::bsdf::MicrofacetKind::Ggx, 0.3)
                );
                assert_eq!(p.internal, steradian::bsdf::InternalScattering::Nonlinear);
            }
            b => panic!("{b:?}"),
        }
        let e = load(r#"<bsdf type="roughplastic"><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.2"/></bsdf>"#).unwrap_err();
        assert!(e.contains("isotropic") && e.contains("t.xml:1:"), "{e}");
        let e = load(r#"<bsdf type="roughplastic"><float name="int_ior" value="1.0"/><float name="ext_ior" value="1.0"/></bsdf>"#).unwrap_err();
        assert!(e.contains("differ"), "{e}");
        let e =
            load(r#"<bsdf type="plastic"><float name="alpha" value="0.1"/></bsdf>"#).unwrap_err();
        assert!(e.contains("unreferenced"), "{e}");
    }

    #[test]
    fn veach_scene_loads() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/veach.xml");
        let scene = crate::load_file(&path, &[]).unwrap();
        let rough: Vec<f32> = scene
            .scene
            .bsdfs
            .iter()
            .filter_map(|b| match b {
                Bsdf::RoughConductor(c) => {
                    assert_eq!(c.distribution.kind, steradian::bsdf::MicrofacetKind::Ggx);
                    Some(c.distribution.alpha_u)
                }
                _ => None,
            })
            .collect();
        assert_eq!(rough, vec![0.005, 0.02, 0.05, 0.1]);
    }
}
