//! The real scenes parse, with spot checks of values.

mod common;

use std::path::Path;

use common::{reference_scene, validation_scene};
use glam::Vec3;
use steradian::testkit::{temp_dir, write_file};
use steradian_mitsuba::{parse_file, parse_string, ObjectTag, PluginNode};

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 1e-5
}

/// Marks everything in the tree as used by reading each property by its own type.
fn read_everything(n: &PluginNode) {
    for (name, _, _) in n.props.iter() {
        n.props.mark_used(name);
    }
    for c in &n.children {
        c.mark_used();
        read_everything(&c.node);
    }
    n.check_all_used().unwrap();
}

#[test]
fn all_scenes_parse() {
    for path in common::all_scenes() {
        let n = path.display();
        let s = parse_file(&path, &[]).unwrap_or_else(|e| panic!("{n}: {e}"));
        assert_eq!(s.tag, ObjectTag::Scene);
        assert!(!s.children.is_empty(), "{n}");
        read_everything(&s);
    }
}

#[test]
fn cornell_values() {
    let s = parse_file(&reference_scene("cornell.xml"), &[]).unwrap();
    let integ = &s.children_of(ObjectTag::Integrator)[0].node;
    assert_eq!(integ.plugin_type, "path");
    assert_eq!(integ.props.get_int("max_depth").unwrap(), Some(8));
    integ.check_all_used().unwrap();

    let sensor = &s.children_of(ObjectTag::Sensor)[0].node;
    assert_eq!(sensor.props.get_float("fov").unwrap(), Some(39.3077));
    assert_eq!(sensor.props.get_string("fov_axis").unwrap().as_deref(), Some("smaller"));
    let cam = sensor.props.get_transform("to_world").unwrap().unwrap();
    assert!(close(cam.point(Vec3::ZERO), Vec3::new(0.0, 0.0, 3.9)));
    assert!(close(cam.vector(Vec3::Z), -Vec3::Z));
    let sampler = &sensor.children_of(ObjectTag::Sampler)[0].node;
    assert_eq!(sampler.props.get_int("sample_count").unwrap(), Some(64), "$spp default");
    let film = &sensor.children_of(ObjectTag::Film)[0].node;
    assert_eq!(film.props.get_int("width").unwrap(), Some(256));
    assert_eq!(film.children_of(ObjectTag::RFilter)[0].node.plugin_type, "gaussian");

    // The light: <scale/><rotate x=1 90/><translate/> → T·R·S maps local (1,1,0) to the
    // corner (0.23, 0.99, 0.2).
    let light = s.ids.get("light").unwrap();
    let m = light.props.get_transform("to_world").unwrap().unwrap();
    assert!(
        close(m.point(Vec3::new(1.0, 1.0, 0.0)), Vec3::new(0.23, 0.99, 0.2)),
        "{}",
        m.point(Vec3::new(1.0, 1.0, 0.0))
    );
    // Normal +z faces down after the rotation.
    assert!(close(m.normal(Vec3::Z).normalize(), -Vec3::Y));
    let em = &light.children_of(ObjectTag::Emitter)[0].node;
    assert!(close(
        em.props.get_spectrum("radiance").unwrap().map(Vec3::from).unwrap(),
        Vec3::new(18.387, 13.9873, 6.75357)
    ));

    // <ref id="white"/> is shared, and the ref keeps its own position.
    let bsdf = &light.children_of(ObjectTag::Bsdf)[0];
    assert_eq!(bsdf.node.id.as_deref(), Some("white"));
    assert!(std::sync::Arc::ptr_eq(&bsdf.node, s.ids.get("white").unwrap()));
    assert_eq!((bsdf.pos().line, bsdf.pos().col), (61, 9));
    assert_eq!((bsdf.node.pos.line, bsdf.node.pos.col), (42, 5));
    assert!(close(
        bsdf.node.props.get_spectrum("reflectance").unwrap().map(Vec3::from).unwrap(),
        Vec3::new(0.885809, 0.698859, 0.666422)
    ));
}

