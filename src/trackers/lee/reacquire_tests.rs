//! `reacquire_near_m` (ours, beyond the paper) on lee-cpf: after the lane was lost, markings
//! that begin only further ahead do not make it valid again; markings near the car do
//! ([`crate::trackers::reacquire_tests`]).

use super::tests::config;
use super::LeeTracker;
use crate::trackers::reacquire_tests::{check, Reacquiring, H, W};

impl Reacquiring for LeeTracker {
    fn valid_on(&mut self, rgba: &[u8]) -> bool {
        self.track(rgba, W, H).unwrap().valid
    }
    fn accepted_m(&self) -> f64 {
        self.measurement.near_positions()[0] + self.reacquire.limit()
    }
}

#[test]
fn markings_only_ahead_do_not_revalidate_a_lost_lane_and_near_ones_do() {
    let mut rule = LeeTracker::new(&config(r#", "reacquire_near_m": 4.0"#)).unwrap();
    let mut paper = LeeTracker::new(&config("")).unwrap();
    // The near range is 5-20 m: markings from 17 m on leave four of its points.
    check(&mut rule, &mut paper, 17.0);
}
