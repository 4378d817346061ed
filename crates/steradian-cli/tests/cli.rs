//! The `steradian` binary, run as a user would: outputs, options, bad input, Ctrl-C.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use steradian::film::{read_exr, Image};
use steradian::testkit::temp_dir;

const BIN: &str = env!("CARGO_BIN_EXE_steradian");

/// Runs `steradian args...` in `dir`.
fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(BIN).args(args).current_dir(dir).output().expect("cannot run the steradian binary")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Runs and expects success; returns stdout.
#[track_caller]
fn ok(dir: &Path, args: &[&str]) -> String {
    let out = run(dir, args);
    let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
    assert!(out.status.success(), "steradian {args:?} failed ({}):\n{stderr}", out.status);
    assert!(!stderr.contains("panicked"), "{stderr}");
    stdout
}

/// Runs and expects a failure whose stderr contains every needle; returns stderr.
#[track_caller]
fn fails(dir: &Path, args: &[&str], needles: &[&str]) -> String {
    let out = run(dir, args);
    let stderr = text(&out.stderr);
    assert!(!out.status.success(), "steradian {args:?} should fail; stderr:\n{stderr}");
    assert_eq!(out.status.code(), Some(1), "steradian {args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "steradian {args:?} panicked:\n{stderr}");
    for needle in needles {
        assert!(
            stderr.contains(needle),
            "stderr of {args:?} does not contain {needle:?}:\n{stderr}"
        );
    }
    // Said once, not `error: file:1:2: error: ...`.
    assert_eq!(stderr.matches("error:").count(), 1, "{stderr}");
    stderr
}

#[track_caller]
fn read(path: &Path) -> Image {
    read_exr(path).unwrap_or_else(|e| panic!("{e}"))
}

#[track_caller]
fn assert_finite_positive(img: &Image) {
    assert!(img.data.iter().all(|v| v.is_finite()), "non-finite pixels");
    let mean = img.data.iter().map(|&v| v as f64).sum::<f64>() / img.data.len() as f64;
    assert!(mean > 0.0, "mean {mean}");
}

/// A small scene with two sensors of different resolutions, ids `small` and `wide`.
fn two_sensor_scene(dir: &Path) -> PathBuf {
    let xml = r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="3"/></integrator>
    <sensor type="perspective" id="small">
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="6"/></film>
    </sensor>
    <sensor type="perspective" id="wide">
        <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="20"/><integer name="height" value="10"/></film>
        <sampler type="independent"><integer name="sample_count" value="2"/></sampler>
    </sensor>
    <shape type="sphere"/>
    <emitter type="constant"/>
</scene>
"#;
    let path = dir.join("two.xml");
    std::fs::write(&path, xml).unwrap();
    path
}

#[test]
fn builtin_scene_without_arguments() {
    let dir = temp_dir("builtin");
    let stdout = ok(&dir, &["render", "--spp", "2"]);
    assert!(stdout.contains("rendered 256x256 at 2 spp"), "{stdout}");
    assert!(stdout.contains("samples/s"), "{stdout}");
    assert!(stdout.contains("dropped NaN/Inf samples"), "{stdout}");
    // the paths traced are counted beside the camera samples when a sample branches
    let branches: u64 = stdout
        .split("path: ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no branch count in {stdout}"));
    assert_eq!(branches > 1, stdout.contains("Mpaths/s"), "{stdout}");
    // and the rays they traced
    assert!(stdout.contains(" Mrays/s)"), "{stdout}");
    // the error reached; at 2 spp no adaptive pilot (auto starts at 32)
    assert!(stdout.contains("error reached: 95 % of the pixels within ±"), "{stdout}");
    assert!(!stdout.contains("allocation:"), "{stdout}");
    // the phases' times: parsing, reading files and the BVH build make up the load
    let line = stdout.lines().find(|l| l.starts_with("time: load ")).expect("a time line");
    let secs: Vec<f64> = line.split(' ').filter_map(|w| w.parse().ok()).collect();
    assert_eq!(secs.len(), 6, "{line}");
    assert!(secs.iter().all(|&t| t >= -0.005), "{line}");
    assert!((secs[1] + secs[2] + secs[3] - secs[0]).abs() <= 0.02, "{line}");
    // and the hierarchy's size: the Cornell box's 6 rectangles and 2 cubes are 36 triangles
    let line = stdout.lines().find(|l| l.starts_with("bvh: ")).expect("a bvh line");
    assert!(line.starts_with("bvh: 36 primitives, built at "), "{line}");
    assert!(dir.join("cornell-box.png").is_file());
    let img = read(&dir.join("cornell-box.exr"));
    assert_eq!((img.width, img.height), (256, 256));
    assert_finite_positive(&img);
}

