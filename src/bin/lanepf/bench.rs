//! `lanepf bench`: time trackers on a standard synthetic sequence (`highway-curve`, seed 1)
//! at 640x480 and 1280x720 (or the given size): median and 95th-percentile ms per frame, and
//! the mean split per stage (a stereo tracker's disparity is part of its preprocess time and
//! also shown on its own; rendering the right frame is not timed, handing it over is).
//! `--warmup N --motion` runs the sequence as the browser bench (`www/bench.html`) does: the
//! first N frames stepped but not timed, and every tracker given the car's motion from the
//! ground truth before each frame. `--preset real-roads` times our options beyond the papers
//! (what the demo runs on real footage: the re-lock detector, the neighbouring lanes, ...)
//! instead of each paper's filter.

use lanepf::synth::{default_camera, scenario, Eye, Scene};
use lanepf::trackers::{
    self, EgoMotion, Preset, StageTimes, TrackerConfig, TrackerOptions, TRACKER_IDS,
};
use lanepf::{Error, Result};
use std::time::Instant;

/// Options of `lanepf bench`.
#[derive(clap::Args)]
pub struct Args {
    /// Tracker id, or `all`.
    #[arg(long, default_value = "all")]
    tracker: String,
    /// Frames per run.
    #[arg(long, default_value_t = 100)]
    frames: u32,
    /// First frames of each run stepped but not timed (fewer than --frames).
    #[arg(long, default_value_t = 0)]
    warmup: u32,
    /// Give every tracker the car's motion from the ground truth before each frame (as the demo
    /// and the browser bench do; the Danescu trackers drift their particles by it).
    #[arg(long)]
    motion: bool,
    /// Only this width (with --height); default: 640x480 and 1280x720.
    #[arg(long, requires = "height")]
    width: Option<usize>,
    /// Only this height.
    #[arg(long, requires = "width")]
    height: Option<usize>,
    /// Named option set each tracker runs with: `paper` (each paper's filter) or `real-roads`
    /// (our options beyond the papers, as the demo runs on real footage).
    #[arg(long, default_value = "paper")]
    preset: String,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

/// One tracker at one size.
#[derive(serde::Serialize)]
struct Row {
    tracker: String,
    preset: String,
    /// Every option the tracker ran with (the preset's).
    options: TrackerOptions,
    width: usize,
    height: usize,
    frames: u32,
    /// Of `frames`, the first ones not timed.
    warmup: u32,
    median_ms: f64,
    p95_ms: f64,
    stages_ms: StageTimes,
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    let k = ((sorted.len() - 1) as f64 * p).round() as usize;
    sorted[k]
}

/// Runs the command.
pub fn run(args: Args) -> Result<()> {
    let ids: Vec<String> = if args.tracker == "all" {
        TRACKER_IDS.iter().map(|s| s.to_string()).collect()
    } else {
        vec![args.tracker.clone()]
    };
    if ids.is_empty() {
        return Err(Error::Config(
            "no tracker is implemented yet, so there is nothing to benchmark (the paper \
             trackers land one by one; `cargo bench` times the vision operations and the filter)"
                .into(),
        ));
    }
    let preset: Preset = args.preset.parse()?;
    if args.frames == 0 {
        return Err(Error::parameter("--frames", 0, "must be at least 1"));
    }
    if args.warmup >= args.frames {
        return Err(Error::parameter(
            "--warmup",
            args.warmup,
            "must be below --frames (some frames must be timed)",
        ));
    }
    let sizes = match (args.width, args.height) {
        (Some(w), Some(h)) => vec![(w, h)],
        _ => vec![(640, 480), (1280, 720)],
    };
    let mut rows = Vec::new();
    for (w, h) in sizes {
        let camera = default_camera(w, h)?;
        let mut scene = Scene::new(scenario("highway-curve")?, camera.clone(), 1)?;
        let mut frame = vec![0u8; w * h * 4];
        let mut right = vec![0u8; w * h * 4];
        for id in &ids {
            let options = TrackerOptions::preset(id, preset)?;
            let config = TrackerConfig::new(camera.to_file(), options.clone());
            let mut tracker = trackers::build(&config)?;
            let mut times = Vec::with_capacity(args.frames as usize);
            let mut stages = StageTimes::default();
            for i in 0..args.frames {
                // Rendering is not timed: only the tracker's step is.
                scene.render(i, Eye::Left, &mut frame, None)?;
                if tracker.is_stereo() {
                    scene.render(i, Eye::Right, &mut right, None)?;
                }
                if args.motion {
                    let state = scene.truth(i).state;
                    tracker.set_ego_motion(EgoMotion {
                        t_s: state["t"],
                        speed_mps: state["speed_mps"],
                        yaw_rate: state["yaw_rate"],
                    })?;
                }
                let start = Instant::now();
                if tracker.is_stereo() {
                    tracker.set_right(&right, w, h)?;
                }
                tracker.step(&frame, w, h)?;
                let ms = start.elapsed().as_secs_f64() * 1e3;
                if i < args.warmup {
                    continue;
                }
                times.push(ms);
                let s = tracker.stage_times();
                stages.preprocess += s.preprocess;
                stages.disparity += s.disparity;
                stages.predict += s.predict;
                stages.weigh += s.weigh;
                stages.resample += s.resample;
                stages.estimate += s.estimate;
            }
            let n = times.len() as f64;
            times.sort_by(f64::total_cmp);
            rows.push(Row {
                tracker: id.clone(),
                preset: args.preset.clone(),
                options,
                width: w,
                height: h,
                frames: args.frames,
                warmup: args.warmup,
                median_ms: percentile(&times, 0.5),
                p95_ms: percentile(&times, 0.95),
                stages_ms: StageTimes {
                    preprocess: stages.preprocess / n,
                    disparity: stages.disparity / n,
                    predict: stages.predict / n,
                    weigh: stages.weigh / n,
                    resample: stages.resample / n,
                    estimate: stages.estimate / n,
                },
            });
        }
    }
    let mut text = String::new();
    if args.json {
        text = serde_json::to_string_pretty(&rows).map_err(|e| Error::Config(e.to_string()))?;
        text.push('\n');
    } else {
        text += &format!(
            "{:18} {:>10} {:>9} {:>9} {:>11} {:>10} {:>9} {:>9} {:>10} {:>10}",
            "tracker",
            "size",
            "median",
            "p95",
            "preprocess",
            "(disparity)",
            "predict",
            "weigh",
            "resample",
            "estimate"
        );
        text.push('\n');
        for r in rows {
            let s = r.stages_ms;
            text += &format!(
                "{:18} {:>10} {:>9.2} {:>9.2} {:>11.2} {:>10.2} {:>9.2} {:>9.2} {:>10.2} {:>10.2}",
                r.tracker,
                format!("{}x{}", r.width, r.height),
                r.median_ms,
                r.p95_ms,
                s.preprocess,
                s.disparity,
                s.predict,
                s.weigh,
                s.resample,
                s.estimate
            );
            text.push('\n');
        }
    }
    super::out(&text)
}
