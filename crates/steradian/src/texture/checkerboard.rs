//! `checkerboard`: two textures alternating on a grid of squares.
//!
//! | parameter | type             | default | meaning |
//! |-----------|------------------|---------|---------|
//! | `color0`  | spectrum/texture | 0.4     | the squares containing (u, v) ∈ [0, ½]² |
//! | `color1`  | spectrum/texture | 0.2     | the other squares |
//! | `to_uv`   | transform        | identity| applied to (u, v) first; of a 4×4 matrix the z row and column are ignored |
//!
//! With (u', v') = to_uv(u, v), Mitsuba 3's pattern picks `color0` where frac(u') > ½ and
//! frac(v') > ½ agree, `color1` where they differ: one period per unit of u' and v'.
//!
//! Scalar lookups (`eval_1`, e.g. a checkerboard `alpha` or `opacity`) reproduce a quirk of
//! Mitsuba 3 (up to 3.9.1): they test the opposite parity, so the two values trade places
//! relative to colour lookups. A checkerboard has no gradient; like Mitsuba, steradian refuses
//! it as a bump map height.

use glam::Vec2;

use super::{Texture, TexturePoint, UvTransform};
use crate::Spectrum;

#[derive(Clone, Debug, PartialEq)]
pub struct Checkerboard {
    pub color0: Box<Texture>,
    pub color1: Box<Texture>,
    pub to_uv: UvTransform,
}

impl Checkerboard {
    /// Default `color0` (Mitsuba's; dimensionless).
    pub const DEFAULT_COLOR0: f32 = 0.4;
    /// Default `color1` (Mitsuba's; dimensionless).
    pub const DEFAULT_COLOR1: f32 = 0.2;

    pub fn new(color0: Texture, color1: Texture, to_uv: UvTransform) -> Self {
        Checkerboard { color0: Box::new(color0), color1: Box::new(color1), to_uv }
    }

    /// True on the squares of `color0` (for colour lookups).
    #[inline]
    fn first(&self, uv: Vec2) -> bool {
        let t = self.to_uv.apply(uv);
        let f = t - t.floor();
        (f.x > 0.5) == (f.y > 0.5)
    }

    /// The colour at `p`. Out of line: it evaluates nested textures, and `Texture::eval` is
    /// always inlined.
    #[inline(never)]
    pub fn eval(&self, p: TexturePoint) -> Spectrum {
        if self.first(p.uv) {
            self.color0.eval(p)
        } else {
            self.color1.eval(p)
        }
    }

    /// Mitsuba's scalar lookup: parity inverted (see the module docs). Out of line, as `eval`.
    #[inline(never)]
    pub fn eval_1(&self, p: TexturePoint) -> f32 {
        if self.first(p.uv) {
            self.color1.eval_1(p)
        } else {
            self.color0.eval_1(p)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pattern_matches_mitsuba() {
        let c = Checkerboard::new(
            Spectrum::splat(0.4).into(),
            Spectrum::splat(0.2).into(),
            UvTransform::IDENTITY,
        );
        // values printed by Mitsuba 3.9.1 (scalar_rgb) for the default checkerboard
        for (uv, v) in [
            ([0.1, 0.1], 0.4),
            ([0.6, 0.1], 0.2),
            ([0.1, 0.6], 0.2),
            ([0.6, 0.6], 0.4),
            ([1.1, 0.1], 0.4),
            ([-0.1, 0.1], 0.2),
        ] {
            assert_eq!(c.eval(TexturePoint::at_uv(Vec2::from(uv))), Spectrum::splat(v), "{uv:?}");
        }
        let s = Checkerboard {
            to_uv: UvTransform { m: glam::Mat2::from_diagonal(Vec2::splat(4.0)), t: Vec2::ZERO },
            ..c.clone()
        };
        assert_eq!(s.eval(TexturePoint::at_uv(Vec2::new(0.2, 0.1))), Spectrum::splat(0.2));
        // Mitsuba's eval_1 quirk: 0.2 at (0.1, 0.1) where eval gives 0.4
        assert_eq!(c.eval_1(TexturePoint::at_uv(Vec2::new(0.1, 0.1))), 0.2);
        let red = Checkerboard::new(
            Spectrum::X.into(),
            Spectrum::splat(0.2).into(),
            UvTransform::IDENTITY,
        );
        assert!((red.eval_1(TexturePoint::at_uv(Vec2::new(0.3, 0.6))) - 1.0 / 3.0).abs() < 1e-6);
        assert!(
            (Texture::Checkerboard(red).mean() - Spectrum::new(0.6, 0.1, 0.1)).abs().max_element()
                < 1e-6
        );
    }
}
