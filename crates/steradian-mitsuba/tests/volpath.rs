//! Purpose: `volpath` and `volpathmis` render participating media as Mitsuba 3.9.1 does (its
//! render-test rule against 4096-spp `llvm_ad_rgb` references with variance images, made by
//! `scripts/mitsuba_reference.py`): a homogeneous sphere behind a null boundary, lights and
//! camera inside a fog, a glass sphere holding a medium, a rough glass cube under a spot light,
//! a chromatic medium under `volpathmis`, a `gridvolume` cloud, a `tabphase` table. Mutated scenes fail the same
//! rule. Closed forms: Beer–Lambert transmittance through a slab and a sphere, a point
//! source's irradiance through an absorbing slab, single scattering from a half-space under a
//! collimated beam, within 3 standard errors; a white furnace inside a non-absorbing medium
//! returns the emitted radiance. A camera fog that no shape bounds lets no sky in, and the
//! scene warns. Bad media are located errors.

mod common;

use std::path::Path;

use common::{
    image_mean_z, read_meter, reference_scene as data, reference_scene_with, z_test_against,
    METER_FILM,
};
use steradian::radiometry;
use steradian::render::{render, Job, RenderOptions};

const SPP: u32 = 64;

fn load(name: &str) -> Job {
    steradian_mitsuba::load_file(&data(&format!("{name}.xml")), &[])
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The scene passes the Z-test against its reference, and its image mean agrees.
fn matches_mitsuba(name: &str) {
    let job = load(name);
    assert!(z_test_against(&job, SPP, name, name).passes(), "{name}");
    let z = image_mean_z(&job, SPP, name, 4096);
    eprintln!("{name} image mean: z = {z:.2}");
    assert!(z < 4.0, "{name}: image mean off by {z:.2} standard errors");
}

/// The mutated scene fails the comparison with the unmutated scene's reference: the per-pixel
/// Z-test, or the image mean by more than 4 standard errors.
fn mutant_fails(name: &str, from: &str, to: &str) {
    let job = reference_scene_with(&format!("{name}.xml"), from, to);
    let what = format!("{name} with {to}");
    let passes = z_test_against(&job, SPP, name, &what).passes();
    let z = image_mean_z(&job, SPP, name, 4096);
    eprintln!("{what} image mean: z = {z:.2}");
    assert!(!passes || z >= 4.0, "{what} passes");
}

#[test]
fn homogeneous_sphere_in_a_null_boundary() {
    matches_mitsuba("volpath-sphere");
    mutant_fails("volpath-sphere", "0.9, 0.8, 0.6", "0.8, 0.7, 0.5");
}

/// `tabphase`: the table read from forward to back as Mitsuba reads it; reversed, it fails.
#[test]
fn tabulated_phase_function() {
    matches_mitsuba("volpath-tabphase");
    mutant_fails(
        "volpath-tabphase",
        "1.2, 0.5, 0.15, 0.1, 0.15, 0.4, 1.5, 5, 14",
        "14, 5, 1.5, 0.4, 0.15, 0.1, 0.15, 0.5, 1.2",
    );
}

#[test]
fn lights_and_camera_inside_a_fog() {
    matches_mitsuba("volpath-fog");
    // the camera outside the fog
    mutant_fails("volpath-fog", "<ref id=\"fog\"/>", "");
}

/// A light may name the medium it sits in, as any Mitsuba endpoint may; like Mitsuba's
/// `volpath`, steradian attenuates light along the path whatever the light names, so the
/// image is the same (one medium at most).
#[test]
fn a_light_naming_its_medium_renders_the_same() {
    let named = r#"<emitter type="area"><ref id="fog"/>"#;
    let job = reference_scene_with("volpath-fog.xml", r#"<emitter type="area">"#, named);
    let plain = load("volpath-fog");
    let opts = RenderOptions { spp: Some(8), seed: Some(3), ..Default::default() };
    let image = |job: &Job| render(job, &opts).unwrap().film().develop().data;
    assert_eq!(image(&job), image(&plain));
    let two = format!(r#"{named}<medium type="homogeneous"/>"#);
    let xml = std::fs::read_to_string(data("volpath-fog.xml"))
        .unwrap()
        .replace(r#"<emitter type="area">"#, &two);
    let e = common::load_error(&xml, "two-media.xml");
    assert!(e.contains("only one medium can be named per emitter"), "{e}");
}

#[test]
fn medium_behind_a_glass_boundary() {
    matches_mitsuba("volpath-glass");
    // the medium's albedo reversed in colour
    mutant_fails("volpath-glass", "0.95, 0.7, 0.5", "0.5, 0.7, 0.95");
}

#[test]
fn medium_behind_a_rough_glass_boundary_under_a_spot_light() {
    matches_mitsuba("volpath-rough");
    mutant_fails(
        "volpath-rough",
        "<float name=\"scale\" value=\"2\"/>",
        "<float name=\"scale\" value=\"5\"/>",
    );
}

#[test]
fn chromatic_medium_under_volpathmis_and_volpath() {
    matches_mitsuba("volpathmis-chromatic");
    // volpath draws free flights the same way: the same image
    let job = reference_scene_with(
        "volpathmis-chromatic.xml",
        "<default name=\"integrator\" value=\"volpathmis\"/>",
        "<default name=\"integrator\" value=\"volpath\"/>",
    );
    assert!(z_test_against(&job, SPP, "volpathmis-chromatic", "under volpath").passes());
    // the blend weight taken from the other side
    mutant_fails(
        "volpathmis-chromatic",
        "<float name=\"weight\" value=\"0.4\"/>",
        "<float name=\"weight\" value=\"0.9\"/>",
    );
}

#[test]
fn heterogeneous_gridvolume_cloud() {
    matches_mitsuba("volpath-cloud");
    mutant_fails(
        "volpath-cloud",
        "<rgb name=\"albedo\" value=\"0.9\"/>",
        "<rgb name=\"albedo\" value=\"0.75\"/>",
    );
}

fn assert_within_3se(value: [f64; 3], stderr: [f64; 3], want: [f64; 3], what: &str) {
    for c in 0..3 {
        let z = (value[c] - want[c]) / stderr[c].max(1e-12);
        eprintln!("{what} channel {c}: {} vs {} (z = {z:.2})", value[c], want[c]);
        assert!(z.abs() <= 3.0, "{what} channel {c}: {} vs {} (z = {z:.2})", value[c], want[c]);
    }
}

/// A radiance meter at z = 5 looking down at a 20 × 20 m emitter of `radiance` at z = −5
/// through a null-bounded `shape` (its default size, about the origin) holding `medium`, under
/// `volpath` with `integrator_params`.
fn emitter_behind_a_medium(
    integrator_params: &str,
    radiance: &str,
    shape: &str,
    medium: &str,
) -> String {
    format!(
        r#"<scene version="3.0.0">
  <integrator type="volpath">{integrator_params}</integrator>
  <sensor type="radiancemeter" id="meter">
    <point name="origin" x="0" y="0" z="5"/><vector name="direction" x="0" y="0" z="-1"/>
    {METER_FILM}
  </sensor>
  <shape type="rectangle">
    <transform name="to_world"><scale value="10"/><translate z="-5"/></transform>
    <emitter type="area"><rgb name="radiance" value="{radiance}"/></emitter>
  </shape>
  <shape type="{shape}">
    <bsdf type="null"/>
    {medium}
  </shape>
</scene>"#
    )
}

/// Radiance through an absorbing (albedo 0) medium is the emitted radiance times
/// exp(−σ_t d): a radiance meter looking at an emitter through a null-bounded cube (d = 2 m
/// across) and through the centre of a sphere (d = 2r).
#[test]
fn beer_lambert_through_a_slab_and_a_sphere() {
    let sigma = [0.3, 0.8, 1.6];
    let medium = r#"<medium type="homogeneous" name="interior">
      <rgb name="albedo" value="0"/>
      <rgb name="sigma_t" value="0.15, 0.4, 0.8"/>
      <float name="scale" value="2"/>
    </medium>"#;
    let scene = |shape: &str| emitter_behind_a_medium("", "2, 3, 4", shape, medium);
    let le = [2.0, 3.0, 4.0];
    for (shape, d) in [("cube", 2.0), ("sphere", 2.0)] {
        let (v, se) = read_meter(&scene(shape), "meter", 4096, 1);
        let want: [f64; 3] = std::array::from_fn(|c| le[c] * radiometry::beer_lambert(sigma[c], d));
        assert_within_3se(v, se, want, &format!("through a {shape}"));
    }
}

/// Irradiance from a point source through an absorbing slab (a null-bounded box much wider
/// than its thickness), on a meter under it: E = I cos θ / r² · exp(−σ_t t / cos θ).
#[test]
fn point_irradiance_through_an_absorbing_slab() {
    let xml = format!(
        r#"<scene version="3.0.0">
  <integrator type="volpath"/>
  <emitter type="point"><point name="position" x="0.6" y="0" z="1.2"/><rgb name="intensity" value="5"/></emitter>
  <shape type="cube">
    <transform name="to_world"><scale x="50" y="50" z="0.2"/><translate z="0.5"/></transform>
    <bsdf type="null"/>
    <medium type="homogeneous" name="interior">
      <rgb name="albedo" value="0"/>
      <rgb name="sigma_t" value="0.5, 1, 2"/>
    </medium>
  </shape>
  <shape type="disk">
    <transform name="to_world"><scale value="1e-4"/></transform>
    <sensor type="irradiancemeter" id="meter">{METER_FILM}</sensor>
  </shape>
</scene>"#
    );
    let (v, se) = read_meter(&xml, "meter", 256, 1);
    let r = (0.6f64 * 0.6 + 1.2 * 1.2).sqrt();
    let theta = (1.2 / r).acos();
    let want: [f64; 3] = std::array::from_fn(|c| {
        radiometry::point_irradiance_through_slab(5.0, r, theta, [0.5, 1.0, 2.0][c], 0.4)
    });
    // a delta light seen through an absorber: each sample reads it exactly, so the error bar
    // is tiny; allow for the ray offsets at the slab's faces (1e-4 (1 + |p|) m each: the
    // shadow ray crosses ~2e-4 m less absorber, 4e-4 of the reading at σ_t d ≈ 0.9)
    for c in 0..3 {
        let tol = 3.0 * se[c] + 5e-4 * want[c];
        assert!((v[c] - want[c]).abs() <= tol, "channel {c}: {} vs {}", v[c], want[c]);
    }
}

/// A white furnace: inside a sphere that emits Le inwards everywhere, filled with a
/// non-absorbing scattering medium, the radiance is Le in every direction at every point
/// (the medium only redistributes a uniform field). A radiance meter and an irradiance meter
/// (π Le) inside it read that within 3 standard errors.
#[test]
fn white_furnace_inside_a_scattering_medium() {
    let xml = format!(
        r#"<scene version="3.0.0">
  <integrator type="volpath"/>
  <medium type="homogeneous" id="fog">
    <rgb name="albedo" value="1"/>
    <rgb name="sigma_t" value="0.5, 1, 0.9"/>
    <float name="scale" value="3"/>
    <phase type="hg"><float name="g" value="0.6"/></phase>
  </medium>
  <sensor type="radiancemeter" id="radiance">
    <point name="origin" x="0.2" y="0.1" z="0"/><vector name="direction" x="1" y="1" z="0.3"/>
    <ref id="fog"/>
    {METER_FILM}
  </sensor>
  <shape type="sphere">
    <float name="radius" value="2"/>
    <boolean name="flip_normals" value="true"/>
    <emitter type="area"><rgb name="radiance" value="0.7, 1.1, 1.5"/></emitter>
  </shape>
  <shape type="disk">
    <transform name="to_world"><scale value="1e-4"/><translate x="-0.5"/></transform>
    <sensor type="irradiancemeter" id="irradiance"><ref id="fog"/>{METER_FILM}</sensor>
  </shape>
</scene>"#
    );
    let le = [0.7, 1.1, 1.5];
    let (v, se) = read_meter(&xml, "radiance", 4096, 1);
    assert_within_3se(v, se, le, "radiance in the furnace");
    let (v, se) = read_meter(&xml, "irradiance", 4096, 1);
    let pi = std::f64::consts::PI;
    assert_within_3se(v, se, le.map(|l| pi * l), "irradiance in the furnace");
}

/// Single scattering in a homogeneous half-space under a collimated beam (`max_depth` 2: the
/// camera ray's one scattering event and its light sample): L₁ = α p E μ₀/(μ₀ + μ), p the
/// Henyey–Greenstein value at the angle between beam and view, within 3 standard errors.
#[test]
fn single_scattering_from_a_half_space() {
    let (theta0, theta) = (30f64.to_radians(), 50f64.to_radians());
    // the beam travels down towards +x; the meter, up on the +x side, looks down towards −x
    let beam = glam::DVec3::new(theta0.sin(), 0.0, -theta0.cos());
    let view = glam::DVec3::new(-theta.sin(), 0.0, -theta.cos());
    let g = 0.5;
    // scattering angle between the beam's travel and the light's way out (−view)
    let cos_scatter = beam.dot(-view);
    let hg = (1.0 - g * g)
        / (4.0 * std::f64::consts::PI * (1.0 + g * g - 2.0 * g * cos_scatter).powf(1.5));
    let origin = -view * 3.0;
    let xml = format!(
        r#"<scene version="3.0.0">
  <integrator type="volpath"><integer name="max_depth" value="2"/></integrator>
  <emitter type="directional">
    <vector name="direction" x="{}" y="0" z="{}"/>
    <rgb name="irradiance" value="2, 3, 4"/>
  </emitter>
  <sensor type="radiancemeter" id="meter">
    <point name="origin" x="{}" y="0" z="{}"/><vector name="direction" x="{}" y="0" z="{}"/>
    {METER_FILM}
  </sensor>
  <shape type="cube">
    <transform name="to_world"><scale x="500" y="500" z="50"/><translate z="-50"/></transform>
    <bsdf type="null"/>
    <medium type="homogeneous" name="interior">
      <rgb name="albedo" value="0.8, 0.6, 0.4"/>
      <rgb name="sigma_t" value="1"/>
      <phase type="hg"><float name="g" value="{g}"/></phase>
    </medium>
  </shape>
</scene>"#,
        beam.x, beam.z, origin.x, origin.z, view.x, view.z
    );
    let (v, se) = read_meter(&xml, "meter", 4096, 1);
    let (e, albedo) = ([2.0, 3.0, 4.0], [0.8, 0.6, 0.4]);
    let want: [f64; 3] = std::array::from_fn(|c| {
        radiometry::single_scattering_half_space(e[c], albedo[c], hg, theta0.cos(), theta.cos())
    });
    assert_within_3se(v, se, want, "single scattering");
}

/// Null crossings are not scattering events (Mitsuba's volpath): with `max_depth` 1 an
/// emitter seen through a null-bounded absorbing cube still shows, dimmed by its
/// transmittance; under `path` the crossing would count as a bounce.
#[test]
fn null_crossings_do_not_count_towards_max_depth() {
    let xml = emitter_behind_a_medium(
        r#"<integer name="max_depth" value="1"/>"#,
        "1",
        "cube",
        r#"<medium type="homogeneous" name="interior"><rgb name="albedo" value="0"/><rgb name="sigma_t" value="0.5"/></medium>"#,
    );
    let (v, se) = read_meter(&xml, "meter", 1024, 1);
    let t = radiometry::beer_lambert(0.5, 2.0);
    assert_within_3se(v, se, [t; 3], "through a null cube at max_depth 1");
}

fn load_error(xml: &str) -> steradian_mitsuba::LoadError {
    steradian_mitsuba::load_string(xml, Path::new("media.xml"), &data(""), &[]).unwrap_err()
}

#[test]
fn bad_media_are_located_errors() {
    let shape = |medium: &str| {
        format!(
            "<scene version=\"3.0.0\">\n<integrator type=\"volpath\"/>\n<shape type=\"sphere\">\n<bsdf type=\"null\"/>\n{medium}\n</shape>\n</scene>"
        )
    };
    // negative extinction, at the parameter
    let e = load_error(&shape(
        "<medium type=\"homogeneous\" name=\"interior\">\n<rgb name=\"sigma_t\" value=\"-1\"/>\n</medium>",
    ));
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(6), "{e}");
    assert!(e.message.contains("sigma_t"), "{e}");
    // albedo above 1
    let e = load_error(&shape(
        "<medium type=\"homogeneous\" name=\"interior\">\n<rgb name=\"albedo\" value=\"1.5\"/>\n</medium>",
    ));
    assert!(e.message.contains("albedo"), "{e}");
    // a medium in a shape without a slot name
    let e = load_error(&shape("<medium type=\"homogeneous\"/>"));
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(5), "{e}");
    assert!(e.message.contains("interior"), "{e}");
    // an unknown parameter
    let e = load_error(&shape(
        "<medium type=\"homogeneous\" name=\"interior\">\n<float name=\"sigma\" value=\"1\"/>\n</medium>",
    ));
    assert!(e.message.contains("sigma"), "{e}");
    // a heterogeneous medium without its grid file, and with a truncated one
    let grid = |file: &str| {
        shape(&format!(
            "<medium type=\"heterogeneous\" name=\"interior\">\n<volume type=\"gridvolume\" name=\"sigma_t\">\n<string name=\"filename\" value=\"{file}\"/>\n</volume>\n</medium>"
        ))
    };
    let e = load_error(&shape(
        "<medium type=\"heterogeneous\" name=\"interior\">\n<volume type=\"gridvolume\" name=\"sigma_t\"/>\n</medium>",
    ));
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(6), "{e}");
    assert!(e.message.contains("filename"), "{e}");
    let e = load_error(&grid("no-such.vol"));
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(7), "{e}");
    let dir = steradian::testkit::temp_dir("volpath-bad-vol");
    let good = std::fs::read(data("volpath-cloud.vol")).unwrap();
    let truncated = dir.join("truncated.vol");
    std::fs::write(&truncated, &good[..good.len() / 2]).unwrap();
    let e = load_error(&grid(&truncated.display().to_string()));
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(7), "{e}");
    assert!(e.message.contains("truncated"), "{e}");
    let mut wrong = good.clone();
    wrong[0..3].copy_from_slice(b"BAD");
    let header = dir.join("header.vol");
    std::fs::write(&header, &wrong).unwrap();
    let e = load_error(&grid(&header.display().to_string()));
    assert!(e.message.contains("VOL"), "{e}");
    // a homogeneous medium takes a constvolume for a value, and refuses a grid
    let load = |medium: &str| {
        steradian_mitsuba::load_string(&shape(medium), Path::new("media.xml"), &data(""), &[])
    };
    let value = load("<medium type=\"homogeneous\" name=\"interior\"><rgb name=\"albedo\" value=\"0.3, 0.4, 0.5\"/></medium>").unwrap();
    let volume = load("<medium type=\"homogeneous\" name=\"interior\"><volume type=\"constvolume\" name=\"albedo\"><rgb name=\"value\" value=\"0.3, 0.4, 0.5\"/></volume></medium>").unwrap();
    assert_eq!(value.scene.media, volume.scene.media);
    let e = load_error(&shape(
        "<medium type=\"homogeneous\" name=\"interior\">\n<volume type=\"gridvolume\" name=\"sigma_t\"><string name=\"filename\" value=\"volpath-cloud.vol\"/></volume>\n</medium>",
    ));
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(6), "{e}");
    assert!(e.message.contains("heterogeneous"), "{e}");
    // sensors in different media
    let e = load_error(
        "<scene version=\"3.0.0\">\n<integrator type=\"volpath\"/>\n<medium type=\"homogeneous\" id=\"a\"/>\n\
         <sensor type=\"perspective\"><ref id=\"a\"/></sensor>\n<sensor type=\"perspective\"/>\n</scene>",
    );
    assert_eq!(e.pos.as_ref().map(|p| p.line), Some(5), "{e}");
}

