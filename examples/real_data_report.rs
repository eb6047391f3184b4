//! The real-data regression report: every mono tracker on every labelled real dataset in
//! `../shared/data`, and on the Udacity videos by eye, as one tracker x dataset table; its last
//! row is the classical pipeline the trackers are compared with ([`ClassicalBaseline`]).
//!
//! `cargo run --release --example real_data_report -- [DATA_DIR] [OUT_DIR] [UDACITY_FRAMES]`
//! (defaults `../shared/data`, `target/real-data`, 300 frames of each Udacity video). Writes
//! OUT_DIR/report.md (the table, also printed) and OUT_DIR/sheet-<video>-<camera>.png: one
//! row of sampled frames per tracker with its boundaries drawn (ego-left red, ego-right blue,
//! others yellow; thin when the frame is not valid), for judging the Udacity videos by eye,
//! and OUT_DIR/per-frame/row<NN> -- <dataset>.txt, each labelled frame's figures with the
//! failing ones marked (`lanepf eval --per-frame`; the rows' names in per-frame/rows.txt).
//! The Udacity frames are cut once with ffmpeg into OUT_DIR/frames/. With the environment
//! variable `REAL_DATA_ROWS` set, only the rows whose name contains it run (e.g.
//! `REAL_DATA_ROWS=adachi`); with `REAL_DATA_RUNS` set, only the datasets (columns) whose
//! label contains it (e.g. `REAL_DATA_RUNS=CULane`; the Udacity frames are still cut).
//!
//! Datasets and cameras (a camera the data ships, or `auto`: `lanepf::calib` on the same
//! frames first, with the known intrinsics where there are some):
//! - Caltech cordova1, 77 frames as a sequence: Aly's rule, ego lanes and all lanes;
//! - CULane 06030819_0755, 60 frames 3 s apart: still mode (5 iterations a frame), auto camera
//!   from the frames as stills, and an oracle camera from the labels (the dataset has none),
//!   F1 at IoU 0.5 on 30 px lanes;
//! - TuSimple, 6 frames: still mode, auto camera as stills, the official accuracy / FP / FN;
//! - Udacity project_video and challenge_video (1280x720), the chessboard intrinsics with the
//!   demo's pose and auto: valid rate, and the sheets.

use lanepf::baseline::ClassicalBaseline;
use lanepf::calib::{Calibrator, CalibratorConfig};
use lanepf::camera::{Camera, CameraFile};
use lanepf::eval::{evaluate_with, EvalOptions, Format, Metrics};
use lanepf::image::{read_rgba, write_rgba_png, RgbaFrame};
use lanepf::lane::{LaneEstimate, Role};
use lanepf::trackers::adachi::config::{AdachiConfig, EdgeResponse, LaneShape};
use lanepf::trackers::danescu::config::DanescuConfig;
use lanepf::trackers::lee::config::LeeConfig;
use lanepf::trackers::liu::config::LiuConfig;
use lanepf::trackers::{self, Preset, Tracker, TrackerConfig, TrackerOptions};
use std::path::{Path, PathBuf};

