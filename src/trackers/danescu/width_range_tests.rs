//! danescu-mono's `real-roads` width limit (`width_range_m` [2.2, 4.5],
//! [`crate::trackers::presets`]) on the shared Caltech frames: after the sequence's gaps the
//! filter keeps a lane a lane wide.

use crate::camera::Camera;
use crate::eval::caltech::{evaluate, read_labels};
use crate::image::read_rgba;
use crate::trackers::paint_output_tests::real_roads_tracker_with;
use serde_json::json;
use std::path::{Path, PathBuf};

/// The last frame run: the second after a gap in the sequence (117 -> 123 -> 128).
const LAST: &str = "f00128.png";

/// danescu-mono `real-roads` with `width_range_m` set to `range`, tracker seed `seed`, through
/// Caltech cordova1's frames up to [`LAST`]: each frame's ego lanes matched by Aly's rule.
fn matched_ego_lanes(dir: &Path, range: [f64; 2], seed: u64) -> Vec<(String, usize)> {
    let labels = read_labels(&dir.join("labels.json")).unwrap();
    let camera = Camera::load(&dir.join("camera.json")).unwrap();
    let mut tracker = real_roads_tracker_with(
        "danescu-mono",
        &camera,
        &[("width_range_m", json!(range)), ("seed", seed.into())],
    );
    let end = labels.frames.iter().position(|f| f.frame == LAST).unwrap() + 1;
    let mut labels = labels;
    labels.frames.truncate(end);
    let estimates: Vec<_> = labels
        .frames
        .iter()
        .map(|f| {
            let frame = read_rgba(&dir.join("frames").join(&f.frame)).unwrap();
            tracker
                .step(&frame.data, frame.width, frame.height)
                .unwrap()
        })
        .collect();
    let preds: Vec<_> = estimates.iter().map(Some).collect();
    let report = evaluate(&labels, &preds, None).unwrap();
    report
        .frames
        .iter()
        .map(|f| (f.frame.clone(), f.ego_lanes.matched))
        .collect()
}

/// Frames 123 and 128 follow gaps of 6 and 5 frames of the clip. With the default's 5.0 m the cloud
/// jumped there to pairs 4.8-5.5 m wide (the kerb, a farther line; widths as reported) on tracker
/// seeds 1-5, a boundary or two off the labels; with 4.5 m both frames match on seeds 1-3 (measured
/// 2026-12-01 over the whole sequence: 128 on seeds 1-4, 123 on all five). Thresholds: [`LAST`]
/// matched on both sides on each seed with the limit, and not on both without it; the frames
/// before the first gap matched as well with it as without.
#[test]
fn after_a_gap_in_caltechs_sequence_the_lane_stays_one_lane_wide() {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data"))
        .join("caltech-cordova1");
    if !dir.exists() {
        println!("note: {} is absent; skipping this test", dir.display());
        return;
    }
    for seed in 1..=3 {
        let with = matched_ego_lanes(&dir, [2.2, 4.5], seed);
        let without = matched_ego_lanes(&dir, [2.2, 5.0], seed);
        let last = |run: &[(String, usize)]| run.last().unwrap().1;
        assert_eq!(last(&with), 2, "seed {seed}: {with:?}");
        assert!(last(&without) < 2, "seed {seed}: {without:?}");
        let before_gap = |run: &[(String, usize)]| -> usize {
            run.iter()
                .take_while(|(f, _)| f.as_str() <= "f00117.png")
                .map(|(_, m)| m)
                .sum()
        };
        assert!(
            before_gap(&with) >= before_gap(&without),
            "seed {seed}: {with:?} against {without:?}"
        );
    }
}
