//! `lanepf track`: run a tracker over a folder of frames, one JSON line per frame.

use super::frames;
use lanepf::camera::CameraFile;
use lanepf::image::{read_rgba, RgbaFrame};
use lanepf::trackers::{self, Preset, TrackerConfig};
use lanepf::{Error, Result};
use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

/// Options of `lanepf track`.
#[derive(clap::Args)]
pub struct Args {
    /// Tracker id.
    #[arg(long)]
    tracker: String,
    /// camera.json of the frames, or `auto` to estimate it from the frames first (see
    /// `lanepf calibrate`; the estimate is printed on stderr).
    #[arg(long)]
    camera: String,
    #[command(flatten)]
    calibration: super::calibrate::CalibrationArgs,
    /// Folder of PNG/JPEG frames, processed in file-name order.
    #[arg(long)]
    frames: PathBuf,
    /// Folder of right-camera frames (stereo trackers), same names.
    #[arg(long)]
    right: Option<PathBuf>,
    /// RNG seed (default 1; give it here or as `seed` in --config, not both).
    #[arg(long)]
    seed: Option<u64>,
    /// JSON file of tracker options (`particles`, `seed` and the tracker's own; the camera
    /// comes from --camera only).
    #[arg(long)]
    config: Option<PathBuf>,
    /// Named option set the options start from: `paper` (each paper's filter, the default) or
    /// `real-roads` (our options beyond the papers for real footage); --config's options
    /// replace its values.
    #[arg(long, default_value = "paper")]
    preset: String,
    /// JSON-lines file of the car's motion, one line per frame in frame order, with `t`
    /// (seconds), `speed_mps` and `yaw_rate` (rad/s, positive left) at the top level or in
    /// `state` (the `gt.jsonl` of `lanepf synth` works); used by trackers with an ego-motion
    /// model (danescu-*).
    #[arg(long)]
    motion: Option<PathBuf>,
    /// Treat every frame as an independent still: reset, then K filter iterations on it.
    #[arg(long)]
    still: Option<u32>,
    /// Output JSON-lines file.
    #[arg(long)]
    out: PathBuf,
}

