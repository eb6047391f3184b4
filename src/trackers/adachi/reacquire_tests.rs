//! `reacquire_near_m` (ours, beyond the paper) on adachi-mmpf: after the lane was lost,
//! markings that begin only further ahead do not make it valid again; markings near the car do
//! ([`crate::trackers::reacquire_tests`]).

use super::tests::config;
use super::AdachiTracker;
use crate::trackers::reacquire_tests::{check, Reacquiring, H, W};

impl Reacquiring for AdachiTracker {
    fn valid_on(&mut self, rgba: &[u8]) -> bool {
        self.track(rgba, W, H).unwrap().valid
    }
    fn accepted_m(&self) -> f64 {
        self.votes.near_m() + self.reacquire.limit()
    }
}

#[test]
fn markings_only_ahead_do_not_revalidate_a_lost_lane_and_near_ones_do() {
    let mut rule = AdachiTracker::new(&config(r#", "reacquire_near_m": 4.0"#)).unwrap();
    let mut paper = AdachiTracker::new(&config("")).unwrap();
    // The voting region is 6-22 m ahead: markings from 18 m on leave its far quarter.
    check(&mut rule, &mut paper, 18.0);
}
