//! The public closed-form radiometry cases (`scenes/validation/cases.json`): each renders its
//! scene at its own spp with a fixed seed and must meet the suite's tolerance in every
//! channel. Also the pure-math checks of the `radiometry` module.

use steradian_mitsuba::verify::{run_case, run_math_cases};

fn check(name: &str) {
    let r = run_case(name, 7, None, None).unwrap_or_else(|e| panic!("{name}: {e}"));
    eprintln!(
        "{name}: expected {:?} measured {:?} ± {:?} (z {:?}) bound {:?} in {:.2} s",
        r.expected, r.measured, r.stderr, r.z, r.bound, r.seconds
    );
    assert!(
        r.pass,
        "{name}: measured {:?}, expected {:?} within {:?}",
        r.measured, r.expected, r.bound
    );
}

macro_rules! cases {
    ($($name:ident),* $(,)?) => {$(
        #[test]
        fn $name() {
            check(stringify!($name));
        }
    )*};
}

cases!(
    point_normal_incidence,
    point_inverse_square_far,
    point_inverse_square_near,
    disk_on_axis_irradiance,
    rect_parallel_corner_irradiance,
    area_emitter_front_grazing,
    area_emitter_back_is_black,
    env_constant_irradiance,
    furnace_convex_sphere,
    emissive_room_radiance,
    rect_perpendicular_corner_irradiance,
    room_flux_balance,
    overcast_sky_horizontal_illuminance,
    roof_opening_sky_component,
    window_sky_component,
    sun_and_sky_horizontal_illuminance,
    sun_disk_radiance,
);

#[test]
fn every_case_has_a_test() {
    let mut names = steradian_mitsuba::verify::case_names();
    names.sort();
    let mut ours = vec![
        "point_normal_incidence",
        "point_inverse_square_far",
        "point_inverse_square_near",
        "disk_on_axis_irradiance",
        "rect_parallel_corner_irradiance",
        "area_emitter_front_grazing",
        "area_emitter_back_is_black",
        "env_constant_irradiance",
        "furnace_convex_sphere",
        "emissive_room_radiance",
        "rect_perpendicular_corner_irradiance",
        "room_flux_balance",
        "overcast_sky_horizontal_illuminance",
        "roof_opening_sky_component",
        "window_sky_component",
        "sun_and_sky_horizontal_illuminance",
        "sun_disk_radiance",
    ];
    ours.sort();
    assert_eq!(names, ours);
}

#[test]
fn math_cases_hold() {
    let results = run_math_cases().unwrap();
    assert_eq!(results.len(), 17);
    for r in &results {
        assert!(r.pass, "{}: {} vs {} (tol {})", r.name, r.measured, r.expected, r.tolerance);
    }
}