/// Runs the command.
pub fn run(args: Args) -> Result<()> {
    let preset: Preset = args.preset.parse()?;
    if args.camera != "auto" && args.calibration.intrinsics.is_some() {
        return Err(Error::Config(
            "--intrinsics is for --camera auto; with a camera file the file's intrinsics are used"
                .into(),
        ));
    }
    if args.camera != "auto" && args.calibration.tangent_yaw {
        return Err(Error::Config(
            "--tangent-yaw is for --camera auto; with a camera file nothing is calibrated".into(),
        ));
    }
    if args.camera != "auto" && args.calibration.tangent_yaw_after.is_some() {
        return Err(Error::Config(
            "--tangent-yaw-after is for --camera auto; with a camera file nothing is calibrated"
                .into(),
        ));
    }
    let camera = if args.camera == "auto" {
        let files = frames::list(&args.frames)?;
        let estimate = super::calibrate::calibrate(&files, &args.calibration)?;
        eprintln!(
            "lanepf: camera auto: {}",
            super::calibrate::summary(&estimate)
        );
        estimate.camera
    } else {
        CameraFile::read(std::path::Path::new(&args.camera))?
    };
    let mut options = match &args.config {
        Some(path) => {
            let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
                path: path.display().to_string(),
                reason: e.to_string(),
            })?;
            serde_json::from_str::<serde_json::Map<String, serde_json::Value>>(&text)
                .map_err(|e| Error::Config(format!("{}: {e}", path.display())))?
        }
        None => serde_json::Map::new(),
    };
    let config_name = || {
        args.config
            .as_ref()
            .map_or_else(String::new, |p| p.display().to_string())
    };
    if options.contains_key("camera") {
        return Err(Error::Config(format!(
            "{}: `camera` comes from --camera; remove it from the config file",
            config_name()
        )));
    }
    if let (Some(flag), Some(file)) = (args.seed, options.get("seed")) {
        return Err(Error::Config(format!(
            "the seed is given twice: --seed {flag} and `seed`: {file} in {}; keep one",
            config_name()
        )));
    }
    options.insert(
        "camera".into(),
        serde_json::to_value(&camera).map_err(|e| Error::Config(e.to_string()))?,
    );
    options
        .entry("seed")
        .or_insert(args.seed.unwrap_or(1).into());
    if preset != Preset::Paper {
        if let serde_json::Value::Object(base) = trackers::preset_options(&args.tracker, preset)? {
            for (key, value) in base {
                options.entry(key).or_insert(value);
            }
        }
    }
    let config = TrackerConfig::from_json_str(&serde_json::Value::Object(options).to_string())?;
    let mut tracker = trackers::create(&args.tracker, &config)?;
    match (&args.right, tracker.is_stereo()) {
        (Some(_), false) => {
            return Err(Error::Config(format!(
                "tracker `{}` takes one camera; --right is for stereo trackers",
                args.tracker
            )))
        }
        (None, true) => {
            return Err(Error::Config(format!(
                "tracker `{}` needs the right camera's frames: give --right DIR (the same file \
                 names as --frames)",
                args.tracker
            )))
        }
        _ => {}
    }
    if args.still == Some(0) {
        return Err(Error::parameter(
            "--still",
            0,
            "must be at least 1 iteration",
        ));
    }
    let files = frames::list(&args.frames)?;
    let motion = match &args.motion {
        Some(path) => Some(read_motion(path, files.len())?),
        None => None,
    };
    let out = std::fs::File::create(&args.out).map_err(|e| Error::Io {
        path: args.out.display().to_string(),
        reason: e.to_string(),
    })?;
    let mut out = std::io::BufWriter::new(out);
    for (index, path) in files.iter().enumerate() {
        let frame = read_rgba(path)?;
        if let Some(m) = &motion {
            tracker.set_ego_motion(m[index])?;
        }
        let right = match &args.right {
            Some(dir) => {
                let file = path
                    .file_name()
                    .ok_or_else(|| Error::Config(format!("{} has no file name", path.display())))?;
                let right = read_rgba(&dir.join(file))?;
                if (right.width, right.height) != (frame.width, frame.height) {
                    return Err(Error::Dimensions(format!(
                        "the right frame {} is {}x{} but the left one is {}x{}",
                        dir.join(file).display(),
                        right.width,
                        right.height,
                        frame.width,
                        frame.height
                    )));
                }
                Some(right)
            }
            None => None,
        };
        if (frame.width, frame.height) != (camera.width, camera.height) {
            return Err(Error::Dimensions(format!(
                "{} is {}x{} but the camera is {}x{}",
                path.display(),
                frame.width,
                frame.height,
                camera.width,
                camera.height
            )));
        }
        let start = Instant::now();
        let mut estimate = match args.still {
            Some(k) => {
                tracker.reset();
                let mut last = step(tracker.as_mut(), &frame, right.as_ref())?;
                for _ in 1..k {
                    last = step(tracker.as_mut(), &frame, right.as_ref())?;
                }
                last
            }
            None => step(tracker.as_mut(), &frame, right.as_ref())?,
        };
        estimate.ms = start.elapsed().as_secs_f64() * 1e3;
        estimate.frame = frames::name(path);
        let line = serde_json::to_string(&estimate).map_err(|e| Error::Config(e.to_string()))?;
        writeln!(out, "{line}").map_err(|e| Error::Io {
            path: args.out.display().to_string(),
            reason: e.to_string(),
        })?;
    }
    out.flush().map_err(|e| Error::Io {
        path: args.out.display().to_string(),
        reason: e.to_string(),
    })?;
    Ok(())
}

/// One step on a frame, with its right frame for a stereo tracker.
fn step(
    tracker: &mut dyn trackers::Tracker,
    frame: &RgbaFrame,
    right: Option<&RgbaFrame>,
) -> Result<lanepf::lane::LaneEstimate> {
    if let Some(r) = right {
        tracker.set_right(&r.data, r.width, r.height)?;
    }
    tracker.step(&frame.data, frame.width, frame.height)
}

/// Reads one ego-motion record per frame from a JSON-lines file.
fn read_motion(path: &std::path::Path, frames: usize) -> Result<Vec<trackers::EgoMotion>> {
    let bad = |line: usize, reason: String| {
        Error::Config(format!("{} line {}: {reason}", path.display(), line + 1))
    };
    let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    })?;
    let mut out = Vec::with_capacity(frames);
    for (i, line) in text.lines().filter(|l| !l.trim().is_empty()).enumerate() {
        let v: serde_json::Value = serde_json::from_str(line).map_err(|e| bad(i, e.to_string()))?;
        let field = |name: &str| {
            v.get(name)
                .or_else(|| v.get("state").and_then(|s| s.get(name)))
                .and_then(serde_json::Value::as_f64)
                .ok_or_else(|| bad(i, format!("no number `{name}`")))
        };
        let m = trackers::EgoMotion {
            t_s: field("t")?,
            speed_mps: field("speed_mps")?,
            yaw_rate: field("yaw_rate")?,
        };
        m.check().map_err(|e| bad(i, e.to_string()))?;
        out.push(m);
    }
    if out.len() < frames {
        return Err(Error::Config(format!(
            "{} has motion for {} frames but there are {frames}",
            path.display(),
            out.len()
        )));
    }
    Ok(out)
}
