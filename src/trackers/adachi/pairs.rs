//! Ego pairs read off the vote histogram: a proposal for (q, w) from the frame's own votes.
//!
//! The paper does not say how the filter starts (Sec. 3.3 gives the motion only). A uniform
//! start over (r, q, w) puts about one particle in a thousand within 0.1 m of the true q and w
//! of the true model, and the likelihood (eqs. 4-6) has strong false modes: on Udacity
//! `project_video` the guard rail 2.6 m left of the yellow line and the yellow line make a
//! "lane" of model 2 at the width limit (right boundary on bare road), 70 log-units below the
//! true lane of model 3 but separated from it by a valley of several hundred; the random walk
//! of eqs. 7-8 (sigma 0.08 / 0.04 m a frame) never crosses it, and the filter is locked in.
//!
//! The ego lane's two boundaries straddle the car (eq. 9 keeps -w/2 <= q < w/2, so rho_1 =
//! q - w/2 <= 0 < rho_2 = q + w/2), each at a peak of H_j. So we list the histogram's peaks
//! (a bin with more votes than the two bins on its left and at least as many as the two on its
//! right; its mass the votes within 2 bins), turn each edge peak into a boundary position by the
//! template's edge offset (+m/2 for the paper's left edges), and pair every peak left of the car
//! with every peak right of it whose distance is an accepted width. A pair is drawn with
//! probability proportional to the product of its peaks' masses, and a particle put at its
//! centre and width with the random walk's spread (sigma_q, sigma_w).
//!
//! Used twice: on a first frame (after construction or a reset), half of the initial particles
//! are drawn from the pairs (the start-up, ours: the paper leaves it open); with a positive
//! `vote_pair_share` (ours, beyond the paper), that share of the particles is redrawn from the
//! pairs each frame, like `relock_share` but from the paper's own cue, so that a cloud locked on
//! a false mode, or lost after a blackout, finds the lane again. The likelihood decides between
//! the drawn particles and the rest: a pair on a false peak dies at the next weighing.
//!
//! Buffers are sized at construction (the number of bins bounds the peaks; at most
//! [`MAX_PEAKS`] a side are paired, the heaviest); no allocation per frame.

use super::votes::Votes;
use crate::filter::Rng;

/// The most peaks kept on each side of the car (the heaviest).
pub const MAX_PEAKS: usize = 16;

/// Peaks and the pairs they form, rebuilt by [`VotePairs::find`] each frame.
#[derive(Debug, Clone)]
pub struct VotePairs {
    /// Boundary positions and masses of the peaks left (rho <= 0) and right of the car.
    left: Vec<(f64, f64)>,
    right: Vec<(f64, f64)>,
    /// (q, w, cumulative weight) of each accepted pair.
    pairs: Vec<(f64, f64, f64)>,
}

impl Default for VotePairs {
    fn default() -> Self {
        Self::new()
    }
}

impl VotePairs {
    /// Empty, with room for [`MAX_PEAKS`] peaks a side and their pairs.
    pub fn new() -> Self {
        Self {
            left: Vec::with_capacity(MAX_PEAKS + 1),
            right: Vec::with_capacity(MAX_PEAKS + 1),
            pairs: Vec::with_capacity(MAX_PEAKS * MAX_PEAKS),
        }
    }

    /// Finds the peaks of `votes` and the pairs of accepted width (`width_range`); `offset` is
    /// the boundary's position minus its voting edge's (m/2 for left edges, -m/2 for right
    /// edges, 0 for both). Returns the number of pairs.
    pub fn find(&mut self, votes: &Votes, offset: f64, width_range: [f64; 2]) -> usize {
        self.left.clear();
        self.right.clear();
        self.pairs.clear();
        let h = &votes.histogram;
        let n = h.len();
        for j in 0..n {
            let v = h[j];
            if v <= 0.0 {
                continue;
            }
            let below = |k: usize| j.checked_sub(k).map_or(0.0, |i| h[i]);
            let above = |k: usize| h.get(j + k).copied().unwrap_or(0.0);
            if !(v > below(1) && v > below(2) && v >= above(1) && v >= above(2)) {
                continue;
            }
            let mass = below(1) + below(2) + v + above(1) + above(2);
            let rho = votes.rho(j) + offset;
            let side = if rho <= 0.0 {
                &mut self.left
            } else {
                &mut self.right
            };
            keep_heaviest(side, (rho, mass));
        }
        let [lo, hi] = width_range;
        let mut total = 0.0;
        for &(a, ma) in &self.left {
            for &(b, mb) in &self.right {
                let w = b - a;
                if (lo..=hi).contains(&w) {
                    total += ma * mb;
                    self.pairs.push((0.5 * (a + b), w, total));
                }
            }
        }
        self.pairs.len()
    }

    /// Number of pairs of the last [`VotePairs::find`].
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    /// Whether the last [`VotePairs::find`] found no pair.
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// One pair's (q, w), drawn with probability proportional to its weight (`None` when there
    /// is none).
    pub fn draw(&self, rng: &mut Rng) -> Option<(f64, f64)> {
        let total = self.pairs.last()?.2;
        let u = rng.uniform() * total;
        let k = self.pairs.partition_point(|p| p.2 <= u);
        let (q, w, _) = self.pairs[k.min(self.pairs.len() - 1)];
        Some((q, w))
    }
}

/// Adds `peak` to `side`, keeping the [`MAX_PEAKS`] heaviest (the lightest is dropped).
fn keep_heaviest(side: &mut Vec<(f64, f64)>, peak: (f64, f64)) {
    if side.len() < MAX_PEAKS {
        side.push(peak);
        return;
    }
    let (k, lightest) =
        side.iter().enumerate().fold(
            (0, f64::INFINITY),
            |(k, m), (i, p)| {
                if p.1 < m {
                    (i, p.1)
                } else {
                    (k, m)
                }
            },
        );
    if peak.1 > lightest {
        side[k] = peak;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trackers::adachi::config::AdachiConfig;

    #[test]
    fn pairs_straddle_the_car_at_an_accepted_width() {
        let cam = crate::synth::default_camera(320, 240).unwrap();
        let config = AdachiConfig::default();
        let mut votes = Votes::new(&cam, &config).unwrap();
        votes.histogram.fill(0.0);
        // Edges (left edges, 7.5 cm left of each boundary) at boundaries -4.2 (a rail),
        // -1.5 (the yellow line), 2.2 (the dashes) and 5.9 (the next dashes).
        for (rho, n) in [(-4.2, 40.0), (-1.5, 60.0), (2.2, 15.0), (5.9, 20.0)] {
            let j = votes.bin_of(rho - 0.075);
            votes.histogram[j] += n;
            votes.histogram[j + 1] += n / 3.0;
        }
        let mut pairs = VotePairs::new();
        // Only (-1.5, 2.2) straddles the car at 2.5-4.8 m.
        assert_eq!(pairs.find(&votes, 0.075, config.width_range_m), 1);
        let mut rng = Rng::new(1);
        let (q, w) = pairs.draw(&mut rng).unwrap();
        assert!(
            (q - 0.35).abs() < 0.06 && (w - 3.7).abs() < 0.06,
            "q {q} w {w}"
        );
        // No votes, no pairs.
        votes.histogram.fill(0.0);
        assert_eq!(pairs.find(&votes, 0.075, config.width_range_m), 0);
        assert!(pairs.draw(&mut rng).is_none());
    }
}
