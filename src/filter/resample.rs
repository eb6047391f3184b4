//! Resampling: choosing N ancestors in proportion to the weights.
//!
//! With normalised weights w_i and cumulative sums c_i = w_1 + ... + w_i, each scheme draws N
//! ordered points u_1 <= ... <= u_N in [0, 1) and takes as ancestor of the k-th new particle the
//! first i with c_i > u_k:
//!
//! - multinomial: u_k i.i.d. uniform (sorted in O(N) from normalised cumulative sums of
//!   exponential draws);
//! - stratified: u_k = (k + U_k) / N with independent U_k;
//! - systematic: u_k = (k + U) / N with one U, so particle i gets floor(N w_i) or
//!   ceil(N w_i) copies;
//! - residual: floor(N w_i) copies deterministically, the remaining R = N - sum floor(N w_i)
//!   drawn multinomially from the residual weights (N w_i - floor(N w_i)) / R.
//!
//! All are unbiased: the expected number of copies of particle i is N w_i. Ancestors are
//! written in increasing order into a caller-owned buffer (no allocation once it has capacity).

use super::rng::Rng;
use serde::{Deserialize, Serialize};

/// A resampling scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Resampler {
    /// I.i.d. draws from the weights.
    Multinomial,
    /// One uniform per stratum of width 1/N.
    Stratified,
    /// One uniform shared by all strata (lowest variance in practice).
    Systematic,
    /// Deterministic copies of the integer parts, multinomial for the rest.
    Residual,
}

/// When to resample.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ResamplePolicy {
    /// Every step.
    Always,
    /// When the effective sample size falls below this fraction of N (Lee Algorithm 1).
    EssBelow(f64),
    /// Never (sequential importance sampling).
    Never,
}

impl ResamplePolicy {
    /// Whether to resample with effective sample size `ess` out of `n` particles.
    pub fn should_resample(self, ess: f64, n: usize) -> bool {
        match self {
            ResamplePolicy::Always => true,
            ResamplePolicy::EssBelow(f) => ess < f * n as f64,
            ResamplePolicy::Never => false,
        }
    }
}

impl Resampler {
    /// Writes `n` ancestor indices drawn from the normalised `weights` into `ancestors`
    /// (cleared first), in increasing order.
    pub fn resample(self, weights: &[f64], n: usize, rng: &mut Rng, ancestors: &mut Vec<usize>) {
        ancestors.clear();
        if weights.is_empty() || n == 0 {
            return;
        }
        match self {
            Resampler::Multinomial => multinomial(weights, 1.0, n, rng, ancestors),
            Resampler::Stratified => {
                let mut points = (0..n).map(|k| (k as f64 + rng.uniform()) / n as f64);
                walk(weights, 1.0, n, &mut points, ancestors);
            }
            Resampler::Systematic => {
                let u = rng.uniform();
                let mut points = (0..n).map(|k| (k as f64 + u) / n as f64);
                walk(weights, 1.0, n, &mut points, ancestors);
            }
            Resampler::Residual => residual(weights, n, rng, ancestors),
        }
    }
}

/// Ancestors for the sorted points of `points` under weights `w` (summing to `total`).
fn walk(
    w: &[f64],
    total: f64,
    n: usize,
    points: &mut impl Iterator<Item = f64>,
    out: &mut Vec<usize>,
) {
    let last = w.iter().rposition(|&x| x > 0.0).unwrap_or(w.len() - 1);
    let mut i = 0;
    let mut cumulative = w[0];
    for u in points.take(n) {
        let u = u * total;
        while cumulative <= u && i < last {
            i += 1;
            cumulative += w[i];
        }
        out.push(i);
    }
}

/// Multinomial draws from weights `w` (summing to `total`), appended to `out`.
fn multinomial(w: &[f64], total: f64, n: usize, rng: &mut Rng, out: &mut Vec<usize>) {
    // Sorted uniforms: U_(k) = S_k / S_{n+1} with S_k the sum of k standard exponentials.
    // Two passes over the same stream: first the total S_{n+1}, then the points.
    let state = rng.clone();
    let mut s = 0.0;
    for _ in 0..=n {
        s += -crate::math::ln(1.0 - rng.uniform());
    }
    let mut replay = state;
    let mut acc = 0.0;
    let mut points = (0..n).map(|_| {
        acc += -crate::math::ln(1.0 - replay.uniform());
        acc / s
    });
    walk(w, total, n, &mut points, out);
}

