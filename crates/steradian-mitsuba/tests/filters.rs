//! Purpose: the reconstruction filters with negative lobes (`mitchell`, `catmullrom`, `lanczos`)
//! render `reference/filters.xml` (a directly seen light's edges, a checkerboard) as Mitsuba
//! 3.9.1 renders it (its Z-test rule, references at 4096 spp from `llvm_ad_rgb`, which
//! evaluates the filters exactly), and the test tells the filters apart: the `gaussian` image
//! fails against the `mitchell` reference.

mod common;

use common::{reference_scene as data, z_test_against};
use steradian::film::ZTest;

const SPP: u32 = 64;

/// The scene rendered with `filter`, Z-tested against the reference of `reference`.
fn z(filter: &str, reference: &str) -> ZTest {
    let defines = [("filter".to_string(), filter.to_string())];
    let job = steradian_mitsuba::load_file(&data("filters.xml"), &defines)
        .unwrap_or_else(|e| panic!("{e}"));
    let what = format!("{filter} vs Mitsuba's {reference}");
    z_test_against(&job, SPP, &format!("filters-{reference}"), &what)
}

#[test]
fn mitchell_matches_mitsuba() {
    assert!(z("mitchell", "mitchell").passes());
}

#[test]
fn catmullrom_matches_mitsuba() {
    assert!(z("catmullrom", "catmullrom").passes());
}

#[test]
fn lanczos_matches_mitsuba() {
    assert!(z("lanczos", "lanczos").passes());
}

#[test]
fn another_filter_fails_the_test() {
    assert!(!z("gaussian", "mitchell").passes());
}

#[test]
fn filter_parameters_are_read_and_checked() {
    let load = |rfilter: &str| {
        let xml = format!(
            "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<sensor type=\"perspective\">\n\
             <film type=\"hdrfilm\">\n{rfilter}\n</film>\n</sensor>\n</scene>"
        );
        steradian_mitsuba::load_string(
            &xml,
            std::path::Path::new("f.xml"),
            std::path::Path::new("."),
            &[],
        )
    };
    load(r#"<rfilter type="mitchell"><float name="B" value="0.5"/><float name="C" value="0.25"/></rfilter>"#).unwrap();
    load(r#"<rfilter type="lanczos"><integer name="lobes" value="2"/></rfilter>"#).unwrap();
    for (rfilter, needle) in [
        (r#"<rfilter type="lanczos"><integer name="lobes" value="0"/></rfilter>"#, "lobes"),
        (r#"<rfilter type="catmullrom"><float name="B" value="0.5"/></rfilter>"#, "B"),
        (r#"<rfilter type="mitchell"><float name="b" value="0.5"/></rfilter>"#, "b"),
    ] {
        let e = load(rfilter).err().unwrap_or_else(|| panic!("{rfilter} was accepted"));
        assert_eq!(e.pos.as_ref().map(|p| p.line), Some(5), "{e}");
        assert!(e.message.contains(needle), "{e}");
    }
}
