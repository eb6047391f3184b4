//! `reacquire_near_m` (ours, beyond the papers; lee-cpf and adachi-mmpf): after the lane was
//! lost, a frame is valid again only when a marking supports one of its boundaries near the
//! car.
//!
//! The reach of a frame is how far beyond the nearest measured distance the nearest supported
//! point of either boundary lies. Markings that begin only ahead, past an unmarked crossing,
//! have a long reach; so has a road of dashed lines whose dashes on both sides leave a gap at
//! the near end. The limit after a loss is therefore the larger of `reacquire_near_m` and the
//! longest reach of the last [`REACH_FRAMES`] valid frames that saw both boundaries (a frame
//! valid on one boundary and the other's remembered support says little of the road's gaps):
//! a lane kept along a solid line (reach 0) must find a marking near again, one kept between
//! dashed lines accepts the gaps it was tracked through. A run's first lock (since the start
//! or a reset) is not held back.

use super::support_memory;

/// Valid frames whose reach sets the limit after a loss.
pub const REACH_FRAMES: usize = 30;

/// Where a run's validity stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Lock {
    /// No valid frame since the start or the last reset (lee-cpf's restart after
    /// `lost_restart` frames without support keeps the lane lost).
    Starting,
    /// The last frame was valid.
    Valid,
    /// The last frame was not valid, an earlier one was: the limit applies.
    Lost,
}

/// The rule's state: the lock and the reach of recent valid frames.
#[derive(Debug, Clone)]
pub struct Reacquire {
    near_m: f64,
    lock: Lock,
    reach: [f64; REACH_FRAMES],
    len: usize,
    next: usize,
}

impl Reacquire {
    /// The rule with limit `near_m` metres (0: off).
    pub fn new(near_m: f64) -> Self {
        Self {
            near_m,
            lock: Lock::Starting,
            reach: [0.0; REACH_FRAMES],
            len: 0,
            next: 0,
        }
    }

    /// Forgets the run: the next lock is a first lock.
    pub fn reset(&mut self) {
        self.lock = Lock::Starting;
        self.len = 0;
        self.next = 0;
    }

    /// The reach a frame may have after a loss, metres.
    pub fn limit(&self) -> f64 {
        self.reach[..self.len]
            .iter()
            .fold(self.near_m, |limit, &r| limit.max(r))
    }

    /// Whether a frame is valid: its `support` (left, right) with the `remembered` mean holds
    /// at `threshold` ([`support_memory::supported`]) and, after a loss, its nearest supported
    /// point lies at most [`Reacquire::limit`] metres beyond the nearest measured distance
    /// (`reach`). A valid frame with both sides at `threshold` joins the memory.
    pub fn valid(
        &mut self,
        support: [f64; 2],
        remembered: [f64; 2],
        threshold: f64,
        reach: f64,
    ) -> bool {
        let held = support_memory::supported(support, remembered, threshold);
        let both = support.iter().all(|&s| s >= threshold);
        self.decide(held, both, reach)
    }

    /// A frame without the ego pair: not valid (the lane is lost if it was valid).
    pub fn no_lane(&mut self) -> bool {
        self.decide(false, false, f64::INFINITY)
    }

    /// [`Reacquire::valid`] once the support is read: `held` whether it holds, `both` whether
    /// both sides reach the threshold this frame.
    fn decide(&mut self, held: bool, both: bool, reach: f64) -> bool {
        let valid =
            held && (self.near_m <= 0.0 || self.lock != Lock::Lost || reach <= self.limit());
        if valid && both && reach.is_finite() {
            self.reach[self.next] = reach;
            self.next = (self.next + 1) % REACH_FRAMES;
            self.len = (self.len + 1).min(REACH_FRAMES);
        }
        self.lock = match (valid, self.lock) {
            (true, _) => Lock::Valid,
            (false, Lock::Starting) => Lock::Starting,
            (false, _) => Lock::Lost,
        };
        valid
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lane_lost_along_a_solid_line_needs_a_near_marking_again() {
        let mut r = Reacquire::new(4.0);
        assert!(r.decide(true, true, 9.0), "the first lock is not held back");
        for _ in 0..REACH_FRAMES {
            assert!(r.decide(true, true, 0.0));
        }
        assert!(!r.decide(false, true, f64::INFINITY));
        assert!(!r.decide(true, true, 6.0), "markings from 6 m on only");
        assert!(!r.decide(true, true, 4.5));
        assert!(r.decide(true, true, 3.0));
        assert!(
            r.decide(true, true, 9.0),
            "once valid, the reach does not matter"
        );
    }

    #[test]
    fn a_lane_lost_between_dashes_accepts_the_gaps_it_was_tracked_through() {
        let mut r = Reacquire::new(4.0);
        for k in 0..12 {
            assert!(r.decide(true, true, (k % 8) as f64));
        }
        assert_eq!(r.limit(), 7.0);
        assert!(!r.decide(false, true, 10.0));
        assert!(r.decide(true, true, 6.0));
        r.reset();
        assert_eq!(r.limit(), 4.0);
    }

    #[test]
    fn a_frame_valid_on_one_boundary_does_not_widen_the_limit() {
        let mut r = Reacquire::new(4.0);
        assert!(r.decide(true, true, 0.0));
        assert!(r.decide(true, false, 7.0));
        assert_eq!(r.limit(), 4.0);
    }

    #[test]
    fn a_frame_without_the_ego_pair_loses_the_lane() {
        let mut r = Reacquire::new(4.0);
        assert!(!r.no_lane(), "no lock yet");
        assert!(r.decide(true, true, 2.0));
        assert!(!r.no_lane());
        assert!(!r.decide(true, true, 6.0), "lost: the limit applies");
        assert!(r.decide(true, true, 1.0));
    }

    #[test]
    fn off_it_changes_nothing() {
        let mut r = Reacquire::new(0.0);
        assert!(r.decide(true, true, 0.0));
        assert!(!r.decide(false, true, 0.0));
        assert!(r.decide(true, true, f64::INFINITY));
    }

    #[test]
    fn the_memory_keeps_only_the_last_frames() {
        let mut r = Reacquire::new(4.0);
        assert!(r.decide(true, true, 8.0));
        for _ in 0..REACH_FRAMES - 1 {
            assert!(r.decide(true, true, 1.0));
        }
        assert_eq!(r.limit(), 8.0);
        assert!(r.decide(true, true, 1.0));
        assert_eq!(r.limit(), 4.0, "the 8 m frame has left the memory");
    }
}
