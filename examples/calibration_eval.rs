//! How well auto-calibration recovers a camera, and what it costs a tracker.
//!
//! `cargo run --release --example calibration_eval -- [SEED_FROM SEED_TO] [FRAMES] [SCENARIOS]
//! [--tangent-yaw | --chord-yaw] [--no-trackers] [--preset=NAME] [--tracker-seeds=N]`
//! (defaults: seeds 101..=112,
//! 150 frames, scenarios highway-straight,highway-curve,s-curve,shadows,worn-markings,multi-lane
//! cycled over the seeds; `--tangent-yaw` sets the calibrator's `tangent_yaw`, `--chord-yaw`
//! its `tangent_yaw_after` to 0 (the crossing's yaw throughout), `--no-trackers` skips the
//! tracking, `--preset=real-roads` runs the trackers with that preset instead of the papers'
//! defaults, `--tracker-seeds=N` averages each tracker's accuracy over its seeds 1..=N, 1 by
//! default). The "used" column marks with "t" an estimate whose yaw is the tangent's.
//!
//! For each seed a camera pose is drawn (`synth::drawn_camera`: pitch -2..8 deg, yaw -3..3 deg,
//! height 1.1..2.4 m, horizontal field of view 50..90 deg at 640x480) and the scenario rendered through it. The
//! calibrator is fed every frame, once with the true intrinsics and once with none (focal
//! length from its 60 degree default); the pose errors are printed, the yaw error also against
//! the yaw the vanishing point can show (the mount's yaw minus the car's mean heading relative
//! to the lane over the frames the calibrator used: the simulated driver weaves by about half
//! a degree over a few seconds, which a short clip cannot average out). Then every mono tracker
//! runs on the same frames with the true camera and with the estimated one (true intrinsics),
//! and the image-space boundary accuracy of both is printed (`lanepf eval --format synthetic`'s
//! "boundaries" figure), with the detection rate.

use lanepf::calib::{Calibrator, CalibratorConfig};
use lanepf::camera::{Camera, CameraFile};
use lanepf::eval::synthetic::evaluate;
use lanepf::lane::LaneEstimate;
use lanepf::synth::{drawn_camera, scenario, Eye, Scene};
use lanepf::trackers::{self, Preset, TrackerConfig, TrackerOptions};

const TRACKERS: [&str; 4] = ["adachi-mmpf", "danescu-mono", "lee-cpf", "liu-ppf"];

