//! Loading textures and the BSDF adapters (`mask`, `blendbsdf`, `bumpmap`, `normalmap`) from
//! scene files: where Mitsuba accepts a texture, what the loaded values are, and the errors
//! (with file, line and column) for missing or corrupt images and mistyped parameters.

mod common;

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use steradian::bsdf::Bsdf;
use steradian::emitter::Emitter;
use steradian::testkit::{temp_dir, write_file};
use steradian::texture::{FilterType, Texture, TexturePoint, WrapMode};
use steradian::{Spectrum, Vec2};
use steradian_mitsuba::{load_file, LoadError};

fn assets() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/reference/textures")
}

/// Writes `body` (scene-level elements after an integrator and a sensor, from line 4) to
/// `name` in a fresh folder (tests run in parallel) next to copies of the reference assets,
/// and loads it.
fn load(name: &str, body: &str) -> Result<steradian::render::Job, LoadError> {
    load_at(name, body).1
}

/// [`load`], with the path of the scene file written.
fn load_at(name: &str, body: &str) -> (PathBuf, Result<steradian::render::Job, LoadError>) {
    static CALLS: AtomicUsize = AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, Ordering::Relaxed);
    let dir = temp_dir(&format!("textures-{call}"));
    for f in ["wall.png", "leaf.jpg", "leaf_mask.png", "bumps.png", "normals.png", "light.exr"] {
        std::fs::copy(assets().join(f), dir.join(f)).unwrap();
    }
    write_file(&dir, "corrupt.png", b"\x89PNG\r\n\x1a\n not really");
    write_file(&dir, "tri.obj", "v 0 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\n");
    let xml = format!("<scene version=\"3.0.0\">\n<integrator type=\"path\"/>\n<sensor type=\"perspective\"/>\n{body}\n</scene>");
    let path = write_file(&dir, name, xml);
    let scene = load_file(&path, &[]);
    (path, scene)
}

#[track_caller]
fn err(name: &str, body: &str, line: u32, col: u32, needles: &[&str]) {
    let (path, e) = match load_at(name, body) {
        (_, Ok(_)) => panic!("expected an error for {body}"),
        (path, Err(e)) => (path, e),
    };
    common::check_error(&e, &path, line, col, needles);
}

fn bsdf_of(body: &str) -> Bsdf {
    let scene = load("ok.xml", &format!("<shape type=\"rectangle\">{body}</shape>"))
        .unwrap_or_else(|e| panic!("{e}"));
    scene.scene.bsdfs.last().unwrap().clone()
}

#[test]
fn bitmap_parameters_and_values() {
    let b = bsdf_of(
        r#"<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="wall.png"/>
           <string name="filter_type" value="nearest"/><string name="wrap_mode" value="clamp"/>
           <transform name="to_uv"><scale x="2" y="3"/></transform></texture></bsdf>"#,
    );
    let Bsdf::Diffuse(d) = b else { panic!("{b:?}") };
    let Texture::Bitmap(t) = &d.reflectance else { panic!() };
    assert_eq!(
        (t.filter, t.wrap, t.resolution()),
        (FilterType::Nearest, WrapMode::Clamp, (64, 64))
    );
    assert_eq!(t.to_uv.apply(Vec2::new(0.1, 0.1)), Vec2::new(0.2, 0.3));
    // Mitsuba 3.9.1 (scalar_rgb, bilinear, repeat) at uv (0.3, 0.7) of wall.png
    let b = bsdf_of(
        r#"<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="wall.png"/></texture></bsdf>"#,
    );
    let Bsdf::Diffuse(d) = b else { panic!() };
    let v = d.reflectance.eval(TexturePoint::at_uv(Vec2::new(0.3, 0.7)));
    let mitsuba = Spectrum::new(MITSUBA_WALL[0], MITSUBA_WALL[1], MITSUBA_WALL[2]);
    assert!((v - mitsuba).abs().max_element() < 1e-3, "{v} vs {mitsuba}");
    // JPEG: decoders may differ by one code value (≈ 0.4 % after sRGB decoding)
    let b = bsdf_of(
        r#"<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="leaf.jpg"/><string name="filter_type" value="nearest"/></texture></bsdf>"#,
    );
    let Bsdf::Diffuse(d) = b else { panic!() };
    let v = d.reflectance.eval(TexturePoint::at_uv(Vec2::new(0.5, 0.5)));
    let mitsuba = Spectrum::new(MITSUBA_LEAF[0], MITSUBA_LEAF[1], MITSUBA_LEAF[2]);
    assert!((v - mitsuba).abs().max_element() < 0.01 * mitsuba.max_element(), "{v} vs {mitsuba}");
}

