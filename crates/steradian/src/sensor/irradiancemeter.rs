//! `irradiancemeter`: measures the irradiance on a shape, averaged over its area.
//!
//! Declared as a child of a `<shape>`; it has no `to_world` of its own. Film must be 1×1.
//!
//! The value is the mean irradiance H (W/m²) over the shape's area on the side its normal
//! points to: each sample picks a point uniformly on the surface and estimates
//! H = ∫ L(ωi) cos θi dωi over the hemisphere around the normal.
//!
//! **Where steradian differs from Mitsuba 3 on purpose.** Mitsuba's meter only traces
//! cosine-distributed rays, so point, spot and directional lights (which no ray can hit) read 0
//! (mitsuba3 issue #365). steradian's meter samples every emitter at the measurement point,
//! delta lights included (H = I·cos θ/r² for a point light), and combines that with
//! cosine-weighted hemisphere sampling by multiple importance sampling. For extended lights
//! both estimate the same integral, so the two meters agree wherever Mitsuba's is right.

/// The irradiance meter attached to shape number `shape`.
#[derive(Clone, Debug)]
pub struct IrradianceMeter {
    pub shape: u32,
}
