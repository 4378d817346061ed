//! BSDFs: ρ(wo, wi), the ratio of reflected radiance to incident irradiance (1/sr).
//!
//! Conventions (see the crate docs): directions are given in the local shading frame (+z is
//! the shading normal), both point away from the surface, and `eval` returns the BSDF itself
//! **without** the cosine factor. Surfaces are one-sided like Mitsuba's: reflection models
//! return 0 unless both directions lie above the surface; `twosided` makes both faces
//! reflect.

mod blendbsdf;
mod bumpmap;
mod conductor;
mod dielectric;
mod diffuse;
mod disney;
pub mod fresnel;
mod hair;
pub mod ior;
mod mask;
mod measured;
mod merl;
pub mod microfacet;
mod normalmap;
mod perturbed;
mod phong;
mod plastic;
mod pplastic;
mod principled;
mod principledthin;
mod roughconductor;
mod roughdielectric;
mod roughplastic;
mod tensor_file;
mod thindielectric;
mod twosided;

pub use blendbsdf::BlendBsdf;
pub use bumpmap::BumpMap;
pub use conductor::Conductor;
pub use dielectric::Dielectric;
pub use diffuse::Diffuse;
pub use hair::{Hair, HairAbsorption};
pub use mask::Mask;
pub use measured::{Measured, MeasuredTables};
pub use merl::{Merl, MerlTable};
pub use microfacet::{MicrofacetDistribution, MicrofacetKind};
pub use normalmap::NormalMap;
pub use perturbed::PerturbOptions;
pub use phong::Phong;
pub use plastic::{InternalScattering, Plastic};
pub use pplastic::PPlastic;
pub use principled::{Principled, PrincipledSamplingRates};
pub use principledthin::{PrincipledThin, PrincipledThinSamplingRates};
pub use roughconductor::RoughConductor;
pub use roughdielectric::RoughDielectric;
pub use roughplastic::RoughPlastic;
pub use thindielectric::ThinDielectric;
pub use twosided::TwoSided;

use glam::{Vec2, Vec3};

use crate::texture::TexturePoint;
use crate::Spectrum;

/// What kind of scattering a sampled direction came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lobe {
    /// Spreads over a solid angle (Lambertian, rough microfacets): has a finite density.
    Smooth,
    /// A Dirac delta (mirror, smooth glass): only reachable by sampling.
    Delta,
    /// Straight through, unchanged (Mitsuba's `BSDFFlags::Null`: the `null` BSDF, a `mask`'s
    /// transparent part, a `thindielectric`'s transmission): a delta that `volpath` does not
    /// count as a scattering event.
    Null,
}

impl Lobe {
    /// Whether the direction came from a Dirac delta (a mirror, smooth glass, a null
    /// pass-through), which only sampling can reach: MIS gives it full weight.
    #[inline]
    pub fn is_delta(self) -> bool {
        match self {
            Lobe::Smooth => false,
            Lobe::Delta | Lobe::Null => true,
        }
    }
}

/// A direction drawn from a BSDF.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// Sampled incident direction, local frame.
    pub wi: Vec3,
    /// Density of `wi` in 1/sr; for `Lobe::Delta`, the probability of having chosen that delta
    /// lobe (1 when it is the BSDF's only lobe). MIS never uses it for delta lobes.
    pub pdf: f32,
    /// The Monte Carlo weight ρ(wo, wi)·|cos θi| / pdf (dimensionless).
    pub weight: Spectrum,
    pub lobe: Lobe,
    /// Relative index of refraction η_t/η_i of the interface crossed by the sampled
    /// direction (1 for reflection and for straight pass-through), as Mitsuba's
    /// `BSDFSample::eta`. Transmission weights include the radiance factor (η_i/η_t)², so
    /// Russian roulette uses throughput·η² with η the product of these values along the path.
    pub eta: f32,
}

/// Where the BSDF is evaluated: the surface coordinates textures need and the local
/// differential geometry that bump and normal maps perturb.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadingPoint {
    /// Surface (texture) coordinates.
    pub uv: Vec2,
    /// ∂p/∂u and ∂p/∂v in the local shading frame (m per unit of u, v).
    pub dpdu: Vec3,
    pub dpdv: Vec3,
    /// The geometric normal in the local shading frame (unit).
    pub ng: Vec3,
    /// The primitive and barycentrics, for mesh-attribute textures ([`TexturePoint`]).
    pub prim: u32,
    pub bary: Vec2,
    /// World position, m, for `volume` textures.
    pub p: Vec3,
}

