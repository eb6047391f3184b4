//! `lanepf track`: run a tracker over a folder of frames, one JSON line per frame.

use super::frames;
use lanepf::camera::CameraFile;
use lanepf::image::read_rgba;
use lanepf::trackers::{self, TrackerConfig};
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
    /// camera.json of the frames.
    #[arg(long)]
    camera: PathBuf,
    /// Folder of PNG/JPEG frames, processed in file-name order.
    #[arg(long)]
    frames: PathBuf,
    /// Folder of right-camera frames (stereo trackers), same names.
    #[arg(long)]
    right: Option<PathBuf>,
    /// RNG seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// JSON file of tracker options (merged over `camera`, `particles`, `seed`).
    #[arg(long)]
    config: Option<PathBuf>,
    /// Treat every frame as an independent still: reset, then K filter iterations on it.
    #[arg(long)]
    still: Option<u32>,
    /// Output JSON-lines file.
    #[arg(long)]
    out: PathBuf,
}

/// Runs the command.
pub fn run(args: Args) -> Result<()> {
    let camera = CameraFile::read(&args.camera)?;
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
    options.insert(
        "camera".into(),
        serde_json::to_value(&camera).map_err(|e| Error::Config(e.to_string()))?,
    );
    options.entry("seed").or_insert(args.seed.into());
    let config = TrackerConfig::from_json_str(&serde_json::Value::Object(options).to_string())?;
    let mut tracker = trackers::create(&args.tracker, &config)?;
    if args.right.is_some() {
        return Err(Error::Config(format!(
            "tracker `{}` takes one camera; --right is for stereo trackers",
            args.tracker
        )));
    }
    if args.still == Some(0) {
        return Err(Error::parameter(
            "--still",
            0,
            "must be at least 1 iteration",
        ));
    }
    let files = frames::list(&args.frames)?;
    let out = std::fs::File::create(&args.out).map_err(|e| Error::Io {
        path: args.out.display().to_string(),
        reason: e.to_string(),
    })?;
    let mut out = std::io::BufWriter::new(out);
    for path in &files {
        let frame = read_rgba(path)?;
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
                let mut last = tracker.step(&frame.data, frame.width, frame.height)?;
                for _ in 1..k {
                    last = tracker.step(&frame.data, frame.width, frame.height)?;
                }
                last
            }
            None => tracker.step(&frame.data, frame.width, frame.height)?,
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
