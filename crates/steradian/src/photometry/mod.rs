//! Photometric files: a luminaire's luminous intensity I(γ, C) in candela, as its maker
//! publishes it, in IES LM-63 (`ies.rs`) or EULUMDAT (`eulumdat.rs`) form, and the table
//! ([`IntensityTable`]) that the `luminaire` emitter evaluates and samples.
//!
//! **Angles** (type C photometry, the one both formats share): γ is the vertical angle from the
//! photometric nadir (0°, straight down) to the zenith (180°), C the azimuth of the half-plane
//! through the vertical axis (C0 the luminaire's reference plane, increasing counter-clockwise
//! seen from above). With z up, nadir −z and C0 along +x, the direction (γ, C) is
//!   d = (sin γ cos C, sin γ sin C, −cos γ).
//! A file may give only some C planes and rely on symmetry: one plane (rotational symmetry),
//! 0°–90° (both C0–C180 and C90–C270 planes are mirror planes), 0°–180° (mirror plane
//! C0–C180) or 90°–270° (mirror plane C90–C270); the table expands them to the full circle.
//! Outside the file's vertical range (a 0°–90° table has nothing above the horizontal) I = 0.
//!
//! **Interpolation.** Bilinear in (γ, C) between the tabulated angles, as Radiance's `ies2rad`
//! output and the common viewers do (neither format prescribes one). The flux
//! Φ = ∫ I dω (lm) is the exact integral of that interpolant.
//!
//! **Sampling.** A cell between two vertical and two horizontal angles is chosen with
//! probability proportional to its flux, and a direction uniformly by solid angle inside it
//! (cos γ and C uniform), so the density p(ω) = P(cell)/Ω(cell) is exact and I(ω)/p(ω) varies
//! only as much as I inside one cell.

mod eulumdat;
mod ies;

pub use eulumdat::parse_eulumdat;
pub use ies::parse_ies;

use std::fmt;

use glam::{Vec2, Vec3};

use crate::sampling::piecewise_constant::PiecewiseConstant2D;

/// What a photometric file holds, in the units of the file's own definitions resolved: angles
/// in degrees, intensities in candela (multipliers and lamp flux applied).
#[derive(Clone, Debug, PartialEq)]
pub struct Photometry {
    /// Vertical angles γ in degrees, increasing, within [0, 180].
    pub vertical: Vec<f64>,
    /// Horizontal angles C in degrees, increasing, within [0, 360].
    pub horizontal: Vec<f64>,
    /// I in cd: `candela[h][v]` at `horizontal[h]`, `vertical[v]`.
    pub candela: Vec<Vec<f64>>,
    /// The luminous flux the file states for its lamps (lm), where it states one: IES's
    /// lamps × lumens per lamp (none for absolute photometry), EULUMDAT's lamp flux.
    pub lamp_lumens: Option<f64>,
    /// The luminous opening, m: width (along C90), length (along C0), height.
    pub opening: [f64; 3],
}

/// A malformed photometric file: the line (1-based) and what is wrong there.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PhotometryError {
    pub line: usize,
    pub message: String,
}

impl PhotometryError {
    pub(crate) fn new(line: usize, message: impl Into<String>) -> Self {
        PhotometryError { line, message: message.into() }
    }
}

impl fmt::Display for PhotometryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

impl std::error::Error for PhotometryError {}

/// Checks the angles and values of a parsed table (`line` for the messages: where the data
/// start).
pub(crate) fn check(p: &Photometry, line: usize) -> Result<(), PhotometryError> {
    let err = |m: String| Err(PhotometryError::new(line, m));
    let increasing = |a: &[f64]| a.windows(2).all(|w| w[0] < w[1]);
    if p.vertical.is_empty() || !increasing(&p.vertical) {
        return err("the vertical angles must be given in increasing order".into());
    }
    if p.vertical[0] < 0.0 || p.vertical[p.vertical.len() - 1] > 180.0 {
        return err(format!(
            "vertical angles must lie in [0°, 180°], got {}° to {}°",
            p.vertical[0],
            p.vertical[p.vertical.len() - 1]
        ));
    }
    if p.horizontal.is_empty() || !increasing(&p.horizontal) {
        return err("the horizontal angles must be given in increasing order".into());
    }
    if p.horizontal[0] < 0.0 || p.horizontal[p.horizontal.len() - 1] > 360.0 {
        return err("horizontal angles must lie in [0°, 360°]".into());
    }
    for row in &p.candela {
        if let Some(v) = row.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
            return err(format!("intensities must be finite and non-negative, got {v}"));
        }
    }
    Ok(())
}

