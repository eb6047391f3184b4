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