/// Each row: the options a tracker runs with (which name the tracker), so that a named option
/// beyond a paper is reported beside the paper's method; the table names a row by the options
/// that differ from the defaults.
const TRACKERS: [fn() -> TrackerOptions; 23] = [
    || TrackerOptions::AdachiMmpf(AdachiConfig::default()),
    || {
        TrackerOptions::AdachiMmpf(AdachiConfig {
            lane_shape: LaneShape::Curved,
            ..AdachiConfig::default()
        })
    },
    || {
        TrackerOptions::AdachiMmpf(AdachiConfig {
            relock_share: 0.05,
            ..AdachiConfig::default()
        })
    },
    || {
        TrackerOptions::AdachiMmpf(AdachiConfig {
            vote_pair_share: 0.05,
            ..AdachiConfig::default()
        })
    },
    || real_roads("adachi-mmpf"),
    || {
        TrackerOptions::AdachiMmpf(AdachiConfig {
            edge_response: EdgeResponse::Gradient,
            ..adachi_real_roads()
        })
    },
    || {
        TrackerOptions::AdachiMmpf(AdachiConfig {
            vote_pair_share: 0.05,
            ..adachi_real_roads()
        })
    },
    || {
        TrackerOptions::AdachiMmpf(AdachiConfig {
            edge_response: EdgeResponse::Gradient,
            ..AdachiConfig::default()
        })
    },
    || TrackerOptions::DanescuMono(DanescuConfig::default()),
    || {
        TrackerOptions::DanescuMono(DanescuConfig {
            relock_share: 0.1,
            ..DanescuConfig::default()
        })
    },
    || {
        TrackerOptions::DanescuMono(DanescuConfig {
            relock_share: 0.1,
            adjacent_lanes: true,
            ..DanescuConfig::default()
        })
    },
    || real_roads("danescu-mono"),
    || TrackerOptions::LeeCpf(LeeConfig::default()),
    || {
        TrackerOptions::LeeCpf(LeeConfig {
            relock_share: 0.05,
            ..LeeConfig::default()
        })
    },
    || {
        TrackerOptions::LeeCpf(LeeConfig {
            relock_share: 0.05,
            adjacent_lanes: true,
            ..LeeConfig::default()
        })
    },
    || real_roads("lee-cpf"),
    || TrackerOptions::LiuPpf(LiuConfig::default()),
    || {
        TrackerOptions::LiuPpf(LiuConfig {
            relock_share: 0.1,
            ..LiuConfig::default()
        })
    },
    || {
        TrackerOptions::LiuPpf(LiuConfig {
            boundaries: 4,
            ..LiuConfig::default()
        })
    },
    || real_roads("liu-ppf"),
    || {
        let TrackerOptions::LiuPpf(c) = real_roads("liu-ppf") else {
            unreachable!("liu-ppf's preset holds liu-ppf's options")
        };
        TrackerOptions::LiuPpf(LiuConfig {
            valid_paint_contrast: 10.0,
            ..c
        })
    },
    || TrackerOptions::LiuPpfNokernel(LiuConfig::default()),
    || {
        TrackerOptions::LiuPpfNokernel(LiuConfig {
            relock_share: 0.1,
            ..LiuConfig::default()
        })
    },
];

/// The `real-roads` preset of a registered tracker.
fn real_roads(id: &str) -> TrackerOptions {
    TrackerOptions::preset(id, Preset::RealRoads).expect("a registered tracker id")
}

/// adachi-mmpf's `real-roads` options, for rows that add one of ours to them.
fn adachi_real_roads() -> AdachiConfig {
    match real_roads("adachi-mmpf") {
        TrackerOptions::AdachiMmpf(c) => c,
        _ => unreachable!("adachi-mmpf's preset holds adachi-mmpf's options"),
    }
}

/// A row of the table: a tracker with its options, or the classical baseline.
enum Row {
    Tracker(Box<TrackerOptions>),
    Baseline,
}

/// The baseline row's name.
const BASELINE_ROW: &str =
    "classical baseline (ridges, Hough lines, Kalman; `lanepf::baseline`, not a particle filter)";

/// Every row: the trackers, then the baseline.
fn rows() -> Vec<Row> {
    let mut rows: Vec<Row> = TRACKERS
        .iter()
        .map(|r| Row::Tracker(Box::new(r())))
        .collect();
    rows.push(Row::Baseline);
    rows
}

impl Row {
    fn name(&self) -> Res<String> {
        match self {
            Row::Tracker(options) => row_name(options),
            Row::Baseline => Ok(BASELINE_ROW.into()),
        }
    }

    fn build(&self, camera: &CameraFile) -> Res<Box<dyn Tracker>> {
        Ok(match self {
            Row::Tracker(options) => {
                trackers::build(&TrackerConfig::new(camera.clone(), (**options).clone()))?
            }
            Row::Baseline => Box::new(ClassicalBaseline::new(&Camera::from_file(camera)?)?),
        })
    }
}

/// A row's name: the tracker id, and the options that differ from its defaults as JSON.
fn row_name(options: &TrackerOptions) -> Res<String> {
    let id = options.id();
    let defaults = serde_json::to_value(TrackerOptions::defaults(id)?)?;
    let serde_json::Value::Object(given) = serde_json::to_value(options)? else {
        return Err("options serialise to an object".into());
    };
    let changed: serde_json::Map<_, _> = given
        .into_iter()
        .filter(|(k, v)| defaults.get(k) != Some(v))
        .collect();
    Ok(if changed.is_empty() {
        id.to_string()
    } else {
        format!("{id} `{}`", serde_json::Value::Object(changed))
    })
}
const STILL_ITERATIONS: u32 = 5;
type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// Where a dataset's camera comes from.
enum CameraSource {
    File(PathBuf),
    /// CULane ships no camera: an oracle one from its own labels (see [`camera_from_labels`]).
    CulaneLabels(PathBuf),
    Auto {
        intrinsics: Option<PathBuf>,
        stills: bool,
    },
}

