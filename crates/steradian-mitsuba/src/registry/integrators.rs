//! Integrator plugins: `path`, `volpath`, `volpathmis`, `direct`, `depth`, `moment`, `aov`,
//! `ptracer`; and Mitsuba's differentiable integrators by the images they render (their
//! primal): `prb` and `prb_projective` as `path`, `prbvolpath` as `volpath`,
//! `direct_projective` as `path` with `max_depth` 2. Their default `max_depth` is 6, as in
//! Mitsuba 3.9.1's Python integrators; the gradient-only parameters of the projective ones
//! (`sppc`, `sppp`, `sppi`, `guiding`, `guiding_proj`, `guiding_rounds`, `project_seed`) are
//! checked and have no effect. `prb_basic` samples BSDFs only, with no light sampling, MIS or
//! Russian roulette (`max_depth` 6 by default; `rr_depth` is read, as Mitsuba's base class
//! reads it, and does nothing): it sees area lights and environments where its rays hit them,
//! and no point, spot or directional light, as in Mitsuba.

use steradian::emitter::LightSelection;
use steradian::integrator::{
    parse_branches, parse_max_depth, parse_rr_scale, Branches, EmitterVisibility, LastVertex,
    NextEvent, NullPaths, DEFAULT_MAX_DEPTH, DEFAULT_RR_DEPTH, DEFAULT_RR_SCALE,
};
use steradian::integrator::{
    AovField, AovIntegrator, DepthIntegrator, DirectIntegrator, Integrator, MomentIntegrator,
    ParticleTracer, PathTracer, VolPathTracer,
};

use super::{at_param, choice, lookup, Plugins};
use crate::error::LoadError;
use crate::tree::PluginNode;

/// `hide_emitters`.
fn visibility(hide: Option<bool>) -> EmitterVisibility {
    match hide {
        None => EmitterVisibility::default(),
        Some(true) => EmitterVisibility::Hidden,
        Some(false) => EmitterVisibility::Visible,
    }
}

fn count(node: &PluginNode, name: &str, default: i64) -> Result<u32, LoadError> {
    let v = node.props.get_int(name)?.unwrap_or(default);
    u32::try_from(v).map_err(|_| {
        LoadError::at(
            node.props.position(name).unwrap_or(&node.pos),
            format!("{}: '{name}' must be >= 0, got {v}", node.desc()),
        )
    })
}

/// steradian's own `light_selection` parameter (default `uniform`, Mitsuba's rule).
fn light_selection(node: &PluginNode) -> Result<LightSelection, LoadError> {
    match node.props.get_string("light_selection")? {
        None => Ok(LightSelection::default()),
        Some(s) => LightSelection::parse(&s).map_err(|m| {
            LoadError::at(
                node.props.position("light_selection").unwrap_or(&node.pos),
                format!("{}: {m}", node.desc()),
            )
        }),
    }
}

/// Builds one integrator from its node.
type BuildIntegrator = fn(&PluginNode) -> Result<Integrator, LoadError>;

/// Every integrator plugin, by Mitsuba `type`.
pub(super) const INTEGRATORS: &Plugins<BuildIntegrator> = &[
    ("path", path),
    ("volpath", volpath),
    ("volpathmis", volpath),
    ("prb", prb),
    ("prb_projective", prb_projective),
    ("prb_basic", prb_basic),
    ("prbvolpath", prbvolpath),
    ("direct_projective", direct_projective),
    ("direct", direct),
    ("depth", depth),
    ("moment", moment),
    ("aov", aov),
    ("ptracer", ptracer),
];

