use glam::Vec3;

/// A ray `o + t·d` for `t ∈ (0, t_max)`. `d` is a unit vector, so `t` is a distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub o: Vec3,
    pub d: Vec3,
    pub t_max: f32,
}

impl Ray {
    #[inline]
    pub fn new(o: Vec3, d: Vec3, t_max: f32) -> Self {
        Ray { o, d, t_max }
    }

    /// An unbounded ray.
    #[inline]
    pub fn infinite(o: Vec3, d: Vec3) -> Self {
        Ray { o, d, t_max: f32::INFINITY }
    }

    /// The point at distance `t`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.o + self.d * t
    }
}