fn residual(w: &[f64], n: usize, rng: &mut Rng, out: &mut Vec<usize>) {
    let nf = n as f64;
    let mut deterministic = 0;
    for (i, &wi) in w.iter().enumerate() {
        let copies = (nf * wi).floor() as usize;
        for _ in 0..copies {
            out.push(i);
        }
        deterministic += copies;
    }
    let rest = n.saturating_sub(deterministic);
    if rest == 0 {
        out.truncate(n);
        return;
    }
    // Residual weights N w_i - floor(N w_i), summing to `rest` (up to rounding).
    let residual_total: f64 = w.iter().map(|&wi| nf * wi - (nf * wi).floor()).sum();
    let residual_weights = w.iter().map(|&wi| nf * wi - (nf * wi).floor());
    // Walk the residual weights without storing them: a second multinomial pass.
    let state = rng.clone();
    let mut s = 0.0;
    for _ in 0..=rest {
        s += -crate::math::ln(1.0 - rng.uniform());
    }
    let mut replay = state;
    let mut acc = 0.0;
    let mut i = 0;
    let mut weights = residual_weights;
    let mut cumulative = weights.next().unwrap_or(0.0);
    let last = w.len() - 1;
    for _ in 0..rest {
        acc += -crate::math::ln(1.0 - replay.uniform());
        let u = acc / s * residual_total;
        while cumulative <= u && i < last {
            i += 1;
            cumulative += weights.next().unwrap_or(0.0);
        }
        out.push(i);
    }
    // Deterministic copies and residual draws are each ascending; merge them (in place).
    out.sort_unstable();
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [Resampler; 4] = [
        Resampler::Multinomial,
        Resampler::Stratified,
        Resampler::Systematic,
        Resampler::Residual,
    ];

    #[test]
    fn every_scheme_is_unbiased() {
        // Expected copies N w_i. Over R repetitions the mean count has standard error at most
        // sqrt(N w_i (1 - w_i) / R) (the multinomial variance, which the others do not
        // exceed); the tolerance is 5 standard errors.
        let w = [0.05, 0.3, 0.0, 0.15, 0.4, 0.1];
        let (n, reps) = (50, 4000);
        for scheme in ALL {
            let mut rng = Rng::new(11);
            let mut counts = [0usize; 6];
            let mut anc = Vec::new();
            for _ in 0..reps {
                scheme.resample(&w, n, &mut rng, &mut anc);
                assert_eq!(anc.len(), n);
                assert!(anc.windows(2).all(|p| p[0] <= p[1]), "{scheme:?} sorted");
                for &a in &anc {
                    counts[a] += 1;
                }
            }
            for (i, &wi) in w.iter().enumerate() {
                let mean = counts[i] as f64 / reps as f64;
                let se = (n as f64 * wi * (1.0 - wi) / reps as f64).sqrt();
                assert!(
                    (mean - n as f64 * wi).abs() <= 5.0 * se + 1e-9,
                    "{scheme:?}: particle {i} mean {mean} vs {}",
                    n as f64 * wi
                );
            }
            assert_eq!(
                counts[2], 0,
                "{scheme:?} never copies a zero-weight particle"
            );
        }
    }

    #[test]
    fn systematic_and_residual_copy_counts_are_floor_or_ceil() {
        let w = [0.123, 0.377, 0.25, 0.18, 0.07];
        let n = 40;
        for scheme in [Resampler::Systematic, Resampler::Residual] {
            let mut rng = Rng::new(5);
            let mut anc = Vec::new();
            for _ in 0..200 {
                scheme.resample(&w, n, &mut rng, &mut anc);
                for (i, &wi) in w.iter().enumerate() {
                    let c = anc.iter().filter(|&&a| a == i).count() as f64;
                    let e = n as f64 * wi;
                    if scheme == Resampler::Systematic {
                        assert!(
                            c == e.floor() || c == e.ceil(),
                            "{scheme:?} {i}: {c} vs {e}"
                        );
                    } else {
                        assert!(
                            c >= e.floor(),
                            "residual keeps the integer part: {c} vs {e}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn policy_resamples_only_when_ess_is_low() {
        assert!(ResamplePolicy::EssBelow(0.5).should_resample(40.0, 100));
        assert!(!ResamplePolicy::EssBelow(0.5).should_resample(60.0, 100));
        assert!(ResamplePolicy::Always.should_resample(100.0, 100));
        assert!(!ResamplePolicy::Never.should_resample(1.0, 100));
    }

    #[test]
    fn no_allocation_once_the_buffer_has_capacity() {
        let w = vec![1.0 / 1000.0; 1000];
        let mut anc = Vec::with_capacity(1000);
        let ptr = anc.as_ptr();
        let mut rng = Rng::new(1);
        for scheme in ALL {
            scheme.resample(&w, 1000, &mut rng, &mut anc);
            assert_eq!(anc.as_ptr(), ptr);
        }
    }
}