/// `ptracer` (see `steradian::integrator::ParticleTracer`): `max_depth`, `rr_depth`,
/// `hide_emitters`; `samples_per_pass` is accepted (steradian renders pass by pass anyway).
fn ptracer(node: &PluginNode) -> Result<Integrator, LoadError> {
    let p = &node.props;
    let max_depth = match p.get_int("max_depth")? {
        None => None,
        Some(v) => parse_max_depth(v).map_err(at_param(node))?,
    };
    let rr_depth = count(node, "rr_depth", ParticleTracer::DEFAULT_RR_DEPTH as i64)?;
    let hide_emitters =
        p.get_bool("hide_emitters")?.unwrap_or(ParticleTracer::DEFAULT_HIDE_EMITTERS);
    if let Some(n) = p.get_int("samples_per_pass")? {
        if n < 1 {
            return Err(LoadError::at(
                p.position("samples_per_pass").unwrap_or(&node.pos),
                format!("{}: 'samples_per_pass' must be at least 1, got {n}", node.desc()),
            ));
        }
    }
    Ok(Integrator::ParticleTracer(ParticleTracer { max_depth, rr_depth, hide_emitters }))
}

pub(crate) fn build(node: &PluginNode) -> Result<Integrator, LoadError> {
    let integrator = lookup(INTEGRATORS, node)?(node)?;
    node.check_all_used()?;
    Ok(integrator)
}

fn path(node: &PluginNode) -> Result<Integrator, LoadError> {
    path_with(node, DEFAULT_MAX_DEPTH)
}

/// `max_depth` where a scene leaves it unset under Mitsuba's differentiable integrators.
const RB_DEFAULT_MAX_DEPTH: Option<u32> = Some(6);

/// `prb`: path replay backpropagation, whose image is `path`'s except that paths through
/// null surfaces alone count (`NullPaths::Kept`).
fn prb(node: &PluginNode) -> Result<Integrator, LoadError> {
    keep_null_paths(path_with(node, RB_DEFAULT_MAX_DEPTH)?)
}

/// `prb_basic`: `prb` without light sampling, MIS or Russian roulette (module docs).
fn prb_basic(node: &PluginNode) -> Result<Integrator, LoadError> {
    Ok(match keep_null_paths(path_with(node, RB_DEFAULT_MAX_DEPTH)?)? {
        Integrator::Path(p) => Integrator::Path(PathTracer {
            next_event: NextEvent::Skipped,
            rr_depth: u32::MAX,
            last_vertex: LastVertex::Mis,
            ..p
        }),
        other => other,
    })
}

/// `prb_projective`: `prb` with projective sampling for visibility gradients.
fn prb_projective(node: &PluginNode) -> Result<Integrator, LoadError> {
    projective_parameters(node)?;
    keep_null_paths(path_with(node, RB_DEFAULT_MAX_DEPTH)?)
}

/// The differentiable integrators keep the paths that `path` zeroes (Mitsuba 3.9.1: an
/// emitter with a null BSDF seen against nothing shows under `prb`, not under `path`).
fn keep_null_paths(integrator: Integrator) -> Result<Integrator, LoadError> {
    Ok(match integrator {
        Integrator::Path(p) => Integrator::Path(PathTracer { null_paths: NullPaths::Kept, ..p }),
        other => other,
    })
}

/// `direct_projective`: direct illumination (Mitsuba fixes `max_depth` at 2 and `rr_depth` at
/// 2, whatever the scene gives).
fn direct_projective(node: &PluginNode) -> Result<Integrator, LoadError> {
    projective_parameters(node)?;
    let p = &node.props;
    for name in ["max_depth", "rr_depth"] {
        // read, as Mitsuba reads them before overriding them
        p.get_int(name)?;
    }
    Ok(Integrator::Path(PathTracer {
        null_paths: NullPaths::Kept,
        max_depth: Some(2),
        emitters: visibility(p.get_bool("hide_emitters")?),
        light_selection: light_selection(node)?,
        ..PathTracer::default()
    }))
}

/// The projective integrators' gradient-only parameters, checked as Mitsuba checks them.
fn projective_parameters(node: &PluginNode) -> Result<(), LoadError> {
    let p = &node.props;
    for name in ["sppc", "sppp", "sppi", "guiding_rounds"] {
        p.get_int(name)?;
    }
    p.get_bool("guiding_proj")?;
    choice(node, "guiding", (), &[("none", ()), ("grid", ()), ("octree", ())])?;
    choice(node, "project_seed", (), &[("both", ()), ("bsdf", ()), ("emitter", ())])?;
    Ok(())
}