struct Run {
    label: String,
    frames: Vec<PathBuf>,
    camera: CameraSource,
    still: bool,
    eval: Option<(Format, PathBuf)>,
    sheet: Option<String>,
}

fn list(dir: &Path, limit: usize) -> Res<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "png" || x == "jpg"))
        .collect();
    files.sort();
    files.truncate(limit);
    Ok(files)
}

fn camera(source: &CameraSource, frames: &[RgbaFrame]) -> Res<(CameraFile, String)> {
    match source {
        CameraSource::File(p) => Ok((CameraFile::read(p)?, "given".into())),
        CameraSource::CulaneLabels(dir) => {
            let f0 = frames.first().ok_or("no frames")?;
            let cam = camera_from_labels(dir, f0.width, f0.height)?;
            let note = format!(
                "from the labels: pitch {:.2}, yaw {:.2}, h {:.2} m (60 deg field of view assumed)",
                cam.pitch_deg, cam.yaw_deg, cam.height_m
            );
            Ok((cam, note))
        }
        CameraSource::Auto { intrinsics, stills } => {
            let intr = intrinsics.as_deref().map(CameraFile::read).transpose()?;
            let config = CalibratorConfig {
                stable_frames: if *stills {
                    1
                } else {
                    CalibratorConfig::default().stable_frames
                },
                ..CalibratorConfig::default()
            };
            let f0 = frames.first().ok_or("no frames")?;
            let mut cal = Calibrator::new(f0.width, f0.height, intr.as_ref(), config)?;
            for f in frames {
                cal.feed_rgba(&f.data, f.width, f.height)?;
            }
            let e = cal
                .estimate()
                .ok_or("auto-calibration found no straight lane markings")?;
            let note = format!(
                "auto: pitch {:.2}, yaw {:.2}, h {:.2} m, conf {:.2}, {} frames",
                e.camera.pitch_deg,
                e.camera.yaw_deg,
                e.camera.height_m,
                e.confidence,
                e.frames_used
            );
            Ok((e.camera, note))
        }
    }
}

/// An oracle camera for a CULane folder, from its labels (the dataset has no camera): for each
/// frame, a straight line through the lower half of the points of the labelled ego pair (the
/// nearest lanes left and right of the middle at the bottom); where the two meet is the
/// vanishing point (pitch, yaw with a 60 degree field of view), and the 3.6 m lane-width prior
/// over their distance at the bottom row gives the height; medians over the frames. It says
/// what the trackers do with a right camera; it is not a calibration a user could run.
fn camera_from_labels(dir: &Path, width: usize, height: usize) -> Res<CameraFile> {
    use lanepf::calib::pose::{lateral_at_unit_height, pose_from_vanishing_point, Pinhole};
    let f = 0.5 * width as f64 / lanepf::math::tan(30f64.to_radians());
    let k = Pinhole {
        fx: f,
        fy: f,
        cx: 0.5 * width as f64,
        cy: 0.5 * height as f64,
    };
    // x = a + b y through the lower half of a lane's points.
    let fit = |pts: &[[f64; 2]]| -> Option<(f64, f64)> {
        let mut p: Vec<[f64; 2]> = pts.to_vec();
        p.sort_by(|a, b| b[1].total_cmp(&a[1]));
        p.truncate(p.len().div_ceil(2).max(2));
        let n = p.len() as f64;
        let (my, mx) = (
            p.iter().map(|q| q[1]).sum::<f64>() / n,
            p.iter().map(|q| q[0]).sum::<f64>() / n,
        );
        let syy: f64 = p.iter().map(|q| (q[1] - my).powi(2)).sum();
        let sxy: f64 = p.iter().map(|q| (q[1] - my) * (q[0] - mx)).sum();
        (p.len() >= 2 && syy > 1e-9).then(|| (mx - sxy / syy * my, sxy / syy))
    };
    let bottom = height as f64 - 1.0;
    let (mut pitches, mut yaws, mut heights) = (Vec::new(), Vec::new(), Vec::new());
    for frame in lanepf::eval::culane::read_labels(dir)? {
        let lines: Vec<(f64, f64)> = frame.lanes.iter().filter_map(|l| fit(l)).collect();
        let at = |l: &(f64, f64)| l.0 + l.1 * bottom;
        let mid = 0.5 * width as f64;
        let left = lines
            .iter()
            .filter(|l| at(l) < mid)
            .max_by(|a, b| at(a).total_cmp(&at(b)));
        let right = lines
            .iter()
            .filter(|l| at(l) >= mid)
            .min_by(|a, b| at(a).total_cmp(&at(b)));
        let (Some(l), Some(r)) = (left, right) else {
            continue;
        };
        if (l.1 - r.1).abs() < 1e-6 {
            continue;
        }
        let y = (r.0 - l.0) / (l.1 - r.1);
        let vp = [l.0 + l.1 * y, y];
        let [pitch, yaw] = pose_from_vanishing_point(&k, vp);
        let yl = lateral_at_unit_height(&k, pitch, yaw, [at(l), bottom]);
        let yr = lateral_at_unit_height(&k, pitch, yaw, [at(r), bottom]);
        if let (Some(yl), Some(yr)) = (yl, yr) {
            pitches.push(pitch.to_degrees());
            yaws.push(yaw.to_degrees());
            heights.push(3.6 / (yl - yr));
        }
    }
    let median = |v: &mut Vec<f64>| -> Res<f64> {
        v.sort_by(f64::total_cmp);
        Ok(*v.get(v.len() / 2).ok_or("no labelled ego pair")?)
    };
    let mut cam = CameraFile::pinhole(width, height, f);
    cam.pitch_deg = median(&mut pitches)?;
    cam.yaw_deg = median(&mut yaws)?;
    cam.height_m = median(&mut heights)?;
    Ok(cam)
}

