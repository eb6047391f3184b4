//! adachi-mmpf on drawn members of the scenario families (issue 20): each member its own road
//! and camera, the camera given to the tracker. (Declared in `trackers/mod.rs`, beside the
//! reference-road tests in `adachi/mod.rs`; it uses only the tracker's public interface.)

use super::adachi::{AdachiEstimate, AdachiTracker};
use super::fresh_roads::{changes_match, config_for, describe, lane_change_events, member_scene};
use crate::lane::LaneEstimate;
use crate::synth::Eye;

/// Runs the tracker (400 particles, seed 2) over the first `frames` frames of member `seed` of
/// the family `name` (all of them when it has fewer) at 320x240; (truth, estimate) pairs.
fn run_member(name: &str, seed: u64, frames: u32) -> Vec<(LaneEstimate, AdachiEstimate)> {
    let (member, mut scene) = member_scene(name, seed, 320, 240, frames);
    eprintln!("{}", describe(&member));
    let config = config_for(&scene, r#", "particles": 400, "seed": 2"#);
    let mut tracker = AdachiTracker::new(&config).unwrap();
    let mut rgba = vec![0; 320 * 240 * 4];
    (0..member.config.frames)
        .map(|f| {
            scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            (
                crate::trackers::scene_truth(&scene, f),
                tracker.track(&rgba, 320, 240).unwrap(),
            )
        })
        .collect()
}

/// Drawn `highway-straight` members (2-4 lanes of 2.8-4.2 m, the car in any lane), scene seeds
/// 1-4, the first 60 frames at 320x240: RMSE of q and w against the truth on every member; the
/// model r (which neighbouring lanes exist) right in more than 95 % of the frames on at least 2
/// of the 4. Not on seed 1 (2 lanes of 4.08 m, the car in the left one, a camera 1.18 m high
/// with a 76 deg field of view: model 1, no neighbour, instead of 3 on every frame; the right
/// neighbour's solid outer line, 6.1 m out, crosses the image nearly flat from 1.18 m high and
/// its horizontal Sobel response stays under the threshold: `edge_response: "gradient"`
/// (ours) finds it, see `edge_response_tests`) nor seed 3 (4 lanes, the car in the leftmost, a
/// double yellow left edge: model 1 on 33 of 60 frames), RESULTS' known failures on fresh
/// roads.
#[test]
fn tracks_straight_highways() {
    let (mut bad, mut model_right) = (Vec::new(), 0);
    for seed in 1..=4 {
        let out = run_member("highway-straight", seed, 60);
        let n = out.len() as f64;
        let rms = |f: &dyn Fn(&LaneEstimate, &AdachiEstimate) -> f64| {
            (out.iter().map(|(t, e)| f(t, e).powi(2)).sum::<f64>() / n).sqrt()
        };
        let q = rms(&|t, e| e.q - t.state["adachi.q"]);
        let w = rms(&|t, e| e.w - t.lane_width_m);
        let model = out
            .iter()
            .filter(|(t, e)| e.r as f64 == t.state["adachi.r"])
            .count() as f64
            / n;
        let mut chosen = [0; 5];
        let mut true_r = [0; 5];
        for (t, e) in &out {
            chosen[e.r] += 1;
            true_r[t.state["adachi.r"] as usize] += 1;
        }
        let line = format!(
            "seed {seed}: q {q:.3} w {w:.3} model {model:.3} (frames with r = 1..4: true {:?}, \
             estimated {:?})",
            &true_r[1..],
            &chosen[1..]
        );
        eprintln!("{line}");
        if !(q < 0.15 && w < 0.05) {
            bad.push(line);
        }
        model_right += usize::from(model > 0.95);
    }
    assert!(bad.is_empty(), "{bad:?}");
    assert!(model_right >= 2, "model right on {model_right} of 4");
}

/// Drawn `lane-change` members (two changes each, drawn timing and direction), scene seeds 1-3,
/// every frame at 320x240: each change reported once, in its direction (+1 left), within 15
/// frames (0.5 s) of the truth, on at least 2 of the 3 members. The events come 5-10 frames
/// early (the paper's lanes have no heading: the car crosses the boundary at an angle). Not on
/// seed 1 (3 lanes of 3.10 m, a camera 1.18 m high): the second change is reported 27 frames
/// late (RESULTS, the known failures on fresh roads).
#[test]
fn lane_changes_are_reported_once_in_the_right_direction() {
    let mut bad = Vec::new();
    for seed in 1..=3 {
        let out = run_member("lane-change", seed, u32::MAX);
        let gt: Vec<LaneEstimate> = out.iter().map(|(t, _)| t.clone()).collect();
        let (truth, events) = lane_change_events(&gt, out.iter().map(|(_, e)| e.change));
        let line = format!("seed {seed}: events {events:?} truth {truth:?}");
        eprintln!("{line}");
        assert_eq!(truth.len(), 2, "{line}");
        if !changes_match(&events, &truth, 15) {
            bad.push(line);
        }
    }
    assert!(bad.len() <= 1, "{bad:?}");
}
