//! `lane_shape: "curved"` against the paper's straight lanes on seeded synthetic roads.

use super::AdachiTracker;
use crate::eval::synthetic::evaluate;
use crate::lane::LaneEstimate;
use crate::synth::{default_camera, scenario, Eye, Scene};
use crate::trackers::{Tracker, TrackerConfig};

const FRAMES: u32 = 200;

/// The `s-curve` scenario with its curvatures times `tighter` (1: 300 m radius arcs; 2.5:
/// 120 m, an urban bend like Caltech's cordova1 frames 210-217).
fn s_curve(tighter: f64) -> crate::synth::SceneConfig {
    let mut c = scenario("s-curve").unwrap();
    for s in &mut c.road.segments {
        s.curvature *= tighter;
        s.curvature_rate *= tighter;
    }
    c
}

/// (truth, estimate) of the first frames of `config` (scene seed `seed`, 320x240) with
/// `lane_shape`.
fn run(
    config: crate::synth::SceneConfig,
    frames: u32,
    seed: u64,
    lane_shape: &str,
) -> Vec<(LaneEstimate, LaneEstimate)> {
    let camera = default_camera(320, 240).unwrap();
    let mut scene = Scene::new(config, camera.clone(), seed).unwrap();
    let cam = serde_json::to_string(&camera.to_file()).unwrap();
    let config = TrackerConfig::from_json_str(&format!(
        r#"{{"camera": {cam}, "particles": 400, "seed": {seed}, "lane_shape": "{lane_shape}"}}"#
    ))
    .unwrap();
    let mut tracker = AdachiTracker::new(&config).unwrap();
    let mut rgba = vec![0; 320 * 240 * 4];
    (0..frames)
        .map(|f| {
            scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            (scene.truth(f), tracker.step(&rgba, 320, 240).unwrap())
        })
        .collect()
}

/// (boundary accuracy, valid share, curvature sign right on the frames bending more than
/// 1/1000 m) over the runs.
fn figures(runs: &[Vec<(LaneEstimate, LaneEstimate)>]) -> (f64, f64, f64) {
    let (mut acc, mut valid, mut n, mut bent, mut sign) = (0.0, 0, 0, 0, 0);
    for run in runs {
        let gt: Vec<LaneEstimate> = run.iter().map(|(t, _)| t.clone()).collect();
        let preds: Vec<Option<&LaneEstimate>> = run.iter().map(|(_, e)| Some(e)).collect();
        acc += evaluate(&gt, &preds)
            .unwrap()
            .boundaries
            .accuracy
            .unwrap_or(0.0);
        for (t, e) in run {
            n += 1;
            valid += usize::from(e.valid);
            if t.curvature_per_m.abs() > 1e-3 {
                bent += 1;
                sign += usize::from(t.curvature_per_m * e.curvature_per_m > 0.0);
            }
        }
    }
    (
        acc / runs.len() as f64,
        valid as f64 / n as f64,
        sign as f64 / bent.max(1) as f64,
    )
}

/// Measured (2026-11-25, 320x240, 400 particles, scene and tracker seeds 1-2, 200 frames):
/// on the 120 m s-curve the paper's straight lanes score a boundary accuracy of 0.63 and are
/// valid in 78 % of the frames, the curved ones 0.999 and 100 %, with the bend's direction right
/// in 98 % of the bent frames; on the straight highway (100 frames) both 1.0 and 100 %.
/// Thresholds: curved 0.95 / 95 % / 90 % on the bend and 0.98 / 98 % on the straight road; the
/// paper's model below 0.8 on the bend (the failure this option exists for).
#[test]
fn curved_lanes_follow_bends_the_straight_model_cannot() {
    let both = |config: &dyn Fn() -> crate::synth::SceneConfig, frames| {
        let runs = |shape| {
            (1..=2)
                .map(|s| run(config(), frames, s, shape))
                .collect::<Vec<_>>()
        };
        (figures(&runs("straight")), figures(&runs("curved")))
    };
    let (straight, curved) = both(&|| s_curve(2.5), FRAMES);
    let (flat_straight, flat_curved) = both(&|| scenario("highway-straight").unwrap(), 100);
    let all = format!(
        "(accuracy, valid, bend sign) 120 m s-curve: straight {straight:.3?}, curved \
         {curved:.3?}; straight road: straight {flat_straight:.3?}, curved {flat_curved:.3?}"
    );
    assert!(
        curved.0 >= 0.95 && curved.1 >= 0.95 && curved.2 >= 0.9 && straight.0 < 0.8,
        "{all}"
    );
    assert!(flat_curved.0 >= 0.98 && flat_curved.1 >= 0.98, "{all}");
}

#[test]
fn lane_shape_options_out_of_range_are_refused_by_name() {
    let cam = serde_json::to_string(&default_camera(320, 240).unwrap().to_file()).unwrap();
    for (option, value) in [
        ("lane_shape", r#""wiggly""#),
        ("max_heading_rad", "-0.1"),
        ("max_heading_rad", "1e300"),
        ("max_curvature_per_m", "0.5"),
        ("shape_gain", "0"),
        ("shape_gain", "1.5"),
    ] {
        let config = TrackerConfig::from_json_str(&format!(
            r#"{{"camera": {cam}, "lane_shape": "curved", "{option}": {value}}}"#
        ))
        .unwrap();
        let err = AdachiTracker::new(&config).unwrap_err().to_string();
        // A bad name is refused by listing the good ones; a bad number by naming its option.
        let named = err.contains(option) || err.contains("`straight` or `curved`");
        assert!(named, "{option} = {value}: {err}");
    }
}
