//! Lane-change events: one rule for every tracker that reports them (`lee-cpf`, `danescu-*`,
//! `adachi-mmpf`; issue 20).
//!
//! None of the papers says how a tracker decides that the car has moved into the next lane
//! (Lee et al. show the offset jumping by a lane width at each change, Fig. 10; Adachi's eq. 9
//! wraps each particle's lane position; Danescu & Nedevschi are silent). Ours: the car has
//! changed lanes when it has crossed the **centre** of one of its lane's boundaries, by more
//! than a margin: with the lane centre at y_c (road frame, y to the left, metres, relative to
//! the car) and the boundary centres at y_c + d_L and y_c - d_R,
//!
//! ```text
//! y_c < -(d_L + margin)  =>  +1: the car is in the lane on its left now
//! y_c >  (d_R + margin)  =>  -1: the car is in the lane on its right now
//! ```
//!
//! The tracker then moves its estimate (and its cloud) into the new lane, by d_L plus the new
//! lane's own half width, so that the estimate is inside the new lane at once. The rule
//! compares with the boundary's **centre**, the same point the shift is measured to (and the
//! point where the ground truth's lane index changes). `danescu-*` compared X_CW with W_0 / 2
//! (the marking's inner edge) but shifted by W_0 + the marking's width: an estimate just past
//! the inner edge landed past the other inner edge after the shift, and the event fired back
//! and forth on every frame until the car was clear of the marking (`lane-change` family,
//! seeds 1000-1005: 12 right and 28 spurious events before, 12 and 2 after).
//!
//! The margin is a hysteresis: after a change the estimate sits `margin` inside the new lane.
//! [`MARGIN_M`] (0, `lee-cpf` and `danescu-*`) changes where the truth does; a margin delays
//! each change by margin / lateral speed (0.1 m: 2-3 frames, which cost `lee-cpf` 34 -> 45 cm
//! of offset RMSE on `lane-change` seeds 1000-1005 with the same events). `adachi-mmpf` keeps
//! its 0.1 m ([`super::adachi`]): its estimate of q comes from per-particle wraps (eq. 9) and is
//! noisy at the seam.
//!
//! Each tracker keeps what it moves (Lee: stage 1's y0 by whole lane widths; Danescu: X_CW by
//! W_0 plus the crossed marking's width, the crossed marking becoming the new near one;
//! Adachi: its lane index over the unwrapped q of eq. 9) and reports the event in its state
//! (`lee.change`, `danescu.change`, `adachi.change`: +1 left, -1 right, 0 none).

/// The margin of `lee-cpf` and `danescu-*`, metres: none, the change happens where the car
/// crosses the boundary's centre.
pub const MARGIN_M: f64 = 0.0;

/// The car's lane as a tracker estimates it, in the road frame (y to the left, metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EgoLane {
    /// Lateral position of the lane centre relative to the car, positive to the left.
    pub centre_left_m: f64,
    /// From the lane centre to the centre of the left boundary, metres (positive).
    pub to_left_m: f64,
    /// From the lane centre to the centre of the right boundary, metres (positive).
    pub to_right_m: f64,
}

impl EgoLane {
    /// A lane whose two boundary centres are `width_m` apart, the centre at `centre_left_m`.
    pub fn symmetric(centre_left_m: f64, width_m: f64) -> Self {
        Self {
            centre_left_m,
            to_left_m: width_m / 2.0,
            to_right_m: width_m / 2.0,
        }
    }

    /// The distance between the two boundary centres, metres.
    pub fn width_m(&self) -> f64 {
        self.to_left_m + self.to_right_m
    }

    /// The lane change this estimate shows with hysteresis `margin_m` (see the module docs):
    /// +1 into the lane on the left, -1 into the lane on the right, 0 none (also for a
    /// non-finite estimate).
    pub fn change(&self, margin_m: f64) -> i8 {
        if self.centre_left_m < -(self.to_left_m + margin_m) {
            1
        } else if self.centre_left_m > self.to_right_m + margin_m {
            -1
        } else {
            0
        }
    }
}

/// The lane change an output shows from one frame to the next when its lane centre jumps by
/// more than half a lane `width_m` without the rule having fired (a tracker whose estimate can
/// switch to another hypothesis, as an MBSAS cluster does): +1 when the centre jumped to the
/// left (the car is in the lane on its left now), -1 to the right, 0 otherwise. This is the
/// event `eval::lane_changes` reads from any output.
pub fn jump(previous_centre_left_m: f64, centre_left_m: f64, width_m: f64) -> i8 {
    let d = centre_left_m - previous_centre_left_m;
    if d > width_m / 2.0 {
        1
    } else if d < -width_m / 2.0 {
        -1
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_change_needs_the_boundary_centre_crossed_by_the_margin() {
        let lane = |c| EgoLane::symmetric(c, 3.6);
        assert_eq!(lane(0.0).change(0.1), 0);
        assert_eq!(lane(-1.85).change(0.1), 0); // past the centre, within the margin
        assert_eq!(lane(-1.95).change(0.1), 1); // the lane centre is right: moved left
        assert_eq!(lane(1.95).change(0.1), -1);
        assert_eq!(lane(1.85).change(MARGIN_M), -1);
        assert_eq!(lane(1.79).change(MARGIN_M), 0);
        assert_eq!(lane(f64::NAN).change(MARGIN_M), 0);
        // Asymmetric: a wide left marking puts its centre further out.
        let wide = EgoLane {
            centre_left_m: -1.8,
            to_left_m: 1.9,
            to_right_m: 1.7,
        };
        assert_eq!(wide.change(0.0), 0);
    }

    #[test]
    fn a_jump_of_more_than_half_a_lane_is_a_change() {
        assert_eq!(jump(0.1, 0.2, 3.6), 0);
        assert_eq!(jump(0.1, 2.0, 3.6), 1); // the centre moved left: the car's lane is left
        assert_eq!(jump(0.1, -1.9, 3.6), -1);
        assert_eq!(jump(f64::NAN, 1.0, 3.6), 0);
        assert_eq!(EgoLane::symmetric(0.0, 3.6).width_m(), 3.6);
    }

    /// After a change and its shift by (the crossed boundary's distance + the new lane's half
    /// width) the estimate is inside the new lane by the margin: one change, not a flip-flop.
    #[test]
    fn the_shifted_estimate_does_not_change_back() {
        for margin in [MARGIN_M, 0.1] {
            for &c in &[-1.91, -2.0, -2.3] {
                let lane = EgoLane::symmetric(c, 3.6);
                assert_eq!(lane.change(margin), 1);
                let moved = EgoLane::symmetric(c + 3.6, 3.6);
                assert_eq!(moved.change(margin), 0, "{c}");
            }
        }
    }
}
