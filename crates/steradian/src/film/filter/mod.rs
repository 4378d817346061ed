//! Reconstruction filters (Mitsuba `rfilter` plugins): `box`, `tent`, `gaussian`, `mitchell`,
//! `catmullrom`, `lanczos`.
//!
//! A filter is a 1D weight function `w(x)` of the offset `x` (pixels) between a sample and a pixel
//! centre, zero at and beyond its [`radius`](ReconstructionFilter::radius). Films use it
//! separably: a sample at `p` contributes to the pixel with centre `c` with weight
//! `w(c.x − p.x)·w(c.y − p.y)`, and each pixel is developed as `Σw·L / Σw`.
//!
//! The set of filters is closed (an enum, no trait objects). Every filter is symmetric,
//! `w(−x) = w(x)`; `box`, `tent` and `gaussian` are non-negative, the cubics and `lanczos`
//! have negative lobes, which the films' `Σw·L / Σw` divides out as Mitsuba's does.

#[path = "box.rs"]
mod box_filter;
mod catmullrom;
mod gaussian;
mod lanczos;
mod mitchell;
mod tent;

pub use box_filter::BoxFilter;
pub use catmullrom::CatmullRomFilter;
pub use gaussian::GaussianFilter;
pub use lanczos::LanczosFilter;
pub use mitchell::MitchellFilter;
pub use tent::TentFilter;

/// Largest filter radius accepted, in pixels. Bounds the per-axis footprint so that splatting
/// can use fixed-size stack arrays (see [`MAX_FILTER_TAPS`]).
pub const MAX_FILTER_RADIUS: f32 = 32.0;

/// Most pixels a sample can touch along one axis: pixel centres strictly within the radius,
/// at most ⌈2r⌉ + 1 of them.
pub const MAX_FILTER_TAPS: usize = 2 * MAX_FILTER_RADIUS as usize + 1;

/// Shared radius validation for filter constructors.
pub(crate) fn check_radius(plugin: &str, name: &str, radius: f32) -> Result<(), String> {
    if !(radius.is_finite() && radius > 0.0) {
        return Err(format!(
            "{plugin} filter: `{name}` must be a positive finite number of pixels, got {radius}"
        ));
    }
    if radius > MAX_FILTER_RADIUS {
        return Err(format!(
            "{plugin} filter: `{name}` = {radius} px exceeds the supported maximum of \
             {MAX_FILTER_RADIUS} px"
        ));
    }
    Ok(())
}

/// A reconstruction filter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ReconstructionFilter {
    Box(BoxFilter),
    Tent(TentFilter),
    Gaussian(GaussianFilter),
    Mitchell(MitchellFilter),
    CatmullRom(CatmullRomFilter),
    Lanczos(LanczosFilter),
}

impl ReconstructionFilter {
    /// Filter radius in pixels: `w(x) = 0` for `|x| ≥ radius` (box: weight 1 up to 0.5 inclusive).
    #[inline]
    pub fn radius(&self) -> f32 {
        match self {
            ReconstructionFilter::Box(f) => f.radius(),
            ReconstructionFilter::Tent(f) => f.radius(),
            ReconstructionFilter::Gaussian(f) => f.radius(),
            ReconstructionFilter::Mitchell(f) => f.radius(),
            ReconstructionFilter::CatmullRom(f) => f.radius(),
            ReconstructionFilter::Lanczos(f) => f.radius(),
        }
    }

    /// 1D weight at offset `x` pixels from a pixel centre.
    #[inline]
    pub fn eval(&self, x: f32) -> f32 {
        match self {
            ReconstructionFilter::Box(f) => f.eval(x),
            ReconstructionFilter::Tent(f) => f.eval(x),
            ReconstructionFilter::Gaussian(f) => f.eval(x),
            ReconstructionFilter::Mitchell(f) => f.eval(x),
            ReconstructionFilter::CatmullRom(f) => f.eval(x),
            ReconstructionFilter::Lanczos(f) => f.eval(x),
        }
    }

    /// Replaces every offset `x` in `xs` by its weight `w(x)` (0 at and beyond the radius):
    /// one dispatch for the lot, so that the loop compiles to vector code.
    #[inline]
    pub fn eval_in_place(&self, xs: &mut [f32]) {
        let r = self.radius();
        match self {
            ReconstructionFilter::Box(f) => {
                xs.iter_mut().for_each(|x| *x = if x.abs() < r { f.eval(*x) } else { 0.0 })
            }
            ReconstructionFilter::Tent(f) => {
                xs.iter_mut().for_each(|x| *x = if x.abs() < r { f.eval(*x) } else { 0.0 })
            }
            ReconstructionFilter::Gaussian(f) => {
                xs.iter_mut().for_each(|x| *x = if x.abs() < r { f.eval_inside(*x) } else { 0.0 })
            }
            ReconstructionFilter::Mitchell(f) => {
                xs.iter_mut().for_each(|x| *x = if x.abs() < r { f.eval(*x) } else { 0.0 })
            }
            ReconstructionFilter::CatmullRom(f) => {
                xs.iter_mut().for_each(|x| *x = if x.abs() < r { f.eval(*x) } else { 0.0 })
            }
            ReconstructionFilter::Lanczos(f) => {
                xs.iter_mut().for_each(|x| *x = if x.abs() < r { f.eval(*x) } else { 0.0 })
            }
        }
    }

