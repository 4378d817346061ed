//! The scene: shapes with their BSDFs and emitters, lights, sensors, and the acceleration
//! structure that answers ray queries. The integrator that estimates its light is not part of
//! it (integrators sit a layer above the scene): a scene file's scene and integrator travel
//! together as a [`Job`](crate::render::Job).

use glam::{Vec2, Vec3};

use std::cell::Cell;
use std::sync::Arc;

use crate::accel::{Accel, AccelStats, Instance, Isa, ShapeGroup};
use crate::bsdf::Bsdf;
use crate::emitter::{Emitter, EmitterSample, LightSelection, Support};
use crate::geometry::SurfacePoint;
use crate::geometry::{Aabb, Ray, SurfaceInteraction, Transform, NO_INSTANCE};
use crate::medium::Medium;
use crate::sampling::PixelSampler;
use crate::sensor::Sensor;
use crate::shape::Shape;
use crate::Spectrum;

thread_local! {
    /// Ray queries (closest hits and shadow rays) this thread has made of any scene: one
    /// increment per query, about a nanosecond against the hundreds a query takes.
    static RAYS_TRACED: Cell<u64> = const { Cell::new(0) };
}

/// Ray queries ([`Scene::intersect`], [`Scene::occluded`]) made on the calling thread so far:
/// the renderer reads it around each block to report rays per second.
pub fn rays_traced_on_this_thread() -> u64 {
    RAYS_TRACED.with(Cell::get)
}

#[inline(always)]
fn count_ray() {
    RAYS_TRACED.with(|n| n.set(n.get() + 1));
}

/// What a shape is made of, whether it glows, and the media it bounds.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ShapeBinding {
    /// Index into [`Scene::bsdfs`].
    pub bsdf: u32,
    /// Index into [`Scene::emitters`] of the shape's area light.
    pub emitter: Option<u32>,
    /// Whether the shape carries an emitter at all (see [`SurfaceEmitter`]).
    pub surface_emitter: SurfaceEmitter,
    /// The shape's `id` in the scene file (empty when it has none).
    pub id: String,
    /// Index into [`Scene::media`] of the medium inside the shape (behind its geometric
    /// normal), Mitsuba's `interior`.
    pub interior: Option<u32>,
    /// The medium outside (in front of the normal), Mitsuba's `exterior`.
    pub exterior: Option<u32>,
}

/// Whether a shape carries an emitter in the scene file, which camera rays pass through under
/// `hide_emitters` (Mitsuba 3.9.1 lets them through any emitter shape): an area light, a
/// luminous opening, and also a `directionalarea`, which adds no light to a path tracer's
/// image and so has no [`ShapeBinding::emitter`]. (A `directionalarea` disk in front of a wall
/// under `hide_emitters`: image mean 0.79 of Mitsuba's when it was drawn black.)
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SurfaceEmitter {
    #[default]
    Absent,
    Present,
}

impl ShapeBinding {
    /// Whether the shape carries an emitter (an area light or one that adds no light).
    #[inline]
    pub fn carries_emitter(&self) -> bool {
        self.emitter.is_some() || self.surface_emitter == SurfaceEmitter::Present
    }

    /// Whether crossing the shape changes the medium (it names an interior or an exterior).
    #[inline]
    fn is_medium_transition(&self) -> bool {
        self.interior.is_some() || self.exterior.is_some()
    }
}

/// A placed copy of a shape group ([`SceneDescription::groups`]): Mitsuba's `instance`.
#[derive(Clone, Debug)]
pub struct InstanceDescription {
    /// Index into [`SceneDescription::groups`].
    pub group: u32,
    /// Group space to world.
    pub to_world: Transform,
}

/// Everything a scene is made of, before the acceleration structure is built.
#[derive(Clone, Debug, Default)]
pub struct SceneDescription {
    pub shapes: Vec<(Shape, ShapeBinding)>,
    /// Shape groups (Mitsuba's `shapegroup`): shapes in their group's space, rendered only
    /// through `instances`; one copy of each group's geometry and BVH serves all its
    /// instances. Their bindings carry no emitter.
    pub groups: Vec<Vec<(Shape, ShapeBinding)>>,
    pub instances: Vec<InstanceDescription>,
    pub bsdfs: Vec<Bsdf>,
    pub emitters: Vec<Emitter>,
    pub sensors: Vec<Sensor>,
    /// Participating media, referenced by the bindings' `interior` and `exterior`.
    pub media: Vec<Medium>,
    /// The medium the sensors sit in (Mitsuba's sensor `medium`).
    pub camera_medium: Option<u32>,
    /// How next-event estimation chooses among the emitters (the integrator's
    /// `light_selection`): the scene tabulates the choice once.
    pub light_selection: LightSelection,
}

