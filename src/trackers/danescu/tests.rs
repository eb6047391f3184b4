use super::*;
use crate::synth::{default_camera, scenario, Eye, Scene};

fn config(w: usize, h: usize, extra: &str) -> TrackerConfig {
    let cam = serde_json::to_string(&default_camera(w, h).unwrap().to_file()).unwrap();
    TrackerConfig::from_json_str(&format!(r#"{{"camera": {cam}, "seed": 3 {extra}}}"#)).unwrap()
}

/// Runs danescu-mono over `frames` frames of a scenario with the simulator's ego motion;
/// returns (truth, estimate) pairs.
fn run(name: &str, frames: u32, w: usize, h: usize) -> Vec<(LaneEstimate, DanescuEstimate)> {
    run_with(name, frames, w, h, "")
}

fn run_with(
    name: &str,
    frames: u32,
    w: usize,
    h: usize,
    extra: &str,
) -> Vec<(LaneEstimate, DanescuEstimate)> {
    let mut scene = Scene::new(scenario(name).unwrap(), default_camera(w, h).unwrap(), 1).unwrap();
    let mut tracker = DanescuTracker::new(&config(w, h, extra), ID_MONO).unwrap();
    let mut rgba = vec![0; w * h * 4];
    (0..frames)
        .map(|f| {
            let pose = scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            tracker
                .set_ego_motion(EgoMotion {
                    t_s: pose.t,
                    speed_mps: pose.speed,
                    yaw_rate: pose.yaw_rate,
                })
                .unwrap();
            (scene.truth(f), tracker.track(&rgba, w, h).unwrap())
        })
        .collect()
}

fn rms(v: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = v.fold((0.0, 0.0), |(s, n), x| (s + x * x, n + 1.0));
    (s / n).sqrt()
}

#[test]
fn drift_with_the_true_ego_motion_carries_the_truth_to_the_next_frame() {
    let scene = Scene::new(
        scenario("highway-curve").unwrap(),
        default_camera(320, 240).unwrap(),
        1,
    )
    .unwrap();
    let lane_of = |f: u32| {
        let t = scene.truth(f);
        let mut a = [0.0; 11];
        for (k, n) in Lane3d::NAMES.iter().enumerate() {
            a[k] = t.state[&format!("danescu.{n}")];
        }
        Lane3d::from_array(a)
    };
    let (mut moved, mut still) = (0.0f64, 0.0f64);
    for f in (0..150).step_by(10) {
        let (p0, p1) = (scene.pose(f), scene.pose(f + 1));
        let dt = p1.t - p0.t;
        let m = Motion {
            travelled_m: p0.speed * dt,
            turned_rad: p0.yaw_rate * dt,
            diffusion: [0.0; 11],
        };
        let (mut a, b) = (lane_of(f), lane_of(f + 1));
        still = still.max((a.psi - b.psi).abs());
        m.drift(&mut a);
        moved = moved.max((a.psi - b.psi).abs());
        assert!(
            (a.xcw - b.xcw).abs() < 0.01,
            "frame {f}: {} vs {}",
            a.xcw,
            b.xcw
        );
    }
    // The drift explains the change of psi (an order of magnitude below standing still).
    assert!(moved < still / 5.0, "{moved} vs {still}");
}

#[test]
fn mono_tracks_a_straight_highway() {
    let run = run("highway-straight", 90, 320, 240);
    let tail = &run[30..];
    let off = rms(tail.iter().map(|(t, e)| t.lateral_offset_m - e.lane.xcw));
    let head = rms(tail.iter().map(|(t, e)| t.heading_rad + e.lane.psi));
    let width = rms(tail.iter().map(|(t, e)| t.state["danescu.w0"] - e.lane.w0));
    let valid = tail.iter().filter(|(_, e)| e.valid).count();
    eprintln!(
        "offset {off} heading {head} width {width} valid {valid}/{}",
        tail.len()
    );
    assert!(
        off < 0.15 && head < 0.02 && width < 0.15,
        "offset {off} heading {head} width {width}"
    );
    assert!(valid * 100 >= tail.len() * 95, "{valid}");
}

#[test]
fn mono_follows_curves_and_width_changes() {
    // 640x480 (marking widths are 2-9 pixels there), frames 30.. after the burn-in.
    let curve = run("highway-curve", 120, 640, 480);
    let tail = &curve[30..];
    let off = rms(tail.iter().map(|(t, e)| t.lateral_offset_m - e.lane.xcw));
    let ch = rms(tail.iter().map(|(t, e)| t.state["danescu.ch"] - e.lane.ch));
    let valid = tail.iter().filter(|(_, e)| e.valid).count();
    assert!(off < 0.1 && ch < 0.0005, "curve: offset {off} C_H {ch}");
    assert!(valid * 100 >= tail.len() * 95, "curve: {valid} valid");
    // Frames 60-150 drive through the widening from 3.6 to 4.5 m (W_l = 0.009): W_0 follows
    // within 0.15 m and the estimated W_l has the right sign on average.
    let widening = run("width-change", 150, 640, 480);
    let part = &widening[60..150];
    let w = rms(part.iter().map(|(t, e)| t.state["danescu.w0"] - e.lane.w0));
    let wl: f64 = part.iter().map(|(_, e)| e.lane.wl).sum::<f64>() / part.len() as f64;
    assert!(w < 0.15 && wl > 0.002, "width-change: W_0 {w} W_l {wl}");
}

/// The estimate the browser test `danescu_mono_runs_in_the_browser_with_the_native_result`
/// (tests/web.rs) must reproduce bit for bit.
const CROSS_TARGET_OFFSET_BITS: u64 = 0xbfe3_42c5_da14_0de7;

#[test]
fn same_result_as_the_browser_build() {
    let mut scene = Scene::new(
        scenario("highway-curve").unwrap(),
        default_camera(320, 240).unwrap(),
        1,
    )
    .unwrap();
    let cam = serde_json::to_string(&default_camera(320, 240).unwrap().to_file()).unwrap();
    let c = TrackerConfig::from_json_str(&format!(
        r#"{{"camera": {cam}, "particles": 300, "seed": 2}}"#
    ))
    .unwrap();
    let mut tracker = super::super::create(ID_MONO, &c).unwrap();
    let mut rgba = vec![0; 320 * 240 * 4];
    let mut last = None;
    for f in 0..5 {
        scene.render(f, Eye::Left, &mut rgba, None).unwrap();
        last = Some(tracker.step(&rgba, 320, 240).unwrap());
    }
    let o = last.unwrap().lateral_offset_m;
    assert_eq!(
        o.to_bits(),
        CROSS_TARGET_OFFSET_BITS,
        "{:#x} ({o})",
        o.to_bits()
    );
}

#[test]
fn bad_input_is_an_error_and_the_tracker_goes_on() {
    for (option, name) in [
        (r#", "init_fraction": 1.0"#, "init_fraction"),
        (r#", "points": 1"#, "points"),
        (r#", "far_m": 2"#, "far_m"),
        (r#", "sigma_gradient": -3"#, "sigma_gradient"),
        (r#", "width_range_m": [4, 3]"#, "width_range_m"),
        (r#", "diffusion": [0,0,0,0,0,0,0,0,0,0,-1]"#, "diffusion"),
        (r#", "hgradient": {"gain": 0}"#, "gain"),
        (r#", "stereo": true"#, "unknown field"),
    ] {
        let e = DanescuTracker::new(&config(320, 240, option), ID_MONO)
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains(name), "{option}: {e}");
    }
    let mut t = DanescuTracker::new(&config(320, 240, ""), ID_MONO).unwrap();
    let e = t.track(&[0; 16], 320, 240).unwrap_err().to_string();
    assert!(e.contains("bytes") || e.contains("buffer"), "{e}");
    let e = t
        .track(&vec![0; 640 * 480 * 4], 640, 480)
        .unwrap_err()
        .to_string();
    assert!(e.contains("320x240"), "{e}");
    for (m, name) in [
        (
            EgoMotion {
                t_s: f64::NAN,
                ..EgoMotion::default()
            },
            "t_s",
        ),
        (
            EgoMotion {
                speed_mps: 1e4,
                ..EgoMotion::default()
            },
            "speed_mps",
        ),
        (
            EgoMotion {
                yaw_rate: f64::INFINITY,
                ..EgoMotion::default()
            },
            "yaw_rate",
        ),
    ] {
        let e = t.set_ego_motion(m).unwrap_err().to_string();
        assert!(e.contains(name), "{e}");
    }
    // A blank frame is tracked without panicking (and is not valid), then a real one works.
    let e = t.track(&vec![0; 320 * 240 * 4], 320, 240).unwrap();
    assert!(!e.valid && e.lane.to_array().iter().all(|v| v.is_finite()));
    let mut scene = Scene::new(
        scenario("highway-straight").unwrap(),
        default_camera(320, 240).unwrap(),
        1,
    )
    .unwrap();
    let mut rgba = vec![0; 320 * 240 * 4];
    for f in 0..3 {
        scene.render(f, Eye::Left, &mut rgba, None).unwrap();
        assert!(t.track(&rgba, 320, 240).is_ok());
    }
}