    /// Separable 2D weight `w(dx)·w(dy)`.
    #[inline]
    pub fn eval_2d(&self, dx: f32, dy: f32) -> f32 {
        self.eval(dx) * self.eval(dy)
    }

    /// True for the box filter (no splatting: one pixel, weight 1).
    #[inline]
    pub fn is_box(&self) -> bool {
        matches!(self, ReconstructionFilter::Box(_))
    }

    /// Border in pixels that an image block needs around its rectangle so that every sample
    /// inside the rectangle can be splatted completely: ⌈radius − 0.5⌉.
    #[inline]
    pub fn border_size(&self) -> u32 {
        (self.radius() - 0.5).ceil().max(0.0) as u32
    }

    /// The Mitsuba plugin name.
    pub fn plugin_name(&self) -> &'static str {
        match self {
            ReconstructionFilter::Box(_) => "box",
            ReconstructionFilter::Tent(_) => "tent",
            ReconstructionFilter::Gaussian(_) => "gaussian",
            ReconstructionFilter::Mitchell(_) => "mitchell",
            ReconstructionFilter::CatmullRom(_) => "catmullrom",
            ReconstructionFilter::Lanczos(_) => "lanczos",
        }
    }
}

impl Default for ReconstructionFilter {
    /// Mitsuba's default: `gaussian` with stddev 0.5.
    fn default() -> Self {
        ReconstructionFilter::Gaussian(GaussianFilter::default())
    }
}

