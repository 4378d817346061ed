//! `phong` and `merl` through the loader: the shipped scenes render, MERL files tabulating
//! known BRDFs render like those BRDFs (statistically), the shipped MERL asset is what its
//! documentation says, and bad input gives errors at file:line:column.

mod common;

use std::io::{Read, Write};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

use steradian::bsdf::{
    Bsdf, InternalScattering, MerlTable, MicrofacetDistribution, MicrofacetKind, RoughPlastic,
};
use steradian::film::Image;
use steradian::render::{render, RenderOptions};
use steradian::sampling::{Pcg32, SamplerKind};
use steradian::testkit::bsdf::sp;
use steradian::testkit::{temp_dir, write_file};
use steradian::texture::TexturePoint;
use steradian::{Spectrum, Vec2, Vec3};
use steradian_mitsuba::{load_file, LoadError};

use common::check_error;

fn repo_file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..").join(name)
}

/// Renders with i.i.d. samples (so that per-pixel standard errors are valid); returns the
/// image and its per-pixel standard errors.
fn render_with_stderr(
    path: &Path,
    defines: &[(&str, &str)],
    spp: u32,
    seed: u64,
) -> (Image, Image, steradian::render::Job) {
    let defines: Vec<(String, String)> =
        defines.iter().map(|(a, b)| (a.to_string(), b.to_string())).collect();
    let scene = load_file(path, &defines).unwrap_or_else(|e| panic!("{e}"));
    let opts = RenderOptions {
        spp: Some(spp),
        seed: Some(seed),
        sampler: Some(SamplerKind::Independent),
        ..Default::default()
    };
    let out = render(&scene, &opts).unwrap();
    assert_eq!(out.dropped_samples, 0, "NaN/Inf samples in {}", path.display());
    (out.film().develop(), out.film().develop_stderr(), scene)
}

// ---------------------------------------------------------------------------------------------
// The shipped scenes

/// The asset of `scenes/merl.xml`: steradian's roughplastic (GGX α 0.15, η 1.5, diffuse
/// 0.55/0.12/0.06) tabulated at the MERL samples, stored values rounded to 0.25.
const ASSET: &str = "scenes/merl-red-plastic.binary.gz";
const ASSET_QUANTUM: f64 = 0.25;

fn asset_bsdf() -> Bsdf {
    let d = MicrofacetDistribution::new(MicrofacetKind::Ggx, 0.15, 0.15, true);
    Bsdf::RoughPlastic(RoughPlastic::new(
        d,
        1.5,
        Spectrum::new(0.55, 0.12, 0.06).into(),
        Spectrum::ONE.into(),
        InternalScattering::Linear,
    ))
}

fn asset_bytes() -> Vec<u8> {
    let b = asset_bsdf();
    MerlTable::tabulate(|wo, wi| b.eval(&sp(), wo, wi)).to_bytes(ASSET_QUANTUM)
}

