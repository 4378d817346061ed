//! `gridvolume`: values on a regular 3-D grid, read from Mitsuba's binary `.vol` file.
//!
//! | parameter       | type      | default     | meaning |
//! |-----------------|-----------|-------------|---------|
//! | `filename`      | string    | —           | the `.vol` file |
//! | `filter_type`   | string    | `trilinear` | `trilinear` or `nearest` |
//! | `wrap_mode`     | string    | `clamp`     | `clamp`, `repeat` or `mirror`: lookups outside [0, 1]³ |
//! | `to_world`      | transform | identity    | places the unit cube [0, 1]³ that the grid fills |
//! | `use_grid_bbox` | boolean   | false       | place the grid in the file's bounding box instead (then `to_world` applies after it) |
//! | `max_value`     | float     | the data's  | the largest value, for a heterogeneous medium's majorant (must not be below the data's) |
//! | `raw`           | boolean   | false       | accepted; RGB rendering uses the values as they are |
//!
//! **File format** (little-endian): the bytes `VOL`, version 3 (one byte), encoding 1 (int32:
//! float32 data), the resolution x, y, z (three int32), the channel count (int32: 1 or 3), a
//! bounding box (six float32: min x, y, z, max x, y, z), then x·y·z·channels float32 values,
//! x varying fastest: value (x, y, z, c) at ((z·yres + y)·xres + x)·channels + c.
//!
//! **Lookups** as Mitsuba's: voxel centres at (i + ½)/res; `trilinear` interpolates between
//! the eight nearest centres, `nearest` takes the voxel holding the point; indices past the
//! border follow `wrap_mode`. A one-channel grid gives the same value in every channel.

use std::path::Path;

use glam::Vec3;

use crate::Spectrum;

/// How a lookup between voxel centres is filtered (`filter_type`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum VolumeFilter {
    #[default]
    Trilinear,
    Nearest,
}

/// Where lookups past the grid's border land (`wrap_mode`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum VolumeWrap {
    #[default]
    Clamp,
    Repeat,
    Mirror,
}

/// A grid of values with 1 or 3 channels.
#[derive(Clone, Debug, PartialEq)]
pub struct GridVolume {
    /// Voxels along x, y, z.
    pub res: [usize; 3],
    pub channels: usize,
    /// Values, x fastest, then y, then z, channels interleaved.
    data: Vec<f32>,
    /// The file's bounding box (min, max).
    pub bbox: (Vec3, Vec3),
    pub filter: VolumeFilter,
    pub wrap: VolumeWrap,
    /// The largest value over voxels and channels.
    max: f32,
}

/// Size of a `.vol` header, bytes.
const HEADER: usize = 48;

impl GridVolume {
    /// A grid from its values (x fastest); errors on a size mismatch or non-finite values.
    pub fn new(res: [usize; 3], channels: usize, data: Vec<f32>) -> Result<GridVolume, String> {
        if !matches!(channels, 1 | 3) {
            return Err(format!("a grid has 1 or 3 channels, not {channels}"));
        }
        if res.contains(&0) {
            return Err(format!("the grid resolution {res:?} is empty"));
        }
        let n = res[0] * res[1] * res[2] * channels;
        if data.len() != n {
            return Err(format!("the grid needs {n} values, got {}", data.len()));
        }
        if let Some(i) = data.iter().position(|v| !v.is_finite()) {
            return Err(format!("value {i} of the grid is not finite ({})", data[i]));
        }
        let max = data.iter().copied().fold(f32::NEG_INFINITY, f32::max);
        Ok(GridVolume {
            res,
            channels,
            data,
            bbox: (Vec3::ZERO, Vec3::ONE),
            filter: VolumeFilter::default(),
            wrap: VolumeWrap::default(),
            max,
        })
    }

    /// The samples, x fastest, channels interleaved (an `sdfgrid` takes them over).
    pub fn into_values(self) -> Vec<f32> {
        self.data
    }

    /// Reads a `.vol` file (see the module docs); errors name the problem.
    pub fn read(path: &Path) -> Result<GridVolume, String> {
        let bytes =
            std::fs::read(path).map_err(|e| format!("cannot read \"{}\": {e}", path.display()))?;
        Self::from_bytes(&bytes).map_err(|e| format!("\"{}\": {e}", path.display()))
    }