fn track(
    mut tracker: Box<dyn Tracker>,
    frames: &[RgbaFrame],
    names: &[String],
    still: bool,
) -> Res<Vec<LaneEstimate>> {
    let mut out = Vec::new();
    for (f, name) in frames.iter().zip(names) {
        let mut e = if still {
            tracker.reset();
            let mut last = tracker.step(&f.data, f.width, f.height)?;
            for _ in 1..STILL_ITERATIONS {
                last = tracker.step(&f.data, f.width, f.height)?;
            }
            last
        } else {
            tracker.step(&f.data, f.width, f.height)?
        };
        e.frame = name.clone();
        out.push(e);
    }
    Ok(out)
}

fn summary(metrics: &Metrics) -> String {
    let pct = |r: Option<f64>| r.map_or("n/a".into(), |r| format!("{:.1}", 100.0 * r));
    match metrics {
        Metrics::Caltech(r) => format!(
            "ego {} / {} FP, all {} / {} FP",
            pct(r.ego_lanes.correct_rate),
            pct(r.ego_lanes.false_positive_rate),
            pct(r.all_lanes.correct_rate),
            pct(r.all_lanes.false_positive_rate)
        ),
        Metrics::Culane(r) => format!(
            "F1 {:.2} (P {} R {})",
            r.f1.unwrap_or(0.0),
            pct(r.precision),
            pct(r.recall)
        ),
        Metrics::Tusimple(r) => format!(
            "acc {:.1}, FP {:.2}, FN {:.2}",
            100.0 * r.accuracy,
            r.fp,
            r.fn_rate
        ),
        Metrics::KittiRoad(r) => format!(
            "F1 {:.3} (P {} R {})",
            r.f1.unwrap_or(0.0),
            pct(r.precision),
            pct(r.recall)
        ),
        Metrics::Synthetic(_) => String::new(),
    }
}

fn draw(frame: &mut RgbaFrame, e: &LaneEstimate) {
    let (w, h) = (frame.width, frame.height);
    let r = if e.valid { 2i64 } else { 0 };
    for b in &e.boundaries {
        let c = match b.role {
            Role::EgoLeft => [255, 40, 40],
            Role::EgoRight => [40, 90, 255],
            _ => [255, 220, 0],
        };
        for pair in b.points.windows(2) {
            let (a, z) = (pair[0], pair[1]);
            let n = ((z[0] - a[0]).abs().max((z[1] - a[1]).abs()).ceil() as usize).max(1);
            for k in 0..=n {
                let t = k as f64 / n as f64;
                let (x, y) = (
                    (a[0] + t * (z[0] - a[0])) as i64,
                    (a[1] + t * (z[1] - a[1])) as i64,
                );
                for dy in -r..=r {
                    for dx in -r..=r {
                        let (px, py) = (x + dx, y + dy);
                        if px >= 0 && py >= 0 && (px as usize) < w && (py as usize) < h {
                            let i = (py as usize * w + px as usize) * 4;
                            frame.data[i..i + 3].copy_from_slice(&c);
                        }
                    }
                }
            }
        }
    }
}

