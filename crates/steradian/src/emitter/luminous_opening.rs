//! A `luminaire` nested in a flat shape (steradian's own): an area source over the luminous
//! opening, whose intensity distribution is the photometric file's.
//!
//! Parameters are the `luminaire`'s (`luminaire.rs`: `filename`, `scale`, `color`, and
//! `to_world`, here a rotation only: it turns the photometric frame, nadir −z and C0 towards
//! +x; the shape places the opening). The shape must be flat (`rectangle` or `disk`), of area
//! A; it emits from its front side (towards its normal), as `area` does, the radiance
//!   L(ω) = I(ω) / (A cos θ),   cos θ = n·ω > 0,
//! so that the opening's intensity ∫_A L cos θ dA is the table's I(ω) in every direction of
//! the front hemisphere (the table's light towards the back is not emitted). Seen from far
//! away it is the point `luminaire`; up close its light spreads over the opening, with the
//! penumbrae and the near-field illuminance of a real fitting. Light sampling picks a point of
//! the shape as `area` does; emission (for `ptracer`) draws a point uniformly on the opening
//! and a direction by the table's flux, with weight I(ω)/p(ω).

use std::sync::Arc;

use glam::{Mat3, Vec2, Vec3};

use super::{EmitterSample, Support};
use crate::geometry::{is_positive, SurfacePoint};
use crate::photometry::IntensityTable;
use crate::shape::{Shape, UvRequest};
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct LuminousOpening {
    /// Index of the emitting shape in the scene.
    pub shape: u32,
    /// World to luminaire frame (a rotation).
    to_local: Mat3,
    /// Luminaire frame to world.
    to_world: Mat3,
    table: Arc<IntensityTable>,
    /// W/sr per cd per channel, divided by the opening's area A (m²).
    per_candela_per_area: Spectrum,
    /// W/sr per cd per channel.
    per_candela: Spectrum,
    /// The opening's area, m².
    area: f32,
}

impl LuminousOpening {
    /// The opening of area `area` (m²) of shape `shape`, its photometric frame turned by
    /// `rotation`, emitting `per_candela` W/sr per candela of `table`.
    pub fn new(
        shape: u32,
        area: f32,
        rotation: Mat3,
        table: Arc<IntensityTable>,
        per_candela: Spectrum,
    ) -> Result<LuminousOpening, String> {
        if !(area.is_finite() && area > 0.0) {
            return Err(format!("the luminous opening's area must be positive, got {area} m²"));
        }
        if !(rotation.transpose() * rotation).abs_diff_eq(Mat3::IDENTITY, 1e-4) {
            return Err("to_world of a luminaire in a shape must be a rotation (the shape places \
                        and sizes the opening)"
                .into());
        }
        Ok(LuminousOpening {
            shape,
            to_local: rotation.transpose(),
            to_world: rotation,
            table,
            per_candela_per_area: per_candela / area,
            per_candela,
            area,
        })
    }

    /// Radiance leaving the opening at a point with normal `n` towards world direction `wo`
    /// (unit), W/(m²·sr).
    #[inline]
    pub fn radiance(&self, wo: Vec3, n: Vec3) -> Spectrum {
        let cos = n.dot(wo);
        if !is_positive(cos) {
            return Spectrum::ZERO;
        }
        self.per_candela_per_area * (self.table.eval(self.to_local * wo) / cos)
    }

    #[inline]
    pub fn sample_direction(&self, shapes: &[Shape], p: Vec3, u: Vec2) -> Option<EmitterSample> {
        let ds = shapes[self.shape as usize].sample_direction(p, u, UvRequest::Skip)?;
        if ds.n.dot(ds.wi) >= 0.0 || !is_positive(ds.pdf) {
            return None;
        }
        let le = self.radiance(-ds.wi, ds.n);
        Some(EmitterSample {
            wi: ds.wi,
            dist: ds.dist,
            pdf: ds.pdf,
            weight: le / ds.pdf,
            support: Support::Extended,
        })
    }

    #[inline]
    pub fn pdf_direction(&self, shapes: &[Shape], p: Vec3, wi: Vec3, light: &SurfacePoint) -> f32 {
        if light.n.dot(wi) >= 0.0 {
            return 0.0;
        }
        shapes[self.shape as usize].pdf_direction(p, light)
    }

    /// Radiant flux towards the front hemisphere of a shape with normal `n`, at most the
    /// table's whole flux (used only to choose among lights by power: the whole flux).
    pub fn flux(&self) -> Spectrum {
        self.per_candela * self.table.flux() as f32
    }

    /// An emission direction (world) from a point of the opening with normal `n`, drawn by
    /// the table's flux, and the ray's weight L cos θ / (p_A p(ω)) = I(ω) / (A p_A p(ω)) (W),
    /// `pdf_area` the density of the point (1/m²); `None` towards the back.
    #[inline]
    pub fn sample_emission(&self, n: Vec3, pdf_area: f32, u: Vec2) -> Option<(Vec3, Spectrum)> {
        let (local, pdf) = self.table.sample(u)?;
        let d = self.to_world * local;
        if !is_positive(n.dot(d)) || !is_positive(pdf_area) {
            return None;
        }
        let weight = self.per_candela * (self.table.eval(local) / (pdf * self.area * pdf_area));
        Some((d, weight))
    }
}
