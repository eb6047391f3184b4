//! Where the lane lines of recent frames met: a decaying 2-D histogram of vanishing-point
//! candidates, so that the calibrator knows roughly where the road vanishes before it has
//! measured anything.
//!
//! Every frame, each pair of a left-leaning and a right-leaning line votes at its crossing
//! with weight min(support): lane boundaries cross at the same place frame after frame, while
//! lines from trees, shadows and cars cross anywhere. The histogram (bins of 1 % of the image
//! width and height over u in [-W/2, 3W/2), v in [-H/2, H)) decays by [`DECAY`] a frame; its
//! mode is the vote-weighted centre of the 3 x 3 bin neighbourhood with the largest sum.

/// Fraction of the votes kept from one frame to the next (a half-life of about 35 frames).
pub const DECAY: f32 = 0.98;
const BINS_PER_SIDE: usize = 100;

/// The histogram.
#[derive(Debug, Clone)]
pub struct VpVotes {
    width: f64,
    height: f64,
    cols: usize,
    rows: usize,
    bins: Vec<f32>,
    total: f32,
}

impl VpVotes {
    /// An empty histogram for `width` x `height` frames.
    pub fn new(width: usize, height: usize) -> Self {
        let (cols, rows) = (2 * BINS_PER_SIDE, 3 * BINS_PER_SIDE / 2);
        Self {
            width: width as f64,
            height: height as f64,
            cols,
            rows,
            bins: vec![0.0; cols * rows],
            total: 0.0,
        }
    }

    fn cell(&self, p: [f64; 2]) -> Option<(usize, usize)> {
        let c = (p[0] / self.width + 0.5) * BINS_PER_SIDE as f64;
        let r = (p[1] / self.height + 0.5) * BINS_PER_SIDE as f64;
        (c >= 0.0 && r >= 0.0 && (c as usize) < self.cols && (r as usize) < self.rows)
            .then_some((c as usize, r as usize))
    }

    /// Ages every vote by one frame.
    pub fn decay(&mut self) {
        self.bins.iter_mut().for_each(|b| *b *= DECAY);
        self.total *= DECAY;
    }

    /// Adds a vote at pixel `p` (ignored outside the histogram).
    pub fn vote(&mut self, p: [f64; 2], weight: f32) {
        if let Some((c, r)) = self.cell(p) {
            self.bins[r * self.cols + c] += weight;
            self.total += weight;
        }
    }

    /// Forgets every vote.
    pub fn clear(&mut self) {
        self.bins.iter_mut().for_each(|b| *b = 0.0);
        self.total = 0.0;
    }

    /// The centre of the strongest 3 x 3 neighbourhood and the share of all votes it holds.
    pub fn mode(&self) -> Option<([f64; 2], f32)> {
        if self.total <= 0.0 {
            return None;
        }
        let mut best = (0.0f32, 0, 0);
        for r in 1..self.rows - 1 {
            for c in 1..self.cols - 1 {
                let mut sum = 0.0;
                for dr in 0..3 {
                    let row = (r + dr - 1) * self.cols;
                    sum += self.bins[row + c - 1] + self.bins[row + c] + self.bins[row + c + 1];
                }
                if sum > best.0 {
                    best = (sum, c, r);
                }
            }
        }
        let (sum, c, r) = best;
        if sum <= 0.0 {
            return None;
        }
        // The vote-weighted centre of the neighbourhood's bins.
        let (mut cu, mut cv) = (0.0, 0.0);
        for rr in r - 1..=r + 1 {
            for cc in c - 1..=c + 1 {
                let b = self.bins[rr * self.cols + cc] as f64;
                cu += b * (cc as f64 + 0.5);
                cv += b * (rr as f64 + 0.5);
            }
        }
        let n = BINS_PER_SIDE as f64;
        let u = (cu / sum as f64 / n - 0.5) * self.width;
        let v = (cv / sum as f64 / n - 0.5) * self.height;
        Some(([u, v], sum / self.total))
    }

    /// Sum of the (decayed) votes.
    pub fn total(&self) -> f32 {
        self.total
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mode_is_where_votes_agree() {
        let mut votes = VpVotes::new(640, 480);
        assert!(votes.mode().is_none());
        for k in 0..20 {
            votes.decay();
            votes.vote([320.0 + (k % 3) as f64, 200.0], 1.0);
            votes.vote([(k * 37 % 640) as f64, (k * 53 % 480) as f64], 1.0);
        }
        let ([u, v], share) = votes.mode().unwrap();
        assert!(
            (u - 323.2).abs() <= 0.1 && (v - 199.2).abs() <= 0.1,
            "the bin centres: {u} {v}"
        );
        assert!(share > 0.45 && share <= 1.0, "{share}");
        let total = votes.total();
        votes.vote([1e9, 0.0], 5.0);
        assert_eq!(
            total,
            votes.total(),
            "a vote off the histogram is not counted"
        );
    }
}
