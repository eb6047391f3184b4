//! [`Draw`]: the uniform draws a scenario family makes from its seed.
//!
//! A thin layer over the seeded [`Rng`] (PCG32, bit-identical natively and in wasm): every
//! value of a family member is `lo + (hi - lo) u` with u ~ U[0, 1), a sign or a choice, drawn
//! in a fixed order, so one seed gives one scene on every target.

use crate::filter::Rng;

/// The draws of one family member.
#[derive(Debug, Clone)]
pub struct Draw {
    rng: Rng,
}

impl Draw {
    /// Draws for `seed`, on the stream `salt` (independent streams for the road and the
    /// camera, so that adding a draw to one does not move the other).
    pub fn new(seed: u64, salt: u64) -> Self {
        Self {
            rng: Rng::new(seed ^ salt),
        }
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.rng.uniform()
    }

    /// +1 or -1 with equal probability.
    pub fn sign(&mut self) -> f64 {
        if self.rng.uniform() < 0.5 {
            1.0
        } else {
            -1.0
        }
    }

    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.rng.uniform() < p
    }

    /// Uniform integer in [lo, hi] (inclusive).
    pub fn int(&mut self, lo: usize, hi: usize) -> usize {
        lo + self.rng.below(hi.saturating_sub(lo) + 1)
    }

    /// A magnitude in [lo, hi) with a random sign.
    pub fn signed(&mut self, lo: f64, hi: f64) -> f64 {
        let sign = self.sign();
        sign * self.range(lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_stay_in_their_ranges_and_repeat_per_seed() {
        let mut a = Draw::new(5, 1);
        let mut b = Draw::new(5, 1);
        for _ in 0..1000 {
            let x = a.range(2.8, 4.2);
            assert!((2.8..4.2).contains(&x));
            assert_eq!(x, b.range(2.8, 4.2));
            let k = a.int(2, 4);
            assert!((2..=4).contains(&k));
            b.int(2, 4);
            let s = a.signed(1.0, 2.0);
            assert!((1.0..2.0).contains(&s.abs()));
            b.signed(1.0, 2.0);
        }
        assert_ne!(
            Draw::new(5, 1).range(0.0, 1.0),
            Draw::new(5, 2).range(0.0, 1.0)
        );
    }
}
