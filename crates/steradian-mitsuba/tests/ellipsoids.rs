//! Purpose: `ellipsoids` and `ellipsoidsmesh` render `reference/ellipsoids.xml` (an analytic
//! cloud from a binary PLY file, turned and scaled by `to_world`; a Gaussian-splatting ASCII
//! file as triangle shells with adaptive extents) as Mitsuba 3.9.1 renders it, with each of
//! its three shell templates and with a texture on the shells (its Z-test rule against
//! 4096-spp `llvm_ad_rgb` references); a wrong extent or another template fails the rule; what Mitsuba refuses on these shapes and
//! malformed files are located errors.

mod common;

use std::path::Path;

use common::{reference_scene as data, reference_scene_with, z_test_against};

const SPP: u32 = 64;

fn load(shell: &str) -> steradian::render::Job {
    steradian_mitsuba::load_file(
        &data("ellipsoids.xml"),
        &[("shell".to_string(), shell.to_string())],
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn ellipsoid_clouds_match_mitsuba_with_every_shell() {
    for (shell, reference) in [
        ("ico_sphere", "ellipsoids"),
        ("box", "ellipsoids-box"),
        ("uv_sphere", "ellipsoids-uv_sphere"),
    ] {
        let job = load(shell);
        let z = z_test_against(&job, SPP, reference, &format!("ellipsoids, {shell} shells"));
        assert!(z.passes(), "{shell}: {:.4} of the pixels pass", z.pass_fraction());
        let mean_z = common::image_mean_z(&job, SPP, reference, 4096);
        eprintln!("ellipsoids, {shell} shells, image mean: z = {mean_z:.2}");
        assert!(mean_z < 4.0, "{shell}: image mean off by {mean_z:.2} standard errors");
    }
}

/// The test sees the geometry: the analytic cloud 10 % larger, or the splats' shells made
/// of another template, fail the rule.
#[test]
fn a_wrong_extent_or_template_fails() {
    let larger = reference_scene_with(
        "ellipsoids.xml",
        "<float name=\"extent\" value=\"2\"/>",
        "<float name=\"extent\" value=\"2.2\"/>",
    );
    let z = z_test_against(&larger, SPP, "ellipsoids", "ellipsoids, extent 2.2");
    assert!(!z.passes(), "extent 2.2: {:.4} of the pixels pass", z.pass_fraction());
    let z = z_test_against(&load("uv_sphere"), SPP, "ellipsoids", "uv_sphere against ico_sphere");
    assert!(!z.passes(), "uv_sphere shells: {:.4} of the pixels pass", z.pass_fraction());
}

/// Loads a scene of one shape of type `ty` reading `file` (line 4) with `inner` (line 5);
/// an error's message must be placed on line `line`.
/// A shell has no texture coordinates of its own: a hit's (u, v) are its triangle's
/// barycentrics, so a checkerboard on the icosahedral shells shows the order of each
/// triangle's vertices, which must be Mitsuba's.
#[test]
fn textures_on_shells_follow_mitsubas_vertex_order() {
    let job = reference_scene_with(
        "ellipsoids.xml",
        "<rgb name=\"diffuse_reflectance\" value=\"0.2, 0.4, 0.7\"/>",
        "<texture type=\"checkerboard\" name=\"diffuse_reflectance\">\
         <rgb name=\"color0\" value=\"0.05, 0.1, 0.6\"/><rgb name=\"color1\" value=\"0.8, 0.7, 0.2\"/>\
         <transform name=\"to_uv\"><scale value=\"4\"/></transform></texture>",
    );
    let z = z_test_against(&job, SPP, "ellipsoids-checker", "ellipsoids, checkerboard shells");
    assert!(z.passes(), "{:.4} of the pixels pass", z.pass_fraction());
}

fn scene_with(ty: &str, file: &str, inner: &str, line: usize) -> Result<(), String> {
    let xml = format!(
        "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<shape type=\"{ty}\">\n\
         <string name=\"filename\" value=\"{file}\"/>\n{inner}\n</shape>\n</scene>"
    );
    match steradian_mitsuba::load_string(&xml, Path::new("s.xml"), &data(""), &[]) {
        Ok(_) => Ok(()),
        Err(e) => {
            assert_eq!(e.pos.as_ref().map(|p| p.line as usize), Some(line), "{e}");
            Err(e.message)
        }
    }
}

#[test]
fn what_ellipsoids_cannot_do_is_refused_where_it_is_written() {
    for ty in ["ellipsoids", "ellipsoidsmesh"] {
        scene_with(ty, "ellipsoids/cloud.ply", "", 5).unwrap_or_else(|e| panic!("{ty}: {e}"));
        for (inner, needle) in [
            ("<emitter type=\"area\"/>", "not supported"),
            ("<float name=\"extent\" value=\"0\"/>", "extent"),
            ("<float name=\"scale_factor\" value=\"-1\"/>", "scale_factor"),
            ("<float name=\"centers\" value=\"1\"/>", "centers"),
        ] {
            let e = scene_with(ty, "ellipsoids/cloud.ply", inner, 5)
                .err()
                .unwrap_or_else(|| panic!("{ty} accepted: {inner}"));
            assert!(e.contains(needle), "{ty}, {inner}: {e}");
        }
    }
    for (ty, inner, needle) in [
        ("ellipsoids", "<boolean name=\"flip_normals\" value=\"true\"/>", "flip_normals"),
        ("ellipsoids", "<string name=\"shell\" value=\"box\"/>", "shell"),
        ("ellipsoidsmesh", "<string name=\"shell\" value=\"cube\"/>", "shell"),
        ("ellipsoidsmesh", "<shape type=\"sphere\" name=\"shell\"/>", "not a triangle mesh"),
    ] {
        let e = scene_with(ty, "ellipsoids/cloud.ply", inner, 5)
            .err()
            .unwrap_or_else(|| panic!("{ty} accepted: {inner}"));
        assert!(e.contains(needle), "{ty}, {inner}: {e}");
    }
    // a nested mesh is a shell; `face_normals` and `flip_normals` are Mitsuba's mesh options
    scene_with(
        "ellipsoidsmesh",
        "ellipsoids/cloud.ply",
        "<shape type=\"cube\" name=\"shell\"/><boolean name=\"face_normals\" value=\"true\"/>\
         <boolean name=\"flip_normals\" value=\"true\"/>",
        5,
    )
    .unwrap();
}

#[test]
fn malformed_files_are_located_errors() {
    let dir = std::env::temp_dir().join("steradian-ellipsoids-test");
    std::fs::create_dir_all(&dir).unwrap();
    let header = |props: &[&str], n: usize| {
        let mut h = format!("ply\nformat ascii 1.0\nelement vertex {n}\n");
        for p in props {
            h += &format!("property float {p}\n");
        }
        h + "end_header\n"
    };
    let layout = [
        "x", "y", "z", "nx", "ny", "nz", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1",
        "rot_2", "rot_3",
    ];
    for (name, text, needle) in [
        ("no-rotation.ply", header(&layout[..9], 1) + "0 0 0 0 0 1 0 0 0\n", "rot_0"),
        ("zero-quaternion.ply", header(&layout, 1) + "0 0 0 0 0 1 0 0 0 0 0 0 0\n", "zero"),
        ("short.ply", header(&layout, 2) + "0 0 0 0 0 1 0 0 0 1 0 0 0\n", "ends early"),
        ("nan.ply", header(&layout, 1) + "0 nan 0 0 0 1 0 0 0 1 0 0 0\n", "not finite"),
        ("empty.ply", header(&layout, 0), "no ellipsoid"),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let file = path.to_str().unwrap().replace('\\', "/");
        for ty in ["ellipsoids", "ellipsoidsmesh"] {
            let e = scene_with(ty, &file, "", 4)
                .err()
                .unwrap_or_else(|| panic!("{ty} accepted {name}"));
            assert!(e.contains(needle) && e.contains(name), "{ty}, {name}: {e}");
        }
    }
}
