//! The field of view shared by the pinhole-like sensors (`perspective`, `thinlens`) and the
//! `projector` emitter: `fov` in degrees measured along `fov_axis` (`x`, `y`, `diagonal`,
//! `smaller`, `larger`; default `x`), or `focal_length` of a 35 mm camera (`"50mm"`, the
//! default when neither is given). Giving both is an error, as is `fov_axis` without `fov`.
//! It sits apart from the sensor plugins so that emitters can use it without importing them.

use steradian::sensor::{FieldOfView, FovAxis};

use crate::error::LoadError;
use crate::tree::PluginNode;

/// `fov` (with `fov_axis`) or `focal_length` of a projective camera, or of the `projector`
/// emitter that shares its parameters.
pub(crate) fn field_of_view(node: &PluginNode) -> Result<FieldOfView, LoadError> {
    let p = &node.props;
    Ok(match (p.get_float("fov")?, p.get_string("focal_length")?) {
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
                None => FovAxis::default(),
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
                    None => FieldOfView::DEFAULT_FOCAL_LENGTH,
                },
            }
        }
    })
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
