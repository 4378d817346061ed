//! `batch`: several cameras side by side on one film (Mitsuba 3's batch sensor), e.g. views
//! of one scene rendered in one pass.
//!
//! | parameter  | type    | meaning |
//! |------------|---------|---------|
//! | (nested)   | sensor  | one or more cameras (`perspective`, `thinlens`, `orthographic`) |
//! | (film)     | film    | the batch's film: its width is split evenly between the cameras |
//!
//! With n cameras on a film W pixels wide (W a multiple of n), camera i renders the columns
//! [i·W/n, (i + 1)·W/n), each as if its own film were W/n × H (its field of view and aspect
//! ratio follow from that size): film position u maps to camera ⌊u·n⌋ at u·n − ⌊u·n⌋, as in
//! Mitsuba. Meters and nested batches are refused by the loader.

use glam::Vec2;

use super::SensorKind;
use crate::geometry::Ray;

#[derive(Clone, Debug)]
pub struct Batch {
    /// The cameras, left to right.
    pub cameras: Vec<SensorKind>,
}

impl Batch {
    /// The ray of the camera whose columns hold film position `film_uv`, `aperture` the
    /// 2-D sample of a thin lens.
    #[inline]
    pub fn sample_ray(&self, film_uv: Vec2, aperture: Vec2) -> Option<Ray> {
        let n = self.cameras.len();
        let x = film_uv.x * n as f32;
        let i = (x.max(0.0) as usize).min(n - 1);
        let local = Vec2::new(x - i as f32, film_uv.y);
        self.cameras[i].camera_ray_with(local, aperture)
    }
}