/// `mi.load_dict({'type': 'bitmap', 'filename': 'wall.png'}).eval(si)` at uv (0.3, 0.7).
const MITSUBA_WALL: [f32; 3] = [0.739077, 0.29277, 0.0262082];
/// The same for leaf.jpg, nearest, at uv (0.5, 0.5).
const MITSUBA_LEAF: [f32; 3] = [0.266356, 0.672443, 0.0822828];

#[test]
fn textures_wherever_mitsuba_takes_them() {
    let tex = r#"<texture type="checkerboard" name="NAME"><rgb name="color0" value="0.1, 0.2, 0.3"/></texture>"#;
    for (bsdf, names) in [
        ("diffuse", &["reflectance"][..]),
        ("plastic", &["diffuse_reflectance", "specular_reflectance"][..]),
        ("roughplastic", &["diffuse_reflectance", "specular_reflectance"][..]),
        ("conductor", &["specular_reflectance"][..]),
        ("roughconductor", &["specular_reflectance"][..]),
        ("dielectric", &["specular_reflectance", "specular_transmittance"][..]),
        ("thindielectric", &["specular_reflectance", "specular_transmittance"][..]),
        ("roughdielectric", &["specular_reflectance", "specular_transmittance"][..]),
    ] {
        let body: String = names.iter().map(|n| tex.replace("NAME", n)).collect();
        bsdf_of(&format!("<bsdf type=\"{bsdf}\">{body}</bsdf>"));
    }
    // roughness textures: roughconductor and roughdielectric (alpha or alpha_u/alpha_v)
    let a = r#"<texture type="bitmap" name="NAME"><string name="filename" value="bumps.png"/><boolean name="raw" value="true"/></texture>"#;
    let Bsdf::RoughConductor(c) =
        bsdf_of(&format!("<bsdf type=\"roughconductor\">{}</bsdf>", a.replace("NAME", "alpha")))
    else {
        panic!()
    };
    let (u, v) = *c.alpha_textures.clone().unwrap();
    assert_eq!(u, v);
    assert!(matches!(u, Texture::Bitmap(_)));
    let Bsdf::RoughDielectric(d) = bsdf_of(&format!(
        "<bsdf type=\"roughdielectric\">{}<float name=\"alpha_v\" value=\"0.3\"/></bsdf>",
        a.replace("NAME", "alpha_u")
    )) else {
        panic!()
    };
    let (u, v) = *d.alpha_textures.clone().unwrap();
    assert!(
        matches!((u, v), (Texture::Bitmap(_), Texture::Constant(c)) if c == Spectrum::splat(0.3))
    );
    // constant roughness keeps the plain distribution
    let Bsdf::RoughConductor(c) =
        bsdf_of(r#"<bsdf type="roughconductor"><float name="alpha" value="0.2"/></bsdf>"#)
    else {
        panic!()
    };
    assert!(c.alpha_textures.is_none() && c.distribution.alpha_u == 0.2);
    // area light radiance, from a scene-level texture by reference
    let scene = load(
        "ok.xml",
        r#"<texture type="bitmap" id="sky"><string name="filename" value="light.exr"/><string name="filter_type" value="nearest"/></texture>
           <shape type="rectangle"><emitter type="area"><ref name="radiance" id="sky"/></emitter></shape>"#,
    )
    .unwrap();
    let Emitter::Area(a) = &scene.scene.emitters[0] else { panic!() };
    // light.exr texel (0, 0) = (16, 15, 13)
    assert_eq!(
        a.radiance.eval(TexturePoint::at_uv(Vec2::new(0.1, 0.1))),
        Spectrum::new(16.0, 15.0, 13.0)
    );
}

#[test]
fn adapters_load_with_mitsuba_defaults() {
    let Bsdf::Mask(m) = bsdf_of(r#"<bsdf type="mask"><bsdf type="diffuse"/></bsdf>"#) else {
        panic!()
    };
    assert_eq!(m.opacity, Texture::Constant(Spectrum::splat(0.5)));
    let Bsdf::Mask(m) = bsdf_of(
        r#"<bsdf type="mask"><texture type="bitmap" name="opacity"><string name="filename" value="leaf_mask.png"/></texture><bsdf type="diffuse"/></bsdf>"#,
    ) else {
        panic!()
    };
    assert_eq!(
        (
            m.opacity.eval_1(TexturePoint::at_uv(Vec2::new(0.5, 0.5))),
            m.opacity.eval_1(TexturePoint::at_uv(Vec2::new(0.01, 0.5)))
        ),
        (1.0, 0.0)
    );
    let Bsdf::BlendBsdf(b) = bsdf_of(
        r#"<bsdf type="blendbsdf"><float name="weight" value="0.3"/><bsdf type="diffuse"/><bsdf type="conductor"/></bsdf>"#,
    ) else {
        panic!()
    };
    assert!(matches!((&*b.bsdf0, &*b.bsdf1), (Bsdf::Diffuse(_), Bsdf::Conductor(_))));
    assert_eq!(b.weight.eval_1(TexturePoint::at_uv(Vec2::ZERO)), 0.3);
    let Bsdf::BumpMap(b) = bsdf_of(
        r#"<bsdf type="bumpmap"><texture type="bitmap"><string name="filename" value="bumps.png"/><boolean name="raw" value="true"/></texture><bsdf type="roughplastic"/></bsdf>"#,
    ) else {
        panic!()
    };
    assert_eq!(b.scale, 1.0);
    let Bsdf::NormalMap(n) = bsdf_of(
        r#"<bsdf type="normalmap"><texture type="bitmap" name="normalmap"><string name="filename" value="normals.png"/><boolean name="raw" value="true"/></texture><bsdf type="diffuse"/></bsdf>"#,
    ) else {
        panic!()
    };
    assert!(matches!(n.normals, Texture::Bitmap(_)));
}

#[test]
fn missing_and_corrupt_images() {
    let body = "<shape type=\"rectangle\">\n<bsdf type=\"diffuse\">\n<texture type=\"bitmap\" name=\"reflectance\">\n  <string name=\"filename\" value=\"nowhere.png\"/>\n</texture></bsdf></shape>";
    err("missing.xml", body, 7, 3, &["nowhere.png", "<texture type=\"bitmap\">"]);
    err(
        "corrupt.xml",
        &body.replace("nowhere.png", "corrupt.png"),
        7,
        3,
        &["corrupt.png", "cannot read image"],
    );
    err(
        "text.xml",
        &body.replace("nowhere.png", "text.xml"),
        7,
        3,
        &["text.xml", "not a PNG, JPEG, OpenEXR, Radiance RGBE"],
    );
}

#[test]
fn bad_bitmap_options() {
    let tex = |extra: &str| {
        format!("<shape type=\"rectangle\"><bsdf type=\"diffuse\"><texture type=\"bitmap\" name=\"reflectance\"><string name=\"filename\" value=\"wall.png\"/>\n{extra}\n</texture></bsdf></shape>")
    };
    err(
        "wrap.xml",
        &tex("  <string name=\"wrap_mode\" value=\"wrap\"/>"),
        5,
        3,
        &["invalid wrap_mode \"wrap\"", "\"repeat\", \"mirror\", \"clamp\""],
    );
    err(
        "filter.xml",
        &tex("  <string name=\"filter_type\" value=\"cubic\"/>"),
        5,
        3,
        &["invalid filter_type \"cubic\"", "\"bilinear\", \"nearest\""],
    );
    err(
        "raw.xml",
        &tex("  <string name=\"raw\" value=\"yes\"/>"),
        5,
        3,
        &["'raw'", "must be boolean"],
    );
    err(
        "unused.xml",
        &tex("  <float name=\"gamma\" value=\"2.2\"/>"),
        5,
        3,
        &["unreferenced property 'gamma'"],
    );
    err(
        "nofile.xml",
        "<texture type=\"bitmap\" id=\"t\"/>",
        4,
        1,
        &["missing parameter 'filename'"],
    );
    err(
        "type.xml",
        "<texture type=\"noise\" id=\"t\"/>",
        4,
        1,
        &["unknown texture plugin type 'noise'", "bitmap, checkerboard"],
    );
}

#[test]
fn mistyped_parameters() {
    // a texture where Mitsuba takes only a number
    err(
        "ior.xml",
        "<shape type=\"sphere\"><bsdf type=\"dielectric\">\n  <texture type=\"checkerboard\" name=\"int_ior\"/>\n</bsdf></shape>",
        5,
        3,
        &["unreferenced object <texture type=\"checkerboard\">"],
    );
    // a BSDF where a texture belongs
    err("refl.xml", "<shape type=\"sphere\"><bsdf type=\"diffuse\">\n  <bsdf type=\"diffuse\" name=\"reflectance\"/>\n</bsdf></shape>", 5, 3, &["'reflectance' must be a texture or a value"]);
    err("str.xml", "<shape type=\"sphere\"><bsdf type=\"mask\">\n  <string name=\"opacity\" value=\"half\"/><bsdf type=\"diffuse\"/>\n</bsdf></shape>", 5, 3, &["'opacity'", "must be rgb, spectrum or float"]);
    err("blendw.xml", "<shape type=\"sphere\">\n<bsdf type=\"blendbsdf\"><bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf></shape>", 5, 1, &["missing parameter 'weight'"]);
    err("blend1.xml", "<shape type=\"sphere\">\n<bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.5\"/><bsdf type=\"diffuse\"/></bsdf></shape>", 5, 1, &["two nested BSDFs, got 1"]);
    err("mask2.xml", "<shape type=\"sphere\">\n<bsdf type=\"mask\"><bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf></shape>", 5, 1, &["exactly one nested BSDF, got 2"]);
    err(
        "bumpcheck.xml",
        "<shape type=\"sphere\"><bsdf type=\"bumpmap\">\n  <texture type=\"checkerboard\"/><bsdf type=\"diffuse\"/>\n</bsdf></shape>",
        5,
        3,
        &["checkerboard or mesh_attribute has no gradient"],
    );
    // Mitsuba's roughplastic precomputes tables for one α: numbers only
    err(
        "rpalpha.xml",
        "<shape type=\"sphere\"><bsdf type=\"roughplastic\">\n  <texture type=\"checkerboard\" name=\"alpha\"/>\n</bsdf></shape>",
        5,
        3,
        &["'alpha' of <bsdf type=\"roughplastic\"> cannot be spatially varying", "(float)"],
    );
    err("aniso.xml", "<shape type=\"sphere\">\n<bsdf type=\"roughconductor\"><texture type=\"checkerboard\" name=\"alpha_u\"/></bsdf></shape>", 5, 1, &["both 'alpha_u' and 'alpha_v'"]);
    err(
        "bumpnone.xml",
        "<shape type=\"sphere\">\n<bsdf type=\"bumpmap\"><bsdf type=\"diffuse\"/></bsdf></shape>",
        5,
        1,
        &["exactly one nested texture"],
    );
    err(
        "nmap.xml",
        "<shape type=\"sphere\">\n<bsdf type=\"normalmap\"><bsdf type=\"diffuse\"/></bsdf></shape>",
        5,
        1,
        &["missing parameter 'normalmap'"],
    );
    err("scale.xml", "<shape type=\"sphere\"><bsdf type=\"bumpmap\"><texture type=\"bitmap\"><string name=\"filename\" value=\"bumps.png\"/></texture>\n  <string name=\"scale\" value=\"2\"/><bsdf type=\"diffuse\"/></bsdf></shape>", 5, 3, &["'scale'", "must be float"]);
}

#[test]
fn reference_scene_loads() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/textures.xml");
    let scene = load_file(&path, &[]).unwrap();
    let kinds: Vec<&str> = scene
        .scene
        .bsdfs
        .iter()
        .map(|b| match b {
            Bsdf::Mask(_) => "mask",
            Bsdf::BlendBsdf(_) => "blendbsdf",
            Bsdf::BumpMap(_) => "bumpmap",
            Bsdf::NormalMap(_) => "normalmap",
            _ => "other",
        })
        .filter(|k| *k != "other")
        .collect();
    assert_eq!(kinds, ["bumpmap", "normalmap", "blendbsdf", "mask"]);
}