#[test]
fn defines_override_defaults() {
    let d = [("spp".to_string(), "7".to_string()), ("res".to_string(), "32".to_string())];
    let s = parse_file(&reference_scene("cornell.xml"), &d).unwrap();
    let sensor = &s.children_of(ObjectTag::Sensor)[0].node;
    assert_eq!(
        sensor.children_of(ObjectTag::Sampler)[0].node.props.get_int("sample_count").unwrap(),
        Some(7)
    );
    assert_eq!(
        sensor.children_of(ObjectTag::Film)[0].node.props.get_int("height").unwrap(),
        Some(32)
    );
}

#[test]
fn validation_scene_values() {
    let s = parse_file(&validation_scene("point_normal_incidence.xml"), &[]).unwrap();
    let em = &s.children_of(ObjectTag::Emitter)[0].node;
    assert_eq!(em.props.get_point("position").unwrap(), Some(Vec3::new(0.0, 0.0, 2.0)));
    assert_eq!(
        em.props.get_spectrum("intensity").unwrap().map(Vec3::from),
        Some(Vec3::new(10.0, 20.0, 30.0))
    );
    let meter = s.ids.get("meter").unwrap();
    let d = meter.props.get_vector("direction").unwrap().unwrap();
    assert!((d.length() - 1.0).abs() < 1e-6);

    // Row-major matrix: translation in the last column.
    let s = parse_file(&validation_scene("disk_on_axis_irradiance.xml"), &[]).unwrap();
    let disk = &s.children_of(ObjectTag::Shape)[0].node;
    let m = disk.props.get_transform("to_world").unwrap().unwrap();
    assert!(close(m.point(Vec3::ZERO), Vec3::new(0.0, 0.0, 1.5)));
    assert!(close(m.point(Vec3::X), Vec3::new(0.8, 0.0, 1.5)));
    assert_eq!(disk.props.get_bool("flip_normals").unwrap(), Some(true));
    // The irradiance meter is a child of the shape.
    let meter = &s.children_of(ObjectTag::Shape)[1].node.children_of(ObjectTag::Sensor)[0].node;
    assert_eq!(meter.plugin_type, "irradiancemeter");
    assert_eq!(
        meter.children_of(ObjectTag::Sampler)[0].node.props.get_int("sample_count").unwrap(),
        Some(16777216)
    );
}

#[test]
fn veach_lookat_after_scale() {
    let s = parse_file(&reference_scene("veach.xml"), &[]).unwrap();
    let plate = s.ids.get("plate_alpha_0.1").unwrap();
    let m = plate.props.get_transform("to_world").unwrap().unwrap();
    // Origin of the plate is the lookat origin; local +z points at the target.
    let o = Vec3::new(0.0, -0.95, 0.85);
    assert!(close(m.point(Vec3::ZERO), o));
    let dir = (Vec3::new(0.0, 0.0, 1.1624) - o).normalize();
    assert!(close(m.vector(Vec3::Z).normalize(), dir));
    // Scale applied first: local x stretched by 4.
    assert!((m.vector(Vec3::X).length() - 4.0).abs() < 1e-5);
}

fn one_transform(ops: &str) -> steradian::geometry::Transform {
    let xml = format!(
        r#"<scene version="3.0.0"><shape type="sphere"><transform name="to_world">{ops}</transform></shape></scene>"#
    );
    let s = parse_string(&xml, Path::new("."), &[]).unwrap();
    s.children[0].node.props.get_transform("to_world").unwrap().unwrap()
}