/// `prbvolpath`: `prb` through participating media, whose image is `volpath`'s.
fn prbvolpath(node: &PluginNode) -> Result<Integrator, LoadError> {
    volpath_with(node, RB_DEFAULT_MAX_DEPTH)
}

/// `path` and the integrators that render as it does, with their default `max_depth`.
fn path_with(node: &PluginNode, default_max_depth: Option<u32>) -> Result<Integrator, LoadError> {
    let p = &node.props;
    let max_depth = match p.get_int("max_depth")? {
        None => default_max_depth,
        Some(v) => parse_max_depth(v).map_err(at_param(node))?,
    };
    let rr_depth = count(node, "rr_depth", DEFAULT_RR_DEPTH as i64)?;
    if rr_depth == 0 {
        let pos = p.position("rr_depth").unwrap_or(&node.pos);
        return Err(LoadError::at(pos, format!("{}: 'rr_depth' must be at least 1", node.desc())));
    }
    // steradian's own: the roulette's κ (integrator/path.rs)
    let rr_scale = match p.get_float("rr_scale")? {
        None => DEFAULT_RR_SCALE,
        Some(v) => parse_rr_scale(v).map_err(at_param(node))?,
    };
    // steradian's own: paths continued from each first hit (integrator/path.rs); unset, a
    // pilot chooses (integrator/branching.rs)
    let branches = match p.get_int("branches")? {
        None => Branches::default(),
        Some(v) => parse_branches(v).map_err(at_param(node))?,
    };
    Ok(Integrator::Path(PathTracer {
        max_depth,
        rr_depth,
        rr_scale,
        emitters: visibility(p.get_bool("hide_emitters")?),
        light_selection: light_selection(node)?,
        branches,
        ..PathTracer::default()
    }))
}

/// `volpath` and `volpathmis` (one estimator, `steradian::integrator::VolPathTracer`):
/// `max_depth`, `rr_depth`, `hide_emitters`, and steradian's `light_selection`.
fn volpath(node: &PluginNode) -> Result<Integrator, LoadError> {
    volpath_with(node, DEFAULT_MAX_DEPTH)
}

/// `volpath` and the integrators that render as it does, with their default `max_depth`.
fn volpath_with(
    node: &PluginNode,
    default_max_depth: Option<u32>,
) -> Result<Integrator, LoadError> {
    let p = &node.props;
    let max_depth = match p.get_int("max_depth")? {
        None => default_max_depth,
        Some(v) => parse_max_depth(v).map_err(at_param(node))?,
    };
    let rr_depth = count(node, "rr_depth", DEFAULT_RR_DEPTH as i64)?;
    Ok(Integrator::VolPath(VolPathTracer {
        max_depth,
        rr_depth,
        emitters: visibility(p.get_bool("hide_emitters")?),
        light_selection: light_selection(node)?,
    }))
}

fn direct(node: &PluginNode) -> Result<Integrator, LoadError> {
    let p = &node.props;
    if p.contains("shading_samples")
        && (p.contains("emitter_samples") || p.contains("bsdf_samples"))
    {
        return Err(LoadError::at(
            p.position("shading_samples").unwrap_or(&node.pos),
            format!(
                "{}: give either 'shading_samples' or 'emitter_samples'/'bsdf_samples', not both (Mitsuba refuses both)",
                node.desc()
            ),
        ));
    }
    let shading = count(node, "shading_samples", DirectIntegrator::DEFAULT_SHADING_SAMPLES as i64)?;
    let emitter_samples = count(node, "emitter_samples", shading as i64)?;
    let bsdf_samples = count(node, "bsdf_samples", shading as i64)?;
    Ok(Integrator::Direct(DirectIntegrator {
        emitter_samples,
        bsdf_samples,
        emitters: visibility(node.props.get_bool("hide_emitters")?),
        light_selection: light_selection(node)?,
    }))
}

/// `depth` (no parameters): distance to the first hit (`steradian::integrator::DepthIntegrator`).
fn depth(_: &PluginNode) -> Result<Integrator, LoadError> {
    Ok(Integrator::Depth(DepthIntegrator))
}

/// `moment`: one to eight nested integrators ([`nested_integrators`]).
fn moment(node: &PluginNode) -> Result<Integrator, LoadError> {
    let nested = nested_integrators(node, 1)?;
    Ok(Integrator::Moment(MomentIntegrator { nested }))
}

