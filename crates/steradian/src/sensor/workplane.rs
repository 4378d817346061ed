//! `workplane` (steradian's own sensor): illuminance on a grid over a plane, the lighting
//! engineer's calculation surface, each value with its standard error.
//!
//! | parameter  | type      | default       | meaning |
//! |------------|-----------|---------------|---------|
//! | `to_world` | transform | identity      | maps the square [−1, 1]² at z = 0 (normal +z) onto the plane, as Mitsuba's `rectangle` |
//! | `nx`, `ny` | integer   | 10, 10        | cells along the plane's x and y |
//! | `mode`     | string    | `point`       | `point`: at each cell's centre; `cell`: averaged over the cell |
//! | `quantity` | string    | `illuminance` | `illuminance` (lx), `irradiance` (W/m²) or `daylight_factor` (%): how `steradian measure` reports it |
//! | `batch`    | integer   | 1             | Sobol points per sample (1 to 65536): each sample the mean of that many points under a scramble of its own (`measure --batch` overrides it) |
//!
//! The film is nx × ny pixels (a `<film>` child, if given, must be that size; its filter plays
//! no part): pixel (i, j) is the cell at x from −1 + 2i/nx, y from 1 − 2j/ny downwards, so the
//! picture is the plan seen from the normal's side with +x to the right and +y up. Every
//! value is the irradiance on the side the normal points to (W/m² per RGB channel, estimated
//! as the `irradiancemeter` estimates it: every light sampled at the point, MIS with cosine
//! samples); illuminance is 683 lm/W × its luminance Y. Samples are independent, so each
//! cell's standard error is honest; all cells render in one pass over the grid. With `batch`
//! N > 1 each sample is a randomised quasi-Monte Carlo replicate of N stratified points (the
//! render driver's `block.rs`): still independent of each other, and far less noisy: on
//! `scenes/lighting_room.xml` 64 × 64 points per cell reach 0.055 % where 4096 independent
//! points reach 0.19 % (2026-12-06, Intel Xeon; `benches/results/`).
//!
//! **Daylight factor.** With `quantity` `daylight_factor` each value is DF = 100 · E_in / E_out
//! (%), E_in the cell's illuminance from everything in the scene (the sky through openings,
//! inter-reflections, any lamps: the scene decides what it holds) and E_out the illuminance the
//! scene's `ciesky` gives an unobstructed horizontal plane, in closed form for the overcast
//! sky (7π/9 · L_z, or the `horizontal_illuminance` given). A scene without a `ciesky` has no
//! daylight factor: the loader says so. The standard error scales with it (E_out is exact).

use glam::{Vec2, Vec3};

use crate::geometry::Transform;
use crate::param::ParamError;

/// Where on a cell the plane is measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WorkplaneMode {
    /// At the cell's centre.
    Point,
    /// Averaged over the cell's area.
    Cell,
}

/// How a work plane's values are reported.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WorkplaneUnit {
    /// lx (683 lm/W × Y of the RGB irradiance).
    Illuminance,
    /// W/m² per channel.
    Irradiance,
    /// The daylight factor, %: 100 × the illuminance over `outdoor_lux`, the sky's illuminance
    /// on an unobstructed horizontal plane (CIE: DF = E_in / E_out under the overcast sky).
    DaylightFactor { outdoor_lux: f64 },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Workplane {
    to_world: Transform,
    /// The plane's unit normal (world).
    normal: Vec3,
    pub nx: u32,
    pub ny: u32,
    pub mode: WorkplaneMode,
    pub unit: WorkplaneUnit,
    /// Sobol points per sample (1: one independent point).
    pub batch: u32,
}

impl Workplane {
    pub const DEFAULT_CELLS: u32 = 10;
    pub const DEFAULT_MODE: WorkplaneMode = WorkplaneMode::Point;
    pub const DEFAULT_UNIT: WorkplaneUnit = WorkplaneUnit::Illuminance;
    pub const DEFAULT_BATCH: u32 = 1;

    pub fn new(
        to_world: Transform,
        nx: u32,
        ny: u32,
        mode: WorkplaneMode,
        unit: WorkplaneUnit,
    ) -> Result<Self, ParamError> {
        let n = to_world.normal(Vec3::Z);
        if !(n.is_finite() && n.length_squared() > 0.0) {
            return Err(ParamError::new("to_world", "to_world flattens the plane to a line"));
        }
        Ok(Workplane {
            to_world,
            normal: n.normalize(),
            nx,
            ny,
            mode,
            unit,
            batch: Self::DEFAULT_BATCH,
        })
    }

    /// The point measured for film position `film_uv` ∈ [0, 1]² (a pixel plus the sample's
    /// position in it) and the plane's normal there.
    #[inline]
    pub fn point(&self, film_uv: Vec2) -> (Vec3, Vec3) {
        let (nx, ny) = (self.nx as f32, self.ny as f32);
        let uv = match self.mode {
            WorkplaneMode::Cell => film_uv,
            WorkplaneMode::Point => {
                let i = (film_uv.x * nx).floor().clamp(0.0, nx - 1.0);
                let j = (film_uv.y * ny).floor().clamp(0.0, ny - 1.0);
                Vec2::new((i + 0.5) / nx, (j + 0.5) / ny)
            }
        };
        let local = Vec3::new(2.0 * uv.x - 1.0, 1.0 - 2.0 * uv.y, 0.0);
        (self.to_world.point(local), self.normal)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_map_onto_the_plane_as_a_plan_view() {
        let t = Transform::scale(Vec3::new(2.0, 1.5, 1.0))
            .unwrap()
            .then(&Transform::translate(Vec3::Z));
        let w = Workplane::new(t, 4, 3, WorkplaneMode::Point, WorkplaneUnit::Illuminance).unwrap();
        // pixel (0, 0) is the top-left cell: x = −2 + 0.5, y = 1.5 − 0.5; any point of it
        for uv in [Vec2::new(0.01, 0.01), Vec2::new(0.24, 0.3)] {
            let (p, n) = w.point(uv);
            assert!((p - Vec3::new(-1.5, 1.0, 1.0)).length() < 1e-6, "{p}");
            assert_eq!(n, Vec3::Z);
        }
        let cell = Workplane { mode: WorkplaneMode::Cell, ..w };
        let (p, _) = cell.point(Vec2::new(0.01, 0.01));
        assert!((p - Vec3::new(-2.0 + 0.04, 1.5 - 0.03, 1.0)).length() < 1e-5, "{p}");
    }
}
