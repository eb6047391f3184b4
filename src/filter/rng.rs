//! The filter's seeded random number generator.
//!
//! PCG-XSH-RR 64/32 (O'Neill 2014, `rand_pcg::Pcg32`) seeded with `seed_from_u64`. Uniforms are
//! u / 2^53 for the top 53 bits of a 64-bit draw; normals come from the Box-Muller transform
//! z = sqrt(-2 ln u1) (cos 2 pi u2, sin 2 pi u2), both values used, computed with
//! [`crate::math`] so that the same seed gives the same numbers natively and in wasm.
//! Integers below n use Lemire's multiply-and-reject method (no modulo bias).

use crate::math;
use rand_core::{Rng as _, SeedableRng};
use rand_pcg::Pcg32;
use std::f64::consts::PI;

/// A seeded generator owned by a filter.
#[derive(Debug, Clone)]
pub struct Rng {
    inner: Pcg32,
    spare: Option<f64>,
}

impl Rng {
    /// A generator for `seed`.
    pub fn new(seed: u64) -> Self {
        Self {
            inner: Pcg32::seed_from_u64(seed),
            spare: None,
        }
    }

    /// A raw 64-bit draw.
    pub fn next_u64(&mut self) -> u64 {
        self.inner.next_u64()
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Standard normal N(0, 1).
    pub fn normal(&mut self) -> f64 {
        if let Some(z) = self.spare.take() {
            return z;
        }
        // u1 in (0, 1] so that ln(u1) is finite.
        let u1 = 1.0 - self.uniform();
        let u2 = self.uniform();
        let r = (-2.0 * math::ln(u1)).sqrt();
        let theta = 2.0 * PI * u2;
        self.spare = Some(r * math::sin(theta));
        r * math::cos(theta)
    }

    /// Normal with the given mean and standard deviation.
    pub fn gaussian(&mut self, mean: f64, sd: f64) -> f64 {
        mean + sd * self.normal()
    }

    /// Uniform integer in [0, n); 0 when n is 0.
    pub fn below(&mut self, n: usize) -> usize {
        if n <= 1 {
            return 0;
        }
        let n = n as u64;
        let threshold = n.wrapping_neg() % n;
        loop {
            let m = (self.next_u64() as u128) * (n as u128);
            if (m as u64) >= threshold {
                return (m >> 64) as usize;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_sequence_and_different_seeds_differ() {
        let (mut a, mut b, mut c) = (Rng::new(7), Rng::new(7), Rng::new(8));
        let xa: Vec<f64> = (0..50).map(|_| a.normal()).collect();
        let xb: Vec<f64> = (0..50).map(|_| b.normal()).collect();
        let xc: Vec<f64> = (0..50).map(|_| c.normal()).collect();
        assert_eq!(xa, xb);
        assert_ne!(xa, xc);
    }

    #[test]
    fn moments_are_right() {
        // n = 200 000: the standard error of a mean of U(0,1) is 0.29/sqrt(n) = 6.5e-4 and of a
        // normal 2.2e-3; the tolerances are about 5 standard errors.
        let mut r = Rng::new(1);
        let n = 200_000;
        let u: Vec<f64> = (0..n).map(|_| r.uniform()).collect();
        let mean = u.iter().sum::<f64>() / n as f64;
        let var = u.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n as f64;
        assert!(
            (mean - 0.5).abs() < 3e-3 && (var - 1.0 / 12.0).abs() < 2e-3,
            "{mean} {var}"
        );
        assert!(u.iter().all(|&x| (0.0..1.0).contains(&x)));
        let z: Vec<f64> = (0..n).map(|_| r.gaussian(2.0, 3.0)).collect();
        let mean = z.iter().sum::<f64>() / n as f64;
        let var = z.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n as f64;
        assert!(
            (mean - 2.0).abs() < 0.035 && (var - 9.0).abs() < 0.15,
            "{mean} {var}"
        );
    }

    #[test]
    fn below_is_uniform_over_its_range() {
        // Chi-square with 6 degrees of freedom: the 99.9 % quantile is 22.5.
        let mut r = Rng::new(3);
        let mut counts = [0usize; 7];
        let n = 70_000;
        for _ in 0..n {
            counts[r.below(7)] += 1;
        }
        let e = n as f64 / 7.0;
        let chi2: f64 = counts.iter().map(|&c| (c as f64 - e).powi(2) / e).sum();
        assert!(chi2 < 22.5, "{counts:?} chi2 = {chi2}");
        assert_eq!(r.below(0), 0);
        assert_eq!(r.below(1), 0);
    }
}
