//! BSDF plugins: `diffuse`, `twosided`.

use std::sync::Arc;

use steradian::bsdf::{Bsdf, Diffuse, TwoSided};
use steradian::Spectrum;

use super::unknown_type;
use crate::error::LoadError;
use crate::xml::{ObjectTag, PluginNode};

const KNOWN: &[&str] = &["diffuse", "twosided"];

/// Builds a BSDF node (not cached: use `Builder::bsdf_index` for scene BSDFs).
pub(crate) fn build(node: &Arc<PluginNode>) -> Result<Bsdf, LoadError> {
    let p = &node.props;
    let bsdf = match node.plugin_type.as_str() {
        "diffuse" => {
            let reflectance = p.get_spectrum("reflectance")?.unwrap_or(Spectrum::splat(0.5));
            Bsdf::Diffuse(Diffuse::new(reflectance.into()))
        }
        "twosided" => {
            let children = node.children_of(ObjectTag::Bsdf);
            let built: Vec<Bsdf> = children.iter().map(|c| build(&c.node)).collect::<Result<_, _>>()?;
            if built.iter().any(|b| matches!(b, Bsdf::TwoSided(_))) {
                return Err(LoadError::at(&node.pos, "twosided: a nested twosided BSDF makes no sense"));
            }
            match <[Bsdf; 1]>::try_from(built.clone()) {
                Ok([one]) => Bsdf::TwoSided(TwoSided::new(one.clone(), one)),
                Err(_) => match <[Bsdf; 2]>::try_from(built) {
                    Ok([front, back]) => Bsdf::TwoSided(TwoSided::new(front, back)),
                    Err(v) => {
                        return Err(LoadError::at(
                            &node.pos,
                            format!("twosided: expects one or two nested BSDFs, got {}", v.len()),
                        ))
                    }
                },
            }
        }
        _ => return Err(unknown_type(node, KNOWN)),
    };
    node.check_all_used()?;
    Ok(bsdf)
}