#[test]
fn shipped_merl_asset_is_the_tabulated_roughplastic() {
    let path = repo_file(ASSET);
    let raw = asset_bytes();
    if std::env::var_os("STERADIAN_REGENERATE_MERL").is_some() {
        let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
        gz.write_all(&raw).unwrap();
        std::fs::write(&path, gz.finish().unwrap()).unwrap();
    }
    let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
    MerlTable::read(&path)
        .unwrap_or_else(|e| panic!("{e} (STERADIAN_REGENERATE_MERL=1 regenerates it)"));
    // Value by value, in the file's units: the table is regenerated with f32 arithmetic that
    // may change in its last bits (a faster sine, a different summation), and a value that
    // close to a rounding boundary of the quantum moves by one step. A different BSDF moves
    // most values by many steps.
    let mut shipped = Vec::new();
    flate2::read::GzDecoder::new(std::fs::File::open(&path).unwrap())
        .read_to_end(&mut shipped)
        .unwrap();
    assert_eq!(shipped.len(), raw.len(), "{ASSET}: wrong size");
    assert_eq!(shipped[..12], raw[..12], "{ASSET}: wrong dimensions");
    let values = |b: &[u8]| -> Vec<f64> {
        b[12..].chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect()
    };
    let (a, b) = (values(&shipped), values(&raw));
    let worst = a.iter().zip(&b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    let moved = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    eprintln!("{ASSET}: {moved} of {} values moved by one quantum", a.len());
    assert!(
        worst <= ASSET_QUANTUM * (1.0 + 1e-9) && moved * 10_000 < a.len(),
        "{ASSET} differs from the tabulated roughplastic: {moved} values moved, by up to {worst} \
         (STERADIAN_REGENERATE_MERL=1 regenerates it)"
    );
    eprintln!("{ASSET}: {size} bytes (raw {} bytes)", raw.len());
    assert!(size < 3_000_000, "{size} bytes");
}

#[test]
fn shipped_scenes_render() {
    for name in ["scenes/phong.xml", "scenes/merl.xml"] {
        let (img, _, scene) =
            render_with_stderr(&repo_file(name), &[("width", "48"), ("height", "24")], 4, 7);
        let m = img.channel_means();
        eprintln!("{name}: channel means {m:.4?}");
        assert!(m.iter().all(|x| x.is_finite() && *x > 0.01), "{name}: {m:?}");
        let want = if name.contains("merl") { "Merl" } else { "Phong" };
        assert!(
            scene.scene.bsdfs.iter().any(|b| format!("{b:?}").starts_with(want)),
            "{name} has no {want} BSDF"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// MERL files of known BRDFs render like those BRDFs

/// A unit sphere seen from +z, lit by a point light (which tests ρ pointwise) and a constant
/// sky (which tests sampling and albedo), one bounce.
fn sphere_scene(bsdf_xml: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="2"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="34"/>
    <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="32"/><rfilter type="box"/></film>
  </sensor>
  <emitter type="constant"><rgb name="radiance" value="0.3"/></emitter>
  <emitter type="point"><point name="position" value="2.5, 2, 3"/><rgb name="intensity" value="12"/></emitter>
  <shape type="sphere">{bsdf_xml}</shape>
</scene>"#
    )
}

/// Renders the sphere with a MERL table of `analytic` and with `analytic_xml`, and compares
/// 8 × 8 blocks of 4 × 4 pixels and the channel means: |a − b| ≤ 5σ + ε·b, σ the two images'
/// combined standard error and ε the largest relative error of the table's interpolation
/// found over 20 000 random direction pairs (0 for a constant table).
fn compare_table_with_analytic(test: &str, analytic: &Bsdf, analytic_xml: &str) {
    let table = MerlTable::tabulate(|wo, wi| analytic.eval(&sp(), wo, wi));
    compare_file_with_analytic(test, &table.to_bytes(0.0), analytic, analytic_xml);
}

/// [`compare_table_with_analytic`] for the MERL file `merl_bytes`.
fn compare_file_with_analytic(test: &str, merl_bytes: &[u8], analytic: &Bsdf, analytic_xml: &str) {
    let dir = temp_dir(test);
    write_file(&dir, "t.binary", merl_bytes);
    let merl_file = write_file(
        &dir,
        "merl.xml",
        sphere_scene(r#"<bsdf type="merl"><string name="filename" value="t.binary"/></bsdf>"#),
    );
    let analytic_file = write_file(&dir, "analytic.xml", sphere_scene(analytic_xml));
    let spp = 64;
    // different seeds: the two images are independent, so σ² adds
    let (a, sa, scene) = render_with_stderr(&merl_file, &[], spp, 1);
    let (b, sb, _) = render_with_stderr(&analytic_file, &[], spp, 2);

    let merl = scene.scene.bsdfs.iter().find(|b| matches!(b, Bsdf::Merl(_))).unwrap();
    let mut rng = Pcg32::new(5, 9);
    let mut eps = 0f32;
    for _ in 0..20_000 {
        let mut dir = || {
            steradian::sampling::warp::square_to_uniform_hemisphere(Vec2::new(
                rng.next_f32(),
                rng.next_f32(),
            ))
        };
        let (wo, wi): (Vec3, Vec3) = (dir(), dir());
        let (x, y) = (merl.eval(&sp(), wo, wi), analytic.eval(&sp(), wo, wi));
        eps = eps.max(((x - y).abs() / y.max(Spectrum::splat(1e-6))).max_element());
    }
    let eps = eps as f64;

    let (mut chi2, mut worst_rel, mut n) = (0f64, 0f64, 0);
    for by in 0..8 {
        for bx in 0..8 {
            let (mut ma, mut mb, mut va, mut vb) = ([0f64; 3], [0f64; 3], [0f64; 3], [0f64; 3]);
            for y in by * 4..by * 4 + 4 {
                for x in bx * 4..bx * 4 + 4 {
                    let (pa, pb, ea, eb) = (a.get(x, y), b.get(x, y), sa.get(x, y), sb.get(x, y));
                    for c in 0..3 {
                        ma[c] += pa[c] as f64 / 16.0;
                        mb[c] += pb[c] as f64 / 16.0;
                        va[c] += (ea[c] as f64 / 16.0).powi(2);
                        vb[c] += (eb[c] as f64 / 16.0).powi(2);
                    }
                }
            }
            for c in 0..3 {
                let sigma = (va[c] + vb[c]).sqrt();
                let d = (ma[c] - mb[c]).abs();
                assert!(d <= 5.0 * sigma + eps * mb[c] + 1e-6, "{test}: block ({bx}, {by}) channel {c}: merl {} vs analytic {} (σ {sigma:.2e}, ε {eps:.2e})", ma[c], mb[c]);
                if mb[c] > 1e-3 {
                    worst_rel = f64::max(worst_rel, d / mb[c]);
                }
                if sigma > 0.0 {
                    chi2 += (d / sigma).powi(2);
                    n += 1;
                }
            }
        }
    }
    let (m, r) = (a.channel_means(), b.channel_means());
    // Jointly, without the ε allowance: Σz² over the noisy blocks is χ²(n) when the images
    // agree (the interpolation bias is far below σ on average), so it must stay below
    // n + 5·√(2n), five standard deviations of χ²(n). A wrong lookup fails this at once.
    let bound = n as f64 + 5.0 * (2.0 * n as f64).sqrt();
    eprintln!("{test}: ε = {eps:.2e}; Σz² = {chi2:.1} over {n} block-channels (bound {bound:.1}); worst relative block difference {worst_rel:.2e}; means {m:.5?} vs {r:.5?}");
    assert!(n > 100, "{test}: only {n} noisy blocks");
    assert!(chi2 <= bound, "{test}: Σz² = {chi2:.1} over {n} blocks exceeds {bound:.1}");
}

#[test]
fn lambertian_table_renders_like_diffuse() {
    let rho = Spectrum::new(0.7, 0.45, 0.2);
    let analytic = Bsdf::Diffuse(steradian::bsdf::Diffuse::new(rho.into()));
    compare_table_with_analytic(
        "lambert",
        &analytic,
        r#"<bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.45, 0.2"/></bsdf>"#,
    );
}

#[test]
fn phong_table_renders_like_phong() {
    let analytic = Bsdf::Phong(
        steradian::bsdf::Phong::new(
            Spectrum::new(0.4, 0.3, 0.1).into(),
            Spectrum::new(0.4, 0.5, 0.6).into(),
            15.0,
        )
        .unwrap(),
    );
    compare_table_with_analytic(
        "phong",
        &analytic,
        r#"<bsdf type="phong"><rgb name="diffuse_reflectance" value="0.4, 0.3, 0.1"/><rgb name="specular_reflectance" value="0.4, 0.5, 0.6"/><float name="exponent" value="15"/></bsdf>"#,
    );
}

#[test]
fn shipped_asset_renders_like_roughplastic() {
    let bytes = std::fs::read(repo_file(ASSET)).unwrap();
    compare_file_with_analytic(
        "asset",
        &bytes,
        &asset_bsdf(),
        r#"<bsdf type="roughplastic"><string name="distribution" value="ggx"/><float name="alpha" value="0.15"/><float name="int_ior" value="1.5"/><float name="ext_ior" value="1"/><rgb name="diffuse_reflectance" value="0.55, 0.12, 0.06"/></bsdf>"#,
    );
}

// ---------------------------------------------------------------------------------------------
// Loader errors

/// Writes `files` and a scene whose sphere has `bsdf` (the BSDF element at line 3, its
/// first property at line 4, column 5); loads it expecting an error and no panic.
fn load_err(test: &str, bsdf: &str, files: &[(&str, &[u8])]) -> (PathBuf, LoadError) {
    let dir = temp_dir(test);
    for (name, bytes) in files {
        write_file(&dir, name, bytes);
    }
    let xml =
        format!("<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n  {bsdf}\n</shape>\n</scene>");
    let path = write_file(&dir, "scene.xml", xml);
    match catch_unwind(AssertUnwindSafe(|| load_file(&path, &[]))) {
        Ok(Ok(_)) => panic!("expected an error for {bsdf}"),
        Ok(Err(e)) => (path, e),
        Err(_) => panic!("the loader panicked on {bsdf}"),
    }
}

const MERL_FILE: &str =
    "<bsdf type=\"merl\">\n    <string name=\"filename\" value=\"m.binary\"/>\n</bsdf>";

#[test]
fn merl_file_errors() {
    let (p, e) = load_err("merl-missing", MERL_FILE, &[]);
    check_error(&e, &p, 4, 5, &["<bsdf type=\"merl\">", "cannot read MERL file", "m.binary"]);

    let good = MerlTable::tabulate(|_, _| Spectrum::splat(0.1)).to_bytes(0.0);
    let (p, e) = load_err("merl-truncated", MERL_FILE, &[("m.binary", &good[..good.len() / 2])]);
    check_error(&e, &p, 4, 5, &["m.binary", "truncated", "34992012"]);

    let mut dims = good.clone();
    dims[0..4].copy_from_slice(&45i32.to_le_bytes());
    let (p, e) = load_err("merl-dims", MERL_FILE, &[("m.binary", &dims)]);
    check_error(&e, &p, 4, 5, &["wrong dimensions 45×90×180", "90×90×180"]);

    let (p, e) = load_err("merl-garbage", MERL_FILE, &[("m.binary", b"\x1f\x8bnot gzip at all")]);
    check_error(&e, &p, 4, 5, &["gzip"]);

    let (p, e) = load_err("merl-nofile", "<bsdf type=\"merl\"/>", &[]);
    check_error(&e, &p, 3, 3, &["missing 'filename'"]);
}

#[test]
fn phong_parameter_errors() {
    let (p, e) = load_err(
        "phong-exponent",
        "<bsdf type=\"phong\">\n    <float name=\"exponent\" value=\"-2\"/>\n</bsdf>",
        &[],
    );
    check_error(
        &e,
        &p,
        4,
        5,
        &["<bsdf type=\"phong\">", "exponent must be a finite number ≥ 0, got -2"],
    );

    let bsdf = "<bsdf type=\"phong\">\n    <rgb name=\"diffuse_reflectance\" value=\"0.6, 0.2, 0.2\"/>\n    <rgb name=\"specular_reflectance\" value=\"0.5\"/>\n</bsdf>";
    let (p, e) = load_err("phong-energy", bsdf, &[]);
    check_error(&e, &p, 4, 5, &["energy conservation", "≤ 1", "reaches 1.1"]);

    // specular only: the error is at the specular reflectance
    let bsdf =
        "<bsdf type=\"phong\">\n    <float name=\"specular_reflectance\" value=\"0.9\"/>\n</bsdf>";
    let (p, e) = load_err("phong-energy-default", bsdf, &[]);
    check_error(&e, &p, 4, 5, &["reaches 1.4"]);

    // a negative specular reflectance: the error is at it, not at the diffuse one before it
    let bsdf = "<bsdf type=\"phong\">\n    <rgb name=\"diffuse_reflectance\" value=\"0.2\"/>\n    <rgb name=\"specular_reflectance\" value=\"0.1, -0.1, 0.1\"/>\n</bsdf>";
    let (p, e) = load_err("phong-negative-specular", bsdf, &[]);
    check_error(&e, &p, 5, 5, &["'specular_reflectance' must be finite and non-negative"]);

    let (p, e) = load_err(
        "phong-unknown",
        "<bsdf type=\"phong\">\n    <float name=\"shininess\" value=\"2\"/>\n</bsdf>",
        &[],
    );
    check_error(&e, &p, 4, 5, &["unreferenced property 'shininess'"]);
}

#[test]
fn phong_defaults_and_parameters() {
    let load = |bsdf: &str| {
        let xml = format!(
            r#"<scene version="3.0.0"><integrator type="path"/><sensor type="perspective"/><shape type="sphere">{bsdf}</shape></scene>"#
        );
        let scene = steradian_mitsuba::load_string(&xml, Path::new("t.xml"), Path::new("."), &[])
            .unwrap_or_else(|e| panic!("{e}"));
        match scene.scene.bsdfs.into_iter().next().unwrap() {
            Bsdf::Phong(p) => p,
            b => panic!("{b:?}"),
        }
    };
    let p = load(r#"<bsdf type="phong"/>"#);
    let uv = Vec2::ZERO;
    assert_eq!(
        (
            p.diffuse_reflectance.eval(TexturePoint::at_uv(uv)),
            p.specular_reflectance.eval(TexturePoint::at_uv(uv)),
            p.exponent
        ),
        (Spectrum::splat(0.5), Spectrum::splat(0.2), 30.0)
    );
    let p = load(
        r#"<bsdf type="phong"><rgb name="diffuse_reflectance" value="0.1, 0.2, 0.3"/><float name="specular_reflectance" value="0.7"/><float name="exponent" value="0"/></bsdf>"#,
    );
    assert_eq!(
        (
            p.diffuse_reflectance.eval(TexturePoint::at_uv(uv)),
            p.specular_reflectance.eval(TexturePoint::at_uv(uv)),
            p.exponent
        ),
        (Spectrum::new(0.1, 0.2, 0.3), Spectrum::splat(0.7), 0.0)
    );
}
