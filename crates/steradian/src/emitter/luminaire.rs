//! `luminaire` (steradian's own plugin): a point source whose intensity is a photometric file's
//! table, I(γ, C) in candela (`crate::photometry`).
//!
//! | parameter  | type      | default    | meaning |
//! |------------|-----------|------------|---------|
//! | `filename` | string    | (required) | an IES LM-63 (`.ies`) or EULUMDAT (`.ldt`) file, relative to the scene file |
//! | `to_world` | transform | identity   | places and turns the luminaire: a rotation and a translation |
//! | `position` | point     | —          | instead of `to_world`: where it sits, unturned |
//! | `scale`    | float     | 1          | factor on the file's intensities (≥ 0) |
//! | `color`    | spectrum  | 1 (white)  | the colour of the light; its luminance does not change the candela |
//!
//! **Frame.** In the luminaire's frame the photometric nadir (γ = 0) is −z and the C0 plane
//! holds +x (C90 holds +y), as both formats define them with z up; `to_world` turns and places
//! that frame. A Mitsuba scene is often y-up: `<rotate x="1" angle="-90"/>` turns the nadir
//! to −y.
//!
//! **Units** (`photometric.rs`, as for every photometric parameter): radiant intensity (W/sr)
//! = I (cd) × `scale` × `color` / (683 lm/W × Y(`color`)), Y the luminance of the linear
//! Rec. 709 primaries (0.2126, 0.7152, 0.0722): luminous intensity is the file's whatever the
//! colour, and a white luminaire (equal RGB, the equal-energy white of steradian's RGB) emits
//! I/683 W/sr in each channel. Illuminance meters
//! (`steradian measure`, Y × 683) read lux back.
//!
//! Its flux (for choosing among lights by power, and for `ptracer`'s emission sampling) is the
//! table's ∫ I dω; emission directions are drawn from the table by flux with the exact density.
//! A `luminaire` nested in a flat shape is an area source over that luminous opening
//! (`luminous_opening.rs`).

use std::sync::Arc;

use glam::{Mat3, Vec2, Vec3};

use super::photometric::from_photometric;
use super::{towards, EmitterSample, Support};
use crate::geometry::Transform;
use crate::param::ParamError;
use crate::photometry::IntensityTable;
use crate::Spectrum;

/// Luminous efficacy of the radiometric unit: 683 lm/W (the SI definition of the candela).
pub const LUMENS_PER_WATT: f32 = 683.0;

#[derive(Clone, Debug, PartialEq)]
pub struct Luminaire {
    pub position: Vec3,
    /// World to luminaire frame (a rotation).
    to_local: Mat3,
    /// Luminaire frame to world.
    to_world: Mat3,
    table: Arc<IntensityTable>,
    /// W/sr per cd, per channel: `scale`·`color`/(683·Y(`color`)).
    per_candela: Spectrum,
}

impl Luminaire {
    /// Factor on the file's intensities where the scene gives no `scale`.
    pub const DEFAULT_SCALE: f32 = 1.0;
    /// The colour where the scene gives none: white.
    pub const DEFAULT_COLOR: f32 = 1.0;

    pub fn new(
        to_world: &Transform,
        table: IntensityTable,
        scale: f32,
        color: Spectrum,
    ) -> Result<Luminaire, ParamError> {
        // W/sr per cd (see `photometric.rs`)
        let per_candela = from_photometric(scale, color).map_err(|e| {
            let name = if scale.is_finite() && scale >= 0.0 { "color" } else { "scale" };
            ParamError::new(name, format!("{name} {e}"))
        })?;
        let rotation = to_world.linear();
        if !(rotation.transpose() * rotation).abs_diff_eq(Mat3::IDENTITY, 1e-4) {
            return Err(ParamError::new(
                "to_world",
                "to_world of a luminaire must be a rotation and a translation (its size is the \
                 file's, or the shape's it is nested in, not to_world's)",
            ));
        }
        Ok(Luminaire {
            position: to_world.point(Vec3::ZERO),
            to_local: rotation.transpose(),
            to_world: rotation,
            table: Arc::new(table),
            per_candela,
        })
    }

    /// Radiant intensity towards the world direction `d` (unit), W/sr.
    #[inline]
    pub fn intensity(&self, d: Vec3) -> Spectrum {
        self.per_candela * self.table.eval(self.to_local * d)
    }

