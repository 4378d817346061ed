//! Multiple importance sampling weights.

/// Veach's power heuristic (β = 2) for a sample drawn from strategy a: p_a² / (p_a² + p_b²).
/// Returns 0 when both densities are 0 and handles infinite densities.
#[inline]
pub fn power_heuristic(pdf_a: f32, pdf_b: f32) -> f32 {
    let (a2, b2) = (pdf_a * pdf_a, pdf_b * pdf_b);
    if a2.is_infinite() {
        return 1.0;
    }
    let w = a2 / (a2 + b2);
    if w.is_finite() {
        w
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one() {
        for (a, b) in [(1.0, 1.0), (0.3, 7.0), (1e-20, 1e20), (5.0, 0.0)] {
            assert!((power_heuristic(a, b) + power_heuristic(b, a) - 1.0).abs() < 1e-6);
        }
        assert_eq!(power_heuristic(0.0, 0.0), 0.0);
        assert_eq!(power_heuristic(f32::INFINITY, 1.0), 1.0);
    }
}