impl ShadingPoint {
    /// A point at `uv` of a flat surface whose shading frame is its (u, v, n) frame.
    pub fn at_uv(uv: Vec2) -> Self {
        ShadingPoint {
            uv,
            dpdu: Vec3::X,
            dpdv: Vec3::Y,
            ng: Vec3::Z,
            prim: u32::MAX,
            bary: Vec2::ZERO,
            p: Vec3::ZERO,
        }
    }

    /// Where the BSDF's textures are evaluated.
    #[inline]
    pub fn tex(&self) -> TexturePoint {
        TexturePoint { uv: self.uv, prim: self.prim, bary: self.bary, p: self.p }
    }

    /// The shading point of a surface interaction (its vectors taken to the shading frame).
    #[inline]
    pub fn new(si: &crate::geometry::SurfaceInteraction) -> Self {
        ShadingPoint {
            uv: si.uv,
            dpdu: si.to_local(si.dpdu),
            dpdv: si.to_local(si.dpdv),
            ng: si.to_local(si.n),
            prim: si.prim,
            bary: si.bary,
            p: si.p,
        }
    }
}

/// A BSDF. Closed enum: one variant per BSDF plugin.
#[derive(Clone, Debug, PartialEq)]
pub enum Bsdf {
    Diffuse(Diffuse),
    TwoSided(TwoSided),
    Conductor(Conductor),
    RoughConductor(RoughConductor),
    Dielectric(Dielectric),
    ThinDielectric(ThinDielectric),
    RoughDielectric(RoughDielectric),
    Plastic(Plastic),
    RoughPlastic(RoughPlastic),
    PPlastic(PPlastic),
    Principled(Principled),
    PrincipledThin(PrincipledThin),
    Phong(Phong),
    Merl(Merl),
    Measured(Measured),
    Mask(Mask),
    BlendBsdf(BlendBsdf),
    BumpMap(BumpMap),
    NormalMap(NormalMap),
    Hair(Hair),
}

/// Dispatches a method call to the variant's implementation.
macro_rules! dispatch {
    ($self:expr, $b:ident => $e:expr) => {
        match $self {
            Bsdf::Diffuse($b) => $e,
            Bsdf::TwoSided($b) => $e,
            Bsdf::Conductor($b) => $e,
            Bsdf::RoughConductor($b) => $e,
            Bsdf::Dielectric($b) => $e,
            Bsdf::ThinDielectric($b) => $e,
            Bsdf::RoughDielectric($b) => $e,
            Bsdf::Plastic($b) => $e,
            Bsdf::RoughPlastic($b) => $e,
            Bsdf::PPlastic($b) => $e,
            Bsdf::Principled($b) => $e,
            Bsdf::PrincipledThin($b) => $e,
            Bsdf::Phong($b) => $e,
            Bsdf::Merl($b) => $e,
            Bsdf::Measured($b) => $e,
            Bsdf::Mask($b) => $e,
            Bsdf::BlendBsdf($b) => $e,
            Bsdf::BumpMap($b) => $e,
            Bsdf::NormalMap($b) => $e,
            Bsdf::Hair($b) => $e,
        }
    };
}

