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
        // Modulo a lane width: at a lane change the estimate may re-centre a frame late.
        let d = -s.y0 - t.lateral_offset_m;
        e[0] += (d - (d / s.w).round() * s.w).powi(2);
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

/// RMS error of the estimated lane centre `x` metres ahead (modulo a lane width).
fn centre_rmse(out: &[(LaneEstimate, LeeEstimate)], skip: usize, x: f64) -> f64 {
    let (mut se, mut n) = (0.0, 0.0);
    for (t, e) in &out[skip..] {
        let s = e.state;
        let curve = Curve::new(s.c, s.delta, LeeConfig::default().spiral_length_m);
        if let Some(tc) = t.ego_centre_at(x) {
            let d = s.centre(x, Some(&curve)) - tc;
            se += (d - (d / s.w).round() * s.w).powi(2);
            n += 1.0;
        }
    }
    (se / n).sqrt()
}

fn valid_rate(out: &[(LaneEstimate, LeeEstimate)]) -> f64 {
    out.iter().filter(|(_, e)| e.valid).count() as f64 / out.len() as f64
}

#[test]
fn tracks_a_curve_and_the_curve_stage_reduces_the_far_error() {
    let out = run("highway-curve", 200, "");
    let [o, h, w] = rmse(&out, 10);
    let far = centre_rmse(&out, 10, 30.0);
    assert!(
        o < 0.15 && h < 1.5f64.to_radians() && w < 0.1 && far < 0.35,
        "offset {o} heading {h} width {w} centre at 30 m {far}"
    );
    // Stage 1 alone (PF1, straight lanes) misses the bend 30 m ahead by more.
    let straight = centre_rmse(
        &run("highway-curve", 200, r#", "variant": "first-order""#),
        10,
        30.0,
    );
    assert!(far < straight, "CPF {far} vs PF1 {straight}");
}

#[test]
fn tracks_an_s_curve() {
    let out = run("s-curve", 200, "");
    let [o, h, w] = rmse(&out, 10);
    // The first-order model of stage 1 fits a straight line to the curved near range, which
    // biases the heading by about kappa x / 2 (1.2 deg at kappa = 1/300, x = 12 m).
    assert!(
        o < 0.25 && h < 2.5f64.to_radians() && w < 0.1,
        "offset {o} heading {h} width {w}"
    );
    assert!(valid_rate(&out) > 0.95);
}

#[test]
fn lane_changes_jump_by_a_lane_width_and_tracking_continues() {
    let out = run("lane-change", 330, "");
    let truth: Vec<usize> = out
        .iter()
        .enumerate()
        .filter(|(_, (t, _))| t.state["lane_change"] == 1.0)
        .map(|(i, _)| i)
        .collect();
    let events: Vec<(usize, i8)> = out
        .iter()
        .enumerate()
        .filter(|(_, (_, e))| e.change != 0)
        .map(|(i, (_, e))| (i, e.change))
        .collect();
    assert_eq!(truth.len(), 2);
    assert_eq!(events.len(), 2, "{events:?} vs {truth:?}");
    // First into the lane on the right, then back to the left, each within 5 frames.
    assert_eq!((events[0].1, events[1].1), (-1, 1));
    for (e, t) in events.iter().zip(&truth) {
        assert!(e.0.abs_diff(*t) <= 5, "{events:?} vs {truth:?}");
    }
    // The offset keeps following after each jump (the identity motion model lags by up to
    // 0.3 m while the car moves sideways).
    let [o, h, _] = rmse(&out, 10);
    assert!(o < 0.25 && h < 1f64.to_radians(), "offset {o} heading {h}");
}

#[test]
fn tracks_worn_markings_and_night() {
    let worn = run("worn-markings", 150, "");
    let [o, h, _] = rmse(&worn, 10);
    assert!(
        o < 0.1 && h < 1f64.to_radians(),
        "worn: offset {o} heading {h}"
    );
    let rate = valid_rate(&worn);
    assert!(rate >= 0.6, "worn: valid {rate}");
    let night = run("night", 150, "");
    let [o, h, _] = rmse(&night, 10);
    assert!(
        o < 0.1 && h < 1f64.to_radians(),
        "night: offset {o} heading {h}"
    );
}

#[test]
fn kalman_smoothing_reduces_frame_to_frame_jitter() {
    let jitter = |extra: &str| {
        let out = run("highway-straight", 80, extra);
        let d: Vec<f64> = out[10..]
            .windows(2)
            .map(|p| {
                (p[1].1.state.psi - p[1].0.heading_rad) - (p[0].1.state.psi - p[0].0.heading_rad)
            })
            .collect();
        (d.iter().map(|v| v * v).sum::<f64>() / d.len() as f64).sqrt()
    };
    let (on, off) = (jitter(""), jitter(r#", "kalman": false"#));
    assert!(on < 0.8 * off, "with Kalman {on} without {off}");
}

#[test]
fn bad_input_is_an_error_and_the_tracker_goes_on() {
    for (extra, word) in [
        (r#", "split_m": 2"#, "split_m"),
        (r#", "sigma_q": -1"#, "sigma_q"),
        (r#", "variant": "pf9""#, "variant"),
        (r#", "colour": 1"#, "unknown field"),
        (r#", "process_sd": [1, 1, 1, 1, 1, 0]"#, "process_sd"),
        (r#", "max_curvature": 1"#, "max_curvature"),
    ] {
        let err = LeeTracker::new(&config(extra)).unwrap_err().to_string();
        assert!(err.contains(word), "{extra}: {err}");
    }
    let mut t = LeeTracker::new(&config("")).unwrap();
    assert!(t.track(&[0; 16], 2, 2).is_err());
    assert!(t.track(&[0; 100], 320, 240).is_err());
    let frame = vec![90; 320 * 240 * 4];
    let e = t.track(&frame, 320, 240).unwrap();
    assert_eq!(e.candidates, 0);
    assert!(!e.valid, "no markings, no valid frame");
    assert!(e.state.w.is_finite() && e.state.y0.is_finite());
}

/// Lateral offset after 5 frames of `highway-curve` (seed 1, 320x240, 400 particles, seed 2),
/// as bits; `tests/web.rs` asserts the same value in headless Chromium.
const CROSS_TARGET_OFFSET_BITS: u64 = 0xbfac_3e05_c519_13f4;

#[test]
fn same_result_as_the_browser_build() {
    let out = run("highway-curve", 5, "");
    let o = -out[4].1.state.y0;
    let truth = out[4].0.lateral_offset_m;
    assert!((o - truth).abs() < 0.1, "offset {o} vs truth {truth}");
    assert_eq!(
        o.to_bits(),
        CROSS_TARGET_OFFSET_BITS,
        "{:#x} ({o})",
        o.to_bits()
    );
}

#[test]
fn per_step_mode_moves_the_cloud_step_by_step_and_ends_with_the_estimate() {
    let mut scene = Scene::new(
        scenario("highway-curve").unwrap(),
        default_camera(320, 240).unwrap(),
        1,
    )
    .unwrap();
    let mut rgba = vec![0; 320 * 240 * 4];
    let mut stepped: Box<dyn Tracker> = Box::new(LeeTracker::new(&config("")).unwrap());
    let mut whole = LeeTracker::new(&config("")).unwrap();
    let names = stepped.step_names();
    assert_eq!(names.len(), 7);
    assert!(stepped.advance().is_err(), "no frame in progress");
    for f in 0..3 {
        scene.render(f, Eye::Left, &mut rgba, None).unwrap();
        let expected = whole.step(&rgba, 320, 240).unwrap();
        stepped.begin_frame(&rgba, 320, 240).unwrap();
        let mut result = None;
        for k in 0..names.len() {
            assert_eq!(stepped.next_step(), Some(k));
            let before = stepped.particles();
            result = stepped.advance().unwrap();
            let after = stepped.particles();
            // After the first frame, a predict step moves the states and a weigh step changes
            // the weights (stride 8: [stage, psi, y0, w, w', c, delta, weight]).
            if f > 0 && names[k].contains("predict") {
                let stage = if k == 0 { 1.0 } else { 2.0 };
                let moved = before
                    .chunks(8)
                    .zip(after.chunks(8))
                    .filter(|(a, b)| a[0] == stage && a[1..7] != b[1..7])
                    .count();
                assert!(moved > 300, "step {k}: {moved} particles moved");
            }
            if names[k].contains("weigh") {
                assert_ne!(before, after, "step {k} changed no weight");
            }
            assert_eq!(result.is_some(), k + 1 == names.len());
        }
        assert_eq!(stepped.next_step(), None);
        assert_eq!(
            result.unwrap(),
            expected,
            "frame {f}: per-step run equals step()"
        );
    }
    // An abandoned frame: begin again and the tracker goes on.
    stepped.begin_frame(&rgba, 320, 240).unwrap();
    stepped.advance().unwrap();
    assert!(stepped.begin_frame(&[0; 8], 2, 1).is_err());
    stepped.begin_frame(&rgba, 320, 240).unwrap();
    assert_eq!(stepped.next_step(), Some(0));
}

/// The filter must find the lane within five frames of a cold start on any frame, not only on
/// frames where the cloud's random start happens to land near it. With Q alone in the start
/// iterations and no restart (`start_spread` 1, `start_fresh` 0, `lost_restart` 0) it locked
/// half a lane off, at the width limit, from 20 of these 48 starts (25 with seeds 3-4) and took
/// 20+ frames to come back; with the annealed start alone 12 (12); with the restart too, 1 (0).
#[test]
fn a_cold_start_finds_the_lane_from_almost_any_frame() {
    let camera = default_camera(640, 480).unwrap();
    let cam = serde_json::to_string(&camera.to_file()).unwrap();
    let mut rgba = vec![0; 640 * 480 * 4];
    let (mut starts, mut misses) = (0, Vec::new());
    for seed in 1..=2 {
        let config =
            TrackerConfig::from_json_str(&format!(r#"{{"camera": {cam}, "seed": {seed}}}"#))
                .unwrap();
        for name in ["highway-straight", "highway-curve"] {
            let mut scene = Scene::new(scenario(name).unwrap(), camera.clone(), 1).unwrap();
            for first in (0..60).step_by(5) {
                let mut tracker = LeeTracker::new(&config).unwrap();
                let mut raw = None;
                for f in first..first + 5 {
                    scene.render(f, Eye::Left, &mut rgba, None).unwrap();
                    raw = Some(tracker.track(&rgba, 640, 480).unwrap());
                }
                let truth = scene.truth(first + 4);
                let e = tracker.to_lane_estimate(&raw.unwrap());
                let err = (e.lateral_offset_m - truth.lateral_offset_m).abs();
                starts += 1;
                if !(e.valid && err < 0.2 && (e.lane_width_m - truth.lane_width_m).abs() < 0.2) {
                    misses.push((seed, name, first, e.lateral_offset_m, e.lane_width_m));
                }
            }
        }
    }
    eprintln!(
        "cold starts: {} of {starts} missed: {misses:?}",
        misses.len()
    );
    assert!(
        misses.len() * 20 <= starts,
        "{} of {starts} cold starts missed: {misses:?}",
        misses.len()
    );
}