/// A floor under a small area light, seen from above, with an optional `mask` (opacity
/// `opacity`) between them; 32×32.
fn mask_scene(integrator: &str, opacity: Option<f32>) -> String {
    let mask = opacity.map_or(String::new(), |a| {
        format!(
            r#"<shape type="rectangle"><transform name="to_world"><scale value="0.6"/><rotate x="1" angle="90"/><translate y="1.0"/></transform>
               <bsdf type="mask"><float name="opacity" value="{a}"/><bsdf type="diffuse"/></bsdf></shape>"#
        )
    });
    format!(
        r#"<scene version="3.0.0"><integrator type="{integrator}"/>
        <sensor type="perspective"><float name="fov" value="60"/>
            <transform name="to_world"><lookat origin="0, 4, 0.01" target="0, 0, 0" up="0, 0, -1"/></transform>
            <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="32"/></film></sensor>
        <shape type="rectangle"><transform name="to_world"><scale value="0.5"/><rotate x="1" angle="90"/><translate y="2"/></transform>
            <emitter type="area"><rgb name="radiance" value="10"/></emitter></shape>
        <shape type="rectangle"><transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/></transform><bsdf type="diffuse"/></shape>
        {mask}</scene>"#
    )
}

/// Image means of independent renders (seeds 1..=n): their mean and standard error.
fn mean_and_se(xml: &str, spp: u32, n: u64) -> (f64, f64) {
    use steradian::render::{render, RenderOptions};
    let scene =
        steradian_mitsuba::load_string(xml, Path::new("mask.xml"), Path::new("."), &[]).unwrap();
    let means: Vec<f64> = (1..=n)
        .map(|seed| {
            let out = render(
                &scene,
                &RenderOptions { spp: Some(spp), seed: Some(seed), ..Default::default() },
            )
            .unwrap();
            out.film().develop().channel_means()[0]
        })
        .collect();
    let m = means.iter().sum::<f64>() / n as f64;
    let var = means.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1) as f64;
    (m, (var / n as f64).sqrt())
}

