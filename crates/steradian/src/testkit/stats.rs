//! The mean of i.i.d. Monte Carlo samples and its standard error.

/// Running sums of samples and of their squares.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MeanError {
    n: u64,
    sum: f64,
    sum2: f64,
}

impl MeanError {
    pub fn push(&mut self, x: f64) {
        self.n += 1;
        self.sum += x;
        self.sum2 += x * x;
    }

    /// Number of samples pushed.
    pub fn count(&self) -> u64 {
        self.n
    }

    /// The sample mean.
    pub fn mean(&self) -> f64 {
        self.sum / self.n as f64
    }

    /// The standard error of the mean, √(s²/n) with the unbiased sample variance s².
    pub fn std_error(&self) -> f64 {
        let n = self.n as f64;
        let var = (self.sum2 / n - self.mean().powi(2)).max(0.0) * n / (n - 1.0);
        (var / n).sqrt()
    }

    /// Panics unless the mean lies within `k` standard errors of `expected` (with `slack`
    /// added to the bound, for estimators whose variance can be 0).
    #[track_caller]
    pub fn assert_near(&self, expected: f64, k: f64, slack: f64, what: &str) {
        let (m, se) = (self.mean(), self.std_error());
        assert!(
            (m - expected).abs() <= k * se + slack,
            "{what}: {m} ± {se} (n = {}), expected {expected} (off by {:.1} standard errors)",
            self.n,
            (m - expected).abs() / se
        );
    }
}