impl Bsdf {
    /// ρ(wo, wi) in 1/sr, without the cosine.
    #[inline]
    pub fn eval(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> Spectrum {
        dispatch!(self, b => b.eval(sp, wo, wi))
    }

    /// Density (1/sr) with which `sample` proposes `wi` given `wo`.
    #[inline]
    pub fn pdf(&self, sp: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        dispatch!(self, b => b.pdf(sp, wo, wi))
    }

    /// Draws `wi` given `wo` with uniforms `u1` (lobe choice) and `u2` (direction).
    #[inline]
    pub fn sample(&self, sp: &ShadingPoint, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        dispatch!(self, b => b.sample(sp, wo, u1, u2))
    }

    /// True for a Lambertian surface (`diffuse`, or `twosided` with `diffuse` on both sides):
    /// ρ is a constant, so light sampling alone weighs its samples by the cosine only.
    #[inline]
    pub fn is_lambertian(&self) -> bool {
        match self {
            Bsdf::Diffuse(_) => true,
            Bsdf::TwoSided(b) => b.front.is_lambertian() && b.back.is_lambertian(),
            _ => false,
        }
    }

    /// The fraction of light that passes the surface straight through, unscattered (Mitsuba's
    /// `eval_null_transmission`): 1 − opacity for `mask` (and so 1 for `null`), (1 − R')·
    /// `specular_transmittance` for `thindielectric`, the mix for `blendbsdf`, the facing
    /// side's for `twosided`, 0 for every other BSDF. `volpath`'s shadow rays cross surfaces
    /// with this weight; `path`'s stop at every surface.
    #[inline]
    pub fn null_transmission(&self, sp: &ShadingPoint, wo: Vec3) -> Spectrum {
        match self {
            Bsdf::Mask(b) => b.null_transmission(sp),
            Bsdf::ThinDielectric(b) => b.null_transmission(sp, wo),
            Bsdf::BlendBsdf(b) => b.null_transmission(sp, wo),
            Bsdf::TwoSided(b) => b.null_transmission(sp, wo),
            _ => Spectrum::ZERO,
        }
    }

    /// The chance that [`Bsdf::sample`] takes a null lobe from `wo`: 1 − opacity for `mask`,
    /// 1 − R' for `thindielectric` (whatever its `specular_transmittance`, which weighs the
    /// lobe without changing how often it is chosen), the mix for `blendbsdf`, the facing
    /// side's for `twosided`, 0 for every other BSDF.
    #[inline]
    pub fn null_chance(&self, sp: &ShadingPoint, wo: Vec3) -> f32 {
        match self {
            Bsdf::Mask(b) => b.null_chance(sp),
            Bsdf::ThinDielectric(b) => b.null_chance(wo),
            Bsdf::BlendBsdf(b) => b.null_chance(sp, wo),
            Bsdf::TwoSided(b) => b.null_chance(sp, wo),
            _ => 0.0,
        }
    }

    /// Whether some light may pass the surface unscattered ([`Bsdf::null_transmission`] can
    /// be positive).
    pub fn may_pass_light(&self) -> bool {
        match self {
            Bsdf::Mask(_) | Bsdf::ThinDielectric(_) => true,
            Bsdf::BlendBsdf(b) => b.bsdf0.may_pass_light() || b.bsdf1.may_pass_light(),
            Bsdf::TwoSided(b) => b.front.may_pass_light() || b.back.may_pass_light(),
            _ => false,
        }
    }

    /// Whether the BSDF's value depends on which of its two directions is the viewer's: one
    /// that bends its own normal (`bumpmap`, `normalmap`: the flip of invalid normals and the
    /// shadowing term see the viewer and the light differently), `measured` (tabulated over
    /// the viewer's direction), or a wrapper holding one. A light path must evaluate it with
    /// the viewer's direction as `wo` (`integrator/ptracer.rs`).
    pub fn depends_on_viewer(&self) -> bool {
        match self {
            Bsdf::BumpMap(_) | Bsdf::NormalMap(_) | Bsdf::Measured(_) => true,
            Bsdf::Mask(b) => b.nested.depends_on_viewer(),
            Bsdf::BlendBsdf(b) => b.bsdf0.depends_on_viewer() || b.bsdf1.depends_on_viewer(),
            Bsdf::TwoSided(b) => b.front.depends_on_viewer() || b.back.depends_on_viewer(),
            _ => false,
        }
    }

    /// True when some lobe has a finite density, so that light sampling can help.
    #[inline]
    pub fn has_smooth_lobe(&self) -> bool {
        match self {
            Bsdf::Diffuse(_)
            | Bsdf::RoughConductor(_)
            | Bsdf::RoughDielectric(_)
            | Bsdf::Plastic(_)
            | Bsdf::RoughPlastic(_)
            | Bsdf::PPlastic(_)
            | Bsdf::Principled(_)
            | Bsdf::PrincipledThin(_) => true,
            Bsdf::Phong(_) | Bsdf::Merl(_) | Bsdf::Measured(_) | Bsdf::Hair(_) => true,
            Bsdf::Conductor(_) | Bsdf::Dielectric(_) | Bsdf::ThinDielectric(_) => false,
            Bsdf::TwoSided(b) => b.has_smooth_lobe(),
            Bsdf::Mask(b) => b.has_smooth_lobe(),
            Bsdf::BlendBsdf(b) => b.has_smooth_lobe(),
            Bsdf::BumpMap(b) => b.has_smooth_lobe(),
            Bsdf::NormalMap(b) => b.has_smooth_lobe(),
        }
    }

    /// True when some lobe is a Dirac delta that scatters (a mirror, smooth glass, a smooth
    /// plastic's coating; a null pass-through does not count).
    pub fn has_delta_lobe(&self) -> bool {
        match self {
            Bsdf::Conductor(_)
            | Bsdf::Dielectric(_)
            | Bsdf::ThinDielectric(_)
            | Bsdf::Plastic(_) => true,
            Bsdf::Diffuse(_)
            | Bsdf::RoughConductor(_)
            | Bsdf::RoughDielectric(_)
            | Bsdf::RoughPlastic(_)
            | Bsdf::PPlastic(_)
            | Bsdf::Principled(_)
            | Bsdf::PrincipledThin(_)
            | Bsdf::Phong(_)
            | Bsdf::Merl(_)
            | Bsdf::Measured(_)
            | Bsdf::Hair(_) => false,
            Bsdf::TwoSided(b) => b.front.has_delta_lobe() || b.back.has_delta_lobe(),
            Bsdf::Mask(b) => b.nested.has_delta_lobe(),
            Bsdf::BlendBsdf(b) => b.bsdf0.has_delta_lobe() || b.bsdf1.has_delta_lobe(),
            Bsdf::BumpMap(b) => b.nested.has_delta_lobe(),
            Bsdf::NormalMap(b) => b.nested.has_delta_lobe(),
        }
    }

    /// The diffuse reflectance seen from `wo` (Mitsuba's `eval_diffuse_reflectance`, the
    /// `aov` integrator's `albedo`): the diffuse albedo parameter where the model has one
    /// (`diffuse`, the plastics' `diffuse_reflectance`, the principled `base_color`; a bump or
    /// normal map's nested BSDF's), else π·ρ(wo, n) (0 for delta BSDFs), Mitsuba's default.
    pub fn diffuse_reflectance(&self, sp: &ShadingPoint, wo: Vec3) -> Spectrum {
        match self {
            Bsdf::Diffuse(b) => b.reflectance.eval(sp.tex()),
            Bsdf::Plastic(b) => b.diffuse_reflectance.eval(sp.tex()),
            Bsdf::RoughPlastic(b) => b.diffuse_reflectance.eval(sp.tex()),
            Bsdf::Principled(b) => b.base_color.eval(sp.tex()),
            Bsdf::PrincipledThin(b) => b.base_color.eval(sp.tex()),
            Bsdf::BumpMap(b) => b.nested.diffuse_reflectance(sp, wo),
            Bsdf::NormalMap(b) => b.nested.diffuse_reflectance(sp, wo),
            _ => self.eval(sp, wo, Vec3::Z) * std::f32::consts::PI,
        }
    }

    /// Mitsuba's BSDF for a shape that has none: `diffuse` with reflectance 0.5.
    pub fn default_diffuse() -> Bsdf {
        Bsdf::Diffuse(Diffuse::new(Spectrum::splat(Diffuse::DEFAULT_REFLECTANCE).into()))
    }

    /// Mitsuba's BSDF for an emitting shape that has none: a black `diffuse`.
    pub fn black() -> Bsdf {
        Bsdf::Diffuse(Diffuse::new(Spectrum::ZERO.into()))
    }
}

/// The sample of a BSDF that proposed `wi` with density `pdf`, its whole `pdf(wo, wi)` over
/// every lobe that could have drawn it: weight `f·cos θᵢ / pdf`, with `f` evaluated only when
/// the density is positive. `None` when it is not (or is NaN).
#[inline]
pub(crate) fn smooth_sample(
    wi: Vec3,
    pdf: f32,
    f: impl FnOnce() -> Spectrum,
) -> Option<BsdfSample> {
    if !positive(pdf) {
        return None;
    }
    Some(BsdfSample { wi, pdf, weight: f() * (cos_theta(wi) / pdf), lobe: Lobe::Smooth, eta: 1.0 })
}

/// True for x > 0; false for zero, negatives and NaN.
#[inline]
pub(crate) fn positive(x: f32) -> bool {
    x > 0.0
}

/// cos θ of a local direction.
#[inline]
pub(crate) fn cos_theta(w: Vec3) -> f32 {
    w.z
}
