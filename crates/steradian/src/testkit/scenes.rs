//! Small scenes built in code, each with the radiance it must give in closed form, and the
//! estimate of the radiance along a ray with its standard error.

use glam::Vec3;

use super::stats::MeanError;
use crate::bsdf::{Bsdf, Diffuse};
use crate::emitter::{AreaLight, Emitter, PointLight};
use crate::geometry::{Ray, Transform};
use crate::integrator::{Integrator, PathTracer};
use crate::render::Job;
use crate::sampling::PixelSampler;
use crate::scene::{Scene, SceneDescription, ShapeBinding};
use crate::shape::{Rectangle, Shape, Sphere};
use crate::texture::Texture;
use crate::Spectrum;

/// A grid of `n × n` quads (2n² triangles, counter-clockwise seen from +z where the grid
/// lies flat): `position(i, j)` places vertex (i, j) for i, j in 0..=n, called row by row
/// (j outer). Returns the positions and the triangles.
pub fn grid_mesh(n: u32, mut position: impl FnMut(u32, u32) -> Vec3) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let positions = (0..=n).flat_map(|j| (0..=n).map(move |i| (i, j))).map(|(i, j)| position(i, j));
    let positions: Vec<Vec3> = positions.collect();
    let mut indices = Vec::with_capacity(2 * (n * n) as usize);
    for j in 0..n {
        for i in 0..n {
            let v = j * (n + 1) + i;
            indices.push([v, v + 1, v + n + 2]);
            indices.push([v, v + n + 2, v + n + 1]);
        }
    }
    (positions, indices)
}

/// A furnace: the inside of the unit sphere around the origin (normals flipped inwards),
/// diffuse with reflectance `rho` and emitting radiance `le` (W/(m²·sr)). Every ray from
/// inside sees the radiance [`furnace_radiance`].
pub fn furnace(le: Spectrum, rho: Spectrum, tracer: PathTracer) -> Job {
    let sphere = Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0, &Transform::IDENTITY, true));
    let binding =
        ShapeBinding { bsdf: 0, emitter: Some(0), id: "furnace".into(), ..Default::default() };
    let scene = Scene::new(SceneDescription {
        shapes: vec![(sphere, binding)],
        bsdfs: vec![Bsdf::Diffuse(Diffuse::new(Texture::Constant(rho)))],
        emitters: vec![Emitter::Area(AreaLight::new(0, Texture::Constant(le)))],
        light_selection: tracer.light_selection,
        ..Default::default()
    })
    .expect("the furnace is a valid scene");
    Job { scene, integrator: Integrator::Path(tracer), warnings: Vec::new(), inputs: Vec::new() }
}

/// The radiance inside the [`furnace`]: L = Le + ρ·L' where L' is what the next vertex sees
/// with one segment fewer, so paths of at most d segments (`max_depth`) give
/// Le·(1 + ρ + … + ρ^(d−1)), and unbounded ones Le/(1 − ρ).
pub fn furnace_radiance(le: Spectrum, rho: Spectrum, max_depth: Option<u32>) -> Spectrum {
    match max_depth {
        None => le / (Spectrum::ONE - rho),
        Some(d) => {
            let mut sum = Spectrum::ZERO;
            let mut term = le;
            for _ in 0..d {
                sum += term;
                term *= rho;
            }
            sum
        }
    }
}

/// A lit plane: the square [−`half`, `half`]² of the plane z = 0, facing +z, diffuse with
/// reflectance `rho`, under a point light of intensity `intensity` (W/sr) at `light`. Nothing
/// else is in the scene, so each point sees only the light: [`lit_plane_radiance`].
pub fn lit_plane(
    rho: Spectrum,
    intensity: Spectrum,
    light: Vec3,
    half: f32,
    tracer: PathTracer,
) -> Job {
    let to_world = Transform::scale(Vec3::new(half, half, 1.0)).expect("a positive scale");
    let plane = Shape::Rectangle(Rectangle::new(&to_world, false));
    let binding = ShapeBinding { bsdf: 0, emitter: None, id: "plane".into(), ..Default::default() };
    let scene = Scene::new(SceneDescription {
        shapes: vec![(plane, binding)],
        bsdfs: vec![Bsdf::Diffuse(Diffuse::new(Texture::Constant(rho)))],
        emitters: vec![Emitter::Point(PointLight::new(light, intensity))],
        light_selection: tracer.light_selection,
        ..Default::default()
    })
    .expect("the lit plane is a valid scene");
    Job { scene, integrator: Integrator::Path(tracer), warnings: Vec::new(), inputs: Vec::new() }
}

/// The radiance the [`lit_plane`] reflects at its point `q` (z = 0), in any direction above
/// it: L = ρ/π·H with the irradiance H = I·cos θ/r² (r = |light − q|, cos θ = light.z/r).
pub fn lit_plane_radiance(rho: Spectrum, intensity: Spectrum, light: Vec3, q: Vec3) -> Spectrum {
    let r2 = (light - q).length_squared();
    let cos = light.z / r2.sqrt();
    rho * std::f32::consts::FRAC_1_PI * intensity * (cos / r2)
}

/// The job's integrator's estimate of the radiance arriving along `ray`, per channel: `n`
/// camera samples, sample `i` with the i.i.d. stream `i` of `seed`.
pub fn radiance(job: &Job, ray: &Ray, n: u32, seed: u64) -> [MeanError; 3] {
    let mut acc = [MeanError::default(); 3];
    for i in 0..n {
        let mut sampler = PixelSampler::independent(seed, i as u64);
        let l = job.integrator.li(&job.scene, ray, &mut sampler);
        for (c, a) in acc.iter_mut().enumerate() {
            a.push(l[c] as f64);
        }
    }
    acc
}
