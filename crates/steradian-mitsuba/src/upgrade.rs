//! Upgrading scenes written for older Mitsuba versions.
//!
//! Mitsuba 3 (`upgrade_tree` in `src/core/xml.cpp`) upgrades documents whose version is
//! **below 2.0.0** (Mitsuba 0.x scenes); 2.x files are read as they are. The upgrade
//! renames every `name` attribute (except on `<default>`) from camelCase to snake_case,
//! renames the `<lookAt>` tag to `<lookat>`, renames ids that start with `_` to
//! `ID<id>__UPGR`, renames `diffuse_reflectance` of `<bsdf type="diffuse">` to
//! `reflectance`, and folds `uoffset`/`voffset`/`uscale`/`vscale` floats into a `to_uv`
//! transform. The parser applies these rules while it reads the tree.

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