    /// Total radiant flux, W per channel.
    pub fn flux(&self) -> Spectrum {
        self.per_candela * self.table.flux() as f32
    }

    #[inline]
    pub fn sample_direction(&self, p: Vec3) -> Option<EmitterSample> {
        let (wi, dist, dist2) = towards(self.position, p)?;
        let i = self.intensity(-wi);
        Some(EmitterSample { wi, dist, pdf: 1.0, weight: i / dist2, support: Support::Delta })
    }

    /// An emission direction (world) drawn by flux, and I(ω)/p(ω) (W).
    #[inline]
    pub fn sample_emission(&self, u: Vec2) -> Option<(Vec3, Spectrum)> {
        let (local, pdf) = self.table.sample(u)?;
        let weight = self.per_candela * (self.table.eval(local) / pdf);
        Some((self.to_world * local, weight))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photometry::parse_ies;
    use crate::spectrum::luminance;

    fn downlight(to_world: &Transform, color: Spectrum) -> Luminaire {
        let text = include_str!("../photometry/testdata/cosine_3000lm_point_0-180.ies");
        let table = IntensityTable::new(&parse_ies(text).unwrap()).unwrap();
        Luminaire::new(to_world, table, 1.0, color).unwrap()
    }

    /// Illuminance below a turned and placed downlight is I₀ cos γ · cos θ / r² (lx), whatever
    /// the colour; the flux is the table's 3000 lm.
    #[test]
    fn illuminance_follows_the_inverse_square_law_in_lux() {
        let i0 = 3000.0 / std::f32::consts::PI;
        // y up: the nadir turned from −z to −y, the luminaire 2.5 m above the origin
        let to_world = Transform::rotate(Vec3::X, -90.0)
            .unwrap()
            .then(&Transform::translate(Vec3::new(0.0, 2.5, 0.0)));
        for color in [Spectrum::splat(1.0), Spectrum::new(1.0, 0.5, 0.2)] {
            let l = downlight(&to_world, color);
            assert!((luminance(l.flux()) * LUMENS_PER_WATT / 3000.0 - 1.0).abs() < 5e-3);
            for x in [0.0f32, 0.7, 2.0] {
                let p = Vec3::new(x, 0.0, 0.3 * x);
                let s = l.sample_direction(p).unwrap();
                // horizontal floor: cos θ = cos γ = h / r
                let r2 = (Vec3::new(0.0, 2.5, 0.0) - p).length_squared();
                let cos = 2.5 / r2.sqrt();
                let want = i0 * cos * cos / r2;
                let got = luminance(s.weight) * cos * LUMENS_PER_WATT;
                assert!((got / want - 1.0).abs() < 2e-3, "x = {x}: {got} lx vs {want}");
            }
            // nothing goes up
            assert_eq!(
                l.sample_direction(Vec3::new(0.0, 4.0, 0.0)).unwrap().weight,
                Spectrum::ZERO
            );
        }
    }

    #[test]
    fn emission_weights_average_to_the_flux() {
        let l = downlight(&Transform::IDENTITY, Spectrum::splat(1.0));
        let mut rng = crate::sampling::Pcg32::new(1, 9);
        let n = 100_000;
        let mut sum = 0.0f64;
        for _ in 0..n {
            if let Some((d, w)) = l.sample_emission(Vec2::new(rng.next_f32(), rng.next_f32())) {
                assert!(d.z <= 1e-6, "a downlight emits downwards: {d}");
                sum += w.x as f64;
            }
        }
        let mean = sum / n as f64;
        // a cosine lobe sampled by flux in 5° cells: weights within a few % of Φ, mean to 1e-3
        assert!((mean / l.flux().x as f64 - 1.0).abs() < 1e-3, "{mean} vs {}", l.flux().x);
    }

    #[test]
    fn bad_parameters_are_errors() {
        let text = include_str!("../photometry/testdata/cosine_3000lm_point_0-90.ies");
        let table = || IntensityTable::new(&parse_ies(text).unwrap()).unwrap();
        let one = Spectrum::splat(1.0);
        let scaled = Transform::scale(Vec3::splat(2.0)).unwrap();
        assert!(Luminaire::new(&scaled, table(), 1.0, one).is_err());
        assert!(Luminaire::new(&Transform::IDENTITY, table(), -1.0, one).is_err());
        assert!(Luminaire::new(&Transform::IDENTITY, table(), 1.0, Spectrum::ZERO).is_err());
    }
}