/// The particle tracer's summary counts light paths.
#[test]
fn particle_tracer_summary_counts_light_paths() {
    let dir = temp_dir("ptracer");
    let xml = two_sensor_scene(&dir);
    let text = std::fs::read_to_string(&xml).unwrap();
    let text = text.replacen("<integrator type=\"path\"", "<integrator type=\"ptracer\"", 1);
    assert!(text.contains("ptracer"), "{text}");
    std::fs::write(&xml, text).unwrap();
    let stdout = ok(&dir, &["render", xml.to_str().unwrap(), "--spp", "2"]);
    assert!(stdout.contains("M light paths/s"), "{stdout}");
}

#[test]
fn output_spp_seed_and_defines() {
    let dir = temp_dir("options");
    let stdout = ok(
        &dir,
        &["render", "-o", "out.exr", "--spp", "3", "--seed", "7", "-D", "res=32", "--quiet"],
    );
    assert!(stdout.contains("rendered 32x32 at 3 spp"), "{stdout}");
    assert!(stdout.contains("out.exr") && stdout.contains("out.png"), "{stdout}");
    assert!(dir.join("out.png").is_file());
    assert!(!dir.join("cornell-box.exr").exists());
    let a = read(&dir.join("out.exr"));
    assert_eq!((a.width, a.height), (32, 32));
    assert_finite_positive(&a);
    // Another seed gives another image; the same seed the same one.
    ok(
        &dir,
        &["render", "-o", "seed8.exr", "--spp", "3", "--seed", "8", "-D", "res=32", "--quiet"],
    );
    ok(
        &dir,
        &["render", "-o", "again.exr", "--spp", "3", "--seed", "7", "-D", "res=32", "--quiet"],
    );
    assert_ne!(read(&dir.join("seed8.exr")).data, a.data);
    assert_eq!(read(&dir.join("again.exr")).data, a.data);
}

#[test]
fn scene_file_output_beside_it_and_sensor_choice() {
    let dir = temp_dir("sensor");
    let scene = two_sensor_scene(&dir);
    // The first sensor by default, written beside the scene.
    ok(&dir, &["render", scene.to_str().unwrap(), "--quiet"]);
    let img = read(&dir.join("two.exr"));
    assert_eq!((img.width, img.height), (8, 6));
    assert!(dir.join("two.png").is_file());
    let stdout = ok(&dir, &["render", "two.xml", "--sensor", "wide", "-o", "wide.exr", "--quiet"]);
    assert!(stdout.contains("rendered 20x10 at 2 spp"), "{stdout}");
    let img = read(&dir.join("wide.exr"));
    assert_eq!((img.width, img.height), (20, 10));
    assert_finite_positive(&img);
}

