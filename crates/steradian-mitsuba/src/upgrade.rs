//! Upgrading scenes written for older Mitsuba versions.
//!
//! Mitsuba 3 (`upgrade_tree` in `src/core/xml.cpp`) upgrades documents whose version is
//! **below 2.0.0** (Mitsuba 0.x scenes); 2.x files are read as they are. The upgrade
//! renames every `name` attribute (except on `<default>`) from camelCase to snake_case,
//! renames the `<lookAt>` tag to `<lookat>`, renames ids that start with `_` to
//! `ID<id>__UPGR`, renames `diffuse_reflectance` of `<bsdf type="diffuse">` to
//! `reflectance`, and folds `uoffset`/`voffset`/`uscale`/`vscale` floats into a `to_uv`
//! transform ([`fold_uv`]). The parser applies these rules while it reads the tree.

use glam::Vec3;
use steradian::geometry::Transform;

use crate::error::LoadError;
use crate::properties::{Properties, PropertyValue};

/// Does a file with this version need the upgrade?
pub fn needs_upgrade(version: [u32; 3]) -> bool {
    version < [2, 0, 0]
}

/// Mitsuba's camelCase → snake_case rule: an underscore goes between a lowercase letter
/// and a following uppercase one, and the run of uppercase letters after it is lowercased
/// (`maxDepth` → `max_depth`, `intIOR` → `int_ior`, `sampleCount` → `sample_count`).
pub fn camel_to_snake(name: &str) -> String {
    let mut chars: Vec<char> = name.chars().collect();
    let mut i = 0;
    while i + 1 < chars.len() {
        if chars[i].is_ascii_lowercase() && chars[i + 1].is_ascii_uppercase() {
            chars.insert(i + 1, '_');
            i += 2;
            while i < chars.len() && chars[i].is_ascii_uppercase() {
                chars[i] = chars[i].to_ascii_lowercase();
                i += 1;
            }
        } else {
            i += 1;
        }
    }
    chars.into_iter().collect()
}

/// Reserved ids (leading `_`) in old files are renamed instead of refused.
pub fn upgrade_id(id: &str) -> String {
    if id.starts_with('_') {
        format!("ID{id}__UPGR")
    } else {
        id.to_string()
    }
}

/// Old scenes: `uoffset`/`voffset`/`uscale`/`vscale` floats of one object become its `to_uv`
/// transform (placed where the first of them was).
pub fn fold_uv(props: &mut Properties) -> Result<(), LoadError> {
    let mut get = |n: &str| match props.remove(n) {
        Some((PropertyValue::Float(f), pos)) => Some((f as f32, pos)),
        Some((other, pos)) => {
            // Not a float: put it back untouched.
            let _ = props.insert(n, other, pos);
            None
        }
        None => None,
    };
    let (uo, vo, us, vs) = (get("uoffset"), get("voffset"), get("uscale"), get("vscale"));
    let pos = match [&uo, &vo, &us, &vs].into_iter().flatten().next() {
        Some((_, p)) => p.clone(),
        None => return Ok(()),
    };
    let off = Vec3::new(uo.map_or(0.0, |x| x.0), vo.map_or(0.0, |x| x.0), 0.0);
    let scale = Vec3::new(us.map_or(1.0, |x| x.0), vs.map_or(1.0, |x| x.0), 1.0);
    let mut t = Transform::IDENTITY;
    if off != Vec3::ZERO {
        t = t.then(&Transform::translate(off));
    }
    if scale != Vec3::ONE {
        let s = Transform::scale(scale)
            .map_err(|_| LoadError::at(&pos, "uscale/vscale of zero makes to_uv singular"))?;
        t = t.then(&s);
    }
    props.insert("to_uv", PropertyValue::Transform(t), pos)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn camel_case_becomes_snake_case() {
        assert_eq!(camel_to_snake("maxDepth"), "max_depth");
        assert_eq!(camel_to_snake("sampleCount"), "sample_count");
        assert_eq!(camel_to_snake("intIOR"), "int_ior");
        assert_eq!(camel_to_snake("toWorld"), "to_world");
        assert_eq!(camel_to_snake("fov"), "fov");
        assert_eq!(camel_to_snake("already_snake"), "already_snake");
        assert_eq!(camel_to_snake(""), "");
        assert_eq!(camel_to_snake("aBcDe"), "a_bc_de");
    }

    #[test]
    fn only_pre_2_versions_are_upgraded() {
        assert!(needs_upgrade([0, 6, 0]));
        assert!(needs_upgrade([1, 9, 9]));
        assert!(!needs_upgrade([2, 0, 0]));
        assert!(!needs_upgrade([3, 0, 0]));
        assert_eq!(upgrade_id("_x"), "ID_x__UPGR");
        assert_eq!(upgrade_id("x"), "x");
    }
}
