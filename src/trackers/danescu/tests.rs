use super::*;
use crate::synth::{default_camera, scenario, Eye, Scene};
use crate::trackers::fresh_roads::{config_for, describe, inner_line_m, member_scene};

fn config(w: usize, h: usize, extra: &str) -> TrackerConfig {
    let cam = serde_json::to_string(&default_camera(w, h).unwrap().to_file()).unwrap();
    TrackerConfig::from_json_str(&format!(r#"{{"camera": {cam}, "seed": 3 {extra}}}"#)).unwrap()
}

/// Runs danescu-mono (seed 3, its default particles) with the simulator's ego motion over the
/// first `frames` frames of member `seed` of the family `name` at `w` x `h`, given the member's
/// own camera; (truth, estimate) pairs.
fn run_member(
    name: &str,
    seed: u64,
    frames: u32,
    w: usize,
    h: usize,
) -> Vec<(LaneEstimate, DanescuEstimate)> {
    let (member, mut scene) = member_scene(name, seed, w, h, frames);
    eprintln!("{}", describe(&member));
    let mut tracker = DanescuTracker::new(&config_for(&scene, r#", "seed": 3"#), ID_MONO).unwrap();
    let mut rgba = vec![0; w * h * 4];
    (0..member.config.frames)
        .map(|f| {
            let pose = scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            tracker
                .set_ego_motion(EgoMotion {
                    t_s: pose.t,
                    speed_mps: pose.speed,
                    yaw_rate: pose.yaw_rate,
                })
                .unwrap();
            (
                crate::trackers::scene_truth(&scene, f),
                tracker.track(&rgba, w, h).unwrap(),
            )
        })
        .collect()
}

/// [`run_member`] for danescu-stereo (both cameras of the member's rig), with the estimated
/// pitch change of each frame.
fn run_stereo_member(
    name: &str,
    seed: u64,
    frames: u32,
    w: usize,
    h: usize,
) -> Vec<(LaneEstimate, DanescuEstimate, f64)> {
    let (member, mut scene) = member_scene(name, seed, w, h, frames);
    eprintln!("{}", describe(&member));
    let mut tracker =
        DanescuTracker::new(&config_for(&scene, r#", "seed": 3"#), ID_STEREO).unwrap();
    let (mut left, mut right) = (vec![0; w * h * 4], vec![0; w * h * 4]);
    (0..member.config.frames)
        .map(|f| {
            let e = track_stereo_frame(&mut scene, &mut tracker, f, &mut left, &mut right);
            let pitch = tracker.stereo.as_ref().unwrap().pitch_change();
            (crate::trackers::scene_truth(&scene, f), e, pitch)
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
    let lane_of = |f: u32| true_lane(&crate::trackers::scene_truth(&scene, f));
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

/// Drawn `highway-straight` members, scene seeds 1-3 (each its own road and camera), at
/// 640x480, where a 0.15 m marking is 2-9 pixels wide (at 320x240 the far dashes are a pixel
/// wide), frames 30-59 after the burn-in: offset, heading and W_0 RMSE, valid frames. W_0 is
/// within 0.06 m of the truth's, and the offset within 0.05 m, plus, beside a double line, the
/// distance of its inner line from the pair's centre (W_0) and half of it (the offset) (seed
/// 3: a double yellow left edge, 0.13 m; W_0 RMSE 0.140 m, offset 0.076 m: the tracker takes
/// the inner line, as lee-cpf does).
#[test]
fn mono_tracks_straight_highways() {
    let mut bad = Vec::new();
    for seed in 1..=3 {
        let run = run_member("highway-straight", seed, 60, 640, 480);
        let tail = &run[30..];
        let off = rms(tail.iter().map(|(t, e)| t.lateral_offset_m - e.lane.xcw));
        let head = rms(tail.iter().map(|(t, e)| t.heading_rad + e.lane.psi));
        let width = rms(tail.iter().map(|(t, e)| t.state["danescu.w0"] - e.lane.w0));
        let inner = inner_line_m("highway-straight", seed);
        let valid = tail.iter().filter(|(_, e)| e.valid).count();
        let line = format!(
            "seed {seed}: offset {off:.3} heading {head:.4} width {width:.3} (inner line \
             {inner:.3}) valid {valid} of {}",
            tail.len()
        );
        eprintln!("{line}");
        if !(off < 0.05 + inner / 2.0
            && head < 0.005
            && width < 0.06 + inner
            && valid * 100 >= tail.len() * 95)
        {
            bad.push(line);
        }
    }
    assert!(bad.is_empty(), "{bad:?}");
}

/// Drawn `highway-curve` members (a 30-90 m straight, an 80-160 m clothoid into a 300-1000 m
/// arc), scene seeds 1-3, and drawn `width-change` members (two linear changes to widths
/// 2.8-4.2 m, the first from 30-80 m over 50-100 m), scene seeds 1-3, at 640x480 (marking
/// widths are 2-9 pixels there), frames 30.. after the burn-in. On the curves: offset and C_H
/// RMSE, valid frames (90 frames). On the width changes (150 frames: the first change, from
/// 10-60 m ahead of the car's start, is under way from frame 30 or soon after): W_0 within
/// 0.08 m RMS on every member, and W_l frame by frame below half the error of a W_l held at 0
/// on every member and within 0.002 RMS on at least 2 of the 3. Not on seed 1 (a camera 1.18 m
/// high): 0.0051 against 0.0131 held at 0 (seeds 2 and 3: 0.0012 and 0.0018, close: over
/// their first 120 frames seed 3 is at 0.0020).
#[test]
fn mono_follows_curves_and_width_changes() {
    let (mut bad, mut close_wl) = (Vec::new(), 0);
    for seed in 1..=3 {
        let curve = run_member("highway-curve", seed, 90, 640, 480);
        let tail = &curve[30..];
        let off = rms(tail.iter().map(|(t, e)| t.lateral_offset_m - e.lane.xcw));
        let ch = rms(tail.iter().map(|(t, e)| t.state["danescu.ch"] - e.lane.ch));
        let valid = tail.iter().filter(|(_, e)| e.valid).count();
        let line = format!(
            "curve seed {seed}: offset {off:.3} C_H {ch:.5} valid {valid} of {}",
            tail.len()
        );
        eprintln!("{line}");
        if !(off < 0.05 && ch < 0.0004 && valid * 100 >= tail.len() * 95) {
            bad.push(line);
        }
        let widening = run_member("width-change", seed, 150, 640, 480);
        let part = &widening[30..];
        let w = rms(part.iter().map(|(t, e)| t.state["danescu.w0"] - e.lane.w0));
        let wl = rms(part.iter().map(|(t, e)| t.state["danescu.wl"] - e.lane.wl));
        let held = rms(part.iter().map(|(t, _)| t.state["danescu.wl"]));
        let line =
            format!("width-change seed {seed}: W_0 {w:.3} W_l {wl:.4} (held at 0: {held:.4})");
        eprintln!("{line}");
        if !(w < 0.08 && wl < held / 2.0) {
            bad.push(line);
        }
        close_wl += usize::from(wl < 0.002);
    }
    assert!(bad.is_empty(), "{bad:?}");
    assert!(close_wl >= 2, "W_l within 0.002 on {close_wl} of 3");
}

/// The estimates the browser tests `danescu_mono_runs_in_the_browser_with_the_native_result`
/// and `danescu_stereo_...` (tests/web.rs) must reproduce bit for bit.
const CROSS_TARGET_OFFSET_BITS: u64 = 0xbfe3_d196_9700_a70e;
const CROSS_TARGET_STEREO_PITCH_BITS: u64 = 0x3fb0_8834_3261_06d5;

/// The estimate after five frames of highway-curve (seed 1, 320x240) with 300 particles and
/// seed 2, with the right camera for a stereo tracker: the run the browser tests repeat.
fn five_frames(id: &'static str) -> LaneEstimate {
    let mut scene = Scene::new(
        scenario("highway-curve").unwrap(),
        default_camera(320, 240).unwrap(),
        1,
    )
    .unwrap();
    let c = TrackerConfig {
        seed: 2,
        ..config(320, 240, r#", "particles": 300"#)
    };
    let mut tracker = super::super::create(id, &c).unwrap();
    let (mut left, mut right) = (vec![0; 320 * 240 * 4], vec![0; 320 * 240 * 4]);
    let mut last = None;
    for f in 0..5 {
        scene.render(f, Eye::Left, &mut left, None).unwrap();
        if tracker.is_stereo() {
            scene.render(f, Eye::Right, &mut right, None).unwrap();
            tracker.set_right(&right, 320, 240).unwrap();
        }
        last = Some(tracker.step(&left, 320, 240).unwrap());
    }
    last.unwrap()
}

#[test]
fn stereo_same_result_as_the_browser_build() {
    let alpha = five_frames(ID_STEREO).state["danescu.alpha"];
    assert_eq!(
        alpha.to_bits(),
        CROSS_TARGET_STEREO_PITCH_BITS,
        "{:#x} ({alpha})",
        alpha.to_bits()
    );
}

#[test]
fn same_result_as_the_browser_build() {
    let o = five_frames(ID_MONO).lateral_offset_m;
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

/// Renders frame `f` of `scene` in both cameras and tracks it with danescu-stereo, given the
/// car's motion from the simulator.
fn track_stereo_frame(
    scene: &mut Scene,
    tracker: &mut DanescuTracker,
    f: u32,
    left: &mut [u8],
    right: &mut [u8],
) -> DanescuEstimate {
    let (w, h) = (scene.width(), scene.height());
    let pose = scene.render(f, Eye::Left, left, None).unwrap();
    scene.render(f, Eye::Right, right, None).unwrap();
    tracker
        .set_ego_motion(EgoMotion {
            t_s: pose.t,
            speed_mps: pose.speed,
            yaw_rate: pose.yaw_rate,
        })
        .unwrap();
    tracker.set_right(right, w, h).unwrap();
    tracker.track(left, w, h).unwrap()
}

/// Runs danescu-stereo over `frames` frames of a scenario with the simulator's ego motion.
fn run_stereo(
    name: &str,
    frames: u32,
    w: usize,
    h: usize,
    extra: &str,
) -> Vec<(LaneEstimate, DanescuEstimate, f64)> {
    let mut scene = Scene::new(scenario(name).unwrap(), default_camera(w, h).unwrap(), 1).unwrap();
    let mut tracker = DanescuTracker::new(&config(w, h, extra), ID_STEREO).unwrap();
    let (mut left, mut right) = (vec![0; w * h * 4], vec![0; w * h * 4]);
    (0..frames)
        .map(|f| {
            let e = track_stereo_frame(&mut scene, &mut tracker, f, &mut left, &mut right);
            let pitch = tracker.stereo.as_ref().unwrap().pitch_change();
            (crate::trackers::scene_truth(&scene, f), e, pitch)
        })
        .collect()
}

#[test]
fn the_density_cue_is_least_at_the_true_vertical_profile() {
    // Sec. VI-B on pitch-bumps at 640x480: D^D (eq. 13) of the true lane is under a cell, and
    // moving Y_0 by 4 cm or the pitch by 5 mrad costs at least two more cells. The preliminary
    // pitch follows the true pitch change.
    let (w, h) = (640, 480);
    let camera = default_camera(w, h).unwrap();
    let mut scene = Scene::new(scenario("pitch-bumps").unwrap(), camera.clone(), 1).unwrap();
    let mut tracker = DanescuTracker::new(&config(w, h, ""), ID_STEREO).unwrap();
    let (mut left, mut right) = (vec![0; w * h * 4], vec![0; w * h * 4]);
    for f in [10u32, 20, 30, 40] {
        scene.render(f, Eye::Left, &mut left, None).unwrap();
        scene.render(f, Eye::Right, &mut right, None).unwrap();
        tracker.set_right(&right, w, h).unwrap();
        tracker.begin(&left, w, h).unwrap();
        let truth = crate::trackers::scene_truth(&scene, f);
        let lane = true_lane(&truth);
        let stereo = tracker.stereo.as_ref().unwrap();
        assert!(stereo.road_points() > 10_000, "{}", stereo.road_points());
        let dd = |l: &Lane3d| {
            tracker
                .measurement
                .distances_of(&tracker.camera, l, &tracker.cues, Some(stereo.density()))
                .density
                .unwrap()
        };
        let at = dd(&lane);
        assert!(at < 1.0, "frame {f}: {at}");
        for moved in [
            Lane3d {
                y0: lane.y0 + 0.04,
                ..lane
            },
            Lane3d {
                y0: lane.y0 - 0.04,
                ..lane
            },
            Lane3d {
                alpha: lane.alpha + 0.005,
                ..lane
            },
            Lane3d {
                alpha: lane.alpha - 0.005,
                ..lane
            },
        ] {
            assert!(dd(&moved) > at + 2.0, "frame {f}: {} vs {at}", dd(&moved));
        }
        // The preliminary pitch is the slope of a line through the origin (Sec. IV: it ignores
        // Y_0), so a height offset tilts it by about Y_0 over the distance of the bulk of the
        // points (4-5 m here).
        // The stereo layers show the same profile: at Z = 10 m the density's column maximum
        // is within 2 cm of the true road height.
        let layers = tracker.layers();
        let Some(crate::trackers::Layer::Plane {
            width,
            height,
            axes,
            values,
            ..
        }) = layers.last()
        else {
            panic!("no plane layer");
        };
        let col = ((10.0 - axes.x0) / axes.dx) as usize;
        let want = lane.road_height(camera.pitch(), 10.0);
        let rows: Vec<f64> = (0..*height)
            .filter(|&r| values[r * width + col] > 0.0)
            .map(|r| axes.y0 + (r as f64 + 0.5) * axes.dy)
            .collect();
        assert!(
            rows.iter().any(|y| (y - want).abs() < 0.02),
            "frame {f}: maxima at {rows:?}, road at {want}"
        );
        let change = lane.alpha - camera.pitch();
        assert!(
            (stereo.pitch_change() - change).abs() < 0.003 + lane.y0.abs() / 4.0,
            "frame {f}: detected {} true {change} Y_0 {}",
            stereo.pitch_change(),
            lane.y0
        );
    }
}

/// The simulator's danescu.* truth as a lane.
fn true_lane(truth: &LaneEstimate) -> Lane3d {
    let mut a = [0.0; 11];
    for (k, n) in Lane3d::NAMES.iter().enumerate() {
        a[k] = truth.state[&format!("danescu.{n}")];
    }
    Lane3d::from_array(a)
}

/// Drawn `pitch-bumps` members (body pitch 0.6-1.6 deg and height 2-6 cm at 0.7-1.4 s), scene
/// seeds 1-2, 90 frames, and drawn `highway-straight` members, scene seeds 1-2, 60 frames, at
/// 640x480, frames 30.. after the burn-in. On the bumps stereo must do better than half of a
/// tracker that held the pitch at the calibration (the reference road's figures when this
/// test ran on it: 2.4 against 15 mrad) and nearer than holding Y_0 at 0 (1.2 against 2.8
/// cm), with the lane's offset and W_0 within 0.1 m RMS. On the straight roads: the lane
/// (offset and W_0 within 0.1 m RMS), valid on 90 % of the frames, a median effective sample
/// size above 40 of 500; both marking widths W_L and W_R within 3 cm mean absolute error on
/// average over the members and 4 cm on each. When written W_L 1.5 and 2.3 cm, W_R 3.7 (seed
/// 1: a solid right edge seen by a camera 1.18 m high) and 0.5 cm.
/// (With the earlier defaults, sigma_D 0.5 cell and 8 mrad of pitch diffusion, the density
/// cue was so sharp that the reference road's median ESS was 19 and W_R wandered, 6.7 cm.)
#[test]
fn stereo_tracks_the_pitch_and_height_on_bumps_and_straight_highways() {
    let (mut bad, mut mean_marks) = (Vec::new(), [0.0; 2]);
    for seed in 1..=2 {
        let mount = crate::synth::draw_scenario("pitch-bumps", seed)
            .unwrap()
            .mount;
        let mount_pitch = mount.pitch_deg.to_radians();
        let bumps = run_stereo_member("pitch-bumps", seed, 90, 640, 480);
        let tail = &bumps[30..];
        let alpha = rms(tail
            .iter()
            .map(|(t, e, _)| t.state["danescu.alpha"] - e.lane.alpha));
        let held_alpha = rms(tail
            .iter()
            .map(|(t, _, _)| t.state["danescu.alpha"] - mount_pitch));
        let y0 = rms(tail
            .iter()
            .map(|(t, e, _)| t.state["danescu.y0"] - e.lane.y0));
        let held_y0 = rms(tail.iter().map(|(t, _, _)| t.state["danescu.y0"]));
        let off = rms(tail.iter().map(|(t, e, _)| t.lateral_offset_m - e.lane.xcw));
        let w0 = rms(tail
            .iter()
            .map(|(t, e, _)| t.state["danescu.w0"] - e.lane.w0));
        let line = format!(
            "bumps seed {seed}: alpha {alpha:.4} (held {held_alpha:.4}) Y_0 {y0:.4} (held \
             {held_y0:.4}) offset {off:.3} W_0 {w0:.3}"
        );
        eprintln!("{line}");
        if !(alpha < held_alpha / 2.0 && y0 < held_y0 && off < 0.1 && w0 < 0.1) {
            bad.push(line);
        }
        let straight = run_stereo_member("highway-straight", seed, 60, 640, 480);
        let tail = &straight[30..];
        let off = rms(tail.iter().map(|(t, e, _)| t.lateral_offset_m - e.lane.xcw));
        let w0 = rms(tail
            .iter()
            .map(|(t, e, _)| t.state["danescu.w0"] - e.lane.w0));
        let valid = tail.iter().filter(|(_, e, _)| e.valid).count();
        let n = tail.len() as f64;
        let marks = MARKING_WIDTHS.map(|k| {
            let name = format!("danescu.{}", Lane3d::NAMES[k]);
            tail.iter()
                .map(|(t, e, _)| (t.state[&name] - e.lane.to_array()[k]).abs())
                .sum::<f64>()
                / n
        });
        let mut ess: Vec<f64> = tail.iter().map(|(_, e, _)| e.ess).collect();
        ess.sort_by(f64::total_cmp);
        let ess = ess[ess.len() / 2];
        let line = format!(
            "straight seed {seed}: offset {off:.3} W_0 {w0:.3} valid {valid} of {} marking \
             widths {marks:.3?} median ESS {ess:.0}",
            tail.len()
        );
        eprintln!("{line}");
        if !(off < 0.1
            && w0 < 0.1
            && valid * 100 >= tail.len() * 90
            && marks.iter().all(|&m| m < 0.04)
            && ess > 40.0)
        {
            bad.push(line);
        }
        for (mean, m) in mean_marks.iter_mut().zip(marks) {
            *mean += m / 2.0;
        }
    }
    assert!(bad.is_empty(), "{bad:?}");
    assert!(
        mean_marks.iter().all(|&m| m < 0.03),
        "marking widths {mean_marks:.3?} on average"
    );
}

/// Pearson correlation of two series.
fn correlation(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        ab += (x - ma) * (y - mb);
        aa += (x - ma) * (x - ma);
        bb += (y - mb) * (y - mb);
    }
    ab / (aa * bb).sqrt()
}

/// Drawn `highway-curve` members, scene seeds 1-2, at 640x480, frames 30-89: offset under
/// 4 cm RMS, C_H under 5e-4, psi under 6 mrad, W_0 under 0.1 m, valid on at least 90 % of the
/// frames (the reference road's figures when this test ran on it: 2.5 cm, 3.4e-4, 3.9 mrad,
/// 0.066 m, 87 of 90).
#[test]
fn stereo_follows_curves() {
    let mut bad = Vec::new();
    for seed in 1..=2 {
        let curve = run_stereo_member("highway-curve", seed, 90, 640, 480);
        let tail = &curve[30..];
        let off = rms(tail.iter().map(|(t, e, _)| t.lateral_offset_m - e.lane.xcw));
        let ch = rms(tail
            .iter()
            .map(|(t, e, _)| t.state["danescu.ch"] - e.lane.ch));
        let psi = rms(tail
            .iter()
            .map(|(t, e, _)| t.state["danescu.psi"] - e.lane.psi));
        let w0 = rms(tail
            .iter()
            .map(|(t, e, _)| t.state["danescu.w0"] - e.lane.w0));
        let valid = tail.iter().filter(|(_, e, _)| e.valid).count();
        let line = format!(
            "seed {seed}: offset {off:.3} C_H {ch:.5} psi {psi:.4} W_0 {w0:.3} valid {valid} of {}",
            tail.len()
        );
        eprintln!("{line}");
        if !(off < 0.04 && ch < 0.0005 && psi < 0.006 && w0 < 0.1 && valid * 100 >= tail.len() * 90)
        {
            bad.push(line);
        }
    }
    assert!(bad.is_empty(), "{bad:?}");
}

#[test]
fn stereo_follows_the_width_change() {
    // width-change at 640x480, frames 30-300: the lane widens from 3.45 to 4.35 m over
    // frames 45-165 (true W_l = 0.009) and narrows towards 3.05 m from frame 235 (W_l =
    // -0.016). The estimated W_l follows the true one over the sequence: correlation above
    // 0.7 (0.90 when written, this tracker seed; over tracker seeds 1-6 0.74-0.96, mean 0.87,
    // and 0.81-0.92, mean 0.86, with the earlier sigma_D 0.5 and 8 mrad of pitch diffusion);
    // its mean over frames 60-160 within 0.003 of 0.009 (0.0072). W_0 is within 0.13 m RMS of
    // the truth (0.058), valid on at least 90 % of the frames (269 of 270). W_l is diffused
    // by 0.001 per frame and lags each change, by 0-38 frames over those seeds, so frame by
    // frame it is no closer than that.
    let run = run_stereo("width-change", 300, 640, 480, "");
    let tail = &run[30..];
    let truth: Vec<f64> = tail.iter().map(|(t, _, _)| t.state["danescu.wl"]).collect();
    let est: Vec<f64> = tail.iter().map(|(_, e, _)| e.lane.wl).collect();
    let r = correlation(&truth, &est);
    let widening = &run[60..160];
    assert!(widening
        .iter()
        .all(|(t, _, _)| t.state["danescu.wl"] > 0.008));
    let mean = widening.iter().map(|(_, e, _)| e.lane.wl).sum::<f64>() / 100.0;
    let w0 = rms(tail
        .iter()
        .map(|(t, e, _)| t.state["danescu.w0"] - e.lane.w0));
    let valid = tail.iter().filter(|(_, e, _)| e.valid).count();
    assert!(
        r > 0.7 && (mean - 0.009).abs() < 0.003 && w0 < 0.13,
        "W_l correlation {r}, mean while widening {mean}, W_0 {w0}"
    );
    assert!(valid * 100 >= tail.len() * 90, "{valid} valid");
}

#[test]
fn stereo_input_errors_are_clear() {
    let (w, h) = (320, 240);
    let mut stereo = DanescuTracker::new(&config(w, h, ""), ID_STEREO).unwrap();
    let frame = vec![0; w * h * 4];
    let e = stereo.track(&frame, w, h).unwrap_err().to_string();
    assert!(e.contains("set_right") && e.contains(ID_MONO), "{e}");
    let e = stereo
        .set_right(&frame[..100], w, h)
        .unwrap_err()
        .to_string();
    assert!(e.contains("bytes") || e.contains("buffer"), "{e}");
    // A right frame is used once.
    stereo.set_right(&frame, w, h).unwrap();
    assert!(stereo.track(&frame, w, h).is_ok());
    assert!(stereo.track(&frame, w, h).is_err());
    let mut mono = DanescuTracker::new(&config(w, h, ""), ID_MONO).unwrap();
    let e = mono.set_right(&frame, w, h).unwrap_err().to_string();
    assert!(e.contains("one camera"), "{e}");
    // Without a baseline there is no stereo rig.
    let mut file = default_camera(w, h).unwrap().to_file();
    file.baseline_m = None;
    let c = TrackerConfig::from_json_str(&format!(
        r#"{{"camera": {}}}"#,
        serde_json::to_string(&file).unwrap()
    ))
    .unwrap();
    let e = DanescuTracker::new(&c, ID_STEREO)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("baseline_m"), "{e}");
    assert!(DanescuTracker::new(&c, ID_MONO).is_ok());
    let e = DanescuTracker::new(&c, "danescu-3d")
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains(ID_STEREO), "{e}");
}

#[test]
fn cluster_labels_follow_the_particles_through_a_frame() {
    let (w, h) = (320, 240);
    let mut scene = Scene::new(
        scenario("highway-straight").unwrap(),
        default_camera(w, h).unwrap(),
        1,
    )
    .unwrap();
    let mut t = DanescuTracker::new(&config(w, h, r#", "particles": 200"#), ID_MONO).unwrap();
    let mut rgba = vec![0; w * h * 4];
    let label_count =
        |t: &DanescuTracker| t.particles().chunks(13).filter(|p| p[12] >= 0.0).count();
    assert_eq!(label_count(&t), 0, "nothing clustered yet");
    for f in 0..2 {
        scene.render(f, Eye::Left, &mut rgba, None).unwrap();
        t.begin(&rgba, w, h).unwrap();
        t.advance_step(); // resample (from the second frame)
        if f > 0 {
            assert_eq!(label_count(&t), 0, "labels of the old order are withdrawn");
        }
        while t.advance_step().is_none() {}
        // After the estimate: the resampled particles carry their clusters (all of them
        // from the second frame on; the R initialisation particles none).
        let injected = t.filter.injected();
        assert_eq!(label_count(&t), 200 - injected, "frame {f}");
    }
}

/// Lateral offset of a road polyline at `x` ahead (linear between its points).
fn lateral_at(points: &[[f64; 2]], x: f64) -> Option<f64> {
    points.windows(2).find_map(|p| {
        let ([x0, y0], [x1, y1]) = (p[0], p[1]);
        (x >= x0.min(x1) && x <= x0.max(x1) && x1 != x0)
            .then(|| y0 + (y1 - y0) * (x - x0) / (x1 - x0))
    })
}

#[test]
fn curbs_from_the_elevation_map_put_dt_s_on_the_true_kerbs() {
    // `urban` at 640x480 (kerbs 15 cm high at both road edges, parked cars, sensor noise).
    // The elevation map places curb feet to a cell: between 6 and 15 m, at least 80 % of them
    // within 0.1 m (a cell) of the true kerb line and none beyond 0.35 m. In DT^S, the true
    // kerb foot between 6 and 15 m, where it is seen, is within 2 px of a delimiter edge on
    // at least half of the rows with the curbs (49 of 76 when written), and on at most a
    // fifth without them (0: the kerb has no paint for the marking detector).
    let (w, h) = (640, 480);
    let camera = default_camera(w, h).unwrap();
    let mut scene = Scene::new(scenario("urban").unwrap(), camera.clone(), 1).unwrap();
    let mut with = DanescuTracker::new(&config(w, h, ""), ID_STEREO).unwrap();
    let mut without =
        DanescuTracker::new(&config(w, h, r#", "curbs": {"enabled": false}"#), ID_STEREO).unwrap();
    assert!(without.stereo.as_ref().unwrap().elevation().is_none());
    let (mut left, mut right) = (vec![0; w * h * 4], vec![0; w * h * 4]);
    let mut depth = vec![0.0; w * h];
    let (mut near_with, mut near_without, mut rows) = (0, 0, 0);
    let (mut feet, mut within_cell) = (0, 0);
    for f in [10u32, 40, 70, 100] {
        scene
            .render(f, Eye::Left, &mut left, Some(&mut depth))
            .unwrap();
        scene.render(f, Eye::Right, &mut right, None).unwrap();
        for t in [&mut with, &mut without] {
            t.set_right(&right, w, h).unwrap();
            t.begin(&left, w, h).unwrap();
        }
        let truth = crate::trackers::scene_truth(&scene, f);
        let kerb = |x: f64, right: bool| {
            let lines = truth
                .boundaries
                .iter()
                .filter_map(|b| lateral_at(&b.road_points, x));
            if right {
                lines.fold(f64::INFINITY, f64::min)
            } else {
                lines.fold(f64::NEG_INFINITY, f64::max)
            }
        };
        let map = with.stereo.as_ref().unwrap().elevation().unwrap();
        for foot in map.feet().iter().filter(|p| p.x0 >= 6.0 && p.x1 <= 15.0) {
            let x = (foot.x0 + foot.x1) / 2.0;
            let off = (foot.y - kerb(x, foot.y < 0.0)).abs();
            assert!(
                off <= 0.35,
                "frame {f}: a foot at ({x}, {}) off by {off}",
                foot.y
            );
            feet += 1;
            within_cell += usize::from(off <= 0.1);
        }
        for i in 0..36 {
            let x = 6.0 + 0.25 * i as f64;
            let foot = [x, kerb(x, true), 0.0];
            let Some([u, v]) = camera.project(foot) else {
                continue;
            };
            // Seen, not behind a parked car: the rendered depth is the foot's.
            let z = camera.road_to_camera(foot)[2];
            if (depth[v.round() as usize * w + u.round() as usize] as f64 - z).abs() > 0.05 * z {
                continue;
            }
            let near = |t: &DanescuTracker| t.cues.marking_distance(u, v).is_some_and(|d| d <= 2.0);
            rows += 1;
            near_with += usize::from(near(&with));
            near_without += usize::from(near(&without));
        }
    }
    assert!(
        feet >= 40 && within_cell * 5 >= feet * 4,
        "{within_cell} of {feet} feet"
    );
    // The demo's view of the map: the cell classes of the last frame on the road grid.
    let layers = with.layers();
    let Some(crate::trackers::Layer::Grid { values, .. }) = layers.iter().find(
        |l| matches!(l, crate::trackers::Layer::Grid { name, .. } if name.starts_with("elevation")),
    ) else {
        panic!("no elevation layer");
    };
    let count = |v: f32| values.iter().filter(|&&x| x == v).count();
    let (road, raised) = (count(1.0 / 3.0), count(2.0 / 3.0));
    assert!(road > 1000 && raised > 100, "{road} road, {raised} raised");
    // The kerb is seen (not behind a parked car) on 76 of the 144 rows.
    assert!(rows >= 60, "{rows}");
    assert!(near_with * 2 >= rows, "{near_with} of {rows}");
    assert!(near_without * 5 <= rows, "{near_without} of {rows}");
}

#[test]
fn roads_without_kerbs_give_no_curbs() {
    // Flat highways (with a sag and bumps in `pitch-bumps`) at both resolutions: not a single
    // curb foot in four frames each.
    for (w, h) in [(320, 240), (640, 480)] {
        for name in [
            "highway-straight",
            "highway-curve",
            "pitch-bumps",
            "width-change",
        ] {
            let camera = default_camera(w, h).unwrap();
            let mut scene = Scene::new(scenario(name).unwrap(), camera, 1).unwrap();
            let mut t = DanescuTracker::new(&config(w, h, ""), ID_STEREO).unwrap();
            let (mut left, mut right) = (vec![0; w * h * 4], vec![0; w * h * 4]);
            for f in [10u32, 40, 70, 100] {
                scene.render(f, Eye::Left, &mut left, None).unwrap();
                scene.render(f, Eye::Right, &mut right, None).unwrap();
                t.set_right(&right, w, h).unwrap();
                t.begin(&left, w, h).unwrap();
                let feet = t.stereo.as_ref().unwrap().elevation().unwrap().feet();
                assert!(feet.is_empty(), "{name} {w}x{h} frame {f}: {feet:?}");
            }
        }
    }
}

/// Image column of a polyline at row `v` (linear between its points).
fn column_at(points: &[[f64; 2]], v: f64) -> Option<f64> {
    points.windows(2).find_map(|p| {
        let ([u0, v0], [u1, v1]) = (p[0], p[1]);
        (v <= v0 && v >= v1 && v0 > v1).then(|| u0 + (u1 - u0) * (v0 - v) / (v0 - v1))
    })
}

#[test]
fn the_output_has_each_markings_inner_and_outer_edge_a_marking_width_apart() {
    // The true lane of the first curved frame of highway-curve (the car off centre, 0.15 m
    // markings)
    // put through the output: four delimiters (eqs. 2-3), each marking's inner and outer edge
    // W_L (W_R) apart on the road and the boundary (the marking's centre) half-way between,
    // the inner edges W(Z) apart (eq. 1); in the image, outer-centre-inner in order on every
    // row; and all of them on the simulator's truth (its boundaries are the marking centres).
    let (w, h) = (640, 480);
    let scene = Scene::new(
        scenario("highway-curve").unwrap(),
        default_camera(w, h).unwrap(),
        1,
    )
    .unwrap();
    let truth = (0..300)
        .step_by(10)
        .map(|f| crate::trackers::scene_truth(&scene, f))
        .find(|t| t.state["danescu.ch"].abs() > 5e-4)
        .unwrap();
    let lane = true_lane(&truth);
    assert!(lane.ch.abs() > 1e-4 && lane.wl_mark > 0.1, "{lane:?}");
    let tracker = DanescuTracker::new(&config(w, h, ""), ID_STEREO).unwrap();
    let out = tracker.to_lane_estimate(&DanescuEstimate {
        lane,
        valid: true,
        cluster_share: 1.0,
        clusters: 1,
        change: 0,
        ess: 1.0,
        support: [1.0; 2],
    });
    let find = |role: Role, side: Side| {
        out.delimiters
            .iter()
            .find(|d| d.boundary.role == role && d.side == side)
            .map(|d| &d.boundary)
            .unwrap()
    };
    assert_eq!(out.delimiters.len(), 4);
    let json = serde_json::to_string(&out).unwrap();
    assert!(
        json.contains(r#""side":"outer","role":"ego-left""#),
        "{json}"
    );
    for (role, mark, sign) in [
        (Role::EgoLeft, lane.wl_mark, 1.0),
        (Role::EgoRight, lane.wr_mark, -1.0),
    ] {
        let (inner, outer) = (find(role, Side::Inner), find(role, Side::Outer));
        let centre = out.boundaries.iter().find(|b| b.role == role).unwrap();
        let true_centre = truth.boundaries.iter().find(|b| b.role == role).unwrap();
        for b in [inner, outer] {
            b.check_polyline().unwrap();
            assert!(b.points.len() > 10 && b.road_points.len() == b.points.len());
        }
        for x in [6.0, 10.0, 15.0, 20.0] {
            let (yi, yo, yc) = (
                inner.y_at(x).unwrap(),
                outer.y_at(x).unwrap(),
                centre.y_at(x).unwrap(),
            );
            // y is to the left: the left marking's outer edge is further left.
            assert!(
                ((yo - yi) * sign - mark).abs() < 1e-3,
                "{role:?} at {x} m: {yi} {yo}"
            );
            assert!((yc - (yi + yo) / 2.0).abs() < 1e-3, "{role:?} at {x} m");
            // Within a pixel at x (the model's second-order centre line against the
            // simulator's clothoid, as in lane_3d's tests).
            let t = true_centre.y_at(x).unwrap();
            assert!(
                (yi - (t - sign * mark / 2.0)).abs() < x / tracker.camera.focal()[0],
                "{role:?} at {x} m: inner {yi}, truth centre {t}"
            );
        }
        // On the rows where all three are in the image (a marking leaves it at the side
        // near the bottom).
        let mut rows = 0;
        for v in (250..=450).step_by(25).map(f64::from) {
            let u = |b: &Boundary| column_at(&b.points, v);
            let (Some(ui), Some(uc), Some(uo)) = (u(inner), u(centre), u(outer)) else {
                continue;
            };
            rows += 1;
            assert!(
                (uo - uc) * sign < 0.0 && (uc - ui) * sign < 0.0,
                "{role:?} row {v}: outer {uo} centre {uc} inner {ui}"
            );
        }
        assert!(rows >= 5, "{role:?}: {rows} rows");
    }
    let (li, ri) = (
        find(Role::EgoLeft, Side::Inner),
        find(Role::EgoRight, Side::Inner),
    );
    for x in [6.0, 20.0] {
        let width = li.y_at(x).unwrap() - ri.y_at(x).unwrap();
        assert!((width - lane.width(x)).abs() < 1e-3, "{width} at {x} m");
    }
}

/// The width each mode reports: with the marking-width model, `danescu.w0` is the paper's
/// width (between the inner edges), `lane_width_m` between the marking centres, and the
/// marking widths are in the state; without it (the paper's previous approach), `danescu.w0`
/// is still the paper's width and `lane_width_m` = W_0 (its delimiters are the inner
/// edges), and the marking widths, which that model does not estimate, are absent instead
/// of 0 (the paper's "no marking").
#[test]
fn each_mode_reports_the_papers_width_and_only_the_marking_widths_it_estimates() {
    let (w, h) = (320, 240);
    let scene = Scene::new(
        scenario("highway-straight").unwrap(),
        default_camera(w, h).unwrap(),
        1,
    )
    .unwrap();
    let lane = true_lane(&crate::trackers::scene_truth(&scene, 0));
    assert!(lane.wl_mark > 0.1 && lane.wr_mark > 0.1, "{lane:?}");
    let estimate = DanescuEstimate {
        lane,
        valid: true,
        cluster_share: 1.0,
        clusters: 1,
        change: 0,
        ess: 1.0,
        support: [1.0; 2],
    };
    let with = DanescuTracker::new(&config(w, h, ""), ID_MONO).unwrap();
    let out = with.to_lane_estimate(&estimate);
    assert_eq!(out.state["danescu.w0"], lane.w0);
    assert_eq!(out.state["danescu.wl_mark"], lane.wl_mark);
    let centres = lane.w0 + (lane.wl_mark + lane.wr_mark) / 2.0;
    assert!((out.lane_width_m - centres).abs() < 1e-12);
    let without =
        DanescuTracker::new(&config(w, h, r#", "marking_widths": false"#), ID_MONO).unwrap();
    let flat = Lane3d {
        wl_mark: 0.0,
        wr_mark: 0.0,
        ..lane
    };
    let out = without.to_lane_estimate(&DanescuEstimate {
        lane: flat,
        ..estimate
    });
    assert_eq!(out.state["danescu.w0"], lane.w0);
    assert!((out.lane_width_m - lane.w0).abs() < 1e-12);
    assert!(
        !out.state.contains_key("danescu.wl_mark"),
        "{:?}",
        out.state
    );
    assert!(!out.state.contains_key("danescu.wr_mark"));
}

/// Frames from the end of the first blackout of `member` until danescu-stereo (with the
/// `extra` options) is valid with an offset error under 0.3 m, the `eval-suite` recovery
/// rule; `None` when not within 30 frames.
fn stereo_recovery(member: &crate::synth::FamilyMember, extra: &str) -> Option<usize> {
    let (w, h) = (320, 240);
    let mut scene = member.scene(w, h).unwrap();
    let camera = serde_json::to_string(&scene.camera().to_file()).unwrap();
    let config =
        TrackerConfig::from_json_str(&format!(r#"{{"camera": {camera}, "seed": 1 {extra}}}"#))
            .unwrap();
    let mut tracker = DanescuTracker::new(&config, ID_STEREO).unwrap();
    let (mut left, mut right) = (vec![0; w * h * 4], vec![0; w * h * 4]);
    let mut end = None;
    let mut dark = false;
    for f in 0..member.config.frames {
        let e = track_stereo_frame(&mut scene, &mut tracker, f, &mut left, &mut right);
        let truth = crate::trackers::scene_truth(&scene, f);
        let blackout = truth.state["blackout"] > 0.5;
        // The 3-D data of a blacked-out frame (matches of sensor noise) does not count.
        if blackout && extra.is_empty() {
            assert!(!tracker.stereo.as_ref().unwrap().usable(), "frame {f}");
        }
        if dark && !blackout {
            end = Some(f);
        }
        dark = blackout;
        if let Some(end) = end {
            let out = tracker.to_lane_estimate(&e);
            if out.valid && (out.lateral_offset_m - truth.lateral_offset_m).abs() < 0.3 {
                return Some((f - end) as usize);
            }
            if f - end >= 30 {
                return None;
            }
        }
    }
    None
}

/// After a blackout the stereo tracker re-locks within a few frames: the 3-D data of the
/// blacked-out frames (a few hundred matches of sensor noise) no longer weighs the particles
/// (`min_road_share`), so the cloud does not drift through the blackout. Drawn `occlusion`
/// members, scene seeds 2-11, 320x240, tracker seed 1. Measured 2026-11-25 (frames from the
/// blackout's end to a valid estimate within 0.3 m): 1, 1, 2, 4, 10, 1, 6, 1, 5, 1, mean
/// 3.2; without the gate (`min_road_share: 0`, the behaviour before) 14, 0, 6, 4, 3, 1, 0,
/// 3, 9, 25, mean 6.5. Not every seed gains (seeds 6 and 8 lose), the mean and the worst do.
#[test]
fn stereo_relocks_within_a_few_frames_after_a_blackout() {
    let frames: Vec<usize> = (2..=11)
        .map(|seed| {
            let member = crate::synth::draw_scenario("occlusion", seed).unwrap();
            let r = stereo_recovery(&member, "");
            assert!(r.is_some_and(|r| r <= 12), "seed {seed}: {r:?}");
            r.unwrap_or(usize::MAX)
        })
        .collect();
    let mean = frames.iter().sum::<usize>() as f64 / frames.len() as f64;
    assert!(mean <= 4.0, "{frames:?}");
}
