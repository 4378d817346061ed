//! # `linearcurve`: tubes along polylines, for hair and fibres
//!
//! Mitsuba plugin `linearcurve`.
//!
//! | Parameter | Type | Default | Meaning |
//! |---|---|---|---|
//! | `filename` | string | (required) | curve file: `x y z radius` per line, an empty line between curves ([`read_curves`](super::read_curves)) |
//! | `to_world` | transform | identity | moves the control points; the radii are not transformed (m, as in the file) |
//!
//! **Geometry** (Mitsuba's, which hands the curves to Embree as round linear curves): each
//! segment between control points (p₀, r₀) and (p₁, r₁) is the sweep of a sphere whose
//! radius varies linearly, i.e. the convex hull of the spheres at its ends (a cone touching
//! both spheres, plus their caps); a curve is the union of its segments, with a spherical
//! joint at every inner point and a spherical end cap at each end. Only the outside is seen:
//! a ray from inside a segment passes through it (Mitsuba culls curves' back faces). Ray tests
//! run in double precision, from an origin moved next to the segment, so that hairs a
//! thousandth of the scene's size intersect cleanly.
//!
//! **Surface data** (Mitsuba's): the normal at a hit p is the direction from the centre c of
//! the swept sphere that touches p, c = (1 − v)·p₀ + v·p₁ (v = 0 or 1 on the caps); the
//! texture coordinates are u = the angle of the normal about the segment's axis, in a frame
//! whose first axis is the projection of +z (+y where the segment is vertical), over 2π, and
//! v = (segment index + v) / segment count, along all segments of the file;
//! ∂p/∂u = 2π·(axis × (p − c)), ∂p/∂v = segment count × ((p₁ − p₀) + (r₁ − r₀)·n). The
//! shading frame is the one Mitsuba 3.9.1 gives linear curves (read from its surface
//! interactions): the normal's default frame (Duff et al.), not tied to the axis, so that an
//! anisotropic BSDF such as `hair` sees the fibre where Mitsuba's does (`bsplinecurve`'s frame
//! follows its axis: Mitsuba's does too). With a frame along the axis instead, `hair.xml`
//! failed on the linear curves (289 pixels at z > 4 at 1024 spp).
//!
//! **Where steradian differs on purpose:** a negative radius is an error. Like Mitsuba,
//! curves take no `flip_normals`, cannot emit (Mitsuba cannot sample points on them) and
//! carry no sensors; the loader refuses those. [`LinearCurve::surface_area`] is the
//! segments' frustum area, π(r₀ + r₁)·√(ℓ² + (r₁ − r₀)²), for reports only.

use std::f32::consts::PI;

use glam::{DVec3, Vec2, Vec3, Vec4, Vec4Swizzles};

use super::{PositionSample, ShapeError};
use crate::geometry::{Aabb, Frame, PreliminaryHit, Ray, SurfaceInteraction, Transform};

#[derive(Clone, Debug)]
pub struct LinearCurve {
    /// Control points: world position (m) and radius (m).
    points: Vec<Vec4>,
    /// The first control point of each segment, and whether it begins or ends its curve.
    segments: Vec<(u32, SegmentEnds)>,
    area: f32,
}

impl LinearCurve {
    /// The curves (control points x, y, z, radius before `to_world`, at least two each).
    pub fn new(curves: &[Vec<Vec4>], to_world: &Transform) -> Result<LinearCurve, ShapeError> {
        let ControlPoints { points, curves } =
            world_control_points("linearcurve", curves, 2, to_world)?;
        let mut segments = Vec::new();
        for (first, len) in curves {
            let n = len - 1;
            segments.extend(
                (0..n).map(|j| (first + j, SegmentEnds { first: j == 0, last: j + 1 == n })),
            );
        }
        if segments.is_empty() {
            return Err(ShapeError("linearcurve: no curves".into()));
        }
        let area = segments
            .iter()
            .map(|&(i, _)| frustum_area(points[i as usize], points[i as usize + 1]))
            .sum();
        Ok(LinearCurve { points, segments, area })
    }

    /// Number of segments (the shape's primitives).
    pub fn segment_count(&self) -> u32 {
        self.segments.len() as u32
    }