/// The nested integrators of `moment` or `aov` (at least `min`, at most 8), each named by its
/// XML `name` or, unnamed, `_arg_<i>` (i counting the unnamed ones), as Mitsuba names them. A
/// nested `path` without `branches` traces one path per sample (integrator/moment.rs).
fn nested_integrators(
    node: &PluginNode,
    min: usize,
) -> Result<Vec<(String, Integrator)>, LoadError> {
    let children = node.children_of(crate::tree::ObjectTag::Integrator);
    if children.len() < min {
        return Err(super::at(node)("needs at least one nested <integrator>".into()));
    }
    // each nested integrator writes two layers (moment: mean and m2; aov: RGB and A)
    const MAX_NESTED: usize = steradian::render::MAX_AOV_LAYERS / 2;
    if children.len() > MAX_NESTED {
        return Err(LoadError::at(
            children[MAX_NESTED].pos(),
            format!("{}: at most {MAX_NESTED} nested integrators", node.desc()),
        ));
    }
    let mut unnamed = 0;
    let mut nested = Vec::with_capacity(children.len());
    for c in children {
        if matches!(c.node.plugin_type.as_str(), "moment" | "aov") {
            return Err(LoadError::at(
                c.pos(),
                format!("{} cannot nest another {}", node.desc(), c.node.desc()),
            ));
        }
        if c.node.plugin_type == "ptracer" {
            return Err(LoadError::at(
                c.pos(),
                format!(
                    "{} cannot nest {}: particle tracing splats over the whole film, not per camera sample (Mitsuba refuses it too)",
                    node.desc(),
                    c.node.desc()
                ),
            ));
        }
        let mut integrator = build(&c.node)?;
        if let Integrator::Path(p) = &mut integrator {
            if !c.node.props.contains("branches") {
                p.branches = Branches::Fixed(1);
            }
        }
        let name = match &c.name {
            Some(n) => n.clone(),
            None => {
                unnamed += 1;
                format!("_arg_{}", unnamed - 1)
            }
        };
        nested.push((name, integrator));
    }
    Ok(nested)
}

/// `aov`: the `aovs` list of `name:type` pairs (integrator/aov.rs) and optional nested
/// integrators; at most 16 layers in all.
fn aov(node: &PluginNode) -> Result<Integrator, LoadError> {
    let p = &node.props;
    let pos = p.position("aovs").unwrap_or(&node.pos).clone();
    let list = p.get_string("aovs")?.ok_or_else(|| {
        LoadError::at(&node.pos, format!("{}: missing 'aovs' (name:type, ...)", node.desc()))
    })?;
    let bad = |msg: String| LoadError::at(&pos, format!("{}: {msg}", node.desc()));
    let mut fields = Vec::new();
    for token in list.split(',').map(str::trim).filter(|t| !t.is_empty()) {
        let Some((name, ty)) =
            token.split_once(':').filter(|(n, t)| !n.is_empty() && !t.is_empty())
        else {
            return Err(bad(format!("invalid AOV \"{token}\": expected name:type")));
        };
        let field = match ty {
            "boundary_test" | "duv_dx" | "duv_dy" => {
                return Err(bad(format!("the AOV type \"{ty}\" is not supported by steradian")));
            }
            _ => AovField::parse(ty).ok_or_else(|| {
                bad(format!(
                    "invalid AOV type \"{ty}\" (albedo, depth, position, uv, geo_normal, \
                     sh_normal, dp_du, dp_dv, prim_index or shape_index)"
                ))
            })?,
        };
        fields.push((name.to_string(), field));
    }
    let nested = nested_integrators(node, 0)?;
    let a = AovIntegrator { fields, nested };
    let layers = a.aov_layers().len();
    const MAX_LAYERS: usize = steradian::render::MAX_AOV_LAYERS;
    if layers > MAX_LAYERS {
        return Err(bad(format!(
            "{layers} layers, at most {MAX_LAYERS} (2 per nested integrator)"
        )));
    }
    Ok(Integrator::Aov(a))
}