#[test]
fn masks_in_path_and_direct_behave_as_in_mitsuba() {
    // path: a fully transparent mask changes nothing on average, although shadow rays stop at
    // it (the light behind it is found by BSDF sampling through the null lobe)
    let (m0, s0) = mean_and_se(&mask_scene("path", None), 64, 6);
    let (m1, s1) = mean_and_se(&mask_scene("path", Some(0.0)), 64, 6);
    let se = (s0 * s0 + s1 * s1).sqrt();
    assert!((m1 - m0).abs() < 5.0 * se, "path: {m1} vs {m0} ± {se}");
    // direct: the same transparent mask casts the full shadow, because `direct` neither
    // transmits shadow rays nor follows the null lobe to an emitter. Mitsuba 3.9.1 (1024 spp,
    // llvm_ad_rgb): image means 0.076795 with the mask, 0.090788 without: ratio 0.845872.
    let (d0, e0) = mean_and_se(&mask_scene("direct", None), 64, 6);
    let (d1, e1) = mean_and_se(&mask_scene("direct", Some(0.0)), 64, 6);
    let ratio = d1 / d0;
    let se = ratio * ((e0 / d0).powi(2) + (e1 / d1).powi(2)).sqrt();
    assert!((ratio - 0.845872).abs() < 5.0 * se + 1e-4, "direct: ratio {ratio} ± {se}");
}