    /// The two control points of segment `prim`.
    #[inline]
    fn ends(&self, prim: u32) -> (Vec4, Vec4) {
        let i = self.segments[prim as usize].0 as usize;
        (self.points[i], self.points[i + 1])
    }

    pub fn bounds(&self) -> Aabb {
        (1..self.segment_count()).fold(self.prim_bounds(0), |bb, p| bb.union(&self.prim_bounds(p)))
    }

    /// The box around both end spheres of segment `prim`.
    pub fn prim_bounds(&self, prim: u32) -> Aabb {
        let (a, b) = self.ends(prim);
        chord_bounds(a, b)
    }

    pub fn surface_area(&self) -> f32 {
        self.area
    }

    /// The nearest front-facing hit of segment `prim`: `(t, (v, 0))`, v the parameter of the
    /// touching sphere's centre along the segment (module docs).
    #[inline]
    pub fn intersect_prim(&self, prim: u32, ray: &Ray) -> Option<(f32, Vec2)> {
        let (a, b) = self.ends(prim);
        let (i, ends) = self.segments[prim as usize];
        let next = self.points[i as usize + 2 * usize::from(!ends.last)];
        let caps = Caps {
            begin: ends.first,
            end: if ends.last {
                EndCap::Whole
            } else {
                EndCap::UpTo(next.xyz().as_dvec3(), next.w as f64)
            },
        };
        let (t, v) = intersect_chord(a, b, caps, ray)?;
        Some((t, Vec2::new(v, 0.0)))
    }

    pub fn interaction(&self, ray: &Ray, hit: &PreliminaryHit) -> SurfaceInteraction {
        let (a, b) = self.ends(hit.prim);
        let (p0, p1) = (a.xyz(), b.xyz());
        let v = hit.uv.x;
        let p = ray.o + ray.d * hit.t;
        let c = p0 * (1.0 - v) + p1 * v;
        let axis = (p1 - p0).normalize_or_zero();
        let radial = p - c;
        // a hit on the centre line itself (a zero radius) has no normal of its own
        let n = radial.try_normalize().unwrap_or_else(|| Frame::from_normal(axis).s);
        let u = turns_about(axis, n);
        let count = self.segment_count() as f32;
        let uv = Vec2::new(u, (v + hit.prim as f32) / count);
        let dpdu = 2.0 * PI * axis.cross(radial);
        let dpdv = count * ((p1 - p0) + (b.w - a.w) * n);
        SurfaceInteraction {
            p,
            t: hit.t,
            n,
            // Mitsuba 3.9.1's frame for linear curves: the normal's own, not the axis's
            sh_frame: Frame::from_normal(n),
            uv,
            dpdu,
            dpdv,
            wo: -ray.d,
            shape: hit.shape,
            prim: hit.prim,
            bary: hit.uv,
            instance: hit.instance,
        }
    }

    /// Curves cannot be sampled by area (the loader refuses emitters and sensors on them): a
    /// sample of density 0, which every caller drops.
    pub fn sample_position(&self, _u: Vec2) -> PositionSample {
        let (a, _) = self.ends(0);
        PositionSample { p: a.xyz(), n: Vec3::Z, uv: Vec2::ZERO, pdf_area: 0.0 }
    }
}

/// Whether a segment begins or ends its curve.
#[derive(Clone, Copy, Debug, Default)]
struct SegmentEnds {
    first: bool,
    last: bool,
}

/// Which parts of its end spheres a segment shows, as Embree divides a curve between its
/// segments: the sphere at its start only if it starts the curve, and the sphere at its end
/// up to where the next segment's cone begins (all of it at the curve's end). Seen from
/// outside, the union is the same however the joints are shared; a ray from inside a curve
/// (light through a fibre) meets no joint that Embree would not show.
#[derive(Clone, Copy, Debug)]
pub(super) struct Caps {
    pub begin: bool,
    pub end: EndCap,
}

/// The sphere at a segment's end.
#[derive(Clone, Copy, Debug)]
pub(super) enum EndCap {
    /// None: the curve is open there (`bsplinecurve`'s ends).
    Open,
    /// All of it: the curve ends there.
    Whole,
    /// Up to where the next segment's cone begins, that segment's far end (centre, radius).
    UpTo(DVec3, f64),
}

