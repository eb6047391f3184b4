//! Start-up lock-in and recovery (see [`super::pairs`]): the start from the first frame's vote
//! pairs (default) against the uniform start we had (`start_pair_share` 0), and recovery after
//! the `occlusion` blackout with `vote_pair_share` (ours, beyond the paper) against the paper's
//! filter.

use super::*;
use crate::trackers::fresh_roads::after_blackout;

/// H_j of Udacity `project_video` frame 1 (1280x720, the demo camera
/// `www/clips/udacity-1280x720.camera.json`, default options) as (bin, votes), 501 votes: the
/// guard rail's foot at rho -4.2 m (bins 72-80, 140 votes), the yellow line's left edge at -1.55
/// (125-130, 163), the ego lane's dashes at 2.12 (200-204, 71) and the next dashes at 5.68
/// (271-277, 89). The lane: q = 0.33 m, w = 3.7 m, a lane on the right (model 3), 70
/// log-units above the trap the uniform start fell into: model 2 at w = 2.64 m on the rail and
/// the yellow line, its right boundary on bare road (see [`super::pairs`]).
const PROJECT_VIDEO_FRAME_1: [(usize, f64); 44] = [
    (65, 1.0),
    (67, 1.0),
    (69, 1.0),
    (72, 3.0),
    (73, 11.0),
    (74, 24.0),
    (75, 21.0),
    (76, 21.0),
    (77, 23.0),
    (78, 17.0),
    (79, 20.0),
    (80, 1.0),
    (83, 1.0),
    (84, 3.0),
    (89, 1.0),
    (91, 1.0),
    (98, 1.0),
    (99, 1.0),
    (109, 1.0),
    (120, 1.0),
    (121, 11.0),
    (122, 1.0),
    (125, 4.0),
    (126, 11.0),
    (127, 11.0),
    (128, 36.0),
    (129, 63.0),
    (130, 38.0),
    (132, 3.0),
    (133, 2.0),
    (134, 3.0),
    (143, 3.0),
    (199, 1.0),
    (200, 2.0),
    (201, 8.0),
    (202, 47.0),
    (203, 10.0),
    (204, 4.0),
    (271, 2.0),
    (272, 27.0),
    (273, 41.0),
    (274, 11.0),
    (276, 5.0),
    (277, 3.0),
];

fn udacity_tracker(seed: u64, options: &str) -> AdachiTracker {
    let cam = include_str!("../../../www/clips/udacity-1280x720.camera.json");
    AdachiTracker::new(
        &TrackerConfig::from_json_str(&format!(r#"{{"camera": {cam}, "seed": {seed} {options}}}"#))
            .unwrap(),
    )
    .unwrap()
}

/// The first estimate of a cold start on [`PROJECT_VIDEO_FRAME_1`].
fn cold_start(seed: u64, options: &str) -> AdachiEstimate {
    let mut t = udacity_tracker(seed, options);
    t.step_frame(|t| {
        t.votes.histogram.fill(0.0);
        for (j, n) in PROJECT_VIDEO_FRAME_1 {
            t.votes.histogram[j] += n;
        }
        t.frame_votes = 501;
        t.votes_ready(now());
        Ok(())
    })
    .unwrap()
}

/// Share of tracker seeds 1-24 whose cold start on [`PROJECT_VIDEO_FRAME_1`] gives the lane
/// (model 3, q within 0.1 m of 0.33, w within 0.1 m of 3.7, valid).
fn cold_starts_right(options: &str) -> f64 {
    let right = (1..=24)
        .map(|seed| cold_start(seed, options))
        .filter(|e| e.valid && e.r == 3 && (e.q - 0.33).abs() < 0.1 && (e.w - 3.7).abs() < 0.1)
        .count();
    right as f64 / 24.0
}

/// Measured 2026-11-26: the start from the vote pairs (default) right from 24 of 24 seeds, the
/// uniform start we had 18 of 24 (the rest on a false mode).
#[test]
fn a_cold_start_finds_the_lane_beside_the_guard_rail() {
    let pairs = cold_starts_right("");
    let uniform = cold_starts_right(r#", "start_pair_share": 0"#);
    eprintln!("pairs {pairs} uniform {uniform}");
    assert!(
        pairs == 1.0,
        "start from the vote pairs: {pairs} (uniform start {uniform})"
    );
    // The frame is a trap for the uniform start: the test measures something.
    assert!(uniform < 0.9, "uniform start {uniform}");
}

/// `occlusion` blacks the camera out for 1 s (frames 150-179). Measured 2026-11-26 (scene
/// seed 1, 300 particles, boundary accuracy / valid share over frames 190-229): the paper's
/// filter 0.0 / 0.0 with tracker seeds 1, 2, 3, 5 and 6, 0.91 / 0.95 with seed 4 (its cloud,
/// spread over q and w by the blackout's random walk, settles on a false mode and never leaves
/// it); with `vote_pair_share` 0.05, 1.0 / 1.0 with all six.
#[test]
fn vote_pairs_recover_after_the_blackout() {
    let paper = after_blackout(ID, "", 1, 1);
    assert!(paper.0 < 0.5, "the paper's filter: {paper:?}");
    for seed in 1..=3 {
        let (accuracy, valid) = after_blackout(ID, r#", "vote_pair_share": 0.05"#, 1, seed);
        assert!(
            accuracy >= 0.95 && valid >= 0.95,
            "seed {seed}: accuracy {accuracy}, valid {valid} (paper {paper:?})"
        );
    }
}