/// A renderable scene.
#[derive(Debug)]
pub struct Scene {
    pub shapes: Vec<Shape>,
    pub bindings: Vec<ShapeBinding>,
    pub bsdfs: Vec<Bsdf>,
    pub emitters: Vec<Emitter>,
    /// The light at infinity that escaping rays see (Mitsuba allows one).
    pub environment: Option<u32>,
    /// The sun (steradian's `sun`, at most one), at infinity beside the environment.
    pub sun: Option<u32>,
    pub sensors: Vec<Sensor>,
    /// Participating media (`crate::medium`).
    pub media: Vec<Medium>,
    /// The medium camera rays start in.
    pub camera_medium: Option<u32>,
    /// Whether some surface may let light through unscattered ([`Bsdf::may_pass_light`]):
    /// without one, `volpath`'s shadow rays stop at the first surface.
    null_surfaces: bool,
    /// Whether some shape carries an emitter (camera rays under `hide_emitters` pass
    /// through those: [`Scene::ray_past_emitters`]).
    emitting_surfaces: bool,
    /// The bindings of each group's members, by instance (a hit's `instance` indexes it).
    instance_bindings: Vec<Arc<[ShapeBinding]>>,
    accel: Accel,
    /// Wall time spent building the hierarchies (groups' and the scene's).
    build_time: std::time::Duration,
    /// Next-event estimation's light choice: probability of each emitter, and the running sum.
    light_pmf: Vec<f32>,
    light_cdf: Vec<f32>,
    last_vertex: LastVertexLights,
}

/// What the emitters allow at a path's last vertex (`integrator/path.rs`, "The last vertex").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum LastVertexLights {
    /// Only delta lights (or none): no ray can hit an emitter, so a BSDF sample taken only to
    /// find emitters never finds one.
    Unreachable,
    /// At most [`LAST_VERTEX_MAX_CHECKS`] emitters: whether light sampling alone is bounded is
    /// checked at each last vertex ([`Emitter::light_sampling_bounded`], which also knows the
    /// kinds of light that never are).
    CheckEach,
    /// More emitters: always MIS.
    Mis,
}

/// Whether [`Scene::transmittance`] follows the media along its way or ignores them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MediaAlong {
    Followed,
    Ignored,
}

/// The most surfaces a shadow ray crosses in [`Scene::transmittance`].
const MAX_NULL_CROSSINGS: usize = 256;

/// The most emitters [`LastVertexLights::CheckEach`] checks at a vertex (one distance test
/// each).
const LAST_VERTEX_MAX_CHECKS: usize = 16;

impl LastVertexLights {
    fn of(emitters: &[Emitter]) -> LastVertexLights {
        if emitters.iter().all(|e| e.support() == Support::Delta) {
            LastVertexLights::Unreachable
        } else if emitters.len() <= LAST_VERTEX_MAX_CHECKS {
            LastVertexLights::CheckEach
        } else {
            LastVertexLights::Mis
        }
    }
}

