//! "No lane" as an answer: every mono tracker through unmarked crossings of a simulated road.
//!
//! `cargo run --release --example no_lane_eval -- [SEED_FROM SEED_TO] [SCENARIO] [TRACKERS]
//! [OPTIONS]` (defaults: seeds 301..=312, `highway-straight`, every mono tracker; `TRACKERS` a
//! comma-separated list of ids; `OPTIONS` a JSON object of options set on top of both presets,
//! e.g. `'{"valid_marking_factor": 3}'` with `danescu-mono`).
//!
//! Each seed renders the scenario for [`FRAMES`] frames through its drawn camera
//! (`synth::drawn_camera`; the trackers get the true camera) with every marking of the road
//! removed over [`CROSSINGS`] (a simplification of a crossing: no stop line, crosswalk or cross
//! traffic is drawn). A frame is *unmarked* when the car's next [`NO_LANE_AHEAD_M`] metres
//! lie inside a crossing (Caltech's labelled crossings start their markings about 11 m ahead),
//! *marked* when its next [`MARKED_AHEAD_M`] metres touch no crossing (and the run is past
//! its first second); the frames between are not scored. For each tracker, with the papers'
//! defaults and with `real-roads`: the share of unmarked frames called valid (a lane drawn
//! where there is none), the share of marked frames called not valid, and the re-lock time
//! after each crossing: frames from the first frame whose next `NO_LANE_AHEAD_M` metres reach
//! markings again until the estimate is valid with its lateral offset within
//! [`RECOVERY_THRESHOLD_M`] of the truth (`eval::synthetic::recovery`'s rule); "-" when it
//! does not within the run.

use lanepf::camera::Camera;
use lanepf::eval::params::{error_series, recovery_frames};
use lanepf::eval::synthetic::RECOVERY_THRESHOLD_M;
use lanepf::lane::LaneEstimate;
use lanepf::synth::{drawn_camera, scenario, Eye, Scene, Wear};
use lanepf::trackers::{self, Preset, TrackerConfig};

const TRACKERS: [&str; 4] = ["adachi-mmpf", "danescu-mono", "lee-cpf", "liu-ppf"];
/// Frames a run (12 s at 30 frames a second).
const FRAMES: u32 = 360;
/// Unmarked stretches, metres along the road.
const CROSSINGS: [[f64; 2]; 2] = [[90.0, 120.0], [210.0, 240.0]];
/// A frame is unmarked when this stretch ahead of the car lies inside a crossing, metres.
const NO_LANE_AHEAD_M: f64 = 10.0;
/// A frame is marked when this stretch ahead touches no crossing, metres.
const MARKED_AHEAD_M: f64 = 30.0;
/// Frames at the start that are not scored (the filters' first lock).
const SETTLE_FRAMES: usize = 30;

/// Whether the stretch [s, s + ahead] lies inside a crossing, and whether it touches one.
fn stretch(s: f64, ahead: f64) -> (bool, bool) {
    let inside = CROSSINGS.iter().any(|c| s >= c[0] && s + ahead <= c[1]);
    let touches = CROSSINGS.iter().any(|c| s + ahead >= c[0] && s <= c[1]);
    (inside, touches)
}

fn track(
    id: &str,
    scene_camera: &lanepf::camera::CameraFile,
    frames: &[Vec<u8>],
    preset: Preset,
    extra: &serde_json::Map<String, serde_json::Value>,
) -> Result<Vec<LaneEstimate>, Box<dyn std::error::Error>> {
    let mut options = extra.clone();
    if let serde_json::Value::Object(base) = trackers::preset_options(id, preset)? {
        for (key, value) in base {
            options.entry(key).or_insert(value);
        }
    }
    options.insert("camera".into(), serde_json::to_value(scene_camera)?);
    options.insert("seed".into(), 1.into());
    let config = TrackerConfig::from_json_str(&serde_json::Value::Object(options).to_string())?;
    let mut tracker = trackers::create(id, &config)?;
    let mut out = Vec::with_capacity(frames.len());
    for f in frames {
        out.push(tracker.step(f, scene_camera.width, scene_camera.height)?);
    }
    Ok(out)
}

