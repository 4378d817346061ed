//! `<spectrum type="…">` plugins as property values: `d65`, `srgb` and `uniform` give what
//! Mitsuba 3.9.1's RGB variants render for them, `irregular` and `regular` what the same list
//! written inline gives, and `blackbody` and malformed lists are located errors.

use std::path::Path;

use steradian::render::{render, RenderOptions};
use steradian_mitsuba::{load_string, LoadError};

/// The scene: the camera sees only the emitting rectangle, whose `radiance` is `spectrum`.
fn scene(spectrum: &str) -> String {
    format!(
        "<scene version=\"3.0.0\">\n<integrator type=\"path\"><integer name=\"max_depth\" value=\"1\"/></integrator>\n\
         <sensor type=\"perspective\"><float name=\"fov\" value=\"10\"/>\n\
         <transform name=\"to_world\"><lookat origin=\"0, 0, 3\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>\n\
         <film type=\"hdrfilm\"><integer name=\"width\" value=\"2\"/><integer name=\"height\" value=\"2\"/><rfilter type=\"box\"/></film></sensor>\n\
         <shape type=\"rectangle\"><emitter type=\"area\">\n{spectrum}\n</emitter></shape>\n</scene>"
    )
}

fn load(spectrum: &str) -> Result<steradian::render::Job, LoadError> {
    load_string(&scene(spectrum), Path::new("s.xml"), Path::new("."), &[])
}

/// The radiance the camera sees (every pixel sees the emitter only).
fn seen(spectrum: &str) -> [f32; 3] {
    let job = load(spectrum).unwrap_or_else(|e| panic!("{spectrum}: {e}"));
    let out = render(&job, &RenderOptions { spp: Some(4), ..Default::default() }).unwrap();
    let img = out.film().develop();
    [img.data[0], img.data[1], img.data[2]]
}

fn close(a: [f32; 3], b: [f32; 3]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-5 * y.abs().max(1.0))
}

#[test]
fn typed_spectra_give_mitsubas_rgb_values() {
    // Mitsuba 3.9.1 scalar_rgb renders these three as (1, 1, 1), the colour, and (2, 2, 2)
    let d65 = seen("<spectrum type=\"d65\" name=\"radiance\"/>");
    assert!(close(d65, [1.0; 3]), "{d65:?}");
    let scaled = seen(
        "<spectrum type=\"d65\" name=\"radiance\"><float name=\"scale\" value=\"3\"/></spectrum>",
    );
    assert!(close(scaled, [3.0; 3]), "{scaled:?}");
    let srgb = seen("<spectrum type=\"srgb\" name=\"radiance\"><rgb name=\"color\" value=\"0.8, 0.4, 0.2\"/></spectrum>");
    assert!(close(srgb, [0.8, 0.4, 0.2]), "{srgb:?}");
    let uniform = seen("<spectrum type=\"uniform\" name=\"radiance\"><float name=\"value\" value=\"2\"/></spectrum>");
    assert!(close(uniform, [2.0; 3]), "{uniform:?}");
    // lists convert as the same list written inline
    let inline = seen("<spectrum name=\"radiance\" value=\"400:1, 550:2, 700:3\"/>");
    let irregular = seen(
        "<spectrum type=\"irregular\" name=\"radiance\"><string name=\"wavelengths\" value=\"400, 550, 700\"/>\
         <string name=\"values\" value=\"1, 2, 3\"/></spectrum>",
    );
    let regular = seen(
        "<spectrum type=\"regular\" name=\"radiance\"><float name=\"wavelength_min\" value=\"400\"/>\
         <float name=\"wavelength_max\" value=\"700\"/><string name=\"values\" value=\"1 2 3\"/></spectrum>",
    );
    assert!(
        close(irregular, inline) && close(regular, inline),
        "{inline:?} {irregular:?} {regular:?}"
    );
    assert!(inline[0] > inline[2], "a red-heavy spectrum: {inline:?}");
}

#[test]
fn unsupported_and_malformed_spectra_are_located_errors() {
    for (body, needle) in [
        ("<spectrum type=\"blackbody\" name=\"radiance\"><float name=\"temperature\" value=\"3000\"/></spectrum>", "'blackbody' is not supported"),
        ("<spectrum type=\"srgb\" name=\"radiance\"/>", "missing parameter 'color'"),
        ("<spectrum type=\"d65\" name=\"radiance\"><float name=\"value\" value=\"3\"/></spectrum>", "unreferenced property 'value'"),
        ("<spectrum type=\"irregular\" name=\"radiance\"><string name=\"wavelengths\" value=\"500, 400\"/><string name=\"values\" value=\"1, 2\"/></spectrum>", "wavelengths must increase"),
        ("<spectrum type=\"irregular\" name=\"radiance\"><string name=\"wavelengths\" value=\"400, 500\"/><string name=\"values\" value=\"1, x\"/></spectrum>", "not a number"),
    ] {
        let Err(e) = load(body) else { panic!("{body} was accepted") };
        assert!(e.message.contains(needle), "{body}: {e}");
        assert!(e.pos.as_ref().is_some_and(|p| p.line == 7), "{body}: {e}");
    }
}

/// `<spectrum filename=…>` reads Mitsuba's spectrum files (a "wavelength value" line per
/// sample, `#` comments, blank lines) and gives what the same list written inline gives;
/// a malformed line is an error naming the file and line.
#[test]
fn spectrum_files_give_the_inline_lists_value() {
    use steradian::testkit::{temp_dir, write_file};
    let dir = temp_dir("typed-spectra-spd");
    write_file(&dir, "lamp.spd", "# a lamp\n400 1\n\n550   2\n700\t3\n");
    write_file(&dir, "bad.spd", "400 1\n550 two\n");
    let from = |file: &str| {
        let xml = scene(&format!("<spectrum name=\"radiance\" filename=\"{file}\"/>"));
        load_string(&xml, Path::new("s.xml"), &dir, &[])
    };
    let job = from("lamp.spd").unwrap_or_else(|e| panic!("{e}"));
    let out = render(&job, &RenderOptions { spp: Some(4), ..Default::default() }).unwrap();
    let img = out.film().develop();
    let file = [img.data[0], img.data[1], img.data[2]];
    let inline = seen("<spectrum name=\"radiance\" value=\"400:1, 550:2, 700:3\"/>");
    assert_eq!(file, inline);
    let e = from("bad.spd").unwrap_err().to_string();
    assert!(e.contains("bad.spd:2:") && e.contains("could not parse a number"), "{e}");
    let e = from("missing.spd").unwrap_err().to_string();
    assert!(e.contains("cannot read spectrum file") && e.contains("missing.spd"), "{e}");
}
