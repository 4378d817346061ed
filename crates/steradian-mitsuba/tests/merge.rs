//! Purpose: `merge` renders `reference/merge.xml` (meshes Mitsuba joins because they share a
//! BSDF, a sphere and an emitter it passes through, a nested merge, a merge in a shapegroup) as
//! Mitsuba 3.9.1 renders it (its Z-test rule, a 4096-spp `llvm_ad_rgb` reference); leaving out
//! a child of the nested merge fails the test; what Mitsuba refuses on a merge (a `to_world`, any
//! property) and what steradian refuses in one (objects that are not shapes, a shapegroup) are
//! located errors.

mod common;

use std::path::Path;

use common::{reference_scene as data, reference_scene_with, z_test_against};

const SPP: u32 = 64;

#[test]
fn merged_shapes_match_mitsuba() {
    let job =
        steradian_mitsuba::load_file(&data("merge.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    // the light, the floor, a box and the sphere of the merge, two boxes of the nested one;
    // the shapegroup's merge gives the group its two members, placed twice
    assert_eq!(job.scene.shapes.len(), 6);
    let stats = job.scene.accel_stats();
    assert_eq!(stats.instances, 2, "{stats:?}");
    assert!(z_test_against(&job, SPP, "merge", "merge").passes());
}

/// The green box of the nested merge left out: the image changes where it stood.
#[test]
fn a_missing_child_fails() {
    let from = "<rgb name=\"reflectance\" value=\"0.15, 0.6, 0.2\"/>";
    let job = reference_scene_with("merge.xml", from, "<rgb name=\"reflectance\" value=\"0\"/>");
    assert!(!z_test_against(&job, SPP, "merge", "merge, green box black").passes());
}

#[test]
fn what_a_merge_cannot_hold_is_refused() {
    let load = |body: &str| {
        let xml =
            format!("<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n{body}\n</scene>");
        steradian_mitsuba::load_string(&xml, Path::new("m.xml"), Path::new("."), &[])
    };
    let merge = |inner: &str| format!("<shape type=\"merge\">\n{inner}\n</shape>");
    let job = load(&merge("<shape type=\"sphere\"/>\n<shape type=\"sphere\"/>")).unwrap();
    assert_eq!(job.scene.shapes.len(), 2);
    assert_eq!(load(&merge("")).unwrap().scene.shapes.len(), 0);
    for (body, line, needle) in [
        (merge("<transform name=\"to_world\"><translate x=\"1\"/></transform>"), 4, "to_world"),
        (merge("<float name=\"radius\" value=\"1\"/>"), 4, "radius"),
        (merge("<bsdf type=\"diffuse\"/>"), 4, "holds shapes only"),
        (merge("<shape type=\"shapegroup\" id=\"g\"/>"), 4, "scene level"),
        (
            format!(
                "<shape type=\"shapegroup\" id=\"g\">{}</shape>",
                merge("<shape type=\"sphere\"><emitter type=\"area\"/></shape>")
            ),
            4,
            "not supported",
        ),
    ] {
        let e = load(&body).err().unwrap_or_else(|| panic!("accepted: {body}"));
        assert_eq!(e.pos.as_ref().map(|p| p.line), Some(line), "{e}");
        assert!(e.message.contains(needle), "{e}");
    }
}
