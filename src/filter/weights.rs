//! Log-domain particle weights.
//!
//! Likelihoods of lane models span hundreds of orders of magnitude, so weights live as
//! logarithms l_i and are normalised with the log-sum-exp trick:
//!
//! ```text
//! L = max_i l_i + ln sum_i exp(l_i - max_i l_i),     w_i = exp(l_i - L)
//! ```
//!
//! which never overflows and loses nothing to underflow that matters (the largest term is 1).
//! NaN log-weights are treated as -infinity (a particle the model cannot evaluate gets no
//! weight). When every particle has weight zero, the weights fall back to uniform and the
//! normalisation reports it. The effective sample size is ESS = 1 / sum_i w_i^2.

/// ln sum_i exp(l_i); -infinity for an empty slice or when every l_i is -infinity.
pub fn log_sum_exp(log_weights: &[f64]) -> f64 {
    let max = log_weights
        .iter()
        .copied()
        .filter(|l| !l.is_nan())
        .fold(f64::NEG_INFINITY, f64::max);
    if max == f64::NEG_INFINITY {
        return f64::NEG_INFINITY;
    }
    if max == f64::INFINITY {
        return f64::INFINITY;
    }
    let sum: f64 = log_weights
        .iter()
        .filter(|l| !l.is_nan())
        .map(|&l| crate::math::exp(l - max))
        .sum();
    max + crate::math::ln(sum)
}

/// The outcome of a normalisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Normalised {
    /// ln sum_i exp(l_i) (the log of the unnormalised total weight).
    pub log_total: f64,
    /// True when no particle had positive weight and the weights were set uniform.
    pub degenerate: bool,
}

/// Writes the normalised weights w_i = exp(l_i - L) into `weights` (same length).
pub fn normalise(log_weights: &[f64], weights: &mut [f64]) -> Normalised {
    let n = log_weights.len();
    let log_total = log_sum_exp(log_weights);
    if !log_total.is_finite() {
        // All -inf (or a +inf): uniform over the particles with the largest log-weight.
        let inf = log_weights.iter().filter(|l| **l == f64::INFINITY).count();
        for (w, &l) in weights.iter_mut().zip(log_weights) {
            *w = if inf > 0 {
                f64::from(u8::from(l == f64::INFINITY)) / inf as f64
            } else {
                1.0 / n as f64
            };
        }
        return Normalised {
            log_total,
            degenerate: inf == 0,
        };
    }
    for (w, &l) in weights.iter_mut().zip(log_weights) {
        *w = if l.is_nan() {
            0.0
        } else {
            crate::math::exp(l - log_total)
        };
    }
    Normalised {
        log_total,
        degenerate: false,
    }
}

/// Effective sample size 1 / sum w_i^2 of normalised weights.
pub fn effective_sample_size(weights: &[f64]) -> f64 {
    let s: f64 = weights.iter().map(|w| w * w).sum();
    if s > 0.0 {
        1.0 / s
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn huge_negative_log_weights_do_not_underflow() {
        let l = [-10_000.0, -10_001.0, -10_000.0 - std::f64::consts::LN_2];
        let mut w = [0.0; 3];
        let r = normalise(&l, &mut w);
        assert!(!r.degenerate);
        // Proportions 1 : e^-1 : 1/2.
        let total = 1.0 + crate::math::exp(-1.0) + 0.5;
        assert!((w[0] - 1.0 / total).abs() < 1e-12 && (w[2] - 0.5 / total).abs() < 1e-12);
        assert!((r.log_total - (-10_000.0 + crate::math::ln(total))).abs() < 1e-9);
    }

    #[test]
    fn degenerate_and_nan_weights_are_handled() {
        let mut w = [0.0; 4];
        let r = normalise(&[f64::NEG_INFINITY; 4], &mut w);
        assert!(r.degenerate && w == [0.25; 4]);
        let r = normalise(&[0.0, f64::NAN, 0.0, f64::NEG_INFINITY], &mut w);
        assert!(!r.degenerate && w == [0.5, 0.0, 0.5, 0.0]);
    }

    #[test]
    fn ess_of_uniform_is_n_and_of_one_hot_is_one() {
        assert!((effective_sample_size(&[0.1; 10]) - 10.0).abs() < 1e-9);
        assert_eq!(effective_sample_size(&[0.0, 1.0, 0.0]), 1.0);
    }
}