/// One row per tracker of `samples` frames, each shrunk by `shrink`.
fn sheet(
    path: &Path,
    frames: &[RgbaFrame],
    runs: &[Vec<LaneEstimate>],
    samples: &[usize],
    shrink: usize,
) -> Res<()> {
    let (fw, fh) = (frames[0].width / shrink, frames[0].height / shrink);
    let (cols, rows) = (samples.len(), runs.len());
    let mut out = vec![0u8; cols * fw * rows * fh * 4];
    for (row, run) in runs.iter().enumerate() {
        for (col, &i) in samples.iter().enumerate() {
            let mut f = frames[i].clone();
            draw(&mut f, &run[i]);
            for y in 0..fh {
                for x in 0..fw {
                    let src = ((y * shrink) * f.width + x * shrink) * 4;
                    let dst = ((row * fh + y) * cols * fw + col * fw + x) * 4;
                    out[dst..dst + 4].copy_from_slice(&f.data[src..src + 4]);
                }
            }
        }
    }
    write_rgba_png(path, &out, cols * fw, rows * fh)?;
    Ok(())
}

fn main() -> Res<()> {
    let args: Vec<String> = std::env::args().collect();
    let data = PathBuf::from(args.get(1).map_or("../shared/data", |s| s.as_str()));
    let out = PathBuf::from(args.get(2).map_or("target/real-data", |s| s.as_str()));
    let udacity_frames: usize = args.get(3).map_or(Ok(300), |s| s.parse())?;
    std::fs::create_dir_all(&out)?;
    let caltech = data.join("caltech-cordova1");
    let culane = data.join("culane/06030819_0755.MP4");
    let udacity_cam = PathBuf::from("www/clips/udacity-1280x720.camera.json");
    let mut runs = vec![
        Run {
            label: "Caltech, its camera".into(),
            frames: list(&caltech.join("frames"), usize::MAX)?,
            camera: CameraSource::File(caltech.join("camera.json")),
            still: false,
            eval: Some((Format::Caltech, caltech.join("labels.json"))),
            sheet: None,
        },
        Run {
            label: "Caltech, auto".into(),
            frames: list(&caltech.join("frames"), usize::MAX)?,
            camera: CameraSource::Auto {
                intrinsics: Some(caltech.join("camera.json")),
                stills: false,
            },
            still: false,
            eval: Some((Format::Caltech, caltech.join("labels.json"))),
            sheet: None,
        },
        Run {
            label: "CULane, auto (stills)".into(),
            frames: list(&culane, usize::MAX)?,
            camera: CameraSource::Auto {
                intrinsics: None,
                stills: true,
            },
            still: true,
            eval: Some((Format::Culane, culane.clone())),
            sheet: None,
        },
        Run {
            label: "CULane, camera from its labels (stills)".into(),
            frames: list(&culane, usize::MAX)?,
            camera: CameraSource::CulaneLabels(culane.clone()),
            still: true,
            eval: Some((Format::Culane, culane.clone())),
            sheet: None,
        },
        Run {
            label: "TuSimple, auto (stills)".into(),
            frames: list(&data.join("tusimple/images"), usize::MAX)?,
            camera: CameraSource::Auto {
                intrinsics: None,
                stills: true,
            },
            still: true,
            eval: Some((Format::Tusimple, data.join("tusimple/labels.json"))),
            sheet: None,
        },
    ];
    // Each video's camera: the chessboard intrinsics with the pose `lanepf calibrate` measures
    // over the whole video (www/clips/README.md); the two videos were not filmed with one pose.
    for (video, video_cam) in [
        ("project_video", udacity_cam.clone()),
        (
            "challenge_video",
            PathBuf::from("www/clips/udacity-challenge-1280x720.camera.json"),
        ),
    ] {
        let dir = out.join("frames").join(video);
        if list(&dir, 1).map_or(true, |f| f.is_empty()) {
            std::fs::create_dir_all(&dir)?;
            let status = std::process::Command::new("ffmpeg")
                .args(["-v", "error", "-y", "-i"])
                .arg(data.join("udacity").join(format!("{video}.mp4")))
                .args(["-frames:v", &udacity_frames.to_string(), "-q:v", "2"])
                .arg(dir.join("%05d.jpg"))
                .status()?;
            if !status.success() {
                return Err(format!("ffmpeg could not cut {video}").into());
            }
        }
        for (cam, source) in [
            ("its camera", CameraSource::File(video_cam)),
            (
                "auto",
                CameraSource::Auto {
                    intrinsics: Some(udacity_cam.clone()),
                    stills: false,
                },
            ),
        ] {
            runs.push(Run {
                label: format!("Udacity {video}, {cam}"),
                frames: list(&dir, udacity_frames)?,
                camera: source,
                still: false,
                eval: None,
                sheet: Some(format!("sheet-{video}-{}.png", cam.replace(' ', "-"))),
            });
        }
    }
    if let Ok(only) = std::env::var("REAL_DATA_RUNS") {
        runs.retain(|r| r.label.contains(only.as_str()));
    }
    let mut table = String::from("| tracker |");
    for r in &runs {
        table += &format!(" {} |", r.label);
    }
    table += &format!("\n|---|{}\n", "---|".repeat(runs.len()));
    let all_rows = rows();
    let mut rows: Vec<Vec<String>> = vec![Vec::new(); all_rows.len()];
    let mut notes = Vec::new();
    let only = std::env::var("REAL_DATA_ROWS").ok();
    let selected: Vec<bool> = all_rows
        .iter()
        .map(|row| {
            let name = row.name()?;
            Ok(only.as_ref().is_none_or(|o| name.contains(o.as_str())))
        })
        .collect::<Res<_>>()?;
    if let Some(o) = only.as_ref().filter(|_| !selected.contains(&true)) {
        return Err(format!("REAL_DATA_ROWS={o} names no row (a row's name: the tracker id and its options as JSON, as in report.md)").into());
    }
    if runs.is_empty() {
        return Err("REAL_DATA_RUNS names no dataset (a column's label, as in report.md)".into());
    }
    for run in &runs {
        let frames: Vec<RgbaFrame> = run
            .frames
            .iter()
            .map(|p| read_rgba(p))
            .collect::<Result<_, _>>()?;
        let names: Vec<String> = run
            .frames
            .iter()
            .map(|p| {
                p.file_name()
                    .map_or(String::new(), |n| n.to_string_lossy().into_owned())
            })
            .collect();
        let (cam, note) = camera(&run.camera, &frames)?;
        notes.push(format!("- {}: {note}", run.label));
        let mut all = Vec::new();
        let per_frame = out.join("per-frame");
        std::fs::create_dir_all(&per_frame)?;
        let mut index = String::new();
        for (k, row) in all_rows.iter().enumerate() {
            index.push_str(&format!("row{k:02}: {}\n", row.name()?));
        }
        std::fs::write(per_frame.join("rows.txt"), index)?;
        for (k, row) in all_rows.iter().enumerate() {
            if !selected[k] {
                continue;
            }
            let preds = track(row.build(&cam)?, &frames, &names, run.still)?;
            let valid = preds.iter().filter(|p| p.valid).count();
            let cell = match &run.eval {
                Some((format, gt)) => {
                    let options = EvalOptions {
                        tusimple_time_limit_ms: None,
                        ..EvalOptions::default()
                    };
                    let report = evaluate_with(*format, &preds, gt, &options)?;
                    // Which frames fail, for this row and dataset: named by the row's number
                    // (its full name in per-frame/rows.txt; a name with every option is longer
                    // than a file name may be).
                    let file = format!("row{k:02} -- {}.txt", run.label).replace(
                        |c: char| !c.is_ascii_alphanumeric() && c != '-' && c != '.',
                        "_",
                    );
                    std::fs::write(per_frame.join(file), report.frames_table())?;
                    summary(&report.metrics)
                }
                None => format!(
                    "valid {:.0} %",
                    100.0 * valid as f64 / preds.len().max(1) as f64
                ),
            };
            eprintln!("{} / {}: {cell}", run.label, row.name()?);
            rows[k].push(cell);
            all.push(preds);
        }
        if let Some(name) = &run.sheet {
            let samples: Vec<usize> = (0..8).map(|k| k * (frames.len() - 1) / 7).collect();
            sheet(&out.join(name), &frames, &all, &samples, 4)?;
        }
    }
    for (k, row) in all_rows.iter().enumerate() {
        if !selected[k] {
            continue;
        }
        let name = row.name()?;
        table += &format!("| {name} | {} |\n", rows[k].join(" | "));
    }
    let report = format!("{table}\nCameras:\n{}\n", notes.join("\n"));
    std::fs::write(out.join("report.md"), &report)?;
    println!("{report}");
    Ok(())
}
