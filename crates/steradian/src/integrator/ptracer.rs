//! # `ptracer`: particle tracing (light tracing)
//!
//! Mitsuba plugin `ptracer`.
//!
//! | Parameter | Type | Default | Meaning |
//! |---|---|---|---|
//! | `max_depth` | integer | −1 (∞) | longest path, in segments: 1 renders only the lights seen directly |
//! | `rr_depth` | integer | 5 | depth after which Russian roulette may end a path |
//! | `hide_emitters` | bool | false | leave out the lights seen directly |
//! | `samples_per_pass` | integer | — | accepted; steradian always renders pass by pass |
//!
//! Paths start on the lights and connect to the camera at every surface they reach, as in
//! Mitsuba 3: a film of W × H pixels at N samples per pixel traces N·W·H light paths (one pass
//! of W·H paths per sample), each
//! 1. connecting a point sampled on an extended light (area lights by area; lights at infinity
//!    by their direction sampling from the lens point) straight to the camera, unless
//!    `hide_emitters` or `max_depth` = 0: Le·cos θ_light/pdf · W·cos θ_cam/r² (delta lights
//!    cannot be seen);
//! 2. starting a ray from a light chosen uniformly ([`Emitter::sample_ray`], weight
//!    Φ-density ratio / selection probability) and, at every
//!    surface point reached (while the depth is below `max_depth`), splatting
//!    β·f(x, ω_cam, ω_light)·|cos θ_cam|·W·cos θ/r², visibility tested, before sampling the BSDF
//!    for the next direction with the importance-transport weight (the adjoint shading-normal
//!    correction of Veach's thesis, §5.3, and no (η_i/η_t)² radiance factor at refractions);
//!    Russian roulette after `rr_depth` with q = min(max(β)·η², 0.95).
//!
//! Every splat is spread with the film's filter normalised over its footprint and a pixel is
//! the mean of its per-pass sums (Mitsuba's 1/spp scale), so it is the mean radiance through
//! it, in W/(m²·sr), like the `path` integrator's image of the same scene (and Mitsuba's
//! `ptracer`'s).
//!
//! Light paths connect to `perspective` and `thinlens` cameras, a `thinlens` camera at a point
//! of its aperture drawn uniformly for each connection (`sensor/thinlens.rs`'s importance);
//! the render plan refuses other sensors with `ptracer`, as Mitsuba 3's `ptracer` fails on an
//! `orthographic` camera ("sample_direction(): not implemented").
//! Lights are chosen uniformly, as Mitsuba chooses them. The standard error of each pixel comes
//! from the spread of its per-pass sums, the passes being independent. On surfaces whose BSDF
//! bends its own normal (`normalmap`, `bumpmap`) steradian's light paths evaluate the BSDF
//! with the direction the light goes next as the viewer's (its adjoint) and draw some
//! directions uniformly ([`ParticleTracer::next_direction`]), so `ptracer` renders `path`'s
//! image there too. Mitsuba 3.9.1's `ptracer` takes the light's direction as the viewer's
//! and does not: a normal-mapped diffuse floor under a rectangle light
//! (`scripts/mitsuba_diff/probes.py` `ptracer_normalmap`) has image means 0.12126 with its
//! `ptracer` against 0.12647 with its `path` (steradian: 0.12646 and 0.12648), a bump-mapped
//! one (`reference/ptracer-bump.xml`) 0.0744 against 0.0467 (steradian: 0.04673 and
//! 0.04671). Mitsuba 3.9.1's `ptracer` also lights a scene wrongly from an `envmap` turned by
//! its `to_world` (`reference/ptracer-envmap.xml`, turned 302.753° about +y): image mean 24.58
//! against its `path`'s 17.78 (unturned: 16.88 against 16.86); steradian's `ptracer` gives
//! 17.787 ± 0.008 against its `path`'s 17.770 ± 0.002 (`tests/ptracer.rs`).

use glam::Vec2;

use crate::bsdf::{BsdfSample, Lobe, ShadingPoint};
use crate::emitter::Support;
use crate::film::SplatBlock;
use crate::sampling::{warp, PixelSampler};
use crate::scene::Scene;
use crate::sensor::{Sensor, SensorConnection};
use crate::Spectrum;

/// Mitsuba's particle tracer.
#[derive(Clone, Debug, PartialEq)]
pub struct ParticleTracer {
    /// Longest path in segments; `None` for no limit (Mitsuba's −1).
    pub max_depth: Option<u32>,
    /// Depth after which Russian roulette applies.
    pub rr_depth: u32,
    /// Whether lights seen directly are left out.
    pub hide_emitters: bool,
}