impl Scene {
    /// Builds the acceleration structure and checks cross references.
    pub fn new(desc: SceneDescription) -> Result<Scene, String> {
        let (shapes, bindings): (Vec<Shape>, Vec<ShapeBinding>) = desc.shapes.into_iter().unzip();
        let media = desc.media.len();
        let bad_medium = |b: &ShapeBinding| {
            [b.interior, b.exterior].into_iter().flatten().find(|&m| m as usize >= media)
        };
        if let Some(m) = desc.camera_medium.filter(|&m| m as usize >= media) {
            return Err(format!("the sensors' medium is medium {m} of {media}"));
        }
        for (i, b) in bindings.iter().enumerate() {
            if b.bsdf as usize >= desc.bsdfs.len() {
                return Err(format!("shape {i} refers to BSDF {} of {}", b.bsdf, desc.bsdfs.len()));
            }
            if let Some(m) = bad_medium(b) {
                return Err(format!("shape {i} refers to medium {m} of {media}"));
            }
            if let Some(e) = b.emitter {
                match desc.emitters.get(e as usize) {
                    Some(e) if e.shape() == Some(i as u32) => shapes[i].prepare_sampling(),
                    _ => {
                        return Err(format!(
                            "shape {i} refers to emitter {e}, which is not its area light"
                        ))
                    }
                }
            }
        }
        let envs: Vec<u32> = desc
            .emitters
            .iter()
            .enumerate()
            .filter(|(_, e)| e.is_environment())
            .map(|(i, _)| i as u32)
            .collect();
        if envs.len() > 1 {
            return Err(
                "only one environment emitter (`constant` or `envmap`) is allowed per scene".into(),
            );
        }
        let suns: Vec<u32> = desc
            .emitters
            .iter()
            .enumerate()
            .filter(|(_, e)| matches!(e, Emitter::Sun(_)))
            .map(|(i, _)| i as u32)
            .collect();
        if suns.len() > 1 {
            return Err("only one `sun` is allowed per scene".into());
        }
        let build_start = std::time::Instant::now();
        let mut groups = Vec::with_capacity(desc.groups.len());
        for (g, members) in desc.groups.into_iter().enumerate() {
            let (members, bindings): (Vec<Shape>, Vec<ShapeBinding>) = members.into_iter().unzip();
            for (i, b) in bindings.iter().enumerate() {
                if b.bsdf as usize >= desc.bsdfs.len() {
                    return Err(format!(
                        "member {i} of group {g} refers to BSDF {} of {}",
                        b.bsdf,
                        desc.bsdfs.len()
                    ));
                }
                if b.emitter.is_some() {
                    return Err(format!("member {i} of group {g} is an emitter"));
                }
                if let Some(m) = bad_medium(b) {
                    return Err(format!("member {i} of group {g} refers to medium {m} of {media}"));
                }
            }
            groups
                .push((Arc::new(ShapeGroup::new(members)), Arc::<[ShapeBinding]>::from(bindings)));
        }
        let mut instances = Vec::with_capacity(desc.instances.len());
        let mut instance_bindings = Vec::with_capacity(desc.instances.len());
        for (i, inst) in desc.instances.iter().enumerate() {
            let Some((group, bindings)) = groups.get(inst.group as usize) else {
                return Err(format!(
                    "instance {i} refers to group {} of {}",
                    inst.group,
                    groups.len()
                ));
            };
            instances.push(Instance::new(group.clone(), inst.to_world));
            instance_bindings.push(bindings.clone());
        }
        let accel = Accel::build_with_instances(&shapes, instances, Isa::detect());
        let build_time = build_start.elapsed();
        let mut sensors = desc.sensors;
        for sensor in &mut sensors {
            sensor.set_scene(&accel.bounds());
        }
        let (light_pmf, light_cdf) =
            desc.light_selection.distribution(&desc.emitters, &shapes, accel.bounds());
        let null_surfaces = desc.bsdfs.iter().any(Bsdf::may_pass_light);
        let emitting_surfaces = bindings.iter().any(ShapeBinding::carries_emitter);
        Ok(Scene {
            emitting_surfaces,
            media: desc.media,
            camera_medium: desc.camera_medium,
            null_surfaces,
            last_vertex: LastVertexLights::of(&desc.emitters),
            light_pmf,
            light_cdf,
            shapes,
            bindings,
            bsdfs: desc.bsdfs,
            emitters: desc.emitters,
            environment: envs.first().copied(),
            sun: suns.first().copied(),
            sensors,
            instance_bindings,
            accel,
            build_time,
        })
    }

    /// Wall time the ray-tracing hierarchies took to build (part of loading the scene).
    pub fn build_time(&self) -> std::time::Duration {
        self.build_time
    }

    /// Sizes of the scene's top-level hierarchy.
    pub fn accel_stats(&self) -> AccelStats {
        self.accel.stats()
    }

    /// Bounds of all geometry.
    pub fn bounds(&self) -> Aabb {
        self.accel.bounds()
    }

