//! Photometric files: parsing, symmetry, flux, sampling.

use glam::{Vec2, Vec3};

use super::*;
use crate::sampling::Pcg32;
use crate::testkit::chi2::{directions_pvalue, CapGrid};

const IES_0_90: &str = include_str!("testdata/cosine_3000lm_point_0-90.ies");
const IES_0_180: &str = include_str!("testdata/cosine_3000lm_point_0-180.ies");
const IES_SQUARE: &str = include_str!("testdata/cosine_3000lm_square300mm.ies");
const LDT_SQUARE: &str = include_str!("testdata/cosine_3000lm_square300mm.ldt");

/// The fixtures' distribution: a Lambertian downlight, I(γ) = I₀ cos γ below the horizontal,
/// Φ = π I₀ = 3000 lm.
const I0: f64 = 3000.0 / std::f64::consts::PI;

fn table(p: &Photometry) -> IntensityTable {
    IntensityTable::new(p).unwrap()
}

/// The direction (γ, C) in degrees, as the module docs define it.
fn dir(gamma: f64, c: f64) -> Vec3 {
    let (g, c) = (gamma.to_radians(), c.to_radians());
    Vec3::new((g.sin() * c.cos()) as f32, (g.sin() * c.sin()) as f32, -g.cos() as f32)
}

fn random_dir(rng: &mut Pcg32) -> Vec3 {
    crate::sampling::warp::square_to_uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()))
}

#[test]
fn ies_fixtures_give_the_cosine_downlight_and_its_3000_lumens() {
    for text in [IES_0_90, IES_0_180, IES_SQUARE] {
        let p = parse_ies(text).unwrap();
        assert_eq!(p.lamp_lumens, None, "absolute photometry states no lamp flux");
        let t = table(&p);
        // the flux of the bilinear table: within 0.5 % of the stated 3000 lm (the chords of
        // cos γ at 5° steps lie 0.1 % below it), and equal to a brute-force quadrature
        assert!((t.flux() / 3000.0 - 1.0).abs() < 5e-3, "Φ = {} lm", t.flux());
        let q = flux_by_quadrature(&t, 400);
        assert!((q / t.flux() - 1.0).abs() < 1e-3, "quadrature {q} vs {}", t.flux());
        for (g, want) in
            [(0.0, I0), (30.0, I0 * 30f64.to_radians().cos()), (95.0, 0.0), (180.0, 0.0)]
        {
            for c in [0.0, 77.0, 200.0, 359.0] {
                let got = t.eval(dir(g, c)) as f64;
                assert!((got - want).abs() <= 1e-4 * I0, "I({g}°, {c}°) = {got}, want {want}");
            }
        }
    }
    let square = parse_ies(IES_SQUARE).unwrap();
    assert!((square.opening[0] - 0.3).abs() < 1e-12 && (square.opening[1] - 0.3).abs() < 1e-12);
}

#[test]
fn tables_to_90_and_to_180_degrees_agree_everywhere() {
    let (a, b) = (table(&parse_ies(IES_0_90).unwrap()), table(&parse_ies(IES_0_180).unwrap()));
    let mut rng = Pcg32::new(3, 4);
    for _ in 0..10_000 {
        let d = random_dir(&mut rng);
        assert!((a.eval(d) - b.eval(d)).abs() <= 1e-3, "{d}: {} vs {}", a.eval(d), b.eval(d));
    }
    assert!((a.flux() - b.flux()).abs() < 1e-6 * a.flux());
}

#[test]
fn eulumdat_gives_what_the_same_luminaire_as_ies_gives() {
    let ldt = parse_eulumdat(LDT_SQUARE).unwrap();
    assert_eq!(ldt.lamp_lumens, Some(3000.0));
    assert!((ldt.opening[0] - 0.3).abs() < 1e-12 && (ldt.opening[1] - 0.3).abs() < 1e-12);
    let (a, b) = (table(&ldt), table(&parse_ies(IES_SQUARE).unwrap()));
    let mut rng = Pcg32::new(5, 6);
    for _ in 0..10_000 {
        let d = random_dir(&mut rng);
        assert!((a.eval(d) - b.eval(d)).abs() <= 1e-3, "{d}: {} vs {}", a.eval(d), b.eval(d));
    }
    assert!((a.flux() / 3000.0 - 1.0).abs() < 5e-3, "Φ = {}", a.flux());
}

/// A table with a value per (plane, angle) that tells the planes apart.
fn planes(horizontal: &[f64]) -> Photometry {
    let vertical = vec![0.0, 45.0, 90.0, 135.0, 180.0];
    let candela = horizontal
        .iter()
        .map(|&c| vertical.iter().map(|&g| 10.0 + c + 0.1 * g).collect())
        .collect();
    Photometry {
        vertical,
        horizontal: horizontal.to_vec(),
        candela,
        lamp_lumens: None,
        opening: [0.0; 3],
    }
}

