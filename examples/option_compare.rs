//! Measures a tracker option against another on every dataset together: the A/B check for
//! a change beyond a paper (issue 18: "measure both", "do not tune to a single dataset").
//!
//! `cargo run --release --example option_compare -- TRACKER 'OPTIONS_A' 'OPTIONS_B' [SEED_FROM
//! SEED_TO] [DATA_DIR]`, options as JSON objects (`'{}'` is the default tracker), seeds
//! 201..=213 and `../shared/data` by default. For each option set it prints:
//! - synthetic: every named scenario, cycled over the seeds (201..=213 covers each once), each
//!   seed through its own drawn camera (`synth::drawn_camera`, 640x480, 150 frames), the true
//!   camera given: mean boundary accuracy (`lanepf eval --format synthetic`'s "boundaries") and
//!   detection rate, and the worst scenario;
//! - Caltech cordova1 as a sequence with its camera, tracker seeds 1..=5 (77 frames are few
//!   and a run's figures move by several points with the seed): Aly ego lanes correct / false
//!   positives and all lanes correct, mean and range over the seeds;
//! - TuSimple, still mode (reset, 5 iterations a frame) with the camera auto-calibrated from the
//!   same stills: official accuracy / FP / FN;
//! - ms a frame (native, the Caltech run).
//!
//! With `OPTION_COMPARE_SCENES` set, each synthetic scene's figures go to stderr as well.

use lanepf::calib::{Calibrator, CalibratorConfig};
use lanepf::camera::{Camera, CameraFile};
use lanepf::eval::{evaluate_with, synthetic, EvalOptions, Format, Metrics};
use lanepf::image::{read_rgba, RgbaFrame};
use lanepf::lane::LaneEstimate;
use lanepf::synth::{drawn_camera, scenario, Eye, Scene, SCENARIOS};
use lanepf::trackers::{self, TrackerConfig};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

type Res<T> = Result<T, Box<dyn std::error::Error>>;
type Options = BTreeMap<String, serde_json::Value>;

const SYNTH_FRAMES: u32 = 150;
const STILL_ITERATIONS: u32 = 5;
const CALTECH_SEEDS: u64 = 5;

fn run(
    id: &str,
    seed: u64,
    options: &Options,
    camera: &CameraFile,
    frames: &[&[u8]],
    still: bool,
) -> Res<(Vec<LaneEstimate>, f64)> {
    let config = TrackerConfig {
        camera: camera.clone(),
        particles: None,
        seed,
        options: trackers::Options::ByName(options.clone()),
    };
    let mut tracker = trackers::create(id, &config)?;
    let mut out = Vec::with_capacity(frames.len());
    let t0 = Instant::now();
    for f in frames {
        let iterations = if still {
            tracker.reset();
            STILL_ITERATIONS
        } else {
            1
        };
        let mut e = tracker.step(f, camera.width, camera.height)?;
        for _ in 1..iterations {
            e = tracker.step(f, camera.width, camera.height)?;
        }
        out.push(e);
    }
    let ms = 1e3 * t0.elapsed().as_secs_f64() / frames.len().max(1) as f64;
    Ok((out, ms))
}

fn list(dir: &Path) -> Res<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "png" || x == "jpg"))
        .collect();
    files.sort();
    Ok(files)
}

fn read_all(paths: &[PathBuf]) -> Res<Vec<(RgbaFrame, String)>> {
    paths
        .iter()
        .map(|p| {
            let name = p
                .file_name()
                .map_or(String::new(), |n| n.to_string_lossy().into_owned());
            Ok((read_rgba(p)?, name))
        })
        .collect()
}

/// Scores `preds` (named by `frames`) against the labels at `gt`.
fn score(
    format: Format,
    gt: &Path,
    frames: &[(RgbaFrame, String)],
    mut preds: Vec<LaneEstimate>,
) -> Res<Metrics> {
    for (p, (_, name)) in preds.iter_mut().zip(frames) {
        p.frame = name.clone();
    }
    let options = EvalOptions {
        tusimple_time_limit_ms: None,
        ..EvalOptions::default()
    };
    Ok(evaluate_with(format, &preds, gt, &options)?.metrics)
}

/// One rendered scene: its name, frames, truth and camera.
type SynthScene = (String, Vec<Vec<u8>>, Vec<LaneEstimate>, CameraFile);

struct Synthetic {
    scenes: Vec<SynthScene>,
}

impl Synthetic {
    fn render(from: u64, to: u64) -> Res<Self> {
        let names: Vec<&str> = SCENARIOS.iter().map(|(n, _)| *n).collect();
        let mut scenes = Vec::new();
        for seed in from..=to {
            let name = names[(seed - from) as usize % names.len()];
            let file = drawn_camera(seed);
            let mut config = scenario(name)?;
            config.frames = SYNTH_FRAMES;
            let mut scene = Scene::new(config, Camera::from_file(&file)?, seed)?;
            let (w, h) = (scene.width(), scene.height());
            let (mut frames, mut gt) = (Vec::new(), Vec::new());
            for i in 0..SYNTH_FRAMES {
                let mut rgba = vec![0u8; w * h * 4];
                scene.render(i, Eye::Left, &mut rgba, None)?;
                frames.push(rgba);
                gt.push(lanepf::trackers::scene_truth(&scene, i));
            }
            scenes.push((format!("{name}/{seed}"), frames, gt, file));
        }
        Ok(Self { scenes })
    }

