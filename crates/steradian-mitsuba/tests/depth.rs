//! Purpose: the `depth` integrator renders `reference/depth.xml` (distances from a near-clip
//! plane at 1.5 m, misses) as Mitsuba 3.9.1 renders it (its Z-test rule); measured from the
//! camera's position instead of the near plane, the image fails; meters and irradiance maps
//! refuse it.

use std::path::{Path, PathBuf};

use steradian::film::{read_exr, z_test};
use steradian::render::{render, PixelQuantity, RenderError, RenderOptions};

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference").join(name)
}

const SPP: u32 = 64;

#[test]
fn depth_scene_matches_mitsuba() {
    let job =
        steradian_mitsuba::load_file(&data("depth.xml"), &[]).unwrap_or_else(|e| panic!("{e}"));
    let out = render(&job, &RenderOptions { spp: Some(SPP), seed: Some(1), ..Default::default() })
        .unwrap();
    let img = out.film().develop();
    let mean = read_exr(&data("depth-ref.exr")).unwrap();
    let var = read_exr(&data("depth-var.exr")).unwrap();
    let z = z_test(&img, SPP, &mean, &var);
    eprintln!(
        "depth @ {SPP} spp: {:.4} of {} pixels pass (min p {:.2e})",
        z.pass_fraction(),
        z.pixels,
        z.min_p
    );
    assert!(z.passes());
    // from the camera's position (t + 1.5 / cos θ on hits): fails
    let mut shifted = img.clone();
    for (px, r) in shifted.data.iter_mut().zip(&mean.data) {
        if *r > 0.0 {
            *px += 1.5;
        }
    }
    let z = z_test(&shifted, SPP, &mean, &var);
    eprintln!("depth from the eye: {:.4} pass", z.pass_fraction());
    assert!(!z.passes());
}

#[test]
fn meters_and_maps_refuse_depth() {
    let xml =
        "<scene version=\"3.0.0\">\n<integrator type=\"depth\"/>\n<sensor type=\"perspective\"/>\n\
               <sensor type=\"radiancemeter\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"1\"/><integer name=\"height\" value=\"1\"/></film></sensor>\n<shape type=\"sphere\"/>\n</scene>";
    let job = steradian_mitsuba::load_string(xml, Path::new("d.xml"), Path::new("."), &[]).unwrap();
    let map = RenderOptions {
        spp: Some(1),
        quantity: PixelQuantity::SurfaceIrradiance,
        ..Default::default()
    };
    assert!(matches!(render(&job, &map), Err(RenderError::NotLight)));
    let meter = RenderOptions { spp: Some(1), sensor: Some(1), ..Default::default() };
    assert!(matches!(render(&job, &meter), Err(RenderError::NotLight)));
    let e = steradian_mitsuba::load_string(
        &xml.replace(
            "type=\"depth\"/>",
            "type=\"depth\"><integer name=\"max_depth\" value=\"2\"/></integrator>",
        ),
        Path::new("d.xml"),
        Path::new("."),
        &[],
    )
    .unwrap_err();
    assert!(e.message.contains("max_depth"), "{e}");
}