impl Default for ParticleTracer {
    fn default() -> Self {
        ParticleTracer {
            max_depth: None,
            rr_depth: Self::DEFAULT_RR_DEPTH,
            hide_emitters: Self::DEFAULT_HIDE_EMITTERS,
        }
    }
}

/// Mitsuba's limit on the probability of continuing a path under Russian roulette.
const RR_MAX_CONTINUE: f32 = 0.95;

/// The share of a light path's directions drawn uniformly over the sphere at surfaces whose
/// BSDF depends on which direction is the viewer's ([`ParticleTracer::next_direction`]).
const DEFENSIVE_FRACTION: f32 = 0.25;

impl ParticleTracer {
    /// Default `rr_depth` (Mitsuba's).
    pub const DEFAULT_RR_DEPTH: u32 = 5;
    /// Default `hide_emitters` (Mitsuba's).
    pub const DEFAULT_HIDE_EMITTERS: bool = false;

    /// Whether a path may still connect at `depth` (segments so far).
    #[inline]
    fn below_max(&self, depth: u32) -> bool {
        self.max_depth.is_none_or(|m| depth < m)
    }

    /// The direction a light path leaves a surface by, leaving it towards `wl` (local), with
    /// the importance-transport weight ρ(wi, wl)·|cos θi|/pdf: the adjoint's (no (η_i/η_t)²
    /// radiance factor at a refraction). `wi` and `weight` of the result are those; `pdf`,
    /// `lobe` and `eta` are the sample's.
    ///
    /// A BSDF whose value depends on which direction is the viewer's (one that bends its
    /// normal, a measured one) is not symmetric in its two directions: its value is
    /// evaluated again with the direction the light goes next as the viewer's, and a quarter
    /// of the directions are drawn uniformly over the sphere (one-sample MIS with the BSDF's
    /// own sampling, which, seeing the light's direction as the viewer's, leaves out some
    /// directions the light can go: without it a normal-mapped floor's image was 0.18 % dark
    /// against `path` (z = −12 over 12 seeds) and a bump-mapped one 0.23 % (z = −9); with it,
    /// z = −0.5 and −0.9). A delta or null lobe (a glass in a blend, a mask's pass-through)
    /// is reached only through the BSDF's own sampling, whose weight is then divided by that
    /// branch's probability.
    #[inline]
    fn next_direction(
        &self,
        bsdf: &crate::bsdf::Bsdf,
        sp: &ShadingPoint,
        wl: glam::Vec3,
        s: &mut PixelSampler,
    ) -> Option<BsdfSample> {
        if !bsdf.depends_on_viewer() {
            let bs = bsdf.sample(sp, wl, s.next_1d(), s.next_2d())?;
            return Some(BsdfSample { weight: bs.weight * (bs.eta * bs.eta), ..bs });
        }
        let (u_mix, u1, u2) = (s.next_1d(), s.next_1d(), s.next_2d());
        let (wi, pdf_bsdf) = if u_mix < DEFENSIVE_FRACTION {
            let wi = warp::square_to_uniform_sphere(u2);
            (wi, bsdf.pdf(sp, wl, wi))
        } else {
            let bs = bsdf.sample(sp, wl, u1, u2)?;
            if bs.lobe != Lobe::Smooth {
                // a delta or null lobe is reached only through this branch
                let weight = bs.weight * (bs.eta * bs.eta / (1.0 - DEFENSIVE_FRACTION));
                return Some(BsdfSample { weight, ..bs });
            }
            (bs.wi, bs.pdf)
        };
        let pdf =
            (1.0 - DEFENSIVE_FRACTION) * pdf_bsdf + DEFENSIVE_FRACTION * warp::UNIFORM_SPHERE_PDF;
        let weight = bsdf.eval(sp, wi, wl) * (wi.z.abs() / pdf);
        Some(BsdfSample { wi, pdf, weight, lobe: Lobe::Smooth, eta: 1.0 })
    }