/// A camera in a fog that no shape bounds, under a uniform sky: no light from infinity
/// crosses an unbounded medium, so the image is black (Mitsuba 3.9.1's `volpath` lets the sky
/// in: image mean 0.145, more than the 0.065 of the same fog bounded at 20 m), and the scene
/// loads with a warning at the sensor that says so; bounded by a null sphere of radius 20 m,
/// the sky comes through and nothing is said.
#[test]
fn an_unbounded_camera_fog_under_a_sky_is_dark_and_warns() {
    let xml = |bound: &str| {
        format!(
            r#"<scene version="3.0.0">
<integrator type="volpath"/>
<sensor type="perspective"><float name="fov" value="40"/>
<medium type="homogeneous" name="medium" id="fog"><rgb name="albedo" value="0.8, 0.8, 0.8"/><float name="sigma_t" value="0.3"/></medium>
<transform name="to_world"><lookat origin="0, 1.5, 5" target="0, 0.5, 0" up="0, 1, 0"/></transform>
<film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/><rfilter type="box"/></film></sensor>
<emitter type="constant"/>
<shape type="sphere"><point name="center" x="0" y="0.5" z="0"/><float name="radius" value="0.7"/><bsdf type="diffuse"/></shape>
{bound}
</scene>"#
        )
    };
    let unbounded = common::load_scene(&xml(""), "fog.xml");
    assert_eq!(unbounded.warnings.len(), 1, "{:?}", unbounded.warnings);
    assert!(
        unbounded.warnings[0].contains("fog.xml:3:1")
            && unbounded.warnings[0].contains("fills all space"),
        "{}",
        unbounded.warnings[0]
    );
    let (mean, _) = common::scene_mean_and_error(&unbounded, 1);
    assert_eq!(mean, 0.0, "light from infinity crossed an unbounded fog");
    let bounded = common::load_scene(
        &xml(
            r#"<shape type="sphere"><float name="radius" value="20"/><bsdf type="null"/><ref name="interior" id="fog"/></shape>"#,
        ),
        "fog.xml",
    );
    assert!(bounded.warnings.is_empty(), "{:?}", bounded.warnings);
    let (mean, se) = common::scene_mean_and_error(&bounded, 1);
    assert!(mean > 10.0 * se, "no sky through a bounded fog: {mean} ± {se}");
}
