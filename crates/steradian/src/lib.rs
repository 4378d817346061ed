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
//!
//! ## Layers
//! Each module imports only modules of lower layers, and the files inside a module import each
//! other without cycles (`tests/layers.rs` reads this list and checks the code against it):
//! 1. `spectrum`, `radiometry`, `param`: RGB quantities, units and the closed forms of
//!    radiometry; the typed error of a plugin parameter.
//! 2. `geometry`: rays, frames, transforms, bounding boxes, ray–triangle intersection.
//! 3. `sampling`: random and low-discrepancy numbers, warps, discrete distributions.
//! 4. `film`, `photometry`: images, reconstruction filters, image blocks, EXR and PNG files;
//!    luminaires' photometric files (IES LM-63, EULUMDAT) and their intensity tables.
//! 5. `texture`: bitmaps and procedural textures.
//! 6. `shape`: surfaces, their intersection and their sampling.
//! 7. `bsdf`, `phase`: BRDFs and BTDFs; phase functions of participating media.
//! 8. `emitter`, `medium`: light sources, and how next-event estimation chooses among them;
//!    participating media.
//! 9. `accel`: the BVH over the shapes.
//! 10. `sensor`: cameras and meters.
//! 11. `scene`: shapes, materials, lights and sensors with their BVH.
//! 12. `integrator`: estimators of radiance and irradiance over a scene.
//! 13. `render`: the render driver (a scene and its integrator in, films and readings out).
//! 14. `testkit`: what tests share (built for tests and with the `testkit` feature only).

pub mod accel;
pub mod bsdf;
pub mod emitter;
pub mod film;
pub mod geometry;
pub mod integrator;
pub mod medium;
pub mod param;
pub mod phase;
pub mod photometry;
pub mod radiometry;
pub mod render;
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

/// steradian's version, as recorded in checkpoints and distributed sums.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