    /// Traces one light path with sampler `s`, splatting its contributions to the camera into
    /// `block` (the driver takes the mean over passes, which is the 1/spp).
    pub fn trace(
        &self,
        scene: &Scene,
        sensor: &Sensor,
        s: &mut PixelSampler,
        block: &mut SplatBlock,
    ) {
        // a crop window (`render/particles.rs` traces one path per pixel of the full frame
        // for it) takes the splats of the points it sees; those outside it are dropped, as
        // Mitsuba's importance drops them, even where the filter would reach into the window
        let window = sensor.film.window();
        let size = Vec2::new(block.width() as f32, block.height() as f32);
        let mut splat = |c: &SensorConnection, value: Spectrum| {
            let pos = window.position(c.film_uv);
            let seen = pos.cmpge(Vec2::ZERO).all() && pos.cmple(size).all();
            if value != Spectrum::ZERO && seen {
                block.splat(pos, value);
            }
        };
        if self.max_depth != Some(0) && !self.hide_emitters {
            self.visible_emitter(scene, sensor, s, &mut splat);
        }
        let Some((index, pmf)) = scene.pick_emitter(s.next_1d()) else { return };
        let (u_dir, u_pos) = (s.next_2d(), s.next_2d());
        let emitter = &scene.emitters[index as usize];
        let Some(emitted) =
            emitter.sample_ray(&scene.shapes, scene.bounding_sphere(), u_pos, u_dir)
        else {
            return;
        };
        let mut beta = emitted.weight / pmf;
        let mut eta = 1.0f32;
        let mut ray = emitted.ray;
        let mut depth = 1u32;
        while self.below_max(depth) {
            let Some(si) = scene.intersect(&ray) else { return };
            let bsdf = scene.bsdf(&si);
            let sp = ShadingPoint::new(&si);
            // towards the light the particle came from, local and world
            let w_light = si.wo;
            let wl = si.to_local(w_light);
            let ng_light = si.n.dot(w_light);
            let lens = sensor.sample_lens(s.next_2d());
            if let Some(c) = lens.and_then(|lens| sensor.sample_direction(&lens, si.p)) {
                let wc = si.to_local(c.wi);
                let ng_cam = si.n.dot(c.wi);
                // no light through shading normals' wrong side (Mitsuba's test)
                if ng_light * wl.z > 0.0 && ng_cam * wc.z > 0.0 {
                    let correction = ((wl.z * ng_cam) / (wc.z * ng_light)).abs();
                    let f = bsdf.eval(&sp, wc, wl) * (wc.z.abs() * correction * c.weight);
                    if f != Spectrum::ZERO && scene.unoccluded_along(si.p, si.n, c.wi, c.dist) {
                        splat(&c, beta * f);
                    }
                }
            }
            let Some(bs) = self.next_direction(bsdf, &sp, wl, s) else { return };
            let d = si.to_world(bs.wi);
            let ng_next = si.n.dot(d);
            if !(ng_light * wl.z > 0.0 && ng_next * bs.wi.z > 0.0) {
                return;
            }
            let correction = ((wl.z * ng_next) / (bs.wi.z * ng_light)).abs();
            beta *= bs.weight * correction;
            eta *= bs.eta;
            if beta == Spectrum::ZERO {
                return;
            }
            if !beta.is_finite() {
                block.count_dropped();
                return;
            }
            ray = si.spawn_ray(d);
            depth += 1;
            if depth > self.rr_depth {
                let q = (beta.max_element() * eta * eta).min(RR_MAX_CONTINUE);
                if s.next_1d() >= q {
                    return;
                }
                beta /= q;
            }
        }
    }

    /// Connects a point sampled on an extended light straight to the camera.
    fn visible_emitter(
        &self,
        scene: &Scene,
        sensor: &Sensor,
        s: &mut PixelSampler,
        splat: &mut impl FnMut(&SensorConnection, Spectrum),
    ) {
        let Some((index, pmf)) = scene.pick_emitter(s.next_1d()) else { return };
        let (u, u_lens) = (s.next_2d(), s.next_2d());
        let emitter = &scene.emitters[index as usize];
        let Some(lens) = sensor.sample_lens(u_lens) else { return };
        if emitter.support() == Support::Delta {
            return;
        }
        match emitter.shape() {
            Some(shape) => {
                let ps = scene.shapes[shape as usize].sample_position(u);
                if !crate::geometry::is_positive(ps.pdf_area) {
                    return;
                }
                let Some(c) = sensor.sample_direction(&lens, ps.p) else { return };
                let cos = ps.n.dot(c.wi);
                let le = emitter.radiance(c.wi, ps.n, ps.uv);
                if cos <= 0.0 || le == Spectrum::ZERO {
                    return;
                }
                if scene.unoccluded_along(ps.p, ps.n, c.wi, c.dist) {
                    splat(&c, le * (cos * c.weight / (ps.pdf_area * pmf)));
                }
            }
            // lights at infinity: a direction sampled from the camera
            None => {
                let origin = lens.position;
                let Some(es) = emitter.sample_direction(&scene.shapes, origin, u) else {
                    return;
                };
                let Some(c) = sensor.sample_direction_at_infinity(&lens, es.wi) else { return };
                // the lens is no surface: the shadow ray leaves it along its own direction
                if es.pdf > 0.0 && scene.unoccluded_along(origin, es.wi, es.wi, es.dist) {
                    splat(&c, es.weight * (c.weight / pmf));
                }
            }
        }
    }
}
