//! `lane_shape: "curved"` against the paper's straight lanes on drawn synthetic roads.

use super::AdachiTracker;
use crate::eval::synthetic::evaluate;
use crate::lane::LaneEstimate;
use crate::synth::{default_camera, draw_scenario, Eye, FamilyMember};
use crate::trackers::fresh_roads::describe;
use crate::trackers::{Tracker, TrackerConfig};

const FRAMES: u32 = 200;

/// Member `seed` of the `s-curve` family (arcs of radius 250-500 m) with its curvatures times
/// `tighter` (2.5: radius 100-200 m, an urban bend like Caltech's cordova1 frames 210-217).
fn s_curve(seed: u64, tighter: f64) -> FamilyMember {
    let mut m = draw_scenario("s-curve", seed).unwrap();
    for s in &mut m.config.road.segments {
        s.curvature *= tighter;
        s.curvature_rate *= tighter;
    }
    m
}

/// (truth, estimate) of the first `frames` frames of `member` (320x240, its own camera) with
/// `lane_shape` (tracker seed = the member's seed).
fn run(member: &FamilyMember, frames: u32, lane_shape: &str) -> Vec<(LaneEstimate, LaneEstimate)> {
    eprintln!("{} ({lane_shape})", describe(member));
    let mut scene = member.scene(320, 240).unwrap();
    let cam = serde_json::to_string(&scene.camera().to_file()).unwrap();
    let config = TrackerConfig::from_json_str(&format!(
        r#"{{"camera": {cam}, "particles": 400, "seed": {}, "lane_shape": "{lane_shape}"}}"#,
        member.seed
    ))
    .unwrap();
    let mut tracker = AdachiTracker::new(&config).unwrap();
    let mut rgba = vec![0; 320 * 240 * 4];
    (0..frames.min(member.config.frames))
        .map(|f| {
            scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            (
                crate::trackers::scene_truth(&scene, f),
                tracker.step(&rgba, 320, 240).unwrap(),
            )
        })
        .collect()
}

/// (ego boundary accuracy, valid share, curvature sign right on the frames bending more than
/// 1/1000 m) over the runs. The ego lane's two boundaries only: which neighbouring lanes the
/// model shows is another question (`adachi_fresh_road_tests::tracks_straight_highways`), and
/// where it misses a neighbour the accuracy over all boundaries falls whatever the shape.
fn figures(runs: &[Vec<(LaneEstimate, LaneEstimate)>]) -> (f64, f64, f64) {
    use crate::lane::Role;
    let (mut acc, mut valid, mut n, mut bent, mut sign) = (0.0, 0, 0, 0, 0);
    for run in runs {
        let gt: Vec<LaneEstimate> = run.iter().map(|(t, _)| t.clone()).collect();
        let preds: Vec<Option<&LaneEstimate>> = run.iter().map(|(_, e)| Some(e)).collect();
        let report = evaluate(&gt, &preds).unwrap();
        let (correct, total) = report
            .boundaries
            .per_role
            .iter()
            .filter(|r| matches!(r.role, Role::EgoLeft | Role::EgoRight))
            .fold((0, 0), |(c, t), r| (c + r.correct, t + r.gt));
        acc += correct as f64 / total.max(1) as f64;
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

/// Measured on the reference roads (2026-11-25, 320x240, 400 particles, scene and tracker
/// seeds 1-2, 200 frames): on the 120 m s-curve the paper's straight lanes scored a boundary
/// accuracy of 0.63 and were valid in 78 % of the frames, the curved ones 0.999 and 100 %, with
/// the bend's direction right in 98 % of the bent frames; on the straight highway (100
/// frames) both 1.0 and 100 %. Now on drawn members, scene (and tracker) seeds 1-2, each its
/// own road and camera: `s-curve` tightened 2.5 times (radius 100-200 m) and
/// `highway-straight`, scored on the ego lane's boundaries. Thresholds: curved 0.95 / 95 % /
/// 90 % on the bend, above the paper's straight lanes, and 0.98 / 98 % on the straight road.
/// When written: curved 1.000 / 100 % / 99 % on the bends, the straight lanes 1.000 / 100 %
/// (seed 1) and 0.83 / 83 % (seed 2), and 1.000 / 100 % for both on the straight roads. (The
/// reference road's straight-lane figure, below 0.8, is not a property of the paper's model
/// on every tight bend: seed 1's, seen by a camera 1.18 m high, it follows.)
#[test]
fn curved_lanes_follow_bends_the_straight_model_cannot() {
    let both = |member: &dyn Fn(u64) -> FamilyMember, frames| {
        let runs = |shape| {
            (1..=2)
                .map(|s| {
                    let r = run(&member(s), frames, shape);
                    eprintln!("  {:.3?}", figures(std::slice::from_ref(&r)));
                    r
                })
                .collect::<Vec<_>>()
        };
        (figures(&runs("straight")), figures(&runs("curved")))
    };
    let (straight, curved) = both(&|s| s_curve(s, 2.5), FRAMES);
    let (flat_straight, flat_curved) =
        both(&|s| draw_scenario("highway-straight", s).unwrap(), 100);
    let all = format!(
        "(accuracy, valid, bend sign) tightened s-curves: straight {straight:.3?}, curved \
         {curved:.3?}; straight roads: straight {flat_straight:.3?}, curved {flat_curved:.3?}"
    );
    eprintln!("{all}");
    assert!(
        curved.0 >= 0.95 && curved.1 >= 0.95 && curved.2 >= 0.9 && curved.0 > straight.0,
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