#[test]
fn transform_composition_order() {
    // <scale/><rotate/><translate/> = T·R·S
    let m = one_transform(r#"<scale x="2"/><rotate z="1" angle="90"/><translate z="5"/>"#);
    assert!(close(m.point(Vec3::X), Vec3::new(0.0, 2.0, 5.0)));
    // The other order: translate first, then scale: S·T
    let m = one_transform(r#"<translate x="1"/><scale value="3"/>"#);
    assert!(close(m.point(Vec3::ZERO), Vec3::new(3.0, 0.0, 0.0)));
    // value="x y z" forms
    let m = one_transform(r#"<translate value="1, 2, 3"/><scale value="2 3 4"/>"#);
    assert!(close(m.point(Vec3::ONE), Vec3::new(4.0, 9.0, 16.0)));
}

#[test]
fn rotate_is_in_degrees_and_right_handed() {
    let m = one_transform(r#"<rotate x="1" angle="90"/>"#);
    assert!(close(m.vector(Vec3::Y), Vec3::Z));
    let m = one_transform(r#"<rotate value="0 1 0" angle="180"/>"#);
    assert!(close(m.vector(Vec3::X), -Vec3::X));
}

#[test]
fn lookat_and_matrix() {
    let m = one_transform(r#"<lookat origin="1, 2, 3" target="1, 2, 0" up="0, 1, 0"/>"#);
    assert!(close(m.point(Vec3::ZERO), Vec3::new(1.0, 2.0, 3.0)));
    assert!(close(m.vector(Vec3::Z), -Vec3::Z));
    assert!(close(m.vector(Vec3::X), -Vec3::X), "left = up × dir");
    // Missing up: Mitsuba picks one perpendicular to the direction.
    let m = one_transform(r#"<lookat origin="0, 0, 0" target="0, 0, 1"/>"#);
    assert!(m.vector(Vec3::Y).dot(Vec3::Z).abs() < 1e-6);
    // 4x4 and 3x3 matrices, row-major.
    let m = one_transform(r#"<matrix value="1 0 0 7  0 1 0 8  0 0 1 9  0 0 0 1"/>"#);
    assert!(close(m.point(Vec3::ZERO), Vec3::new(7.0, 8.0, 9.0)));
    let m = one_transform(r#"<matrix value="0 -1 0  1 0 0  0 0 1"/>"#);
    assert!(close(m.point(Vec3::X), Vec3::Y));
}

#[test]
fn forward_references_and_named_refs() {
    let xml = r#"<scene version="3.0.0">
        <shape type="sphere"><ref name="bsdf" id="later"/></shape>
        <bsdf type="diffuse" id="later"><texture name="reflectance" type="checkerboard"/></bsdf>
    </scene>"#;
    let s = parse_string(xml, Path::new("."), &[]).unwrap();
    let shape = &s.children[0].node;
    let c = shape.child("bsdf").unwrap();
    assert_eq!(c.node.plugin_type, "diffuse");
    let tex = c.node.child("reflectance").unwrap();
    assert_eq!(tex.node.tag, ObjectTag::Texture);
    assert_eq!(tex.node.name.as_deref(), Some("reflectance"));
}

#[test]
fn includes_merge_children() {
    let dir = temp_dir("includes-merge-children");
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    write_file(
        &dir,
        "sub/mats.xml",
        r#"<scene version="3.0.0"><bsdf type="diffuse" id="m"/></scene>"#,
    );
    let main = write_file(
        &dir,
        "main.xml",
        r#"<scene version="3.0.0"><include filename="sub/mats.xml"/><shape type="sphere"><ref id="m"/></shape></scene>"#,
    );
    let s = parse_file(&main, &[]).unwrap();
    assert_eq!(s.children.len(), 2);
    let b = &s.children[0].node;
    assert!(b.pos.file.ends_with("sub/mats.xml"));
    assert_eq!(s.children[1].node.children[0].node.id.as_deref(), Some("m"));
}

#[test]
fn old_versions_are_upgraded() {
    let xml = r#"<scene version="0.6.0">
        <integrator type="path"><integer name="maxDepth" value="4"/></integrator>
        <sensor type="perspective">
            <transform name="toWorld"><lookAt origin="0 0 1" target="0 0 0" up="0 1 0"/></transform>
            <sampler type="independent"><integer name="sampleCount" value="$spp"/></sampler>
        </sensor>
        <bsdf type="diffuse"><rgb name="diffuseReflectance" value="0.2"/></bsdf>
        <default name="spp" value="3"/>
    </scene>"#;
    // <default> after its use: Mitsuba substitutes in document order, so this is an error...
    assert!(parse_string(xml, Path::new("."), &[]).is_err());
    // ...unless the define is given.
    let s = parse_string(xml, Path::new("."), &[("spp".into(), "9".into())]).unwrap();
    assert_eq!(s.children[0].node.props.get_int("max_depth").unwrap(), Some(4));
    let sensor = &s.children[1].node;
    assert!(sensor.props.get_transform("to_world").unwrap().is_some());
    assert_eq!(sensor.children[0].node.props.get_int("sample_count").unwrap(), Some(9));
    assert_eq!(
        s.children[2].node.props.get_spectrum("reflectance").unwrap().map(Vec3::from),
        Some(Vec3::splat(0.2))
    );
}

#[test]
fn spectra_and_broadcasts() {
    let xml = r#"<scene version="3.0.0">
        <bsdf type="diffuse">
            <spectrum name="reflectance" value="360:0.5, 830:0.5"/>
        </bsdf>
        <emitter type="constant"><spectrum name="radiance" value="2"/></emitter>
        <bsdf type="conductor"><spectrum name="eta" value="0.2"/><float name="k" value="3"/></bsdf>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>
    </scene>"#;
    let s = parse_string(xml, Path::new("."), &[]).unwrap();
    let r = s.children[0].node.props.get_spectrum("reflectance").unwrap().map(Vec3::from).unwrap();
    assert!((r - Vec3::splat(0.5)).abs().max_element() < 1e-3, "{r}");
    // A flat emitter spectrum is the equal-energy white in sRGB.
    let e = s.children[1].node.props.get_spectrum("radiance").unwrap().map(Vec3::from).unwrap();
    assert!(close(e, 2.0 * Vec3::new(1.204794, 0.948292, 0.908916)), "{e}");
    assert_eq!(
        s.children[2].node.props.get_spectrum("eta").unwrap().map(Vec3::from),
        Some(Vec3::splat(0.2))
    );
    assert_eq!(
        s.children[2].node.props.get_spectrum("k").unwrap().map(Vec3::from),
        Some(Vec3::splat(3.0))
    );
    assert_eq!(
        s.children[3].node.props.get_spectrum("reflectance").unwrap().map(Vec3::from),
        Some(Vec3::splat(0.5))
    );
}

/// The profile-guided build's training scene (`benches/pgo/training.xml`, rendered by
/// `scripts/build-pgo.sh`) loads, holds what the script says it adds to the training set
/// (smooth, rough and thin glass, smooth and GGX rough conductors, a spherical area light, a
/// spot light), and renders finite, non-black light. Without this test a loader change that
/// rejected the scene would only show when the speed benchmark builds.
#[test]
fn pgo_training_scene_renders() {
    use steradian::emitter::Emitter;
    use steradian::render::{render, RenderOptions};
    use steradian::shape::Shape;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../benches/pgo/training.xml");
    let defines = [("res".to_string(), "32".to_string())];
    let scene = steradian_mitsuba::load_file(&path, &defines).unwrap_or_else(|e| panic!("{e}"));
    let bsdfs: Vec<String> = scene.scene.bsdfs.iter().map(|b| format!("{b:?}")).collect();
    for kind in ["Dielectric", "RoughDielectric", "ThinDielectric", "Conductor", "RoughConductor"] {
        assert!(bsdfs.iter().any(|b| b.starts_with(kind)), "no {kind} BSDF in {bsdfs:?}");
    }
    assert!(
        bsdfs.iter().any(|b| b.starts_with("RoughConductor") && b.contains("Ggx")),
        "no GGX rough conductor"
    );
    let sphere_light = scene.scene.emitters.iter().any(|e| matches!(e, Emitter::Area(a) if matches!(scene.scene.shapes[a.shape as usize], Shape::Sphere(_))));
    assert!(sphere_light, "no spherical area light");
    assert!(scene.scene.emitters.iter().any(|e| matches!(e, Emitter::Spot(_))), "no spot light");
    let out = render(&scene, &RenderOptions { spp: Some(2), seed: Some(1), ..Default::default() })
        .unwrap();
    assert_eq!(out.dropped_samples, 0);
    let m = out.film().develop().channel_means();
    assert!(m.iter().all(|x| x.is_finite() && *x > 1e-3), "channel means {m:?}");
}
