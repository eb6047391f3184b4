//! The motion model of Adachi et al. (eqs. 7-9) and the initial distribution.
//!
//! w_k = w_{k-1} + delta_w, q'_k = q_{k-1} + delta_q (Gaussian, sd sigma_w and sigma_q), and q
//! is kept in [-w/2, w/2): q = q' + w when q' < -w/2 (the lane centre is now more than half a
//! lane to the left of the car: the car has moved into the lane on the right), q = q' - w when
//! q' >= w/2 (a change to the left). The wrap is recorded on the particle as a lane-change
//! event, with the sign convention of every tracker's `*.change`: +1 to the left, -1 to the
//! right. The model index switches by the Markov chain of Table 1 before this (see
//! [`crate::filter::SwitchingMotion`]).

use crate::filter::{InitialDistribution, ModelMotion, Regime, Rng};

/// The continuous state of a particle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lane {
    /// Lane position q on the rho axis (the running lane's centre relative to the car, positive
    /// right), metres.
    pub q: f64,
    /// Lane width w, metres.
    pub w: f64,
    /// Lane change in the last prediction: +1 to the left, -1 to the right, 0 none.
    pub change: i8,
}

/// Eqs. 7-9.
#[derive(Debug, Clone, Copy)]
pub struct Motion {
    /// sigma_q.
    pub sigma_q: f64,
    /// sigma_w.
    pub sigma_w: f64,
    /// Accepted widths.
    pub width_range: [f64; 2],
}

/// Eq. 9: wraps q' into [-w/2, w/2) and reports the lane change (+1 left, -1 right).
pub fn wrap(q: f64, w: f64) -> (f64, i8) {
    if q < -w / 2.0 {
        (q + w, -1)
    } else if q >= w / 2.0 {
        (q - w, 1)
    } else {
        (q, 0)
    }
}

impl ModelMotion<Lane> for Motion {
    fn propagate(&self, _model: usize, s: &mut Lane, rng: &mut Rng) {
        s.w = crate::math::clamp(
            s.w + rng.gaussian(0.0, self.sigma_w),
            self.width_range[0],
            self.width_range[1],
        );
        let q = s.q + rng.gaussian(0.0, self.sigma_q);
        let (q, change) = wrap(q, s.w);
        s.q = q;
        s.change = change;
    }
}

/// Uniform over models, widths and positions.
#[derive(Debug, Clone, Copy)]
pub struct Initial {
    /// Accepted widths.
    pub width_range: [f64; 2],
}

impl InitialDistribution<Regime<Lane>> for Initial {
    fn sample(&self, rng: &mut Rng) -> Regime<Lane> {
        let [lo, hi] = self.width_range;
        let w = lo + (hi - lo) * rng.uniform();
        Regime {
            model: rng.below(4),
            state: Lane {
                q: (rng.uniform() - 0.5) * w,
                w,
                change: 0,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_recentres_and_reports_the_direction() {
        assert_eq!(wrap(0.3, 3.6), (0.3, 0));
        let (q, c) = wrap(-1.9, 3.6);
        assert!(
            (q - 1.7).abs() < 1e-12 && c == -1,
            "moved into the right lane"
        );
        let (q, c) = wrap(1.8, 3.6);
        assert!(
            (q + 1.8).abs() < 1e-12 && c == 1,
            "moved into the left lane"
        );
    }
}
