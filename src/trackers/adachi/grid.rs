//! The paper's comparison baseline (Sec. 4.2.3, Fig. 8): per-frame maximum likelihood by grid
//! search over (r, q, w) with the same likelihood, no temporal filtering. q runs over
//! [-w/2, w/2) in steps of the bin size, w over the accepted range in steps of `w_step`.

use super::likelihood::Likelihood;
use super::votes::Votes;

/// The maximum-likelihood (model 1..4, q, w) and its log-likelihood.
pub fn grid_search(
    votes: &Votes,
    likelihood: &Likelihood,
    width_range: [f64; 2],
    w_step: f64,
) -> (usize, f64, f64, f64) {
    let mut best = (1, 0.0, width_range[0], f64::NEG_INFINITY);
    let q_step = votes.bin_m();
    let mut w = width_range[0];
    while w <= width_range[1] + 1e-9 {
        let mut q = -w / 2.0;
        while q < w / 2.0 {
            for model in 0..4 {
                let ll = likelihood.log_likelihood(votes, model, q, w);
                if ll > best.3 {
                    best = (model + 1, q, w, ll);
                }
            }
            q += q_step;
        }
        w += w_step;
    }
    best
}
