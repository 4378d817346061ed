//! A path's last vertex (`path`, "The last vertex"): where light sampling alone is bounded,
//! steradian leaves out the BSDF sample that MIS would add there. That changes the noise,
//! never the expectation: at `max_depth` 2 and 3, with sphere and rectangle lights over
//! diffuse and glossy surfaces, the image's mean equals the always-MIS estimator's within
//! their standard errors, and the two estimators do differ (the shortcut is taken). The
//! emitters are hidden from the camera so that the image is reflected light only.

use std::path::Path;

use glam::Vec3;
use steradian::integrator::{Integrator, LastVertex};
use steradian::render::Job;

mod common;
use common::SENSOR;

fn scene_xml(max_depth: u32, lights: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
        <integrator type="path"><integer name="max_depth" value="{max_depth}"/><integer name="branches" value="2"/>
            <boolean name="hide_emitters" value="true"/></integrator>
        {SENSOR}
        <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform><bsdf type="diffuse"/></shape>
        <shape type="rectangle"><transform name="to_world"><scale value="3"/><rotate y="1" angle="80"/><translate x="-2"/></transform>
            <bsdf type="roughconductor"><float name="alpha" value="0.2"/></bsdf></shape>
        <shape type="rectangle"><transform name="to_world"><scale value="3"/><rotate y="1" angle="-80"/><translate x="2"/></transform>
            <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.5, 0.2"/></bsdf></bsdf></shape>
        {lights}
        </scene>"#
    )
}

/// A small bright sphere, a large dim one close over the floor (from below it fills 2 sr, so
/// its light samples and the cosine-weighted BSDF samples share its light about equally
/// under MIS: leaving out either half, or counting both fully, would show) and a rectangle.
const SPHERES: &str = r#"
        <shape type="sphere"><point name="center" x="0.3" y="0.2" z="1.2"/><float name="radius" value="0.9"/>
            <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
        <shape type="sphere"><point name="center" x="-1" y="0.5" z="1"/><float name="radius" value="0.1"/>
            <emitter type="area"><rgb name="radiance" value="30"/></emitter></shape>
        <shape type="sphere"><point name="center" x="1" y="-0.5" z="0.8"/><float name="radius" value="0.4"/>
            <emitter type="area"><rgb name="radiance" value="3"/></emitter></shape>
        <shape type="rectangle"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="180"/><translate y="1" z="1.5"/></transform>
            <emitter type="area"><rgb name="radiance" value="5"/></emitter></shape>"#;

fn load(xml: &str) -> Job {
    steradian_mitsuba::load_string(xml, Path::new("last_vertex.xml"), Path::new("."), &[])
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The image mean (red channel) and its standard error with the given last-vertex estimator.
fn mean_and_error(mut s: Job, last_vertex: LastVertex, seed: u64) -> (f64, f64) {
    let Integrator::Path(p) = &mut s.integrator else { panic!("a path integrator") };
    p.last_vertex = last_vertex;
    common::scene_mean_and_error(&s, seed)
}

#[test]
fn light_only_last_vertex_keeps_the_expectation() {
    for max_depth in [2, 3] {
        let xml = scene_xml(max_depth, SPHERES);
        let (short, s_short) = mean_and_error(load(&xml), LastVertex::LightOnlyWhereBounded, 1);
        let (mis, s_mis) = mean_and_error(load(&xml), LastVertex::Mis, 2);
        let tol = 5.0 * (s_short * s_short + s_mis * s_mis).sqrt();
        assert!(
            mis > 0.0 && (short - mis).abs() <= tol,
            "max_depth {max_depth}: light only {short} ± {s_short}, MIS {mis} ± {s_mis}"
        );
        // the same seed: the estimators must differ, or the shortcut was never taken
        let (same_seed, _) = mean_and_error(load(&xml), LastVertex::Mis, 1);
        assert_ne!(
            short, same_seed,
            "max_depth {max_depth}: the last vertex never skipped its BSDF sample"
        );
    }
}

#[test]
fn light_sampling_suffices_only_where_bounded() {
    let s = load(&scene_xml(3, SPHERES)).scene;
    let diffuse = &s.bsdfs[s.bindings[0].bsdf as usize];
    let glossy = &s.bsdfs[s.bindings[1].bsdf as usize];
    let twosided = &s.bsdfs[s.bindings[2].bsdf as usize];
    let open = Vec3::new(0.0, -1.5, 0.0); // > √area from the rectangle light, outside the spheres
    assert!(s.light_sampling_suffices(diffuse, open) && s.light_sampling_suffices(twosided, open));
    // glossy: MIS's BSDF sample matters
    assert!(!s.light_sampling_suffices(glossy, open));
    // inside a sphere light, which is then sampled by area
    assert!(!s.light_sampling_suffices(diffuse, Vec3::new(0.3, 0.2, 1.0)));
    // nearer the rectangle light than √area (0.6 m)
    assert!(!s.light_sampling_suffices(diffuse, Vec3::new(0.0, 1.0, 1.2)));

    // a disk light is sampled by area everywhere: always MIS
    let disk = r#"<shape type="disk"><transform name="to_world"><translate z="2"/></transform><emitter type="area"/></shape>"#;
    let s = load(&scene_xml(3, &format!("{SPHERES}{disk}"))).scene;
    assert!(!s.light_sampling_suffices(&s.bsdfs[s.bindings[0].bsdf as usize], open));
    // an environment: always MIS
    let s = load(&scene_xml(3, r#"<emitter type="constant"/>"#)).scene;
    assert!(!s.light_sampling_suffices(&s.bsdfs[s.bindings[0].bsdf as usize], open));
    // delta lights only: no ray can find light, at any BSDF
    let s = load(&scene_xml(
        3,
        r#"<emitter type="point"><point name="position" x="0" y="0" z="1"/></emitter>"#,
    ))
    .scene;
    assert!(s.light_sampling_suffices(&s.bsdfs[s.bindings[1].bsdf as usize], open));
}