/// Totals of one tracker and preset over the seeds.
#[derive(Default)]
struct Tally {
    unmarked: usize,
    unmarked_valid: usize,
    marked: usize,
    marked_invalid: usize,
    relock: Vec<Option<usize>>,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let from: u64 = args.get(1).map_or(Ok(301), |s| s.parse())?;
    let to: u64 = args.get(2).map_or(Ok(312), |s| s.parse())?;
    let name = args.get(3).map_or("highway-straight", String::as_str);
    let ids: Vec<&str> = match args.get(4) {
        Some(list) => list.split(',').collect(),
        None => TRACKERS.to_vec(),
    };
    if let Some(bad) = ids.iter().find(|id| !TRACKERS.contains(id)) {
        return Err(format!("{bad} is not one of {}", TRACKERS.join(", ")).into());
    }
    let extra: serde_json::Map<String, serde_json::Value> = match args.get(5) {
        Some(json) => serde_json::from_str(json)?,
        None => serde_json::Map::new(),
    };
    let presets = [Preset::Paper, Preset::RealRoads];
    let mut tallies: Vec<Tally> = (0..ids.len() * presets.len())
        .map(|_| Tally::default())
        .collect();
    for seed in from..=to {
        let truth_cam = drawn_camera(seed);
        let mut config = scenario(name)?;
        config.frames = FRAMES;
        config.markings.wear.extend(CROSSINGS.iter().map(|c| Wear {
            from_s: c[0],
            to_s: c[1],
            boundary: None,
            visibility: 0.0,
        }));
        let mut scene = Scene::new(config, Camera::from_file(&truth_cam)?, seed)?;
        let (w, h) = (scene.width(), scene.height());
        let mut frames = Vec::new();
        let mut gt = Vec::new();
        let mut kind = Vec::new();
        for i in 0..FRAMES {
            let mut rgba = vec![0u8; w * h * 4];
            scene.render(i, Eye::Left, &mut rgba, None)?;
            frames.push(rgba);
            gt.push(trackers::scene_truth(&scene, i));
            let s = scene.pose(i).s;
            let unmarked = stretch(s, NO_LANE_AHEAD_M).0;
            let marked = !stretch(s, MARKED_AHEAD_M).1 && i as usize >= SETTLE_FRAMES;
            kind.push((unmarked, marked));
        }
        // The first frame after each run of unmarked frames whose stretch reaches markings.
        let ends: Vec<usize> = (1..kind.len())
            .filter(|&i| kind[i - 1].0 && !kind[i].0)
            .collect();
        let mut cells = Vec::new();
        for (t, id) in ids.iter().enumerate() {
            for (p, preset) in presets.iter().enumerate() {
                let preds = track(id, &truth_cam, &frames, *preset, &extra)?;
                let tally = &mut tallies[t * presets.len() + p];
                let (mut u, mut uv, mut m, mut mi) = (0, 0, 0, 0);
                for (e, &(unmarked, marked)) in preds.iter().zip(&kind) {
                    u += usize::from(unmarked);
                    uv += usize::from(unmarked && e.valid);
                    m += usize::from(marked);
                    mi += usize::from(marked && !e.valid);
                }
                let refs: Vec<Option<&LaneEstimate>> = preds.iter().map(Some).collect();
                let errors = error_series(&gt, &refs, |e| e.lateral_offset_m);
                let relock = recovery_frames(&errors, RECOVERY_THRESHOLD_M, &ends)?;
                let relock_text: Vec<String> = relock
                    .iter()
                    .map(|r| r.map_or("-".to_string(), |f| f.to_string()))
                    .collect();
                cells.push(format!(
                    "{uv}/{u} valid, {mi}/{m} not, re-lock {}",
                    relock_text.join(" ")
                ));
                tally.unmarked += u;
                tally.unmarked_valid += uv;
                tally.marked += m;
                tally.marked_invalid += mi;
                tally.relock.extend(relock);
            }
        }
        println!("seed {seed} ({name}): {}", cells.join(" | "));
    }
    println!();
    println!("| tracker | preset | unmarked frames called valid | marked frames called not valid | re-lock frames, median (max; not within the run) |");
    println!("|---|---|---|---|---|");
    for (t, id) in ids.iter().enumerate() {
        for (p, preset) in ["paper", "real-roads"].iter().enumerate() {
            let tally = &tallies[t * presets.len() + p];
            let mut times: Vec<usize> = tally.relock.iter().flatten().copied().collect();
            times.sort_unstable();
            let missing = tally.relock.len() - times.len();
            let median = times
                .get(times.len() / 2)
                .map_or("-".into(), |m| m.to_string());
            let max = times.last().map_or("-".into(), |m| m.to_string());
            let pct = |a: usize, b: usize| 100.0 * a as f64 / b.max(1) as f64;
            println!(
                "| {id} | {preset} | {:.1} % ({} of {}) | {:.1} % ({} of {}) | {median} ({max}; {missing} of {}) |",
                pct(tally.unmarked_valid, tally.unmarked),
                tally.unmarked_valid,
                tally.unmarked,
                pct(tally.marked_invalid, tally.marked),
                tally.marked_invalid,
                tally.marked,
                tally.relock.len()
            );
        }
    }
    Ok(())
}