/// Control points in world space and where each curve's lie among them.
pub(super) struct ControlPoints {
    /// Position (m) and radius (m) of every point.
    pub points: Vec<Vec4>,
    /// Each curve's first point and point count.
    pub curves: Vec<(u32, u32)>,
}

/// The curves' control points moved by `to_world` (radii kept), checked as both curve
/// shapes need them (finite, radii ≥ 0, at least `min_points` per curve).
pub(super) fn world_control_points(
    plugin: &str,
    curves: &[Vec<Vec4>],
    min_points: usize,
    to_world: &Transform,
) -> Result<ControlPoints, ShapeError> {
    let mut points = Vec::new();
    let mut starts = Vec::with_capacity(curves.len());
    for curve in curves {
        if curve.len() < min_points {
            return Err(ShapeError(format!(
                "{plugin}: a curve needs at least {min_points} control points, one has {}",
                curve.len()
            )));
        }
        let first = points.len() as u32;
        for (k, c) in curve.iter().enumerate() {
            let p = to_world.point(c.xyz());
            if !(p.is_finite() && c.w >= 0.0 && c.w.is_finite()) {
                return Err(ShapeError(format!(
                    "{plugin}: control point {} is not finite or has a negative radius",
                    first as usize + k
                )));
            }
            points.push(p.extend(c.w));
        }
        starts.push((first, curve.len() as u32));
    }
    Ok(ControlPoints { points, curves: starts })
}

/// The box around the spheres (centre, radius) `a` and `b`.
pub(super) fn chord_bounds(a: Vec4, b: Vec4) -> Aabb {
    let mut bb = Aabb::new(a.xyz() - a.w, a.xyz() + a.w);
    bb.grow(b.xyz() - b.w);
    bb.grow(b.xyz() + b.w);
    bb
}

/// The lateral area of the frustum between the circles (centre, radius) `a` and `b`, m².
pub(super) fn frustum_area(a: Vec4, b: Vec4) -> f32 {
    let slant = (a.xyz().distance_squared(b.xyz()) + (b.w - a.w) * (b.w - a.w)).sqrt();
    PI * (a.w + b.w) * slant
}

/// [`intersect_round_segment`] for the spheres (centre, radius) `a` and `b` and a ray: the hit
/// `(t, v)` with 0 < t < `ray.t_max`.
#[inline]
pub(super) fn intersect_chord(a: Vec4, b: Vec4, caps: Caps, ray: &Ray) -> Option<(f32, f32)> {
    let (t, v) = intersect_round_segment(
        a.xyz().as_dvec3(),
        a.w as f64,
        b.xyz().as_dvec3(),
        b.w as f64,
        caps,
        ray.o.as_dvec3(),
        ray.d.as_dvec3(),
    )?;
    let t = t as f32;
    (t > 0.0 && t < ray.t_max).then_some((t, v as f32))
}

/// The angle of `dir` about `axis`, in turns ∈ [0, 1), in Mitsuba's frame about a curve's
/// axis: the rotation axis is +z projected off the axis (+y where the axis is parallel to z),
/// the radial axis their cross product.
pub(super) fn turns_about(axis: Vec3, dir: Vec3) -> f32 {
    let guide = Vec3::Z;
    let v_rot = if guide.dot(axis).abs() == 1.0 {
        Vec3::Y
    } else {
        (guide - axis * axis.dot(guide)).normalize()
    };
    let v_rad = v_rot.cross(axis);
    let u = crate::geometry::trig::atan2(v_rot.dot(dir), v_rad.dot(dir)) * (0.5 / PI);
    if u < 0.0 {
        u + 1.0
    } else {
        u
    }
}

