//! The shared test kit: what the tests of every crate check with, in one place.
//!
//! Compiled for this crate's own tests and, through the `testkit` feature, for the other
//! crates' tests (their `[dev-dependencies]` enable it); normal builds do not compile it.
//!
//! - [`chi2`]: Pearson's χ² goodness of fit of sampled directions against the density the
//!   code reports, for BSDFs, emitters and shapes alike.
//! - [`bsdf`]: the checks every BSDF passes (χ², sample weight and pdf consistency,
//!   albedo) and the microfacet parameter grid.
//! - [`scenes`]: small scenes built in code with their closed-form radiance (a furnace, a
//!   plane under a point light), the radiance estimate along a ray, and a grid mesh.
//! - [`stats`]: mean and standard error of i.i.d. samples.
//! - [`files`]: a fresh temporary directory per test.

pub mod bsdf;
pub mod chi2;
pub mod files;
pub mod scenes;
pub mod stats;

pub use files::{temp_dir, write_file};
pub use stats::MeanError;

/// Two uniform numbers in [0, 1) from `rng`.
pub fn u2(rng: &mut crate::sampling::Pcg32) -> glam::Vec2 {
    glam::Vec2::new(rng.next_f32(), rng.next_f32())
}
