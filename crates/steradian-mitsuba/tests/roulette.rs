//! Russian roulette (`path`'s `rr_depth` and steradian's own `rr_scale` κ, "Russian
//! roulette" in `integrator/path.rs`) changes the noise, never the expectation.
//!
//! The scene is an integrating sphere: the camera inside a closed sphere whose inner surface
//! reflects diffusely (albedo ρ) and emits Lₑ everywhere, so the radiance is the same along
//! every ray, L = Lₑ + ρ·L = Lₑ / (1 − ρ) in closed form. With ρ = 0.8 and `max_depth`
//! unbounded, four fifths of L arrives after the first bounce and only roulette ends the
//! paths, from the first bounce on (`rr_depth` 1): a survivor weighted by anything but 1/q, or
//! paths ended without it, would move the image away from Lₑ / (1 − ρ).

mod common;

/// Lₑ (W/(m²·sr)) and ρ of the sphere's inner surface.
const LE: f64 = 1.0;
const RHO: f64 = 0.8;

fn scene(rr_scale: Option<f32>) -> String {
    let rr_scale =
        rr_scale.map(|k| format!(r#"<float name="rr_scale" value="{k}"/>"#)).unwrap_or_default();
    format!(
        r#"<scene version="3.0.0">
        <integrator type="path"><integer name="max_depth" value="-1"/><integer name="rr_depth" value="1"/>
            <integer name="branches" value="2"/>{rr_scale}</integrator>
        <sensor type="perspective"><float name="fov" value="60"/>
            <transform name="to_world"><lookat origin="0, 0, 0.5" target="0, 0, 0" up="0, 1, 0"/></transform>
            <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/><rfilter type="box"/></film></sensor>
        <shape type="sphere"><float name="radius" value="2"/><boolean name="flip_normals" value="true"/>
            <bsdf type="diffuse"><rgb name="reflectance" value="{RHO}"/></bsdf>
            <emitter type="area"><rgb name="radiance" value="{LE}"/></emitter></shape>
        </scene>"#
    )
}

#[test]
fn roulette_keeps_the_integrating_sphere_radiance() {
    let expected = LE / (1.0 - RHO);
    let mut errors = Vec::new();
    // Mitsuba's κ = 1, steradian's default (4), and a harsher one
    for (seed, rr_scale) in [(1, Some(1.0)), (2, None), (3, Some(0.25))] {
        let (mean, se) = common::mean_and_error(&scene(rr_scale), "roulette.xml", seed);
        assert!(
            (mean - expected).abs() <= 5.0 * se,
            "rr_scale {rr_scale:?}: {mean} ± {se}, expected {expected}"
        );
        errors.push(se);
    }
    // Ending fewer paths early must lower the noise: the default (κ = 4) against κ = 1, and
    // κ = 1 against 0.25. With `rr_scale` ignored the three would agree within their noise.
    assert!(
        errors[1] < 0.8 * errors[0] && errors[0] < 0.8 * errors[2],
        "standard errors for κ = 1, 4, 0.25: {errors:?}"
    );
}

#[test]
fn rr_scale_must_be_positive() {
    for bad in ["0", "-1", "nan"] {
        let xml = scene(None).replace(
            r#"<integer name="branches" value="2"/>"#,
            &format!(r#"<float name="rr_scale" value="{bad}"/>"#),
        );
        let e = steradian_mitsuba::load_string(
            &xml,
            std::path::Path::new("roulette.xml"),
            std::path::Path::new("."),
            &[],
        )
        .expect_err("an error");
        assert!(e.to_string().contains("rr_scale must be a positive number"), "{e}");
        assert_eq!(e.pos.as_ref().map(|p| (p.line, p.col)), Some((3, 13)), "{e}");
    }
}
