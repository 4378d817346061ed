//! `sun`: steradian's own: the solar disk, a distant light of finite angular size.
//!
//! | parameter        | type     | default   | meaning |
//! |------------------|----------|-----------|---------|
//! | `sun_direction`  | vector   | —         | towards the sun (world), as `ciesky` takes it; required |
//! | `irradiance`     | spectrum | 1         | direct normal irradiance, W/m² on a surface facing the sun |
//! | `illuminance`    | float    | —         | direct normal illuminance, lx, instead of `irradiance` (with `color`, `photometric.rs`) |
//! | `color`          | spectrum | 1 (white) | the colour of a photometric sun |
//! | `angular_radius` | float    | 0.2666    | the disk's angular radius δ, degrees (the mean solar semi-diameter, 16′) |
//!
//! The disk has uniform radiance L = E_n / (π sin²δ), so a surface facing it receives E_n
//! (its projected solid angle is π sin²δ), and a surface whose normal makes angle Z with the
//! sun's centre receives E_n cos Z exactly while the whole disk is above it (a spherical cap's
//! projected solid angle is π sin²δ cos Z). Rays escaping the scene towards the disk see L;
//! light sampling draws directions uniformly in the disk's cone (density 1/(2π(1 − cos δ)),
//! exact), so the sun is combined by MIS like any extended light and mirrors and glass show it.
//! It goes beside a sky (`ciesky`, `envmap`, `constant`), which it does not replace: the CIE
//! skies hold the diffuse sky only, and the daylight factor reads the sky alone.

use std::f32::consts::PI;

use glam::Vec3;

use super::{EmitterSample, Support};
use crate::geometry::Frame;
use crate::sampling::warp;
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct Sun {
    /// Unit vector towards the disk's centre.
    towards: Vec3,
    frame: Frame,
    cos_max: f32,
    /// 1 − cos δ, without cancellation.
    one_minus_cos: f32,
    /// Radiance of the disk, W/(m²·sr).
    radiance: Spectrum,
    /// Direct normal irradiance, W/m².
    pub irradiance: Spectrum,
}

impl Sun {
    /// Default `irradiance` (W/m²).
    pub const DEFAULT_IRRADIANCE: f32 = 1.0;
    /// Default `angular_radius`, degrees: the mean solar semi-diameter.
    pub const DEFAULT_ANGULAR_RADIUS: f32 = 0.2666;

    /// A sun towards `towards` of direct normal irradiance `irradiance` (W/m²) and angular
    /// radius `angular_radius` (degrees, in (0, 90)).
    pub fn new(towards: Vec3, irradiance: Spectrum, angular_radius: f32) -> Result<Sun, String> {
        let len = towards.length();
        if !(len.is_finite() && len > 0.0) {
            return Err("sun_direction must be a non-zero finite vector".into());
        }
        if !(angular_radius > 0.0 && angular_radius < 90.0) {
            return Err(format!(
                "angular_radius must lie in (0, 90) degrees, got {angular_radius}"
            ));
        }
        let delta = (angular_radius as f64).to_radians();
        let sin2 = delta.sin().powi(2);
        let one_minus_cos = sin2 / (1.0 + delta.cos());
        let towards = towards / len;
        Ok(Sun {
            towards,
            frame: Frame::from_normal(towards),
            cos_max: delta.cos() as f32,
            one_minus_cos: one_minus_cos as f32,
            radiance: irradiance * (1.0 / (std::f64::consts::PI * sin2)) as f32,
            irradiance,
        })
    }

    /// The unit vector towards the disk's centre.
    pub fn towards(&self) -> Vec3 {
        self.towards
    }

    /// The disk's solid angle 2π(1 − cos δ), sr.
    #[inline]
    pub fn solid_angle(&self) -> f32 {
        2.0 * PI * self.one_minus_cos
    }

    /// A direction in the disk, uniformly in its cone.
    #[inline]
    pub fn sample_direction(&self, u: glam::Vec2) -> Option<EmitterSample> {
        let wi = self.frame.to_world(warp::square_to_uniform_cone(u, self.one_minus_cos));
        let omega = self.solid_angle();
        Some(EmitterSample {
            wi,
            dist: f32::INFINITY,
            pdf: 1.0 / omega,
            weight: self.radiance * omega,
            support: Support::Extended,
        })
    }

    /// Whether direction `d` (unit, towards the sky) falls in the disk.
    #[inline]
    fn contains(&self, d: Vec3) -> bool {
        d.dot(self.towards) >= self.cos_max
    }

    /// Radiance from direction `d` and the density of proposing it, 1/sr.
    #[inline]
    pub fn radiance_and_pdf(&self, d: Vec3) -> (Spectrum, f32) {
        if self.contains(d) {
            (self.radiance, 1.0 / self.solid_angle())
        } else {
            (Spectrum::ZERO, 0.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Pcg32;

    /// A horizontal surface under a sun at zenith angle Z receives E_n cos Z: the mean of
    /// the light samples' weight × cos, within 4 standard errors (it is exact per sample up to
    /// the disk's spread), and every sample lies in the disk with the stated density.
    #[test]
    fn horizontal_irradiance_is_normal_irradiance_times_cos_z() {
        for (z_deg, radius) in [(0.0f32, 0.2666f32), (40.0, 0.2666), (60.0, 5.0)] {
            let z = z_deg.to_radians();
            let towards = Vec3::new(z.sin(), z.cos(), 0.0);
            let sun = Sun::new(towards, Spectrum::new(800.0, 900.0, 1000.0), radius).unwrap();
            let n = 20_000;
            let mut rng = Pcg32::new(9, 2);
            let (mut sum, mut sum2) = (0.0f64, 0.0f64);
            for _ in 0..n {
                let s =
                    sun.sample_direction(glam::Vec2::new(rng.next_f32(), rng.next_f32())).unwrap();
                assert!(sun.contains(s.wi));
                let (le, pdf) = sun.radiance_and_pdf(s.wi);
                assert!(
                    (pdf - s.pdf).abs() <= 1e-6 * pdf
                        && (le / pdf - s.weight).abs().max_element()
                            < 1e-2 * s.weight.max_element()
                );
                let h = (s.weight.z * s.wi.y.max(0.0)) as f64;
                sum += h;
                sum2 += h * h;
            }
            let mean = sum / n as f64;
            let se = ((sum2 / n as f64 - mean * mean).max(0.0) / n as f64).sqrt();
            let want = 1000.0 * (z as f64).cos();
            assert!(
                (mean - want).abs() <= 4.0 * se + 1e-4 * want,
                "Z {z_deg}: {mean} vs {want} ± {se}"
            );
        }
        // outside the disk: nothing
        let sun = Sun::new(Vec3::Y, Spectrum::ONE, 0.2666).unwrap();
        assert_eq!(sun.radiance_and_pdf(Vec3::new(0.1, 0.995, 0.0).normalize()).1, 0.0);
        assert!(Sun::new(Vec3::ZERO, Spectrum::ONE, 0.2666).is_err());
        assert!(Sun::new(Vec3::Y, Spectrum::ONE, 0.0).is_err());
    }
}