    /// Decodes the bytes of a `.vol` file.
    pub fn from_bytes(bytes: &[u8]) -> Result<GridVolume, String> {
        if bytes.len() < HEADER {
            return Err(format!(
                "truncated: {} bytes, shorter than the {HEADER}-byte header of a .vol file",
                bytes.len()
            ));
        }
        if &bytes[0..3] != b"VOL" {
            return Err("not a Mitsuba .vol file (it does not start with \"VOL\")".into());
        }
        if bytes[3] != 3 {
            return Err(format!("version {} of the .vol format; only version 3 is read", bytes[3]));
        }
        let int = |at: usize| i32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
        let float = |at: usize| f32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
        let encoding = int(4);
        if encoding != 1 {
            return Err(format!("encoding {encoding}; only 1 (float32) is read"));
        }
        let (x, y, z, channels) = (int(8), int(12), int(16), int(20));
        if x <= 0 || y <= 0 || z <= 0 {
            return Err(format!("invalid resolution {x} x {y} x {z}"));
        }
        if !matches!(channels, 1 | 3) {
            return Err(format!("{channels} channels; a grid has 1 or 3"));
        }
        let res = [x as usize, y as usize, z as usize];
        let n = res
            .iter()
            .try_fold(channels as usize, |n, &r| n.checked_mul(r))
            .ok_or_else(|| format!("resolution {x} x {y} x {z} is too large"))?;
        let need = n
            .checked_mul(4)
            .and_then(|b| b.checked_add(HEADER))
            .ok_or_else(|| format!("resolution {x} x {y} x {z} is too large"))?;
        if bytes.len() < need {
            return Err(format!(
                "truncated: {x} x {y} x {z} x {channels} values need {need} bytes, the file has {}",
                bytes.len()
            ));
        }
        let data: Vec<f32> = bytes[HEADER..need]
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes(c.try_into().expect("4 bytes")))
            .collect();
        let bbox = (
            Vec3::new(float(24), float(28), float(32)),
            Vec3::new(float(36), float(40), float(44)),
        );
        let mut grid = GridVolume::new(res, channels as usize, data)?;
        grid.bbox = bbox;
        Ok(grid)
    }

    /// The largest value over voxels and channels.
    pub fn max(&self) -> f32 {
        self.max
    }

    /// The smallest value over voxels and channels.
    pub fn min(&self) -> f32 {
        self.data.iter().copied().fold(f32::INFINITY, f32::min)
    }

    /// Raises the stated maximum (`max_value`); errors if below the data's.
    pub fn set_max(&mut self, max: f32) -> Result<(), String> {
        if !(max.is_finite() && max >= self.max) {
            return Err(format!("max_value {max} is below the grid's largest value {}", self.max));
        }
        self.max = max;
        Ok(())
    }

    /// Index `i` along an axis of `n` voxels after the wrap mode.
    #[inline]
    fn wrap_index(&self, i: i64, n: usize) -> usize {
        let n = n as i64;
        let j = match self.wrap {
            VolumeWrap::Clamp => i.clamp(0, n - 1),
            VolumeWrap::Repeat => i.rem_euclid(n),
            VolumeWrap::Mirror => {
                let k = i.rem_euclid(2 * n);
                if k < n {
                    k
                } else {
                    2 * n - 1 - k
                }
            }
        };
        j as usize
    }

    #[inline]
    fn voxel(&self, x: usize, y: usize, z: usize) -> Spectrum {
        let i = ((z * self.res[1] + y) * self.res[0] + x) * self.channels;
        if self.channels == 1 {
            Spectrum::splat(self.data[i])
        } else {
            Spectrum::new(self.data[i], self.data[i + 1], self.data[i + 2])
        }
    }

    /// The value at `p` in the grid's unit cube [0, 1]³.
    #[inline]
    pub fn eval(&self, p: Vec3) -> Spectrum {
        let [rx, ry, rz] = self.res;
        match self.filter {
            VolumeFilter::Nearest => {
                let q = p * Vec3::new(rx as f32, ry as f32, rz as f32);
                self.voxel(
                    self.wrap_index(q.x.floor() as i64, rx),
                    self.wrap_index(q.y.floor() as i64, ry),
                    self.wrap_index(q.z.floor() as i64, rz),
                )
            }
            VolumeFilter::Trilinear => {
                let q = p * Vec3::new(rx as f32, ry as f32, rz as f32) - 0.5;
                let f = q.floor();
                let w = q - f;
                let (x0, y0, z0) = (f.x as i64, f.y as i64, f.z as i64);
                let xs = [self.wrap_index(x0, rx), self.wrap_index(x0 + 1, rx)];
                let ys = [self.wrap_index(y0, ry), self.wrap_index(y0 + 1, ry)];
                let zs = [self.wrap_index(z0, rz), self.wrap_index(z0 + 1, rz)];
                let lerp = |a: Spectrum, b: Spectrum, t: f32| a * (1.0 - t) + b * t;
                let plane = |z: usize| {
                    lerp(
                        lerp(self.voxel(xs[0], ys[0], z), self.voxel(xs[1], ys[0], z), w.x),
                        lerp(self.voxel(xs[0], ys[1], z), self.voxel(xs[1], ys[1], z), w.x),
                        w.y,
                    )
                };
                lerp(plane(zs[0]), plane(zs[1]), w.z)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bytes of a version-3 `.vol` file.
    pub(crate) fn vol_bytes(res: [i32; 3], channels: i32, data: &[f32]) -> Vec<u8> {
        let mut b = b"VOL".to_vec();
        b.push(3);
        for v in [1, res[0], res[1], res[2], channels] {
            b.extend(v.to_le_bytes());
        }
        for v in [0.0f32, 0.0, 0.0, 1.0, 1.0, 1.0] {
            b.extend(v.to_le_bytes());
        }
        for v in data {
            b.extend(v.to_le_bytes());
        }
        b
    }

    #[test]
    fn reads_x_fastest_and_filters_like_mitsuba() {
        // 4 x 3 x 2, value = x + 10 y + 100 z
        let data: Vec<f32> = (0..2)
            .flat_map(|z| {
                (0..3).flat_map(move |y| (0..4).map(move |x| (x + 10 * y + 100 * z) as f32))
            })
            .collect();
        let mut g = GridVolume::from_bytes(&vol_bytes([4, 3, 2], 1, &data)).unwrap();
        assert_eq!((g.res, g.channels, g.max()), ([4, 3, 2], 1, 123.0));
        // at a voxel centre: the voxel's value; trilinear is linear in between
        let centre =
            |x: f32, y: f32, z: f32| Vec3::new((x + 0.5) / 4.0, (y + 0.5) / 3.0, (z + 0.5) / 2.0);
        assert!((g.eval(centre(2.0, 1.0, 1.0)).x - 112.0).abs() < 1e-4);
        assert!((g.eval(centre(1.5, 0.25, 0.5)).x - (1.5 + 2.5 + 50.0)).abs() < 1e-3);
        // clamped past the border
        assert!((g.eval(Vec3::new(-0.3, 0.0, 0.0)).x - 0.0).abs() < 1e-6);
        assert!((g.eval(Vec3::new(1.2, 1.5, 1.5)).x - 123.0).abs() < 1e-4);
        g.filter = VolumeFilter::Nearest;
        assert_eq!(g.eval(Vec3::new(0.6, 0.7, 0.2)).x, 2.0 + 20.0);
        g.wrap = VolumeWrap::Repeat;
        assert_eq!(g.eval(Vec3::new(1.1, 0.1, 0.1)).x, 0.0);
        g.wrap = VolumeWrap::Mirror;
        assert_eq!(g.eval(Vec3::new(1.1, 0.1, 0.1)).x, 3.0);
        // three channels
        let rgb = GridVolume::from_bytes(&vol_bytes([1, 1, 1], 3, &[0.1, 0.2, 0.3])).unwrap();
        assert_eq!(rgb.eval(Vec3::splat(0.5)), Spectrum::new(0.1, 0.2, 0.3));
    }

    #[test]
    fn bad_files_are_errors() {
        let good = vol_bytes([2, 2, 2], 1, &[1.0; 8]);
        assert!(GridVolume::from_bytes(&good).is_ok());
        let e = GridVolume::from_bytes(&good[..good.len() - 4]).unwrap_err();
        assert!(e.contains("truncated"), "{e}");
        assert!(GridVolume::from_bytes(&good[..20]).unwrap_err().contains("truncated"));
        let mut bad = good.clone();
        bad[0] = b'X';
        assert!(GridVolume::from_bytes(&bad).unwrap_err().contains("VOL"));
        let mut bad = good.clone();
        bad[3] = 2;
        assert!(GridVolume::from_bytes(&bad).unwrap_err().contains("version 2"));
        let mut bad = good.clone();
        bad[4] = 2;
        assert!(GridVolume::from_bytes(&bad).unwrap_err().contains("encoding 2"));
        let mut bad = good.clone();
        bad[20] = 2;
        assert!(GridVolume::from_bytes(&bad).unwrap_err().contains("2 channels"));
        let nan = vol_bytes([1, 1, 1], 1, &[f32::NAN]);
        assert!(GridVolume::from_bytes(&nan).unwrap_err().contains("not finite"));
        let huge = vol_bytes([i32::MAX, i32::MAX, i32::MAX], 3, &[]);
        assert!(GridVolume::from_bytes(&huge).is_err());
    }
}
