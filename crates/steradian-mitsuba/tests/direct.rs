//! Purpose: `direct` with several light samples per camera ray (`emitter_samples`) renders the
//! same image as with one, for delta lights too: a point light over a diffuse floor (where
//! Mitsuba 3.9.1 counts each of the n samples in full, an image n times too bright, which
//! steradian does not copy) and a rectangle light, each image mean within its standard error
//! of the one-sample image's, and the point-lit one against the closed form ρ/π·I·cos θ/r².
//! Such a scene loads with a warning that says how Mitsuba's image differs; one without a
//! delta light, or with one light sample, loads without it.

mod common;

fn scene(emitter_samples: u32, light: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <integrator type="direct"><integer name="emitter_samples" value="{emitter_samples}"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="20"/>
        <transform name="to_world"><lookat origin="0, 4, 0" target="0, 0, 0" up="0, 0, -1"/></transform>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/><rfilter type="box"/></film>
    </sensor>
    {light}
    <shape type="rectangle">
        <transform name="to_world"><scale value="10"/><rotate x="1" angle="-90"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>
    </shape>
</scene>"#
    )
}

const POINT: &str = r#"<emitter type="point"><point name="position" x="0" y="1" z="0"/><rgb name="intensity" value="10"/></emitter>"#;
const AREA: &str = r#"<shape type="rectangle"><transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate y="1"/></transform>
        <emitter type="area"><rgb name="radiance" value="10"/></emitter></shape>"#;

#[test]
fn several_light_samples_render_the_image_of_one() {
    for (name, light) in [("point", POINT), ("rectangle", AREA)] {
        let (m1, se1) = common::mean_and_error(&scene(1, light), "direct.xml", 3);
        for n in [2, 4] {
            let (m, se) = common::mean_and_error(&scene(n, light), "direct.xml", 4);
            let z = (m - m1) / (se * se + se1 * se1).sqrt();
            eprintln!("{name}, emitter_samples {n}: {m:.5} ± {se:.5} against {m1:.5} ± {se1:.5}, z {z:.2}");
            assert!(z.abs() < 4.0, "{name}, emitter_samples = {n}: z = {z:.2}");
        }
    }
    // the point-lit floor against the closed form: the mean over the view of ρ/π·I·cos θ/r²,
    // the floor seen square-on through a 20° view from 4 m (a midpoint rule on 512 × 512
    // points, accurate to about 1e-6 relative, far below the standard error)
    let (m, se) = common::mean_and_error(&scene(4, POINT), "direct.xml", 5);
    let half = 4.0 * (10f64.to_radians()).tan();
    let k = 512;
    let mut sum = 0.0;
    for j in 0..k {
        for i in 0..k {
            let at = |n: usize| half * (2.0 * (n as f64 + 0.5) / k as f64 - 1.0);
            let r2 = at(i) * at(i) + at(j) * at(j) + 1.0;
            sum += 0.5 / std::f64::consts::PI * 10.0 / r2 * (1.0 / r2.sqrt());
        }
    }
    let expected = sum / (k * k) as f64;
    let z = (m - expected) / se;
    eprintln!(
        "point light, emitter_samples 4: {m:.5} ± {se:.5}, closed form {expected:.5}, z {z:.2}"
    );
    assert!(z.abs() < 4.0, "{m} against {expected}: z = {z:.2}");
}

#[test]
fn several_samples_of_a_delta_light_warn_of_mitsubas_image() {
    let load = |xml: &str| common::load_scene(xml, "d.xml");
    let warned = load(&scene(3, POINT));
    assert_eq!(warned.warnings.len(), 1, "{:?}", warned.warnings);
    let w = &warned.warnings[0];
    assert!(w.contains("d.xml:2:") && w.contains("3 times too bright"), "{w}");
    assert!(load(&scene(1, POINT)).warnings.is_empty());
    assert!(load(&scene(3, AREA)).warnings.is_empty());
}
