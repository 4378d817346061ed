//! # steradian: physically based rendering and light measurement
//!
//! Light is computed as physics. Every quantity keeps its radiometric meaning and unit:
//! flux Φ (W), radiant intensity I (W/sr), irradiance H (W/m²), radiance L (W/(m²·sr)),
//! solid angle ω (sr). Colour is carried as linear RGB triples ([`Spectrum`]), one
//! radiometric quantity per channel.
//!
//! ## Conventions (stated once, used everywhere)
//! - Units: lengths in scene units (metres by convention), angles in radians inside the
//!   library (the Mitsuba loader converts degrees), solid angles in steradians.
//! - Directions point **away** from the surface: `wo` towards the viewer (the direction light
//!   leaves in), `wi` towards the light (the direction light arrives from). Both are unit vectors.
//! - A BSDF is the BRDF/BTDF itself, ρ(wo, wi) = dL(wo) / dH(wi) in 1/sr, **without** the
//!   cosine: integrators multiply by |cos θi| themselves.
//! - Local shading frames have the shading normal along +z: cos θ = w.z.
//! - Geometric normals are the shape's own orientation (never flipped towards the ray), so
//!   one-sided surfaces and emitters can tell front from back.
//! - PDFs are per unit solid angle (1/sr) unless a name says otherwise (`pdf_area`, 1/m²).
//! - Monte Carlo estimates are unbiased; NaN and infinite samples never reach the film: they are
//!   dropped and counted.

pub mod accel;
pub mod bsdf;
pub mod emitter;
pub mod film;
pub mod geometry;
pub mod integrator;
pub mod radiometry;
pub mod sampling;
pub mod scene;
pub mod sensor;
pub mod shape;
pub mod spectrum;
#[cfg(any(test, feature = "testkit"))]
pub mod testkit;
pub mod texture;

pub use glam::{Mat3, Mat4, Vec2, Vec3};
pub use spectrum::Spectrum;
