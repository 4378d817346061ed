//! Choosing lights by flux changes the noise, never the expectation: a floor lit by a bright
//! and a dim disk light renders to the same mean under both rules.

use std::path::Path;

mod common;

fn scene(rule: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
        <integrator type="path"><integer name="max_depth" value="3"/><string name="light_selection" value="{rule}"/></integrator>
        <sensor type="perspective"><float name="fov" value="60"/>
            <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
            <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/><rfilter type="box"/></film></sensor>
        <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform><bsdf type="diffuse"/></shape>
        <shape type="disk"><transform name="to_world"><scale value="0.2"/><rotate x="1" angle="180"/><translate x="-1" z="1"/></transform>
            <emitter type="area"><rgb name="radiance" value="200"/></emitter></shape>
        <shape type="disk"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="180"/><translate x="1" z="0.5"/></transform>
            <emitter type="area"><rgb name="radiance" value="2"/></emitter></shape>
        </scene>"#
    )
}

fn mean_and_error(rule: &str, seed: u64) -> (f64, f64) {
    common::mean_and_error(&scene(rule), "lights.xml", seed)
}

#[test]
fn power_selection_keeps_the_expectation() {
    let (u, su) = mean_and_error("uniform", 1);
    let (p, sp) = mean_and_error("power", 2);
    let tol = 5.0 * (su * su + sp * sp).sqrt();
    assert!(u > 0.0 && (u - p).abs() <= tol, "uniform {u} ± {su}, power {p} ± {sp}");
}

#[test]
fn unknown_rule_is_an_error() {
    let e = steradian_mitsuba::load_string(
        &scene("brightest"),
        Path::new("lights.xml"),
        Path::new("."),
        &[],
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("lights.xml:2:") && e.contains("uniform") && e.contains("power"), "{e}");
}