    /// The closest surface along the ray.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<SurfaceInteraction> {
        count_ray();
        let hit = self.accel.intersect(&self.shapes, ray)?;
        Some(if hit.instance == NO_INSTANCE {
            self.shapes[hit.shape as usize].interaction(ray, &hit)
        } else {
            self.accel.instance(hit.instance).interaction(ray, &hit)
        })
    }

    /// True when something blocks the ray before `ray.t_max`.
    #[inline]
    pub fn occluded(&self, ray: &Ray) -> bool {
        count_ray();
        self.accel.occluded(&self.shapes, ray)
    }

    /// The binding of the shape hit (the scene's own or an instanced group member's).
    #[inline]
    fn binding(&self, si: &SurfaceInteraction) -> &ShapeBinding {
        if si.instance == NO_INSTANCE {
            &self.bindings[si.shape as usize]
        } else {
            &self.instance_bindings[si.instance as usize][si.shape as usize]
        }
    }

    #[inline]
    pub fn bsdf(&self, si: &SurfaceInteraction) -> &Bsdf {
        &self.bsdfs[self.binding(si).bsdf as usize]
    }

    /// The camera ray `ray` continued past the emitting surfaces it meets first (area lights,
    /// luminous openings), as Mitsuba 3's `hide_emitters` has camera rays pass through the
    /// lights they would show, to what lies behind them (Mitsuba 3.9.1 `path`, `volpath`,
    /// `direct` and the `prb` family alike); `ray` itself where its first hit does not emit.
    pub fn ray_past_emitters(&self, ray: &Ray) -> Ray {
        /// Emitting surfaces passed at most (a stack of lights in front of the camera).
        const MAX_PASSED: usize = 64;
        let mut ray = *ray;
        if !self.emitting_surfaces {
            return ray;
        }
        for _ in 0..MAX_PASSED {
            let Some(si) = self.intersect(&ray) else { break };
            if !self.binding(&si).carries_emitter() {
                break;
            }
            let mut next = si.spawn_ray(ray.d);
            // the far clip stays where it was
            next.t_max = ray.t_max - si.t;
            ray = next;
        }
        ray
    }

    /// The area light of the shape hit, if any.
    #[inline]
    pub fn area_emitter(&self, si: &SurfaceInteraction) -> Option<(u32, &Emitter)> {
        let e = self.binding(si).emitter?;
        Some((e, &self.emitters[e as usize]))
    }

    /// Picks an emitter by the light-selection distribution: its index and probability
    /// (`None` without emitters).
    #[inline]
    pub fn pick_emitter(&self, u: f32) -> Option<(u32, f32)> {
        let count = self.emitters.len();
        if count == 0 {
            return None;
        }
        let index = self.light_cdf.partition_point(|&c| c <= u).min(count - 1);
        Some((index as u32, self.light_pmf[index]))
    }

    /// The sphere around the scene's bounds (centre, radius, m); radius 1 for an empty scene.
    pub fn bounding_sphere(&self) -> (Vec3, f32) {
        let b = self.bounds();
        if b.is_empty() {
            return (Vec3::ZERO, 1.0);
        }
        let (center, radius) = b.bounding_sphere();
        (center, radius.max(1e-3))
    }

    /// Probability of choosing emitter `e` for next-event estimation (see [`LightSelection`]).
    #[inline]
    pub fn emitter_selection_pdf(&self, e: u32) -> f32 {
        self.light_pmf[e as usize]
    }

    /// Picks a light and samples a direction to it from `p`. The sample's pdf and weight
    /// include the selection probability. Visibility is *not* tested: callers first check that
    /// the sample can contribute (BSDF and cosine nonzero), then trace the shadow ray with
    /// [`Scene::unoccluded`], so that no ray is traced for a sample that would be discarded.
    #[inline]
    pub fn sample_emitter_direction(&self, p: Vec3, u: Vec2) -> Option<EmitterSample> {
        let count = self.emitters.len();
        if count == 0 {
            return None;
        }
        if count == 1 {
            // nothing to choose: the whole of u goes to the light (what the general case
            // computes too, bit for bit, with a choice probability of exactly 1)
            return self.emitters[0].sample_direction(&self.shapes, p, u);
        }
        // invert the CDF, then reuse u.x's position inside the chosen interval
        let (index, sel) = self.pick_emitter(u.x)?;
        let index = index as usize;
        let lo = if index == 0 { 0.0 } else { self.light_cdf[index - 1] };
        let u = Vec2::new(((u.x - lo) / sel).clamp(0.0, 1.0 - f32::EPSILON / 2.0), u.y);
        let emitter = &self.emitters[index];
        let mut es = emitter.sample_direction(&self.shapes, p, u)?;
        es.weight /= sel;
        if es.support == Support::Extended {
            es.pdf *= sel;
        }
        Some(es)
    }

    /// Whether next-event estimation alone may take all the light arriving at `p`, a path's last
    /// vertex with BSDF `bsdf`, so that the BSDF sample multiple importance sampling would add
    /// can be left out: where no ray can reach an emitter (any BSDF), or where `bsdf` is
    /// Lambertian and every light's samples have bounded weights at `p`
    /// ([`Emitter::light_sampling_bounded`]).
    #[inline]
    pub fn light_sampling_suffices(&self, bsdf: &Bsdf, p: Vec3) -> bool {
        match self.last_vertex {
            LastVertexLights::Unreachable => true,
            LastVertexLights::CheckEach => {
                bsdf.is_lambertian()
                    && self.emitters.iter().all(|e| e.light_sampling_bounded(&self.shapes, p))
            }
            LastVertexLights::Mis => false,
        }
    }

    /// True when nothing blocks the light sample `es` seen from the surface point `p` with
    /// geometric normal `n` (the shadow ray is offset off the surface and stops just short of
    /// the light).
    #[inline]
    pub fn unoccluded(&self, p: Vec3, n: Vec3, es: &EmitterSample) -> bool {
        self.unoccluded_along(p, n, es.wi, es.dist)
    }

    /// Whether nothing lies between `p` (on a surface with geometric normal `n`) and the point
    /// at distance `dist` along unit direction `wi` (`f32::INFINITY`: nothing along the ray).
    #[inline]
    pub fn unoccluded_along(&self, p: Vec3, n: Vec3, wi: Vec3, dist: f32) -> bool {
        let origin = crate::geometry::offset_ray_origin(p, n, wi);
        let shadow = if dist.is_finite() {
            let d = p + wi * dist - origin;
            let dist = d.length();
            Ray::new(origin, d / dist, dist * (1.0 - crate::geometry::interaction::SHADOW_EPSILON))
        } else {
            Ray::infinite(origin, wi)
        };
        !self.occluded(&shadow)
    }

    /// Solid-angle density (selection included) with which [`Scene::sample_emitter_direction`]
    /// from `p` proposes direction `wi` reaching emitter `e` at the point `light`.
    #[inline]
    pub fn pdf_emitter_direction(&self, e: u32, p: Vec3, wi: Vec3, light: &SurfacePoint) -> f32 {
        self.emitters[e as usize].pdf_direction(&self.shapes, p, wi, light)
            * self.emitter_selection_pdf(e)
    }

    /// Radiance arriving from the light at infinity `env` (the environment or the sun) along
    /// world direction `d` (a ray that left the scene), and the density (selection included)
    /// with which
    /// [`Scene::sample_emitter_direction`] proposes `d`.
    #[inline]
    pub fn environment_radiance_and_pdf(&self, env: u32, d: Vec3) -> (crate::Spectrum, f32) {
        let (le, pdf) = self.emitters[env as usize].radiance_and_pdf_from(d);
        (le, pdf * self.emitter_selection_pdf(env))
    }

    /// The medium light travelling in world direction `d` is in after crossing the surface
    /// `si`, having been in `current`: where the shape bounds media, its `exterior` on the
    /// side of its geometric normal and its `interior` behind it (Mitsuba's `target_medium`);
    /// elsewhere `current`.
    #[inline]
    pub fn medium_after(
        &self,
        si: &SurfaceInteraction,
        d: Vec3,
        current: Option<u32>,
    ) -> Option<u32> {
        let b = self.binding(si);
        if !b.is_medium_transition() {
            return current;
        }
        if si.n.dot(d) > 0.0 {
            b.exterior
        } else {
            b.interior
        }
    }

    /// Whether some surface may let light through unscattered (a `null` BSDF, a `mask`).
    #[inline]
    pub fn has_null_surfaces(&self) -> bool {
        self.null_surfaces
    }

    /// The transmittance from `p` (on a surface with geometric normal `n`; zero for a point
    /// in a medium) to the point at distance `dist` along unit direction `wi` (infinite:
    /// out of the scene), starting in `medium`: the product of each medium's transmittance
    /// over its stretch and of the null transmission ([`Bsdf::null_transmission`]) of each
    /// surface crossed, where media change as [`Scene::medium_after`] says (with
    /// [`MediaAlong::Ignored`], of the null transmissions alone, as for `path`, which sees no
    /// media). Zero where an opaque surface lies between.
    #[allow(clippy::too_many_arguments)]
    pub fn transmittance(
        &self,
        p: Vec3,
        n: Vec3,
        wi: Vec3,
        dist: f32,
        mut medium: Option<u32>,
        media: MediaAlong,
        sampler: &mut PixelSampler,
    ) -> Spectrum {
        if media == MediaAlong::Ignored {
            medium = None;
        }
        let shorten = 1.0 - crate::geometry::interaction::SHADOW_EPSILON;
        let target = p + wi * dist;
        let mut origin = crate::geometry::offset_ray_origin(p, n, wi);
        let mut tr = Spectrum::ONE;
        for _ in 0..MAX_NULL_CROSSINGS {
            let ray = if dist.is_finite() {
                let d = target - origin;
                let len = d.length();
                Ray::new(origin, d / len, len * shorten)
            } else {
                Ray::infinite(origin, wi)
            };
            if !self.null_surfaces {
                // every surface is opaque: one occlusion test, then the medium's stretch
                if self.occluded(&ray) {
                    return Spectrum::ZERO;
                }
                if let Some(m) = medium {
                    tr *= self.media[m as usize].transmittance(&ray, ray.t_max, sampler);
                }
                return tr;
            }
            let hit = self.intersect(&ray);
            if let Some(m) = medium {
                let t = hit.as_ref().map_or(ray.t_max, |si| si.t);
                tr *= self.media[m as usize].transmittance(&ray, t, sampler);
            }
            let Some(si) = hit else { return tr };
            let sp = crate::bsdf::ShadingPoint::new(&si);
            tr *= self.bsdf(&si).null_transmission(&sp, si.to_local(si.wo));
            if tr == Spectrum::ZERO {
                return tr;
            }
            if media == MediaAlong::Followed {
                medium = self.medium_after(&si, ray.d, medium);
            }
            origin = crate::geometry::offset_ray_origin(si.p, si.n, ray.d);
        }
        // a shadow ray still crossing surfaces after this many is caught between coincident
        // ones: counted as blocked rather than traced for ever
        Spectrum::ZERO
    }

    /// The radiance arriving along a ray that escaped the scene in world direction `d`, from
    /// every light at infinity (the environment, the sun), each weighted by `mis` of the
    /// density (selection included) with which [`Scene::sample_emitter_direction`] proposes `d`
    /// for that light.
    #[inline]
    pub fn escaped_radiance(&self, d: Vec3, mut mis: impl FnMut(f32) -> f32) -> Spectrum {
        let mut l = Spectrum::ZERO;
        if let Some(env) = self.environment {
            let (le, pdf) = self.environment_radiance_and_pdf(env, d);
            l += le * mis(pdf);
        }
        if let Some(sun) = self.sun {
            let (le, pdf) = self.environment_radiance_and_pdf(sun, d);
            if le != Spectrum::ZERO {
                l += le * mis(pdf);
            }
        }
        l
    }

    /// Whether a ray escaping the scene can see light (an environment or a sun).
    #[inline]
    pub fn has_light_at_infinity(&self) -> bool {
        self.environment.is_some() || self.sun.is_some()
    }

    /// Index of the sensor with the given `id`.
    pub fn sensor_index(&self, id: &str) -> Option<usize> {
        self.sensors.iter().position(|s| s.id == id)
    }

    /// Index of the sensor with the given `id`, or an error that lists the ids there are.
    pub fn find_sensor(&self, id: &str) -> Result<usize, String> {
        self.sensor_index(id).ok_or_else(|| {
            let ids: Vec<&str> =
                self.sensors.iter().map(|s| s.id.as_str()).filter(|s| !s.is_empty()).collect();
            format!(
                "the scene has no sensor with id '{id}' (sensor ids: {})",
                if ids.is_empty() { "none".into() } else { ids.join(", ") }
            )
        })
    }
}
