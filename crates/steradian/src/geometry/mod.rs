//! Rays, bounding boxes, transforms, frames, surface interactions and ray–triangle
//! intersection: the geometry every higher layer builds on.

mod aabb;
mod frame;

mod ray;
mod transform;
pub(crate) mod triangle;
pub mod trig;

pub use aabb::Aabb;
pub use frame::Frame;
pub mod interaction;
pub use interaction::{
    offset_ray_origin, PreliminaryHit, SurfaceInteraction, SurfacePoint, NO_INSTANCE,
};
pub use ray::Ray;
pub use transform::{Transform, TransformError};
pub use triangle::intersect_triangle;

/// `x > 0`, false for NaN (written as a function so that NaN-rejecting tests read clearly).
#[inline]
pub(crate) fn is_positive<T: PartialOrd + Default>(x: T) -> bool {
    x > T::default()
}

/// `0 < x < ∞`, false for NaN.
#[inline]
pub(crate) fn is_positive_finite(x: f32) -> bool {
    x.is_finite() && x > 0.0
}
