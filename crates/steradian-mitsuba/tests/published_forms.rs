//! Forms found in published Mitsuba 3 scenes (Mitsuba's own test scenes, Sionna's, the
//! Blender add-on's exports, Mitsuba 0.6-era films) that Mitsuba 3.9.1 loads: each loads in
//! steradian with the meaning Mitsuba gives it.

use std::path::Path;

use steradian_mitsuba::{load_string, LoadError};

fn load(xml: &str) -> Result<steradian::render::Job, LoadError> {
    load_string(xml, Path::new("s.xml"), Path::new("."), &[])
}

const BODY: &str =
    "<integrator type=\"path\"/>\n<shape type=\"sphere\"/>\n<emitter type=\"constant\"/>";

/// XML forbids `--` inside a comment and a comment ending in `-`; Mitsuba's parser accepts
/// both (Sionna's scenes open with `<!--` / `-- SPDX-License-Identifier…` / `-->`). Errors
/// after such comments keep their file positions.
#[test]
fn comments_with_double_dashes() {
    let xml = format!(
        "<!--\n-- SPDX-License-Identifier: Apache-2.0\n-->\n<scene version=\"3.0.0\">\n\
         <!-- a -- b --->\n{BODY}\n<sensor type=\"perspective\"/>\n</scene>"
    );
    load(&xml).unwrap_or_else(|e| panic!("{e}"));
    let bad = "<!-- x -- y -->\n<scene version=\"3.0.0\">\n<!-- -- -->  <shape type=\"spheer\"/>\n</scene>";
    let e = load(bad).unwrap_err().to_string();
    assert!(e.starts_with("s.xml:3:14:") && e.contains("spheer"), "{e}");
    // a comment that never ends is still malformed
    let e = load("<scene version=\"3.0.0\"><!-- -- </scene>").unwrap_err().to_string();
    assert!(e.contains("malformed XML"), "{e}");
}

/// Mitsuba 0.6's `banner` flag on `hdrfilm`, which Mitsuba 3.9.1 accepts and ignores; other
/// unknown film properties stay errors.
#[test]
fn film_banner() {
    let film = |p: &str| {
        format!(
            "<scene version=\"3.0.0\">\n{BODY}\n<sensor type=\"perspective\"><film type=\"hdrfilm\">{p}</film></sensor>\n</scene>"
        )
    };
    load(&film("<boolean name=\"banner\" value=\"false\"/>")).unwrap_or_else(|e| panic!("{e}"));
    let e = load(&film("<boolean name=\"attachLog\" value=\"false\"/>")).unwrap_err().to_string();
    assert!(e.contains("attachLog"), "{e}");
}

/// `jitter = false` (the Blender add-on writes it) is accepted with a located warning:
/// steradian's samples are randomised whatever the sampler type.
#[test]
fn samplers_without_jitter() {
    for t in ["stratified", "multijitter", "orthogonal"] {
        let xml = format!(
            "<scene version=\"3.0.0\">\n{BODY}\n<sensor type=\"perspective\"><sampler type=\"{t}\">\n\
             <boolean name=\"jitter\" value=\"false\"/></sampler></sensor>\n</scene>"
        );
        let job = load(&xml).unwrap_or_else(|e| panic!("{t}: {e}"));
        assert!(
            job.warnings
                .iter()
                .any(|w| w.starts_with("s.xml:6:1:") && w.contains("jitter = false is ignored")),
            "{t}: {:?}",
            job.warnings
        );
    }
}

/// A sampler, film and filter declared at the scene level with an id and referenced from the
/// sensor are the sensor's; one that no sensor references is built (its errors show) and
/// unused, as in Mitsuba.
#[test]
fn scene_level_sampler_and_film() {
    let xml = format!(
        "<scene version=\"3.0.0\">\n{BODY}\n\
         <sampler type=\"independent\" id=\"s\"><integer name=\"sample_count\" value=\"7\"/></sampler>\n\
         <film type=\"hdrfilm\" id=\"f\"><integer name=\"width\" value=\"12\"/><integer name=\"height\" value=\"10\"/></film>\n\
         <rfilter type=\"tent\" id=\"unused\"/>\n\
         <sensor type=\"perspective\"><ref id=\"s\"/><ref id=\"f\"/></sensor>\n</scene>"
    );
    let job = load(&xml).unwrap_or_else(|e| panic!("{e}"));
    let sensor = &job.scene.sensors[0];
    assert_eq!((sensor.film.width, sensor.film.height, sensor.sampler.sample_count), (12, 10, 7));
    let bad = format!(
        "<scene version=\"3.0.0\">\n{BODY}\n<sampler type=\"independent\"><integer name=\"sample_count\" value=\"0\"/></sampler>\n\
         <sensor type=\"perspective\"/>\n</scene>"
    );
    let e = load(&bad).unwrap_err().to_string();
    assert!(e.starts_with("s.xml:5:") && e.contains("sample_count"), "{e}");
}
