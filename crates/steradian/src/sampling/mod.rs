//! Random numbers, samplers and warps from the unit square to the domains light is
//! integrated over.

pub mod marginal_2d;
mod pcg32;
pub mod piecewise_constant;
mod sampler;
mod sobol4;
pub mod spherical_rectangle;
pub mod spherical_triangle;
pub mod warp;

pub(crate) use pcg32::mix64;
pub use pcg32::Pcg32;
pub use sampler::{PixelSampler, Sampler, SamplerKind};
