//! Ray-tracing acceleration: a bounding volume hierarchy over the primitives of all shapes.

mod bvh;
mod traverse;
mod triangle;

pub use bvh::Accel;
pub use triangle::intersect_triangle;

#[cfg(test)]
mod tests;
