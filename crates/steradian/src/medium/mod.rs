//! Participating media: what light meets between surfaces (fog, smoke, tissue, water).
//!
//! A medium is described by its extinction coefficient σ_t (1/m, per RGB channel), its
//! single-scattering albedo α = σ_s/σ_t and its phase function (`crate::phase`); σ_a = σ_t − σ_s
//! is absorbed. Light crossing a distance d keeps the fraction T(d) = exp(−∫σ_t ds) (Beer–
//! Lambert). One file per Mitsuba 3 plugin: `homogeneous` (constant coefficients). The
//! integrators that trace through media (`volpath`, `volpathmis`) come with the loader's
//! `<medium>` objects; until then no scene reaches this module.

mod homogeneous;

pub use homogeneous::Homogeneous;
