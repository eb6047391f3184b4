//! The free-motion model of Lee et al. (eq. 20) and the initial distribution.
//!
//! x_{t+1} = A x_t + w_t with A = I ("because of the unpredictable characteristics of the
//! lane") and w_t ~ N(0, Q), Q diagonal. Stage 1 moves [psi, y0, w, w'] (eq. 18), stage 2
//! [c, delta] (eq. 19), the single-stage full-model baseline all six. States are clamped to
//! their limits. Lane changes are handled by the tracker, which re-centres the whole cloud when
//! the estimate leaves the lane ([`wrap`]).

use super::clothoid::LaneState;
use crate::filter::{InitialDistribution, MotionModel, Rng};

/// The state limits (and the support of the initial distribution).
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// Largest |psi|, rad.
    pub heading: f64,
    /// Lane widths [min, max].
    pub width: [f64; 2],
    /// Largest |w'|.
    pub width_rate: f64,
    /// c range [-s_o, max].
    pub transition: [f64; 2],
    /// Largest |delta|.
    pub curvature: f64,
}

/// y0 moved by whole lane widths into [-w/2, w/2), and the lane change that means (+1: the
/// car moved into the lane on its left, -1: right, 0: none).
pub fn wrap(y0: f64, w: f64) -> (f64, i8) {
    // A lane centre more than half a lane right of the car (y0 < -w/2): the car is in the
    // lane to the left now, and the other way round.
    if (-w / 2.0..w / 2.0).contains(&y0) {
        return (y0, 0);
    }
    let mut wrapped = (y0 + w / 2.0).rem_euclid(w) - w / 2.0;
    if wrapped >= w / 2.0 {
        // rem_euclid can round up to w for a tiny negative argument.
        wrapped -= w;
    }
    let change = if y0 < -w / 2.0 { 1 } else { -1 };
    (wrapped, change)
}

fn diffuse_first_order(s: &mut LaneState, sd: &[f64; 6], l: &Limits, rng: &mut Rng) {
    s.psi = crate::math::clamp(s.psi + rng.gaussian(0.0, sd[0]), -l.heading, l.heading);
    s.w = crate::math::clamp(s.w + rng.gaussian(0.0, sd[2]), l.width[0], l.width[1]);
    s.w1 = crate::math::clamp(s.w1 + rng.gaussian(0.0, sd[3]), -l.width_rate, l.width_rate);
    s.y0 += rng.gaussian(0.0, sd[1]);
}

fn diffuse_curve(s: &mut LaneState, sd: &[f64; 6], l: &Limits, rng: &mut Rng) {
    s.c = crate::math::clamp(
        s.c + rng.gaussian(0.0, sd[4]),
        l.transition[0],
        l.transition[1],
    );
    s.delta = crate::math::clamp(
        s.delta + rng.gaussian(0.0, sd[5]),
        -l.curvature,
        l.curvature,
    );
}

/// Which states a motion model moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// Stage 1: psi, y0, w, w'.
    FirstOrder,
    /// Stage 2: c, delta.
    Curve,
    /// All six.
    Full,
}

/// Eq. 20 on the states of `part`.
#[derive(Debug, Clone, Copy)]
pub struct Motion {
    /// Which states move.
    pub part: Part,
    /// Standard deviations of Q: psi, y0, w, w', c, delta.
    pub sd: [f64; 6],
    /// State limits.
    pub limits: Limits,
}

impl MotionModel<LaneState> for Motion {
    fn propagate(&self, s: &mut LaneState, rng: &mut Rng) {
        if self.part != Part::Curve {
            diffuse_first_order(s, &self.sd, &self.limits, rng);
        }
        if self.part != Part::FirstOrder {
            diffuse_curve(s, &self.sd, &self.limits, rng);
        }
    }
}

/// Uniform over the limits (y0 over the whole lane), except w', drawn within a tenth of its
/// limit: the near range alone cannot tell a wider lane from a narrowing one (w + w' x is
/// what it sees), so the start assumes a constant width and lets the filter find w' over time.
#[derive(Debug, Clone, Copy)]
pub struct Initial {
    /// The limits.
    pub limits: Limits,
}

impl InitialDistribution<LaneState> for Initial {
    fn sample(&self, rng: &mut Rng) -> LaneState {
        let l = &self.limits;
        let mut u = |lo: f64, hi: f64| lo + (hi - lo) * rng.uniform();
        let w = u(l.width[0], l.width[1]);
        LaneState {
            psi: u(-l.heading, l.heading),
            y0: u(-w / 2.0, w / 2.0),
            w,
            w1: u(-l.width_rate / 10.0, l.width_rate / 10.0),
            c: u(l.transition[0], l.transition[1]),
            delta: u(-l.curvature, l.curvature),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_recentres_on_the_lane_the_car_is_in() {
        assert_eq!(wrap(0.4, 3.6), (0.4, 0));
        let (y0, change) = wrap(-1.9, 3.6);
        assert!((y0 - 1.7).abs() < 1e-12 && change == 1);
        let (y0, change) = wrap(1.8, 3.6);
        assert!((y0 + 1.8).abs() < 1e-12 && change == -1);
    }

    #[test]
    fn each_stage_moves_only_its_own_states() {
        let limits = Limits {
            heading: 0.2,
            width: [2.5, 4.8],
            width_rate: 0.02,
            transition: [-60.0, 60.0],
            curvature: 0.02,
        };
        let start = LaneState {
            psi: 0.0,
            y0: 0.0,
            w: 3.6,
            w1: 0.0,
            c: 20.0,
            delta: 0.001,
        };
        let mut rng = Rng::new(3);
        let sd = [0.01, 0.1, 0.05, 0.001, 2.0, 0.001];
        for (part, first_moves, curve_moves) in [
            (Part::FirstOrder, true, false),
            (Part::Curve, false, true),
            (Part::Full, true, true),
        ] {
            let mut s = start;
            Motion { part, sd, limits }.propagate(&mut s, &mut rng);
            assert_eq!(s.psi != start.psi && s.y0 != start.y0, first_moves);
            assert_eq!(s.c != start.c && s.delta != start.delta, curve_moves);
        }
        // Limits hold.
        let mut s = start;
        let wide = Motion {
            part: Part::Full,
            sd: [10.0; 6],
            limits,
        };
        for _ in 0..100 {
            wide.propagate(&mut s, &mut rng);
            assert!(s.psi.abs() <= 0.2 && (2.5..=4.8).contains(&s.w));
            assert!((-60.0..=60.0).contains(&s.c) && s.delta.abs() <= 0.02);
        }
    }
}