    fn measure(&self, id: &str, options: &Options) -> Res<String> {
        let (mut acc, mut det, mut worst) = (0.0, 0.0, (f64::INFINITY, String::new()));
        for (name, frames, gt, camera) in &self.scenes {
            let refs: Vec<&[u8]> = frames.iter().map(Vec::as_slice).collect();
            let (preds, _) = run(id, 1, options, camera, &refs, false)?;
            let p: Vec<Option<&LaneEstimate>> = preds.iter().map(Some).collect();
            let r = synthetic::evaluate(gt, &p)?;
            let a = 100.0 * r.boundaries.accuracy.unwrap_or(0.0);
            acc += a;
            det += 100.0 * r.params.detection_rate.unwrap_or(0.0);
            if a < worst.0 {
                worst = (a, name.clone());
            }
            if std::env::var_os("OPTION_COMPARE_SCENES").is_some() {
                eprintln!(
                    "    {name} (fx {:.0}): boundaries {a:.1} %, detected {:.1} %",
                    camera.fx,
                    100.0 * r.params.detection_rate.unwrap_or(0.0)
                );
            }
        }
        let n = self.scenes.len().max(1) as f64;
        Ok(format!(
            "synthetic ({} scenes): boundaries {:.1} %, detected {:.1} %, worst {:.1} on {}",
            self.scenes.len(),
            acc / n,
            det / n,
            worst.0,
            worst.1
        ))
    }
}

/// "mean % (min-max)" of per-seed percentages.
fn spread(v: &[f64]) -> String {
    let mean = v.iter().sum::<f64>() / v.len().max(1) as f64;
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    format!("{mean:.1} % ({lo:.1}-{hi:.1})")
}

fn auto_camera(frames: &[(RgbaFrame, String)]) -> Res<CameraFile> {
    let f0 = &frames.first().ok_or("no frames")?.0;
    let config = CalibratorConfig {
        stable_frames: 1,
        ..CalibratorConfig::default()
    };
    let mut cal = Calibrator::new(f0.width, f0.height, None, config)?;
    for (f, _) in frames {
        cal.feed_rgba(&f.data, f.width, f.height)?;
    }
    Ok(cal.estimate().ok_or("no auto camera")?.camera)
}

fn main() -> Res<()> {
    let args: Vec<String> = std::env::args().collect();
    let usage = "option_compare TRACKER 'OPTIONS_A' 'OPTIONS_B' [SEED_FROM SEED_TO] [DATA_DIR]";
    let id = args.get(1).ok_or(usage)?;
    let sets: Vec<Options> = args
        .get(2..4)
        .ok_or(usage)?
        .iter()
        .map(|s| serde_json::from_str(s))
        .collect::<Result<_, _>>()?;
    let from: u64 = args.get(4).map_or(Ok(201), |s| s.parse())?;
    let to: u64 = args.get(5).map_or(Ok(213), |s| s.parse())?;
    let data = PathBuf::from(args.get(6).map_or("../shared/data", |s| s.as_str()));
    let caltech = data.join("caltech-cordova1");
    let caltech_frames = read_all(&list(&caltech.join("frames"))?)?;
    let caltech_camera = CameraFile::read(&caltech.join("camera.json"))?;
    let tusimple_frames = read_all(&list(&data.join("tusimple/images"))?)?;
    let tusimple_camera = auto_camera(&tusimple_frames)?;
    eprintln!("rendering seeds {from}..={to}");
    let synthetic = Synthetic::render(from, to)?;
    for (k, options) in sets.iter().enumerate() {
        let label = args[2 + k].as_str();
        let refs: Vec<&[u8]> = caltech_frames
            .iter()
            .map(|(f, _)| f.data.as_slice())
            .collect();
        let (mut ego, mut fp, mut all, mut ms) = (Vec::new(), Vec::new(), Vec::new(), 0.0);
        for seed in 1..=CALTECH_SEEDS {
            let (preds, t) = run(id, seed, options, &caltech_camera, &refs, false)?;
            ms += t / CALTECH_SEEDS as f64;
            let labels = caltech.join("labels.json");
            if let Metrics::Caltech(r) = score(Format::Caltech, &labels, &caltech_frames, preds)? {
                ego.push(100.0 * r.ego_lanes.correct_rate.unwrap_or(0.0));
                fp.push(100.0 * r.ego_lanes.false_positive_rate.unwrap_or(0.0));
                all.push(100.0 * r.all_lanes.correct_rate.unwrap_or(0.0));
            }
        }
        let c = format!(
            "Caltech ego {} / {} FP, all {}",
            spread(&ego),
            spread(&fp),
            spread(&all)
        );
        let refs: Vec<&[u8]> = tusimple_frames
            .iter()
            .map(|(f, _)| f.data.as_slice())
            .collect();
        let (preds, _) = run(id, 1, options, &tusimple_camera, &refs, true)?;
        let t = match score(
            Format::Tusimple,
            &data.join("tusimple/labels.json"),
            &tusimple_frames,
            preds,
        )? {
            Metrics::Tusimple(r) => format!(
                "TuSimple (auto camera) acc {:.1} FP {:.2} FN {:.2}",
                100.0 * r.accuracy,
                r.fp,
                r.fn_rate
            ),
            _ => String::new(),
        };
        println!("{id} {label}");
        println!("  {}", synthetic.measure(id, options)?);
        println!("  {c}; {ms:.2} ms a frame");
        println!("  {t}");
    }
    Ok(())
}
