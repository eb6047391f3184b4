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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::default_camera;
    use crate::trackers::adachi::config::AdachiConfig;

    #[test]
    fn the_grid_keeps_to_its_steps_and_bad_steps_do_not_hang() {
        let config = AdachiConfig::default();
        let mut votes = Votes::new(&default_camera(320, 240).unwrap(), &config).unwrap();
        // Left edges of boundaries at q = 0.12, w = 3.6 (eq. 3), 30 votes each.
        for rho in [-1.68, 1.92, -5.28, 5.52] {
            let j = votes.bin_of(rho - config.marking_width_m / 2.0);
            votes.histogram[j] = 30.0;
        }
        let mut likelihood = Likelihood::new(&config);
        likelihood.prepare(&votes);
        for (q_step, w_step) in [
            (0.05, 0.02),
            (0.005, 0.02),
            (0.0, f64::NAN),
            (f64::NAN, -1.0),
        ] {
            let (r, q, w, ll) = grid_search(&votes, &likelihood, [3.6, 3.6], q_step, w_step);
            let step = if q_step >= 1e-3 { q_step } else { 1e-3 };
            let k = (q + w / 2.0) / step;
            assert!((k - k.round()).abs() < 1e-6, "q {q} off the {step} m grid");
            assert!(r == 4 && w == 3.6 && ll.is_finite(), "r {r} w {w} ll {ll}");
            // The votes are binned at 5 cm: q within a bin of the truth.
            assert!((q - 0.12).abs() <= 0.05, "q {q} with step {q_step}");
        }
    }
}