impl From<BoxFilter> for ReconstructionFilter {
    fn from(f: BoxFilter) -> Self {
        ReconstructionFilter::Box(f)
    }
}
impl From<TentFilter> for ReconstructionFilter {
    fn from(f: TentFilter) -> Self {
        ReconstructionFilter::Tent(f)
    }
}
impl From<GaussianFilter> for ReconstructionFilter {
    fn from(f: GaussianFilter) -> Self {
        ReconstructionFilter::Gaussian(f)
    }
}
impl From<MitchellFilter> for ReconstructionFilter {
    fn from(f: MitchellFilter) -> Self {
        ReconstructionFilter::Mitchell(f)
    }
}
impl From<CatmullRomFilter> for ReconstructionFilter {
    fn from(f: CatmullRomFilter) -> Self {
        ReconstructionFilter::CatmullRom(f)
    }
}
impl From<LanczosFilter> for ReconstructionFilter {
    fn from(f: LanczosFilter) -> Self {
        ReconstructionFilter::Lanczos(f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all_filters() -> Vec<ReconstructionFilter> {
        vec![
            BoxFilter::new().into(),
            TentFilter::default().into(),
            TentFilter::new(1.7).unwrap().into(),
            GaussianFilter::default().into(),
            GaussianFilter::new(0.8).unwrap().into(),
            MitchellFilter::default().into(),
            MitchellFilter::new(0.0, 0.8).unwrap().into(),
            CatmullRomFilter::new().into(),
            LanczosFilter::default().into(),
            LanczosFilter::new(2).unwrap().into(),
        ]
    }

    #[test]
    fn gaussian_values() {
        let g = GaussianFilter::default();
        assert_eq!(g.stddev(), 0.5);
        assert_eq!(g.radius(), 2.0);
        let sigma = 0.5f64;
        let shift = (-(2.0f64 * 2.0) / (2.0 * sigma * sigma)).exp(); // exp(−8)
                                                                     // At 0: 1 − exp(−8).
        assert!((g.eval(0.0) as f64 - (1.0 - shift)).abs() < 1e-6);
        // At 1σ: exp(−1/2) − exp(−8).
        assert!((g.eval(0.5) as f64 - ((-0.5f64).exp() - shift)).abs() < 1e-6);
        // Exactly zero at the radius and beyond.
        for x in [2.0f32, 2.000001, 2.5, 3.0, 100.0, f32::INFINITY] {
            assert_eq!(g.eval(x), 0.0, "x = {x}");
            assert_eq!(g.eval(-x), 0.0, "x = -{x}");
        }
        // Positive just inside, monotone decreasing.
        assert!(g.eval(1.99) > 0.0);
        let mut prev = g.eval(0.0);
        for i in 1..200 {
            let w = g.eval(i as f32 * 0.01);
            assert!(w <= prev);
            prev = w;
        }
    }

    #[test]
    fn tent_and_box_values() {
        let t = TentFilter::default();
        assert_eq!(t.radius(), 1.0);
        assert_eq!(t.eval(0.0), 1.0);
        assert_eq!(t.eval(0.25), 0.75);
        assert_eq!(t.eval(1.0), 0.0);
        assert_eq!(t.eval(1.5), 0.0);
        let t2 = TentFilter::new(2.0).unwrap();
        assert_eq!(t2.eval(1.0), 0.5);
        let b = BoxFilter::new();
        assert_eq!(b.radius(), 0.5);
        assert_eq!(b.eval(0.0), 1.0);
        assert_eq!(b.eval(0.49), 1.0);
        assert_eq!(b.eval(0.51), 0.0);
    }

    #[test]
    fn filters_are_symmetric_and_zero_beyond_the_radius() {
        for f in all_filters() {
            for i in 0..=400 {
                let x = i as f32 * 0.0137;
                let (a, b) = (f.eval(x), f.eval(-x));
                assert_eq!(a, b, "{} at ±{x}", f.plugin_name());
                let has_negative_lobes = matches!(
                    f,
                    ReconstructionFilter::Mitchell(_)
                        | ReconstructionFilter::CatmullRom(_)
                        | ReconstructionFilter::Lanczos(_)
                );
                assert!(a >= 0.0 || has_negative_lobes, "{} at {x}", f.plugin_name());
                if x >= f.radius() && !f.is_box() {
                    assert_eq!(a, 0.0);
                }
            }
        }
    }

    /// Weights of Mitsuba 3.9.1's `eval` (scalar_rgb) at x = 0, 0.1, 0.25, 0.5, 0.77, 1, 1.3,
    /// 1.9, 2.5 pixels.
    #[test]
    fn cubic_and_lanczos_values_match_mitsuba() {
        let xs = [0.0f32, 0.1, 0.25, 0.5, 0.77, 1.0, 1.3, 1.9, 2.5];
        let cases: [(ReconstructionFilter, [f32; 9]); 3] = [
            (
                MitchellFilter::default().into(),
                [
                    0.888889, 0.870056, 0.782118, 0.534722, 0.235711, 0.055556, -0.029944,
                    -0.002944, 0.0,
                ],
            ),
            (
                CatmullRomFilter::new().into(),
                [1.0, 0.9765, 0.867188, 0.5625, 0.20255, 0.0, -0.0735, -0.0045, 0.0],
            ),
            (
                LanczosFilter::default().into(),
                [1.0, 0.981835, 0.890067, 0.607927, 0.244703, 0.0, -0.14233, -0.02377, 0.024317],
            ),
        ];
        for (f, want) in cases {
            for (x, w) in xs.iter().zip(want) {
                assert!(
                    (f.eval(*x) - w).abs() < 2e-6,
                    "{} at {x}: {} vs {w}",
                    f.plugin_name(),
                    f.eval(*x)
                );
            }
        }
        assert_eq!(ReconstructionFilter::from(LanczosFilter::default()).border_size(), 3);
        assert_eq!(ReconstructionFilter::from(MitchellFilter::default()).border_size(), 2);
    }

    #[test]
    fn constructors_validate() {
        assert!(LanczosFilter::new(0).is_err() && LanczosFilter::new(-2).is_err());
        assert!(LanczosFilter::new(1000).is_err());
        assert!(MitchellFilter::new(f32::NAN, 0.3).is_err());
        for bad in [0.0f32, -1.0, f32::NAN, f32::INFINITY, 1000.0] {
            assert!(TentFilter::new(bad).is_err(), "tent {bad}");
            assert!(GaussianFilter::new(bad).is_err(), "gaussian {bad}");
        }
        assert!(TentFilter::new(0.3).is_ok());
        assert!(GaussianFilter::new(0.1).is_ok());
    }

    #[test]
    fn border_sizes() {
        assert_eq!(ReconstructionFilter::from(BoxFilter::new()).border_size(), 0);
        assert_eq!(ReconstructionFilter::from(TentFilter::default()).border_size(), 1);
        assert_eq!(ReconstructionFilter::default().border_size(), 2);
        assert_eq!(ReconstructionFilter::from(TentFilter::new(1.5).unwrap()).border_size(), 1);
        assert_eq!(ReconstructionFilter::from(TentFilter::new(1.2).unwrap()).border_size(), 1);
    }
}
