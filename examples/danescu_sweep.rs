//! danescu-mono or danescu-stereo on the simulator: per scenario, over several seeds at 640x480
//! with the simulator's ego motion, the RMSE of the lateral offset, yaw, horizontal curvature,
//! lane width W_0 (inner edges; also its mean absolute error, in mm and in % of the true
//! width, the paper's measure in Fig. 10), width change W_l, vertical curvature C_V, pitch,
//! roll and height offset Y_0, the mean absolute error of each marking width W_L, W_R, the
//! valid rate, the median effective sample size after weighing and the median ms/frame
//! (indicative: the runs share the machine). Each scenario runs twice: with the marking-width
//! model and the gradient cue (the paper's new approach) and without (`marking_widths:
//! false`, its previous approach, Fig. 10).
//! `cargo run --release --example danescu_sweep -- [--config JSON] [--new-only] [ID] [SEEDS]
//! [FRAMES] [SCENARIO...]`: `--config` adds options to every run (e.g. `{"sigma_density": 1}`),
//! `--new-only` skips the previous approach.

use lanepf::synth::{default_camera, scenario, Eye, Scene};
use lanepf::trackers::danescu::config::DanescuConfig;
use lanepf::trackers::{build, EgoMotion, TrackerConfig, TrackerOptions};

#[derive(Default)]
struct Sums {
    n: f64,
    offset: f64,
    psi: f64,
    ch: f64,
    w0: f64,
    w0_abs: f64,
    w0_rel: f64,
    wl: f64,
    cv: f64,
    gamma: f64,
    alpha: f64,
    y0: f64,
    marks: [f64; 2],
    valid: f64,
    ms: Vec<f64>,
    ess: Vec<f64>,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().collect();
    // The options every run starts from: the defaults, or `--config`'s object read into the
    // typed config (an unknown option is an error here).
    let mut extra = String::new();
    let mut base = DanescuConfig::default();
    if let Some(k) = args.iter().position(|a| a == "--config") {
        let json = args
            .get(k + 1)
            .ok_or("--config needs a JSON object")?
            .clone();
        base = serde_json::from_str(&json)?;
        extra = format!(", options {json}");
        args.drain(k..k + 2);
    }
    let models: &[bool] = if let Some(k) = args.iter().position(|a| a == "--new-only") {
        args.remove(k);
        &[true]
    } else {
        &[true, false]
    };
    let id = args
        .get(1)
        .map_or("danescu-mono", String::as_str)
        .to_string();
    let seeds: u64 = args.get(2).map_or(Ok(3), |s| s.parse())?;
    let frames: u32 = args.get(3).map_or(Ok(150), |s| s.parse())?;
    let names: Vec<String> = if args.len() > 4 {
        args[4..].to_vec()
    } else {
        [
            "highway-straight",
            "highway-curve",
            "s-curve",
            "width-change",
            "pitch-bumps",
            "shadows",
        ]
        .map(String::from)
        .to_vec()
    };
    let camera = default_camera(640, 480)?;
    println!(
        "{id}: {seeds} seeds x {frames} frames, N = 500, 640x480, first 30 frames of each run skipped{}",
        extra
    );
    println!();
    println!("| scenario | model | offset RMSE (m) | psi RMSE (rad) | C_H RMSE (1/m) | W_0 RMSE (m) | W_0 MAE (mm, %) | W_l RMSE | C_V RMSE (1/m) | pitch RMSE (mrad) | roll RMSE (mrad) | Y_0 RMSE (cm) | W_L MAE (mm) | W_R MAE (mm) | valid | ESS (median) | ms/frame (median) |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for name in &names {
        for &marking_widths in models {
            let mut s = Sums::default();
            for seed in 1..=seeds {
                let mut scene = Scene::new(scenario(name)?, camera.clone(), seed)?;
                let options = DanescuConfig {
                    marking_widths,
                    ..base.clone()
                };
                let options = match id.as_str() {
                    "danescu-stereo" => TrackerOptions::DanescuStereo(options),
                    "danescu-mono" => TrackerOptions::DanescuMono(options),
                    other => return Err(format!("{other} is not a Danescu tracker").into()),
                };
                let config = TrackerConfig::new(camera.to_file(), options).with_seed(seed);
                let mut tracker = build(&config)?;
                let mut rgba = vec![0; 640 * 480 * 4];
                let mut right = vec![0; 640 * 480 * 4];
                for f in 0..frames {
                    let pose = scene.render(f, Eye::Left, &mut rgba, None)?;
                    if tracker.is_stereo() {
                        scene.render(f, Eye::Right, &mut right, None)?;
                        tracker.set_right(&right, 640, 480)?;
                    }
                    tracker.set_ego_motion(EgoMotion {
                        t_s: pose.t,
                        speed_mps: pose.speed,
                        yaw_rate: pose.yaw_rate,
                    })?;
                    let t0 = std::time::Instant::now();
                    let e = tracker.step(&rgba, 640, 480)?;
                    s.ms.push(t0.elapsed().as_secs_f64() * 1e3);
                    if f < 30 {
                        continue;
                    }
                    let t = lanepf::trackers::scene_truth(&scene, f);
                    let sq = |k: &str| (t.state[k] - e.state[k]).powi(2);
                    s.n += 1.0;
                    s.offset += sq("danescu.xcw");
                    s.psi += sq("danescu.psi");
                    s.ch += sq("danescu.ch");
                    s.w0 += sq("danescu.w0");
                    let w0_err = (t.state["danescu.w0"] - e.state["danescu.w0"]).abs();
                    s.w0_abs += w0_err;
                    s.w0_rel += w0_err / t.state["danescu.w0"];
                    s.wl += sq("danescu.wl");
                    s.cv += sq("danescu.cv");
                    s.gamma += sq("danescu.gamma");
                    s.alpha += sq("danescu.alpha");
                    s.y0 += sq("danescu.y0");
                    for (m, k) in s
                        .marks
                        .iter_mut()
                        .zip(["danescu.wl_mark", "danescu.wr_mark"])
                    {
                        // Absent without the marking-width model: counted as NaN (n/a).
                        let v = e.state.get(k).copied().unwrap_or(f64::NAN);
                        *m += (t.state[k] - v).abs();
                    }
                    s.valid += f64::from(u8::from(e.valid));
                    s.ess.push(e.state["danescu.ess"]);
                }
            }
            s.ms.sort_by(f64::total_cmp);
            s.ess.sort_by(f64::total_cmp);
            let r = |x: f64| (x / s.n).sqrt();
            println!(
                "| {name} | {} | {:.3} | {:.4} | {:.5} | {:.3} | {:.1}, {:.2} % | {:.4} | {:.5} | {:.1} | {:.2} | {:.1} | {:.1} | {:.1} | {:.1} % | {:.0} | {:.1} |",
                if marking_widths {
                    "marking widths + gradient"
                } else {
                    "previous (no widths, no gradient)"
                },
                r(s.offset),
                r(s.psi),
                r(s.ch),
                r(s.w0),
                1e3 * s.w0_abs / s.n,
                1e2 * s.w0_rel / s.n,
                r(s.wl),
                r(s.cv),
                1e3 * r(s.alpha),
                1e3 * r(s.gamma),
                1e2 * r(s.y0),
                1e3 * s.marks[0] / s.n,
                1e3 * s.marks[1] / s.n,
                100.0 * s.valid / s.n,
                s.ess[s.ess.len() / 2],
                s.ms[s.ms.len() / 2],
            );
        }
    }
    Ok(())
}