/// Hits `shape_xml` along the ray (o, d).
fn hit(
    scene: &steradian::render::Job,
    o: [f32; 3],
    d: [f32; 3],
) -> steradian::geometry::SurfaceInteraction {
    let ray = steradian::geometry::Ray::infinite(
        steradian::Vec3::from(o),
        steradian::Vec3::from(d).normalize(),
    );
    scene.scene.intersect(&ray).expect("the ray must hit")
}

#[test]
fn dpdu_dpdv_match_mitsuba_and_finite_differences() {
    use steradian::Vec3;
    // Mitsuba 3.9.1 (scalar_rgb) si.dp_du, si.dp_dv for the same shapes and rays
    /// shape, ray origin and direction, Mitsuba's dp/du and dp/dv
    type Case = (&'static str, [f32; 3], [f32; 3], [f32; 3], [f32; 3]);
    let cases: [Case; 6] = [
        (
            r#"<shape type="rectangle"><transform name="to_world"><scale x="2" y="3" z="1"/></transform></shape>"#,
            [0.5, 0.7, 5.0],
            [0.0, 0.0, -1.0],
            [4.0, 0.0, 0.0],
            [0.0, 6.0, 0.0],
        ),
        (
            r#"<shape type="disk"><transform name="to_world"><scale x="2" y="2" z="1"/></transform></shape>"#,
            [0.6, 0.8, 5.0],
            [0.0, 0.0, -1.0],
            [1.2, 1.6, 0.0],
            [-5.02655, 3.76991, 0.0],
        ),
        (
            r#"<shape type="sphere"><float name="radius" value="2"/></shape>"#,
            [0.6, 0.8, 5.0],
            [0.0, 0.0, -1.0],
            [-5.02655, 3.76991, 0.0],
            [3.26484, 4.35312, -std::f32::consts::PI],
        ),
        (
            r#"<shape type="cylinder"><float name="radius" value="2"/></shape>"#,
            [5.0, 0.8, 0.3],
            [-1.0, 0.0, 0.0],
            [-5.02655, 11.5173, 0.0],
            [0.0, 0.0, 1.0],
        ),
        (
            r#"<shape type="cube"/>"#,
            [0.3, 0.2, 5.0],
            [0.0, 0.0, -1.0],
            [0.0, 2.0, 0.0],
            [2.0, 0.0, 0.0],
        ),
        (
            r#"<shape type="cube"/>"#,
            [5.0, 0.3, 0.2],
            [-1.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0, 0.0, -2.0],
        ),
    ];
    for (xml, o, d, dpdu, dpdv) in cases {
        let scene = load("dp.xml", xml).unwrap();
        let si = hit(&scene, o, d);
        assert!(
            (si.dpdu - Vec3::from(dpdu)).length() < 1e-4 * (1.0 + si.dpdu.length()),
            "{xml}: dpdu {} vs {dpdu:?}",
            si.dpdu
        );
        assert!(
            (si.dpdv - Vec3::from(dpdv)).length() < 1e-4 * (1.0 + si.dpdv.length()),
            "{xml}: dpdv {} vs {dpdv:?}",
            si.dpdv
        );
        // first order: a nearby hit moves by dpdu·Δu + dpdv·Δv
        for off in [[1e-3, 0.0, 0.0], [0.0, 1e-3, 0.0], [0.0, 0.0, 1e-3]] {
            let o2 = [o[0] + off[0], o[1] + off[1], o[2] + off[2]];
            let si2 = hit(&scene, o2, d);
            let (dp, duv) = (si2.p - si.p, si2.uv - si.uv);
            if dp.length() < 1e-5 {
                continue; // the offset is along the ray
            }
            let pred = si.dpdu * duv.x + si.dpdv * duv.y;
            assert!((pred - dp).length() < 2e-2 * dp.length(), "{xml} {off:?}: Δp {dp} vs {pred}");
        }
    }
    // a mesh without uvs is parametrised by its barycentrics: uv = (b1, b2), dpdu = p1 − p0,
    // dpdv = p2 − p0 (Mitsuba 3.9.1: uv (0.2, 0.3), dp_du (2, 0, 0), dp_dv (0, 1, 0))
    let scene =
        load("dp.xml", r#"<shape type="obj"><string name="filename" value="tri.obj"/></shape>"#)
            .unwrap();
    let si = hit(&scene, [0.4, 0.3, 1.0], [0.0, 0.0, -1.0]);
    assert!((si.uv - Vec2::new(0.2, 0.3)).length() < 1e-6, "{}", si.uv);
    assert_eq!((si.dpdu, si.dpdv), (Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)));
}

/// `rawconstant` is the constant it holds (a float or a 3-vector, as Mitsuba 3.9.1 takes it);
/// `<rgb>`, a missing value and a negative reflectance are located errors.
#[test]
fn rawconstant_is_its_value() {
    let raw = |value: &str| {
        bsdf_of(&format!(
            "<bsdf type=\"diffuse\"><texture type=\"rawconstant\" name=\"reflectance\">{value}</texture></bsdf>"
        ))
    };
    let reflectance = |b: Bsdf| match b {
        Bsdf::Diffuse(d) => d.reflectance,
        other => panic!("{other:?}"),
    };
    assert_eq!(
        reflectance(raw(r#"<vector name="value" value="0.2, 0.4, 0.6"/>"#)),
        Texture::Constant(Spectrum::new(0.2, 0.4, 0.6))
    );
    assert_eq!(
        reflectance(raw(r#"<float name="value" value="0.3"/>"#)),
        Texture::Constant(Spectrum::splat(0.3))
    );
    let shape = "<shape type=\"rectangle\"><bsdf type=\"diffuse\">";
    let col = (shape.len() + 1) as u32;
    err(
        "raw-rgb.xml",
        &format!("{shape}<texture type=\"rawconstant\" name=\"reflectance\"><rgb name=\"value\" value=\"0.5\"/></texture></bsdf></shape>"),
        4,
        col + 47,
        &["'value'", "float or a 3-vector"],
    );
    err(
        "raw-missing.xml",
        &format!("{shape}<texture type=\"rawconstant\" name=\"reflectance\"/></bsdf></shape>"),
        4,
        col,
        &["missing parameter 'value'"],
    );
    err(
        "raw-negative.xml",
        &format!("{shape}<texture type=\"rawconstant\" name=\"reflectance\"><float name=\"value\" value=\"-0.5\"/></texture></bsdf></shape>"),
        4,
        col,
        &["'reflectance' must be finite and non-negative"],
    );
}
