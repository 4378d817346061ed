//! Purpose: `batch` renders `reference/batch.xml` (a perspective with a vertical field of
//! view, a thin lens and an orthographic camera side by side on one film) as Mitsuba 3.9.1
//! does (its Z-test rule and the image mean against a 4096-spp `llvm_ad_rgb` reference);
//! the cameras in another order fail; a width that the cameras do not divide is refused.

mod common;

use std::path::Path;

use common::{image_mean_z, reference_scene as data, z_test_against};

const SPP: u32 = 64;

#[test]
fn batch_matches_mitsuba() {
    let job =
        steradian_mitsuba::load_file(&data("batch.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    assert!(z_test_against(&job, SPP, "batch", "batch").passes());
    let z = image_mean_z(&job, SPP, "batch", 4096);
    eprintln!("batch image mean: z = {z:.2}");
    assert!(z < 4.0);
}

/// Each camera owns its third of the film: with the orthographic view moved to the front,
/// the rule fails.
#[test]
fn cameras_in_another_order_fail() {
    let xml = std::fs::read_to_string(data("batch.xml")).unwrap();
    let start = xml.find("        <sensor type=\"orthographic\">").unwrap();
    let end =
        xml[start..].find("        </sensor>\n").unwrap() + start + "        </sensor>\n".len();
    let ortho = &xml[start..end];
    let first = xml.find("        <sensor type=\"perspective\">").unwrap();
    let moved = format!("{}{ortho}{}{}", &xml[..first], &xml[first..start], &xml[end..]);
    let job = steradian_mitsuba::load_string(&moved, Path::new("moved.xml"), &data(""), &[])
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(!z_test_against(&job, SPP, "batch", "batch (reordered)").passes());
}

#[test]
fn width_must_divide_between_the_cameras() {
    let xml = "<scene version=\"3.0.0\">\n<sensor type=\"batch\">\n\
               <sensor type=\"perspective\"/><sensor type=\"perspective\"/>\n\
               <film type=\"hdrfilm\"><integer name=\"width\" value=\"33\"/></film>\n\
               </sensor>\n</scene>";
    let e =
        steradian_mitsuba::load_string(xml, Path::new("b.xml"), Path::new("."), &[]).unwrap_err();
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(2), "{e}");
    assert!(e.message.contains("multiple of the number of sensors (2)"), "{e}");
}