/// A luminous intensity distribution over the whole sphere (see the module docs), with its
/// flux and sampling distribution.
#[derive(Clone, Debug, PartialEq)]
pub struct IntensityTable {
    /// γ in radians, increasing; I = 0 outside [γ₀, γ_last].
    gamma: Vec<f32>,
    /// C in radians, increasing from 0 to 2π (the last repeats the first).
    c: Vec<f32>,
    /// cd, `candela[ic * gamma.len() + ig]`.
    candela: Vec<f32>,
    /// Φ = ∫ I dω, lm.
    flux: f64,
    /// Over the (C cells) × (γ cells), by flux.
    distribution: PiecewiseConstant2D,
    /// Each cell's probability over its solid angle, 1/sr (the density inside it).
    cell_pdf: Vec<f32>,
}

impl IntensityTable {
    /// The table of a photometric file: symmetric planes expanded to the full circle.
    pub fn new(p: &Photometry) -> Result<Self, String> {
        if p.vertical.len() < 2 {
            return Err("at least two vertical angles are needed".into());
        }
        let (h0, h_last) = (p.horizontal[0], p.horizontal[p.horizontal.len() - 1]);
        // the given planes as (C°, row) over the full circle
        let given: Vec<(f64, &Vec<f64>)> = p.horizontal.iter().copied().zip(&p.candela).collect();
        let mirror = |planes: &mut Vec<(f64, &Vec<f64>)>, f: &dyn Fn(f64) -> f64| {
            let extra: Vec<_> = planes.iter().map(|&(c, r)| (f(c), r)).collect();
            planes.extend(extra);
        };
        let mut planes: Vec<(f64, &Vec<f64>)>;
        if p.horizontal.len() == 1 {
            planes = vec![(0.0, given[0].1), (360.0, given[0].1)];
        } else if h0 == 0.0 && h_last == 90.0 {
            planes = given.clone();
            mirror(&mut planes, &|c| 180.0 - c);
            mirror(&mut planes, &|c| 360.0 - c);
        } else if h0 == 0.0 && h_last == 180.0 {
            planes = given.clone();
            mirror(&mut planes, &|c| 360.0 - c);
        } else if h0 == 90.0 && h_last == 270.0 {
            planes = given.clone();
            // the mirror image of C about the C90–C270 plane is 180° − C (mod 360°)
            mirror(&mut planes, &|c| (540.0 - c) % 360.0);
        } else if h0 == 0.0 && h_last > 180.0 {
            planes = given.clone();
        } else {
            return Err(format!(
                "horizontal angles {h0}° to {h_last}° match none of the symmetries (one plane, \
                 0–90°, 0–180°, 90–270°, 0–360°)"
            ));
        }
        planes.sort_by(|a, b| a.0.total_cmp(&b.0));
        planes.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-9);
        // close the circle: the plane at 360° is the one at 0°
        if planes[planes.len() - 1].0 < 360.0 {
            let first = planes[0].1;
            planes.push((360.0, first));
        }
        if planes[0].0 > 0.0 {
            return Err("the C planes do not start at 0°".into());
        }
        let gamma: Vec<f32> = p.vertical.iter().map(|g| g.to_radians() as f32).collect();
        let c: Vec<f32> = planes.iter().map(|(c, _)| c.to_radians() as f32).collect();
        let candela: Vec<f32> =
            planes.iter().flat_map(|(_, row)| row.iter().map(|&v| v as f32)).collect();
        let (ng, nc) = (gamma.len(), c.len());
        // each cell's flux: the exact integral of the bilinear interpolant over the cell
        let mut cells = Vec::with_capacity((nc - 1) * ng.saturating_sub(1));
        let mut solid = Vec::with_capacity(cells.capacity());
        let mut flux = 0.0;
        for ic in 0..nc - 1 {
            let dc = (c[ic + 1] - c[ic]) as f64;
            for ig in 0..ng.saturating_sub(1) {
                let (g0, g1) = (gamma[ig] as f64, gamma[ig + 1] as f64);
                let dg = g1 - g0;
                // ∫ (1 − s) sin γ dγ and ∫ s sin γ dγ over the cell, s = (γ − γ₀)/Δγ
                let w1 = (-dg * g1.cos() + g1.sin() - g0.sin()) / dg;
                let w0 = (g0.cos() - g1.cos()) - w1;
                let at = |jc: usize, jg: usize| candela[jc * ng + jg] as f64;
                let lo = 0.5 * (at(ic, ig) + at(ic + 1, ig));
                let hi = 0.5 * (at(ic, ig + 1) + at(ic + 1, ig + 1));
                let cell = dc * (w0 * lo + w1 * hi);
                cells.push(cell as f32);
                solid.push(dc * (g0.cos() - g1.cos()));
                flux += cell;
            }
        }
        if flux.is_nan() || flux <= 0.0 {
            return Err("the luminaire emits no light (every intensity is 0)".into());
        }
        let (nu, nv) = (nc - 1, ng - 1);
        let distribution = PiecewiseConstant2D::new(&cells, nu, nv);
        let cell_pdf = cells
            .iter()
            .zip(&solid)
            .map(|(&f, &omega)| if f > 0.0 { (f as f64 / flux / omega) as f32 } else { 0.0 })
            .collect();
        Ok(IntensityTable { gamma, c, candela, flux, distribution, cell_pdf })
    }

    /// Φ = ∫ I dω over the sphere, lm.
    pub fn flux(&self) -> f64 {
        self.flux
    }

    /// The tabulated vertical angle and C plane below (γ, C) and the fractions towards the
    /// next ones; `None` outside the vertical range.
    #[inline]
    fn locate(&self, gamma: f32, c: f32) -> Option<(usize, usize, f32, f32)> {
        let g = &self.gamma;
        let ng = g.len();
        if gamma < g[0] || gamma > g[ng - 1] || ng < 2 {
            return None;
        }
        let ig = (g.partition_point(|&x| x <= gamma).max(1) - 1).min(ng - 2);
        let nc = self.c.len();
        let ic = (self.c.partition_point(|&x| x <= c).max(1) - 1).min(nc - 2);
        let tg = ((gamma - g[ig]) / (g[ig + 1] - g[ig])).clamp(0.0, 1.0);
        let tc = ((c - self.c[ic]) / (self.c[ic + 1] - self.c[ic])).clamp(0.0, 1.0);
        Some((ig, ic, tg, tc))
    }

    /// (γ, C) of a unit direction in the luminaire's frame.
    #[inline]
    fn angles(d: Vec3) -> (f32, f32) {
        let gamma = crate::geometry::trig::acos(-d.z);
        let mut c = crate::geometry::trig::atan2(d.y, d.x);
        if c < 0.0 {
            c += std::f32::consts::TAU;
        }
        (gamma, c)
    }

    /// I in cd towards the unit direction `d` of the luminaire's frame.
    #[inline]
    pub fn eval(&self, d: Vec3) -> f32 {
        let (gamma, c) = Self::angles(d);
        let Some((ig, ic, tg, tc)) = self.locate(gamma, c) else { return 0.0 };
        let ng = self.gamma.len();
        let at = |jc: usize, jg: usize| self.candela[jc * ng + jg];
        let lo = at(ic, ig) + (at(ic + 1, ig) - at(ic, ig)) * tc;
        let hi = at(ic, ig + 1) + (at(ic + 1, ig + 1) - at(ic, ig + 1)) * tc;
        lo + (hi - lo) * tg
    }

    /// A direction of the luminaire's frame drawn by flux (see the module docs) and its
    /// solid-angle density, 1/sr.
    #[inline]
    pub fn sample(&self, u: Vec2) -> Option<(Vec3, f32)> {
        let cs = self.distribution.sample_cell([u.x, u.y]);
        let [ic, ig] = cs.cell;
        let pdf = self.cell_pdf[ic * (self.gamma.len() - 1) + ig];
        if pdf <= 0.0 {
            return None;
        }
        let (g0, g1) = (self.gamma[ig], self.gamma[ig + 1]);
        let (cos0, cos1) = (g0.cos(), g1.cos());
        let cos_g = cos0 + (cos1 - cos0) * cs.offset[1];
        let sin_g = (1.0 - cos_g * cos_g).max(0.0).sqrt();
        let c = self.c[ic] + (self.c[ic + 1] - self.c[ic]) * cs.offset[0];
        let (sin_c, cos_c) = c.sin_cos();
        Some((Vec3::new(sin_g * cos_c, sin_g * sin_c, -cos_g), pdf))
    }

    /// The density of [`sample`](Self::sample) at the unit direction `d`, 1/sr.
    #[inline]
    pub fn pdf(&self, d: Vec3) -> f32 {
        let (gamma, c) = Self::angles(d);
        match self.locate(gamma, c) {
            Some((ig, ic, _, _)) => self.cell_pdf[ic * (self.gamma.len() - 1) + ig],
            None => 0.0,
        }
    }
}

/// Total flux of `p`'s table the slow way, for tests: a midpoint rule on a fine grid.
#[cfg(test)]
pub(crate) fn flux_by_quadrature(t: &IntensityTable, n: usize) -> f64 {
    use std::f64::consts::PI;
    let mut sum = 0.0;
    for i in 0..n {
        let cos_g = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
        let sin_g = (1.0 - cos_g * cos_g).sqrt();
        for j in 0..2 * n {
            let c = PI * (j as f64 + 0.5) / n as f64;
            let d = Vec3::new((sin_g * c.cos()) as f32, (sin_g * c.sin()) as f32, -cos_g as f32);
            sum += t.eval(d) as f64;
        }
    }
    sum * 4.0 * PI / (2 * n * n) as f64
}

#[cfg(test)]
mod tests;
