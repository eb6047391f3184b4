//! The likelihood of Adachi et al. (eqs. 3-6).
//!
//! Boundaries (eq. 3): rho_l = q + [-1, 1, -3, 3]_l w / 2; model r switches them on with c_r
//! (eq. 5): model 1 `[1,1,0,0]`, 2 `[1,1,1,0]`, 3 `[1,1,0,1]`, 4 `[1,1,1,1]`. The edge distribution
//! (eq. 4) is
//!
//! ```text
//! p(rho_j | r, q, w) = alpha ( sum_l c_{r,l} Hbar_j(rho_l) + beta N_j )
//! ```
//!
//! and the likelihood of the votes H_j (eq. 6) is prod_j p_j^{H_j}, computed as
//! sum_j H_j ln p_j over the bins that received votes.
//!
//! The paper leaves H_bar open ("a histogram where one lane boundary is at rho"); we use the
//! discretised edge-position density of one marking centred at rho: the voting edge lies at
//! rho - m/2 for left edges (rho + m/2 for right edges, both halves for both), spread by a
//! Gaussian of sd s = sqrt(edge_sigma^2 + bin^2 / 12), so Hbar_j = bin * N(rho_j; rho -+ m/2, s)
//! (sums to 1 over the axis when the edge is inside it). alpha makes p sum to 1 over the bins:
//! alpha = 1 / (sum_l c_{r,l} mass_l + beta), with mass_l the part of the template inside the
//! axis (an error-function integral), since N sums to 1.

use super::config::{AdachiConfig, Polarity};
use super::votes::Votes;
use crate::math;

/// Boundary offsets of eq. 3, in units of w / 2.
pub const OFFSETS: [f64; 4] = [-1.0, 1.0, -3.0, 3.0];
/// c_r of eq. 5 for models r = 1..4 (index 0..3).
pub const COEFFICIENTS: [[bool; 4]; 4] = [
    [true, true, false, false],
    [true, true, true, false],
    [true, true, false, true],
    [true, true, true, true],
];

/// The likelihood with its template parameters.
#[derive(Debug, Clone)]
pub struct Likelihood {
    /// Edge offsets from the boundary for the polarity, metres, with their weights.
    edges: Vec<(f64, f64)>,
    sd: f64,
    beta: f64,
    /// Indices of the bins with votes, filled per frame.
    voted: Vec<usize>,
}

impl Likelihood {
    /// The likelihood of `config`: its polarity, marking width m, edge spread, histogram bin
    /// and noise weight beta.
    pub fn new(config: &AdachiConfig) -> Self {
        let m = config.marking_width_m;
        let (edge_sigma, bin) = (config.edge_sigma_m, config.bin_m);
        let edges = match config.polarity {
            Polarity::LeftEdge => vec![(-m / 2.0, 1.0)],
            Polarity::RightEdge => vec![(m / 2.0, 1.0)],
            Polarity::Both => vec![(-m / 2.0, 0.5), (m / 2.0, 0.5)],
        };
        Self {
            edges,
            sd: (edge_sigma * edge_sigma + bin * bin / 12.0).sqrt(),
            beta: config.beta,
            voted: Vec::new(),
        }
    }

    /// Notes which bins have votes (call once per frame before [`Likelihood::log_likelihood`]).
    pub fn prepare(&mut self, votes: &Votes) {
        self.voted.clear();
        self.voted
            .extend((0..votes.bins()).filter(|&j| votes.histogram[j] > 0.0));
    }

    /// The template Hbar_j(rho) at bin centre `rho_j`.
    fn template(&self, rho_j: f64, rho: f64, bin: f64) -> f64 {
        let norm = bin / (self.sd * (2.0 * std::f64::consts::PI).sqrt());
        self.edges
            .iter()
            .map(|&(off, weight)| {
                let e = (rho_j - rho - off) / self.sd;
                if e.abs() > 6.0 {
                    0.0
                } else {
                    weight * norm * math::exp(-0.5 * e * e)
                }
            })
            .sum()
    }

    /// Mass of the template of a boundary at `rho` inside [lo, hi).
    fn mass(&self, rho: f64, lo: f64, hi: f64) -> f64 {
        let cdf = |x: f64| 0.5 * (1.0 + libm::erf(x / (self.sd * std::f64::consts::SQRT_2)));
        self.edges
            .iter()
            .map(|&(off, weight)| weight * (cdf(hi - rho - off) - cdf(lo - rho - off)))
            .sum()
    }

    /// The vote support of one boundary at `rho`: the share of the region's rows in which its
    /// edge voted. Votes are counted within 2 sd of where the template H_bar puts the edge
    /// (rho -+ m/2 by polarity) and divided by the number of region rows crossing that window,
    /// since a solid marking's edge votes once per row; capped at 1 per edge and averaged over
    /// the edges of the polarity. 0 for an edge off the axis. Not part of the paper: it defines
    /// [`super::AdachiEstimate::valid`].
    pub fn support(&self, votes: &Votes, rho: f64) -> f64 {
        self.edge_windows(votes, rho)
            .map(|(window, weight)| {
                let Some((lo, hi)) = window else {
                    return 0.0;
                };
                let rows = votes.rows_crossing(lo, hi);
                if rows == 0 {
                    return 0.0;
                }
                let n: f64 = votes.histogram[lo..=hi].iter().sum();
                weight * (n / rows as f64).min(1.0)
            })
            .sum()
    }

    /// How far beyond the voting region's nearest row the nearest vote of the boundary at
    /// `rho` lies (within the windows of [`Likelihood::support`]), metres; infinite when none.
    pub fn reach(&self, votes: &Votes, rho: f64) -> f64 {
        self.edge_windows(votes, rho)
            .filter_map(|(window, _)| window)
            .map(|(lo, hi)| votes.reach(lo, hi))
            .fold(f64::INFINITY, f64::min)
    }

