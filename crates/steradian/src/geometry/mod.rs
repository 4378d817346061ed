//! Rays, bounding boxes, transforms, frames and surface interactions.

mod aabb;
mod frame;

mod ray;
mod transform;
pub mod trig;

pub use aabb::Aabb;
pub use frame::Frame;
pub mod interaction;
pub use interaction::{offset_ray_origin, PreliminaryHit, SurfaceInteraction};
pub use ray::Ray;
pub use transform::{Transform, TransformError};