#[test]
fn thread_count_does_not_change_the_image() {
    let dir = temp_dir("threads");
    let common = ["render", "--spp", "5", "--seed", "11", "-D", "res=48", "--quiet"];
    ok(&dir, &[&common[..], &["--threads", "1", "-o", "one.exr"]].concat());
    ok(&dir, &[&common[..], &["--threads", "2", "-o", "two.exr"]].concat());
    let (a, b) = (read(&dir.join("one.exr")), read(&dir.join("two.exr")));
    assert_eq!((a.width, a.height), (b.width, b.height));
    let bits = |i: &Image| i.data.iter().map(|v| v.to_bits()).collect::<Vec<u32>>();
    assert!(bits(&a) == bits(&b), "--threads 1 and --threads 2 give different images");
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let dir = temp_dir("bad");
    // Missing scene file.
    fails(&dir, &["render", "nothere.xml"], &["error: ", "cannot read scene file", "nothere.xml"]);
    // Malformed XML: the root is never closed.
    std::fs::write(
        dir.join("malformed.xml"),
        "<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n</scene>\n",
    )
    .unwrap();
    let e = fails(&dir, &["render", "malformed.xml"], &["malformed.xml:3:", "malformed XML"]);
    assert!(e.starts_with("malformed.xml:3:"), "{e}");
    // Unknown plugin.
    std::fs::write(dir.join("unknown.xml"), "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n  <shape type=\"spheer\"/>\n</scene>\n").unwrap();
    let e = fails(
        &dir,
        &["render", "unknown.xml"],
        &["unknown.xml:3:3: error: unknown shape plugin type 'spheer'"],
    );
    assert!(e.starts_with("unknown.xml:3:3: error: "), "{e}");
    // A missing mesh: at the filename, naming the mesh.
    std::fs::write(
        dir.join("mesh.xml"),
        "<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<shape type=\"obj\">\n  <string name=\"filename\" value=\"gone.obj\"/>\n</shape>\n</scene>\n",
    )
    .unwrap();
    fails(
        &dir,
        &["render", "mesh.xml"],
        &["mesh.xml:4:3: error: ", "cannot open OBJ file", "gone.obj"],
    );
    // Command-line mistakes.
    fails(&dir, &["render", "-D", "res"], &["error: -D expects NAME=VALUE, got 'res'"]);
    fails(&dir, &["render", "-D", "resolution=32"], &["unused parameter 'resolution'"]);
    fails(&dir, &["render", "-o", "out.txt"], &["error: output file 'out.txt' must end in .exr"]);
    fails(&dir, &["render", "--spp", "0"], &["error: --spp must be at least 1"]);
    fails(&dir, &["render", "--threads", "0"], &["error: --threads must be at least 1"]);
    fails(
        &dir,
        &["render", "--sensor", "nope", "--spp", "1"],
        &["error: the scene has no sensor with id 'nope' (sensor ids: top-down)"],
    );
    let scene = two_sensor_scene(&dir);
    fails(
        &dir,
        &["render", scene.to_str().unwrap(), "--sensor", "big"],
        &["no sensor with id 'big' (sensor ids: small, wide)"],
    );
    // Nothing was written by the failed runs.
    let written: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".exr") || n.ends_with(".png"))
        .collect();
    assert!(written.is_empty(), "{written:?}");
}

#[test]
fn argument_parse_errors_are_usage_errors() {
    // clap's own errors (exit status 2), not panics.
    let dir = temp_dir("usage");
    for args in [&["render", "--spp", "many"][..], &["render", "--bogus"], &["frobnicate"]] {
        let out = run(&dir, args);
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains("error:") && !stderr.contains("panicked"), "{stderr}");
    }
}

/// Ctrl-C stops the render after the passes already finished, writes the image from them,
/// says how many samples per pixel it holds, and exits with status 0.
#[cfg(unix)]
#[test]
fn ctrl_c_keeps_the_finished_passes() {
    use std::time::{Duration, Instant};

    let dir = temp_dir("ctrl-c");
    // 64x64 px (4 tiles) at 5000 spp: each of the 16 passes is short (the render stops at
    // the end of the tiles already started), the whole render long.
    let child = Command::new(BIN)
        .args(["render", "--spp", "5000", "-D", "res=64", "-o", "stopped.exr"])
        .current_dir(&dir)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // Idle, the pilot and the first pass take about 0.5 s; under the load of a full test run
    // on 2 cores 1.5 s once was not enough (0 passes finished). 4 s leaves room, and the whole
    // render would take minutes.
    std::thread::sleep(Duration::from_millis(4000));
    let status = Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    assert!(status.success());
    let start = Instant::now();
    let out = child.wait_with_output().unwrap();
    let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
    assert!(start.elapsed() < Duration::from_secs(120), "took {:?} to stop", start.elapsed());
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stderr.contains("interrupted: the image holds "), "{stderr}");
    let spp: u32 = stderr
        .split("interrupted: the image holds ")
        .nth(1)
        .and_then(|r| r.split(" of 5000 samples per pixel").next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no sample count in: {stderr}"));
    assert!(spp > 0 && spp < 5000, "{spp} spp");
    assert!(stdout.contains(&format!("rendered 64x64 at {spp} spp")), "{stdout}");
    assert!(stdout.contains("wrote stopped.exr and stopped.png"), "{stdout}");
    let img = read(&dir.join("stopped.exr"));
    assert_eq!((img.width, img.height), (64, 64));
    assert_finite_positive(&img);
}