    /// For each edge of the boundary at `rho`: the bins within 2 sd of where the template
    /// puts it (`None` when the window is off the axis) and its weight.
    fn edge_windows<'a>(
        &'a self,
        votes: &'a Votes,
        rho: f64,
    ) -> impl Iterator<Item = (Option<(usize, usize)>, f64)> + 'a {
        let lo_axis = votes.rho_min();
        let hi_axis = lo_axis + votes.bin_m() * votes.bins() as f64;
        self.edges.iter().map(move |&(off, weight)| {
            let (a, b) = (rho + off - 2.0 * self.sd, rho + off + 2.0 * self.sd);
            let window = (b > lo_axis && a < hi_axis).then(|| (votes.bin_of(a), votes.bin_of(b)));
            (window, weight)
        })
    }

    /// ln p(z | r, q, w) (eq. 6) for model index `model` (0..3 for r = 1..4).
    pub fn log_likelihood(&self, votes: &Votes, model: usize, q: f64, w: f64) -> f64 {
        let coefficients = COEFFICIENTS[model.min(3)];
        let bin = votes.bin_m();
        let lo = votes.rho_min();
        let hi = lo + bin * votes.bins() as f64;
        let mut mass = self.beta;
        let mut rhos = [f64::NAN; 4];
        for l in 0..4 {
            if coefficients[l] {
                rhos[l] = q + OFFSETS[l] * w / 2.0;
                mass += self.mass(rhos[l], lo, hi);
            }
        }
        let ln_alpha = -math::ln(mass);
        let mut total = 0.0;
        let mut votes_n = 0.0;
        for &j in &self.voted {
            let rho_j = votes.rho(j);
            let mut p = self.beta * votes.noise[j];
            for rho in rhos.iter().filter(|r| !r.is_nan()) {
                p += self.template(rho_j, *rho, bin);
            }
            let h = votes.histogram[j];
            total += h * math::ln(p.max(1e-300));
            votes_n += h;
        }
        total + votes_n * ln_alpha
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::Rng;
    use crate::synth::default_camera;

    /// Grid steps for q and w, metres.
    const Q_STEP: f64 = 0.025;
    const W_STEP: f64 = 0.05;
    fn grid_q(k: i64) -> f64 {
        k as f64 * Q_STEP
    }
    fn grid_w(i: i64) -> f64 {
        3.0 + i as f64 * W_STEP
    }

    /// H_j for the lanes (model, q, w): at the left edge of each boundary model r has
    /// (rho_l - m/2, eq. 3 and the template's polarity) 40 votes, 15 in each neighbouring bin
    /// and 3 two bins off; plus 60 noise votes in bins drawn uniformly where the region has
    /// pixels.
    fn synthetic(votes: &mut Votes, model: usize, q: f64, w: f64, m: f64, seed: u64) {
        votes.histogram.fill(0.0);
        for l in 0..4 {
            if COEFFICIENTS[model][l] {
                let j = votes.bin_of(q + OFFSETS[l] * w / 2.0 - m / 2.0);
                for (d, n) in [(-2, 3.0), (-1, 15.0), (0, 40.0), (1, 15.0), (2, 3.0)] {
                    votes.histogram[(j as i64 + d) as usize] += n;
                }
            }
        }
        let visible: Vec<usize> = (0..votes.bins())
            .filter(|&j| votes.noise[j] > 0.0)
            .collect();
        let mut rng = Rng::new(seed);
        for _ in 0..60 {
            votes.histogram[visible[rng.below(visible.len())]] += 1.0;
        }
    }

    #[test]
    fn the_likelihood_is_maximal_at_the_true_lanes_of_a_synthetic_histogram() {
        let cam = default_camera(320, 240).unwrap();
        let config = AdachiConfig::default();
        let mut votes = Votes::new(&cam, &config).unwrap();
        let mut likelihood = Likelihood::new(&config);
        // q = 0.1 and w = 3.6 put every boundary's edge on a bin centre.
        let (kq, iw) = (4, 12);
        let (q, w) = (grid_q(kq), grid_w(iw));
        for truth in 0..4 {
            synthetic(
                &mut votes,
                truth,
                q,
                w,
                config.marking_width_m,
                truth as u64 + 1,
            );
            likelihood.prepare(&votes);
            // The best (q, w) of each model over q in [-w/2, w/2), w in 3.0..4.2.
            let mut best = [(f64::NEG_INFINITY, 0, 0); 4];
            for (model, b) in best.iter_mut().enumerate() {
                for i in 0..=24 {
                    for k in -72..72 {
                        if grid_q(k) < -grid_w(i) / 2.0 || grid_q(k) >= grid_w(i) / 2.0 {
                            continue;
                        }
                        let ll = likelihood.log_likelihood(&votes, model, grid_q(k), grid_w(i));
                        if ll > b.0 {
                            *b = (ll, k, i);
                        }
                    }
                }
            }
            let at_truth = likelihood.log_likelihood(&votes, truth, q, w);
            assert_eq!(
                (best[truth].1, best[truth].2),
                (kq, iw),
                "model {}: best q {} w {}",
                truth + 1,
                grid_q(best[truth].1),
                grid_w(best[truth].2)
            );
            assert_eq!(best[truth].0, at_truth);
            for (model, b) in best.iter().enumerate() {
                if model != truth {
                    assert!(
                        b.0 < at_truth - 1.0,
                        "truth r = {}: r = {} reaches {} against {at_truth}",
                        truth + 1,
                        model + 1,
                        b.0
                    );
                }
            }
        }
    }
}
