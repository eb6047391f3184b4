//! Tests of the Lee tracker on simulator scenes.

use super::*;
use crate::synth::{default_camera, scenario, Eye, Scene};

pub(super) fn config(extra: &str) -> TrackerConfig {
    let cam = serde_json::to_string(&default_camera(320, 240).unwrap().to_file()).unwrap();
    TrackerConfig::from_json_str(&format!(
        r#"{{"camera": {cam}, "particles": 400, "seed": 2 {extra}}}"#
    ))
    .unwrap()
}

/// Runs the tracker over `frames` frames of a scenario; returns (truth, estimate) pairs.
pub(super) fn run(name: &str, frames: u32, extra: &str) -> Vec<(LaneEstimate, LeeEstimate)> {
    let mut scene = Scene::new(
        scenario(name).unwrap(),
        default_camera(320, 240).unwrap(),
        1,
    )
    .unwrap();
    let mut tracker = LeeTracker::new(&config(extra)).unwrap();
    let mut rgba = vec![0; 320 * 240 * 4];
    (0..frames)
        .map(|f| {
            scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            (scene.truth(f), tracker.track(&rgba, 320, 240).unwrap())
        })
        .collect()
}

/// RMS errors of (lateral offset m, heading rad, width m) over the frames from `skip` on.
fn rmse(out: &[(LaneEstimate, LeeEstimate)], skip: usize) -> [f64; 3] {
    let rest = &out[skip..];
    let n = rest.len() as f64;
    let mut e = [0.0; 3];
    for (t, est) in rest {
        let s = est.state;
        e[0] += (-s.y0 - t.lateral_offset_m).powi(2);
        e[1] += (s.psi - t.heading_rad).powi(2);
        e[2] += (s.w - t.lane_width_m).powi(2);
    }
    e.map(|v| (v / n).sqrt())
}

#[test]
fn the_measurement_model_peaks_at_the_true_state() {
    let mut c = scenario("highway-straight").unwrap();
    c.ego.sway_amplitude_m = 0.0;
    let mut scene = Scene::new(c, default_camera(320, 240).unwrap(), 1).unwrap();
    let mut rgba = vec![0; 320 * 240 * 4];
    scene.render(0, Eye::Left, &mut rgba, None).unwrap();
    let truth = scene.truth(0);
    let mut tracker = LeeTracker::new(&config("")).unwrap();
    tracker.track(&rgba, 320, 240).unwrap();
    let t = LaneState {
        psi: truth.heading_rad,
        y0: -truth.lateral_offset_m,
        w: truth.lane_width_m,
        ..LaneState::default()
    };
    let m = &tracker.measurement;
    let at = |s: &LaneState| m.near_log_likelihood(s, None, &tracker.map);
    let best = at(&t);
    for (name, s) in [
        (
            "y0 + 0.3",
            LaneState {
                y0: t.y0 + 0.3,
                ..t
            },
        ),
        (
            "y0 - 0.3",
            LaneState {
                y0: t.y0 - 0.3,
                ..t
            },
        ),
        ("w + 0.4", LaneState { w: t.w + 0.4, ..t }),
        ("w - 0.4", LaneState { w: t.w - 0.4, ..t }),
        (
            "psi + 0.03",
            LaneState {
                psi: t.psi + 0.03,
                ..t
            },
        ),
    ] {
        assert!(at(&s) < best, "{name}: {} vs {best}", at(&s));
    }
    // Both ego boundaries are dashed (3 m every 12 m): about a quarter of the points.
    let support = m.near_support(&t, None, &tracker.map);
    assert!(support[0] > 0.15 && support[1] > 0.15, "{support:?}");
}

#[test]
fn tracks_a_straight_highway() {
    let out = run("highway-straight", 60, "");
    let [o, h, w] = rmse(&out, 5);
    let valid = out.iter().filter(|(_, e)| e.valid).count();
    assert!(
        o < 0.1 && h < 0.01 && w < 0.1,
        "offset {o} heading {h} width {w}"
    );
    assert!(valid >= 58, "{valid} valid frames of 60");
}