/// A `moment` scene's EXR holds the image and, beside it, Mitsuba's layers: the nested
/// integrator's mean XYZ (its Y the image's luminance) and second moment (at least m1²).
#[test]
fn moment_writes_its_layers() {
    let dir = temp_dir("moment");
    std::fs::write(
        dir.join("m.xml"),
        r#"<scene version="3.0.0">
    <integrator type="moment"><integrator type="path" name="pt"/></integrator>
    <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="6"/></film></sensor>
    <emitter type="constant"/>
    <shape type="sphere"/>
</scene>"#,
    )
    .unwrap();
    ok(&dir, &["render", "m.xml", "-o", "m.exr", "--spp", "16", "--quiet"]);
    let path = dir.join("m.exr");
    let image = read(&path);
    let m1 = steradian::film::read_exr_channels(&path, &["pt.X", "pt.Y", "pt.Z"]).unwrap();
    let m2 = steradian::film::read_exr_channels(&path, &["m2_pt.X", "m2_pt.Y", "m2_pt.Z"]).unwrap();
    for ((rgb, xyz), sq) in image.data.chunks(3).zip(m1.data.chunks(3)).zip(m2.data.chunks(3)) {
        let y = 0.212671 * rgb[0] + 0.715160 * rgb[1] + 0.072169 * rgb[2];
        assert!((xyz[1] - y).abs() <= 1e-5 * y.max(1e-3), "{xyz:?} vs {rgb:?}");
        assert!(sq[1] >= xyz[1] * xyz[1] * (1.0 - 1e-5), "m2 {} < m1² {}", sq[1], xyz[1] * xyz[1]);
    }
}

/// `pixel_format` sets the EXR's channels: `rgba` adds `A` (1 on the sphere, 0 off it, a
/// fraction on its edge), `luminance_alpha` writes `Y` (the image's luminance) and `A`, `xyz`
/// writes `X`, `Y`, `Z` and no `R`.
#[test]
fn pixel_format_sets_the_channels() {
    let dir = temp_dir("cli-pixel-format");
    let scene = |format: &str| {
        format!(
            r#"<scene version="3.0.0">
    <integrator type="path"/>
    <sensor type="perspective"><float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="12"/><integer name="height" value="10"/>
            <string name="pixel_format" value="{format}"/><rfilter type="box"/></film></sensor>
    <emitter type="point"><point name="position" x="0" y="2" z="3"/><rgb name="intensity" value="5"/></emitter>
    <shape type="sphere"><float name="radius" value="0.9"/></shape>
</scene>"#
        )
    };
    for format in ["rgba", "luminance_alpha", "xyz"] {
        std::fs::write(dir.join(format!("{format}.xml")), scene(format)).unwrap();
        let xml = format!("{format}.xml");
        let exr = format!("{format}.exr");
        ok(&dir, &["render", &xml, "-o", &exr, "--spp", "16", "--seed", "2", "--quiet"]);
    }
    let rgba = read(&dir.join("rgba.exr"));
    let alpha = steradian::film::read_exr_channels(&dir.join("rgba.exr"), &["A"]).unwrap();
    let a: Vec<f32> = alpha.data.iter().step_by(3).copied().collect();
    assert!(a.contains(&0.0) && a.contains(&1.0) && a.iter().any(|&v| v > 0.0 && v < 1.0), "{a:?}");
    // the same seed: the luminance file holds the rgba image's luminance
    let y =
        steradian::film::read_exr_channels(&dir.join("luminance_alpha.exr"), &["Y", "A"]).unwrap();
    for (rgb, ya) in rgba.data.chunks(3).zip(y.data.chunks(3)) {
        let lum = 0.212671 * rgb[0] + 0.715160 * rgb[1] + 0.072169 * rgb[2];
        assert!((ya[0] - lum).abs() <= 1e-5 * lum.max(1e-3), "{ya:?} vs {rgb:?}");
    }
    assert_eq!(y.data.iter().skip(1).step_by(3).copied().collect::<Vec<_>>(), a);
    let xyz = dir.join("xyz.exr");
    steradian::film::read_exr_channels(&xyz, &["X", "Y", "Z"]).unwrap();
    assert!(steradian::film::read_exr_channels(&xyz, &["R"]).is_err());
    assert!(steradian::film::read_exr_channels(&xyz, &["A"]).is_err());
}

