//! A `luminaire` nested in a flat shape (steradian's own): an area source over the luminous
//! opening, whose intensity distribution is the photometric file's.
//!
//! Parameters are the `luminaire`'s (`luminaire.rs`: `filename`, `scale`, `color`, and
//! `to_world`, here a rotation only: it turns the photometric frame, nadir −z and C0 towards
//! +x; the shape places the opening), and it is built as that luminaire is. The shape must be flat (`rectangle` or `disk`), of area
//! A; it emits from its front side (towards its normal), as `area` does, the radiance
//!   L(ω) = I(ω) / (A cos θ),   cos θ = n·ω > 0,
//! so that the opening's intensity ∫_A L cos θ dA is the table's I(ω) in every direction of
//! the front hemisphere (the table's light towards the back is not emitted). Seen from far
//! away it is the point `luminaire`; up close its light spreads over the opening, with the
//! penumbrae and the near-field illuminance of a real fitting. Light sampling picks a point of
//! the shape as `area` does; emission (for `ptracer`) draws a point uniformly on the opening
//! and a direction by the table's flux, with weight I(ω)/p(ω).

use glam::{Vec2, Vec3};

use super::{EmitterSample, Luminaire, Support};
use crate::geometry::{is_positive, SurfacePoint};
use crate::shape::{Shape, UvRequest};
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct LuminousOpening {
    /// Index of the emitting shape in the scene.
    pub shape: u32,
    /// The luminaire's intensity distribution, turned (its position is unused: the shape
    /// places the opening).
    luminaire: Luminaire,
    /// The opening's area, m².
    area: f32,
}

impl LuminousOpening {
    /// The opening of area `area` (m²) of shape `shape`, emitting `luminaire`'s intensities.
    pub fn new(shape: u32, area: f32, luminaire: Luminaire) -> Result<LuminousOpening, String> {
        if !(area.is_finite() && area > 0.0) {
            return Err(format!("the luminous opening's area must be positive, got {area} m²"));
        }
        Ok(LuminousOpening { shape, luminaire, area })
    }

    /// Radiance leaving the opening at a point with normal `n` towards world direction `wo`
    /// (unit), W/(m²·sr).
    #[inline]
    pub fn radiance(&self, wo: Vec3, n: Vec3) -> Spectrum {
        let cos = n.dot(wo);
        if !is_positive(cos) {
            return Spectrum::ZERO;
        }
        self.luminaire.intensity(wo) / (self.area * cos)
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

    /// Radiant flux of the table, W per channel (used only to choose among lights by power:
    /// the part towards the back, which the opening does not emit, is counted too).
    pub fn flux(&self) -> Spectrum {
        self.luminaire.flux()
    }

    /// An emission direction (world) from a point of the opening with normal `n`, drawn by
    /// the table's flux, and the ray's weight L cos θ / (p_A p(ω)) = I(ω) / (A p_A p(ω)) (W),
    /// `pdf_area` the density of the point (1/m²); `None` towards the back.
    #[inline]
    pub fn sample_emission(&self, n: Vec3, pdf_area: f32, u: Vec2) -> Option<(Vec3, Spectrum)> {
        let (d, weight) = self.luminaire.sample_emission(u)?;
        if !is_positive(n.dot(d)) || !is_positive(pdf_area) {
            return None;
        }
        Some((d, weight / (self.area * pdf_area)))
    }
}