fn track(
    id: &str,
    camera: &CameraFile,
    frames: &[Vec<u8>],
    preset: Preset,
    seed: u64,
) -> Result<Vec<LaneEstimate>, Box<dyn std::error::Error>> {
    let config = TrackerConfig {
        camera: camera.clone(),
        particles: None,
        seed,
        options: TrackerOptions::preset(id, preset)?.into(),
    };
    let mut tracker = trackers::create(id, &config)?;
    let mut out = Vec::with_capacity(frames.len());
    for f in frames {
        out.push(tracker.step(f, camera.width, camera.height)?);
    }
    Ok(out)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let all: Vec<String> = std::env::args().collect();
    let flag = |name: &str| all.iter().any(|a| a == name);
    let (tangent_yaw, with_trackers) = (flag("--tangent-yaw"), !flag("--no-trackers"));
    if tangent_yaw && flag("--chord-yaw") {
        return Err("--tangent-yaw and --chord-yaw exclude each other".into());
    }
    let preset: Preset = all
        .iter()
        .find_map(|a| a.strip_prefix("--preset="))
        .unwrap_or("paper")
        .parse()?;
    let tracker_seeds: u64 = all
        .iter()
        .find_map(|a| a.strip_prefix("--tracker-seeds="))
        .unwrap_or("1")
        .parse()?;
    if tracker_seeds == 0 {
        return Err("--tracker-seeds must be at least 1".into());
    }
    let args: Vec<&String> = all.iter().filter(|a| !a.starts_with("--")).collect();
    let d = CalibratorConfig::default();
    let calibration = CalibratorConfig {
        tangent_yaw,
        tangent_yaw_after: if flag("--chord-yaw") {
            0
        } else {
            d.tangent_yaw_after
        },
        ..d
    };
    let from: u64 = args.get(1).map_or(Ok(101), |s| s.parse())?;
    let to: u64 = args.get(2).map_or(Ok(112), |s| s.parse())?;
    let n_frames: u32 = args.get(3).map_or(Ok(150), |s| s.parse())?;
    let names: Vec<String> = args.get(4).map_or_else(
        || {
            [
                "highway-straight",
                "highway-curve",
                "s-curve",
                "shadows",
                "worn-markings",
                "multi-lane",
            ]
            .map(String::from)
            .to_vec()
        },
        |s| s.split(',').map(String::from).collect(),
    );
    println!(
        "| seed | scenario | true pitch / yaw / h / hfov | pitch err | yaw err | yaw err vs lane | h err | conf | used | no-intrinsics pitch / yaw err | {} |",
        TRACKERS.map(|t| format!("{t} true / auto")).join(" | ")
    );
    println!("|{}", "---|".repeat(9 + TRACKERS.len()));
    let (mut ep, mut ey, mut eh, mut eyl) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut losses: Vec<Vec<f64>> = vec![Vec::new(); TRACKERS.len()];
    for seed in from..=to {
        let name = &names[(seed - from) as usize % names.len()];
        let truth_cam = drawn_camera(seed);
        let camera = Camera::from_file(&truth_cam)?;
        let mut config = scenario(name)?;
        config.frames = n_frames;
        let mut scene = Scene::new(config, camera, seed)?;
        let (w, h) = (scene.width(), scene.height());
        let mut frames = Vec::new();
        let mut gt = Vec::new();
        for i in 0..n_frames {
            let mut rgba = vec![0u8; w * h * 4];
            scene.render(i, Eye::Left, &mut rgba, None)?;
            frames.push(rgba);
            gt.push(lanepf::trackers::scene_truth(&scene, i));
        }
        let mut known = Calibrator::new(w, h, Some(&truth_cam), calibration)?;
        let mut unknown = Calibrator::new(w, h, None, calibration)?;
        // The car's heading relative to the lane, summed over the frames the calibrator used.
        let (mut heading_used, mut used) = (0.0, 0);
        for (f, g) in frames.iter().zip(&gt) {
            known.feed_rgba(f, w, h)?;
            unknown.feed_rgba(f, w, h)?;
            if known.last_observation().used {
                heading_used += g.heading_rad;
                used += 1;
            }
        }
        let Some(est) = known.estimate() else {
            println!("| {seed} | {name} | no estimate |");
            continue;
        };
        let c = &est.camera;
        let (dp, dy) = (
            c.pitch_deg - truth_cam.pitch_deg,
            c.yaw_deg - truth_cam.yaw_deg,
        );
        // The vanishing point sees the mount's yaw minus the car's heading relative to the
        // lane: against the mean heading over the frames used, the calibrator's own error.
        let heading = heading_used / used.max(1) as f64;
        let dyl = dy + heading.to_degrees();
        eyl.push(dyl.abs());
        let dh = (c.height_m - truth_cam.height_m) / truth_cam.height_m;
        ep.push(dp.abs());
        ey.push(dy.abs());
        eh.push(dh.abs());
        let no_intr = unknown.estimate().map_or("-".to_string(), |u| {
            format!(
                "{:+.2} / {:+.2}",
                u.camera.pitch_deg - truth_cam.pitch_deg,
                u.camera.yaw_deg - truth_cam.yaw_deg
            )
        });
        let hfov = 2.0 * lanepf::math::atan(0.5 * w as f64 / truth_cam.fx).to_degrees();
        let mut cells = Vec::new();
        for (k, id) in TRACKERS.iter().enumerate().filter(|_| with_trackers) {
            let score = |preds: &[LaneEstimate]| -> Result<(f64, f64), Box<dyn std::error::Error>> {
                let refs: Vec<Option<&LaneEstimate>> = preds.iter().map(Some).collect();
                let r = evaluate(&gt, &refs)?;
                Ok((
                    100.0 * r.boundaries.accuracy.unwrap_or(0.0),
                    100.0 * r.params.detection_rate.unwrap_or(0.0),
                ))
            };
            // Accuracy and detection rate averaged over the tracker's seeds.
            let mean_score =
                |camera: &CameraFile| -> Result<(f64, f64), Box<dyn std::error::Error>> {
                    let (mut a, mut d) = (0.0, 0.0);
                    for tracker_seed in 1..=tracker_seeds {
                        let (ai, di) = score(&track(id, camera, &frames, preset, tracker_seed)?)?;
                        (a, d) = (a + ai, d + di);
                    }
                    let n = tracker_seeds.max(1) as f64;
                    Ok((a / n, d / n))
                };
            let (a_true, d_true) = mean_score(&truth_cam)?;
            let (a_auto, d_auto) = mean_score(c)?;
            losses[k].push(a_true - a_auto);
            cells.push(format!(
                "{a_true:.1} / {a_auto:.1} (det {d_true:.0} / {d_auto:.0})"
            ));
        }
        println!(
            "| {seed} | {name} | {:.2} / {:.2} / {:.2} / {hfov:.0} | {dp:+.2} | {dy:+.2} | {dyl:+.2} | {:+.1} % | {:.2} | {}{} | {no_intr} | {} |",
            truth_cam.pitch_deg,
            truth_cam.yaw_deg,
            truth_cam.height_m,
            100.0 * dh,
            est.confidence,
            est.frames_used,
            if est.yaw_from_tangent { " t" } else { "" },
            cells.join(" | ")
        );
    }
    let summary = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        let n = v.len();
        if n == 0 {
            return "-".to_string();
        }
        format!("median {:.2}, max {:.2}", v[n / 2], v[n - 1])
    };
    println!();
    println!("|pitch| error deg: {}", summary(&mut ep));
    println!("|yaw| error deg: {}", summary(&mut ey));
    println!(
        "|yaw| error relative to the lane over the frames used, deg: {}",
        summary(&mut eyl)
    );
    println!("|height| error (fraction): {}", summary(&mut eh));
    for (k, id) in TRACKERS.iter().enumerate() {
        let mean = losses[k].iter().sum::<f64>() / losses[k].len().max(1) as f64;
        println!(
            "{id}: boundary accuracy true - auto camera, mean {mean:+.2} points, {}",
            summary(&mut losses[k])
        );
    }
    Ok(())
}