/// `measure` on a work plane prints the grid (ny rows of nx), its errors and the statistics,
/// in lux: under a 1000 cd point source the centre cells read I h / d³.
#[test]
fn measure_prints_a_work_plane_grid() {
    let dir = temp_dir("cli-workplane");
    let w = 1000.0 / 683.0;
    std::fs::write(
        dir.join("grid.xml"),
        format!(
            r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="1"/></integrator>
  <emitter type="point"><point name="position" x="0" y="0" z="2"/><rgb name="intensity" value="{w}, {w}, {w}"/></emitter>
  <sensor type="workplane" id="grid">
    <transform name="to_world"><scale x="2" y="1"/></transform>
    <integer name="nx" value="2"/><integer name="ny" value="1"/>
  </sensor>
</scene>"#
        ),
    )
    .unwrap();
    let json = ok(&dir, &["measure", "grid.xml", "--json", "--spp", "4"]);
    for key in
        ["\"unit\":\"lx\"", "\"nx\":2", "\"ny\":1", "\"stats\":{\"avg\":{\"value\":", "\"u0\":"]
    {
        assert!(json.contains(key), "{key} missing from {json}");
    }
    // "values":[[a,b]]: both cells at (±1, 0), d² = 5: E = 1000·2/5^1.5 lx
    let values = json.split("\"values\":[[").nth(1).unwrap().split("]]").next().unwrap();
    let want = 1000.0 * 2.0 / 5f64.powf(1.5);
    for v in values.split(',') {
        let v: f64 = v.parse().unwrap();
        assert!((v / want - 1.0).abs() < 1e-4, "{v} lx vs {want}");
    }
    let text = ok(&dir, &["measure", "grid.xml", "--spp", "4"]);
    assert!(text.contains("2x1 work plane") && text.contains("U0"), "{text}");
    let csv = ok(&dir, &["measure", "grid.xml", "--csv", "--spp", "4"]);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], "i,j,value_lx,stderr_lx");
    assert!(
        lines[1].starts_with("0,0,") && lines[2].starts_with("1,0,") && lines.len() == 3,
        "{csv}"
    );
}

/// `--allocation adaptive` runs the pilot and says what it decided and the samples spent;
/// irradiance maps refuse it.
#[test]
fn adaptive_allocation_is_reported() {
    let dir = temp_dir("adaptive");
    let out = ok(&dir, &["render", "-D", "res=32", "--spp", "8", "--allocation", "adaptive"]);
    assert!(out.contains("allocation: a pilot of 4 spp"), "{out}");
    assert!(out.contains("lower relative variance adaptive: adaptive, "), "{out}");
    let samples: u64 = out
        .split("adaptive, ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no sample count in {out}"));
    // ⌈d·8⌉ per pixel: at least 8 on average, less than one more
    assert!((32 * 32 * 8..32 * 32 * 9).contains(&samples), "{samples}");
    fails(
        &dir,
        &[
            "render",
            "-D",
            "res=32",
            "--spp",
            "8",
            "--allocation",
            "adaptive",
            "--quantity",
            "irradiance",
        ],
        &["allocation", "adaptive applies to radiance images"],
    );
}
