//! The paper's comparison baseline (Sec. 4.2.3, Fig. 8): per-frame maximum likelihood by grid
//! search over (r, q, w) with the same likelihood, no temporal filtering. q runs over
//! [-w/2, w/2) in steps of `q_step`, w over the accepted range in steps of `w_step`. The paper
//! does not give its grid; a q step of the bin size quantises q to the bin, so a finer step
//! tells what of the baseline's jitter is the grid's and what is the data's.

use super::likelihood::Likelihood;
use super::votes::Votes;

/// The maximum-likelihood (model 1..4, q, w) and its log-likelihood.
pub fn grid_search(
    votes: &Votes,
    likelihood: &Likelihood,
    width_range: [f64; 2],
    q_step: f64,
    w_step: f64,
) -> (usize, f64, f64, f64) {
    let mut best = (1, 0.0, width_range[0], f64::NEG_INFINITY);
    // Steps below 1 mm (or not finite) are taken as 1 mm: bad input must not hang the search.
    let q_step = if q_step >= 1e-3 { q_step } else { 1e-3 };
    let w_step = if w_step >= 1e-3 { w_step } else { 1e-3 };
    let (w_lo, w_hi) = (width_range[0], width_range[1]);
    if !(w_lo.is_finite() && w_hi.is_finite()) {
        return best;
    }
    let widths = ((w_hi - w_lo) / w_step + 1e-9).floor().max(0.0) as usize;
    for i in 0..=widths {
        let w = w_lo + i as f64 * w_step;
        let positions = (w / q_step).ceil() as usize;
        for k in 0..positions {
            let q = -w / 2.0 + k as f64 * q_step;
            for model in 0..4 {
                let ll = likelihood.log_likelihood(votes, model, q, w);
                if ll > best.3 {
                    best = (model + 1, q, w, ll);
                }
            }
        }
    }
    best
}