#[test]
fn symmetric_tables_expand_by_their_mirror_planes() {
    let close = |a: f32, b: f32| (a - b).abs() <= 1e-4 * a.abs().max(1.0);
    // quadrant symmetry: C, 180° − C, 180° + C, 360° − C
    let t = table(&planes(&[0.0, 30.0, 60.0, 90.0]));
    for g in [20.0, 100.0] {
        let i = t.eval(dir(g, 30.0));
        for c in [150.0, 210.0, 330.0] {
            assert!(close(t.eval(dir(g, c)), i), "quadrant: C = {c}");
        }
        assert!(!close(t.eval(dir(g, 60.0)), i));
    }
    // mirror plane C0–C180: C and 360° − C
    let t = table(&planes(&[0.0, 45.0, 90.0, 135.0, 180.0]));
    assert!(close(t.eval(dir(50.0, 45.0)), t.eval(dir(50.0, 315.0))));
    assert!(!close(t.eval(dir(50.0, 45.0)), t.eval(dir(50.0, 135.0))));
    // mirror plane C90–C270: C and 180° − C
    let t = table(&planes(&[90.0, 135.0, 180.0, 225.0, 270.0]));
    assert!(close(t.eval(dir(50.0, 60.0)), t.eval(dir(50.0, 120.0))));
    assert!(close(t.eval(dir(50.0, 300.0)), t.eval(dir(50.0, 240.0))));
    // a full table closes the circle between its last plane and 360°
    let t = table(&planes(&[0.0, 90.0, 180.0, 270.0]));
    let mid = t.eval(dir(45.0, 315.0));
    let want = 0.5 * (t.eval(dir(45.0, 270.0)) + t.eval(dir(45.0, 0.0)));
    assert!(close(mid, want), "{mid} vs {want}");
    // an unknown layout is an error
    assert!(IntensityTable::new(&planes(&[10.0, 100.0])).is_err());
}

#[test]
fn sampling_matches_its_density_and_the_flux() {
    for p in [parse_ies(IES_0_180).unwrap(), planes(&[0.0, 30.0, 60.0, 90.0])] {
        let t = table(&p);
        let mut rng = Pcg32::new(7, 8);
        // the weights I/p average to the flux (a luminaire's emission sampling is unbiased)
        let n = 200_000;
        let (mut sum, mut sum2) = (0.0, 0.0);
        for _ in 0..n {
            let Some((d, pdf)) = t.sample(Vec2::new(rng.next_f32(), rng.next_f32())) else {
                continue;
            };
            assert!((d.length() - 1.0).abs() < 1e-5);
            assert!((t.pdf(d) - pdf).abs() <= 1e-3 * pdf, "{} vs {pdf}", t.pdf(d));
            let w = t.eval(d) as f64 / pdf as f64;
            sum += w;
            sum2 += w * w;
        }
        let mean = sum / n as f64;
        let se = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
        assert!(
            (mean - t.flux()).abs() < 4.0 * se + 1e-6 * t.flux(),
            "{mean} ± {se} vs {}",
            t.flux()
        );
        // the density's cell edges (every 5° of γ) cut the grid's cells: 32² points per cell
        let p = directions_pvalue(
            &CapGrid::SPHERE.with_sub(32),
            n,
            || t.sample(Vec2::new(rng.next_f32(), rng.next_f32())).map(|s| s.0),
            |d| t.pdf(d) as f64,
        );
        assert!(p > 0.01 / 4.0, "χ² p = {p}");
    }
}

#[test]
fn malformed_files_are_located_errors() {
    // cut after the candela values start: the line of the end
    let cut: String = IES_0_90.lines().take(11).collect::<Vec<_>>().join("\n");
    let e = parse_ies(&cut).unwrap_err();
    assert!(e.message.contains("ends before") && e.line >= 11, "{e}");
    let e = parse_ies("IESNA:LM-63-2002\n[TEST] x\n").unwrap_err();
    assert!(e.message.contains("TILT"), "{e}");
    let e = parse_ies(&IES_0_90.replace("TILT=NONE", "TILT=lamp.tlt")).unwrap_err();
    assert!(e.message.contains("tilt files are not supported") && e.line == 8, "{e}");
    let e = parse_ies(&IES_0_90.replace("1 -1 1 19 1 1 2", "1 -1 1 19 1 2 2")).unwrap_err();
    assert!(e.message.contains("type B is not supported") && e.line == 9, "{e}");
    let e = parse_ies(&IES_0_90.replace("954.929659", "95x")).unwrap_err();
    assert!(e.message.contains("'95x' is not a number") && e.line == 13, "{e}");
    let e = parse_ies(&IES_0_90.replace("954.929659", "-954.929659")).unwrap_err();
    assert!(e.message.contains("non-negative"), "{e}");
    let e = parse_ies(&format!("{IES_0_90} 7")).unwrap_err();
    assert!(e.message.contains("do not match"), "{e}");
    // TILT=INCLUDE: the multiplier at 0° applies
    let tilted = IES_0_90.replace("TILT=NONE", "TILT=INCLUDE\n1\n2\n0 90\n0.8 1.0");
    let (a, b) = (table(&parse_ies(&tilted).unwrap()), table(&parse_ies(IES_0_90).unwrap()));
    assert!((a.flux() / b.flux() - 0.8).abs() < 1e-6);
    // EULUMDAT
    let cut: String = LDT_SQUARE.lines().take(60).collect::<Vec<_>>().join("\n");
    let e = parse_eulumdat(&cut).unwrap_err();
    assert!(e.message.contains("ends before"), "{e}");
    let e = parse_eulumdat(&LDT_SQUARE.replacen("\r\n1\r\n1\r\n24", "\r\n1\r\n7\r\n24", 1))
        .unwrap_err();
    assert!(e.line == 3 && e.message.contains("symmetry"), "{e}");
    // a decimal comma reads as a point
    let comma =
        parse_eulumdat(&LDT_SQUARE.replace("1.0\r\n0\r\n1\r\n", "1,0\r\n0\r\n1\r\n")).unwrap();
    assert_eq!(comma, parse_eulumdat(LDT_SQUARE).unwrap());
}
