//! `reacquire_near_m` (ours, beyond the paper) on liu-ppf: after the lane was lost, markings
//! that begin only further ahead do not make it valid again; markings near the car do
//! ([`crate::trackers::reacquire_tests`]).

use super::tests::config;
use super::LiuTracker;
use crate::trackers::reacquire_tests::{check, Reacquiring, H, W};

impl Reacquiring for LiuTracker {
    fn valid_on(&mut self, rgba: &[u8]) -> bool {
        self.track(rgba, W, H).unwrap().valid
    }
    fn accepted_m(&self) -> f64 {
        self.config.top_view.x_min_m + self.reacquire.limit()
    }
}

#[test]
fn markings_only_ahead_do_not_revalidate_a_lost_lane_and_near_ones_do() {
    let mut rule = LiuTracker::new(&config(r#", "reacquire_near_m": 4.0"#), true).unwrap();
    let mut paper = LiuTracker::new(&config(""), true).unwrap();
    // Support is counted over the view's near half, 6-21 m: markings from 18 m on leave a
    // fifth of it.
    check(&mut rule, &mut paper, 18.0);
}