/// The nearest front-facing hit (t > 0) of the ray o + t·d with the convex hull of the spheres
/// (p0, r0) and (p1, r1): `(t, v)` with v ∈ [0, 1] the centre of the touching sphere (0 or 1
/// on the caps). The cone touching both spheres is parametrised by
/// y = (h − p0)·(p1 − p0) + r0·(r1 − r0) over h on it: y = 0 where it touches the first sphere,
/// y = g = |p1 − p0|² − (r1 − r0)² where it touches the second, and v = y / g.
fn intersect_round_segment(
    p0: DVec3,
    r0: f64,
    p1: DVec3,
    r1: f64,
    caps: Caps,
    o: DVec3,
    d: DVec3,
) -> Option<(f64, f64)> {
    let dd = d.length_squared();
    // an origin next to the segment keeps the quadratics' terms of the segment's own size
    let shift = (0.5 * (p0 + p1) - o).dot(d) / dd;
    let o = o + shift * d;
    let dp = p1 - p0;
    let dr = r1 - r0;
    let g = dp.length_squared() - dr * dr;
    let oo = o - p0;
    let (odp, ddp) = (oo.dot(dp), d.dot(dp));
    // y along the ray: yp + t·ddp
    let yp = odp + r0 * dr;
    let mut best: Option<(f64, f64)> = None;
    let mut consider = |t: f64, v: f64| {
        let t = t + shift;
        if t > 0.0 && best.is_none_or(|(b, _)| t < b) {
            best = Some((t, v));
        }
    };
    if g > 0.0 {
        let qa = g * dd - ddp * ddp;
        let qb = 2.0 * (g * oo.dot(d) - ddp * yp);
        let qc = g * oo.length_squared()
            - odp * odp
            - r0 * r0 * dp.length_squared()
            - 2.0 * r0 * dr * odp;
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 && qa.abs() > f64::MIN_POSITIVE {
            let q = disc.sqrt();
            for t in [(-qb - q) / (2.0 * qa), (-qb + q) / (2.0 * qa)] {
                let y = yp + t * ddp;
                // on the part of the cone between its two touching circles, facing the ray
                let outward = g * (oo + t * d) - dp * y;
                if (0.0..=g).contains(&y) && outward.dot(d) < 0.0 {
                    consider(t, y / g);
                }
            }
        }
    }
    for (c, r, v) in [(p0, r0, 0.0), (p1, r1, 1.0)] {
        if v == 0.0 && !caps.begin || v == 1.0 && matches!(caps.end, EndCap::Open) {
            continue;
        }
        let oc = o - c;
        let half_b = oc.dot(d);
        let h2 = half_b * half_b - dd * (oc.length_squared() - r * r);
        if h2 < 0.0 {
            continue;
        }
        let t = (-half_b - h2.sqrt()) / dd;
        let y = yp + t * ddp;
        // a cap lies beyond its touching circle; where one sphere holds the other (g ≤ 0)
        // the hull is the larger sphere, whose front is nearer than the smaller one's
        let on_cap = g <= 0.0 || if v == 0.0 { y <= 0.0 } else { y >= g };
        // the end sphere stops where the next segment's cone starts
        let before_next = match caps.end {
            EndCap::UpTo(p2, r2) if v == 1.0 => {
                (o + t * d - p1).dot(p2 - p1) + r1 * (r2 - r1) <= 0.0
            }
            _ => true,
        };
        if on_cap && before_next {
            consider(t, v);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Pcg32;

    fn curve(points: &[[f32; 4]]) -> LinearCurve {
        let c: Vec<Vec4> = points.iter().map(|&p| Vec4::from_array(p)).collect();
        LinearCurve::new(&[c], &Transform::default()).unwrap()
    }

    /// The distance from a point to the hull of two spheres: the least over the swept spheres
    /// of |x − c(s)| − r(s), by dense search (s ∈ [0, 1]).
    fn hull_distance(x: Vec3, a: Vec4, b: Vec4) -> f32 {
        (0..=20000)
            .map(|k| {
                let s = k as f32 / 20000.0;
                let c = a.xyz().lerp(b.xyz(), s);
                x.distance(c) - (a.w + (b.w - a.w) * s)
            })
            .fold(f32::INFINITY, f32::min)
    }

    /// Hits of random rays lie on the surface of the swept sphere (distance 0 to the hull), the
    /// normal is the hull's (moving along it leaves the surface), and v names the touching
    /// sphere: |p − c(v)| = r(v).
    #[test]
    fn hits_lie_on_the_swept_sphere() {
        let (a, b) = (Vec4::new(0.0, 0.0, 0.0, 0.3), Vec4::new(1.0, 0.5, 0.2, 0.1));
        let shape = curve(&[a.to_array(), b.to_array()]);
        let mut rng = Pcg32::new(7, 1);
        let mut hits = 0;
        for _ in 0..2000 {
            let o = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 6.0 - 3.0;
            let target = Vec3::new(rng.next_f32(), rng.next_f32() * 0.5, rng.next_f32() * 0.2);
            let ray = Ray::new(o, (target - o).normalize(), f32::INFINITY);
            if hull_distance(o, a, b) <= 0.0 {
                // from inside: back faces are culled
                assert!(shape.intersect_prim(0, &ray).is_none());
                continue;
            }
            let Some((t, uv)) = shape.intersect_prim(0, &ray) else { continue };
            hits += 1;
            let hit = PreliminaryHit { t, uv, shape: 0, prim: 0, instance: u32::MAX };
            let si = shape.interaction(&ray, &hit);
            assert!(hull_distance(si.p, a, b).abs() < 2e-4, "{:?}", si.p);
            let v = uv.x;
            let c = a.xyz().lerp(b.xyz(), v);
            let r = a.w + (b.w - a.w) * v;
            assert!((si.p.distance(c) - r).abs() < 1e-4, "v {v}");
            assert!(hull_distance(si.p + 0.01 * si.n, a, b) > 0.0099);
            assert!(si.n.dot(ray.d) < 0.0, "front faces only");
        }
        assert!(hits > 500, "{hits}");
    }

    /// A ray across the middle of a long tube of radius 0.01 seen from 100 m: t to 1e-5 m.
    #[test]
    fn thin_distant_tubes_intersect_precisely() {
        let shape = curve(&[[-1.0, 0.0, 0.0, 0.01], [1.0, 0.0, 0.0, 0.01]]);
        let ray = Ray::new(Vec3::new(0.3, 0.0, 100.0), -Vec3::Z, f32::INFINITY);
        let (t, uv) = shape.intersect_prim(0, &ray).unwrap();
        assert!((t - 99.99).abs() < 1e-5 && (uv.x - 0.65).abs() < 1e-5, "{t} {uv}");
        // and one grazing past it misses
        let ray = Ray::new(Vec3::new(0.3, 0.0101, 100.0), -Vec3::Z, f32::INFINITY);
        assert!(shape.intersect_prim(0, &ray).is_none());
    }

    /// A curve's first sphere is whole: a ray from just under it, straight up, hits it (the
    /// end sphere's cut at the next segment does not reach the start).
    #[test]
    fn the_first_sphere_is_whole() {
        let shape =
            curve(&[[0.0, 0.2, 0.0, 0.16], [0.36, 0.83, 0.27, 0.12], [0.63, 0.3, 0.54, 0.09]]);
        let ray = Ray::new(Vec3::new(0.025, 0.0, 0.015), Vec3::Y, f32::INFINITY);
        let (t, _) = shape.intersect_prim(0, &ray).expect("the first sphere");
        let expect = 0.2 - (0.16f32 * 0.16 - 0.025 * 0.025 - 0.015 * 0.015).sqrt();
        assert!((t - expect).abs() < 1e-5, "{t} {expect}");
    }

    /// The sphere at a joint belongs to one segment (Embree's split): a ray at the joint's
    /// outer side hits it once, through the first segment, at v = 1 of it, 0.5 of the curve.
    #[test]
    fn joints_are_spheres_shown_once() {
        let shape = curve(&[[0.0, 0.0, 0.0, 0.1], [1.0, 0.0, 0.0, 0.1], [1.0, 1.0, 0.0, 0.1]]);
        let ray = Ray::new(Vec3::new(1.05, -0.05, 5.0), -Vec3::Z, f32::INFINITY);
        let (t, uv) = shape.intersect_prim(0, &ray).unwrap();
        assert!(shape.intersect_prim(1, &ray).is_none());
        let h = PreliminaryHit { t, uv, shape: 0, prim: 0, instance: u32::MAX };
        let si = shape.interaction(&ray, &h);
        assert!((si.p.distance(Vec3::new(1.0, 0.0, 0.0)) - 0.1).abs() < 1e-5);
        assert!((si.uv.y - 0.5).abs() < 1e-6, "{:?}", si.uv);
    }
}
