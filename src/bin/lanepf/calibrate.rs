//! `lanepf calibrate`: estimate a camera's pitch, yaw and height from the lane markings of a
//! folder of frames (see `lanepf::calib`), and write it as camera.json.

use super::frames;
use lanepf::calib::{CalibrationEstimate, Calibrator, CalibratorConfig};
use lanepf::camera::CameraFile;
use lanepf::image::read_rgba;
use lanepf::{Error, Result};
use std::path::{Path, PathBuf};

/// Calibration options shared by `lanepf calibrate` and `lanepf track --camera auto`.
#[derive(clap::Args)]
pub struct CalibrationArgs {
    /// camera.json whose intrinsics (fx, fy, cx, cy, distortion) are known; its pose is
    /// ignored. Without it the focal length comes from --hfov.
    #[arg(long)]
    pub intrinsics: Option<PathBuf>,
    /// Horizontal field of view in degrees, for the focal length when --intrinsics is not given.
    #[arg(long, default_value_t = CalibratorConfig::default().hfov_deg)]
    pub hfov: f64,
    /// Lane width prior in metres (sets the camera height).
    #[arg(long, default_value_t = CalibratorConfig::default().lane_width_m)]
    pub lane_width: f64,
    /// The frames are independent still images, not a video: each one counts on its own.
    #[arg(long)]
    pub stills: bool,
    /// Calibrate on the first N seconds of the frames only (with --fps).
    #[arg(long)]
    pub seconds: Option<f64>,
    /// Frame rate of the folder, for --seconds.
    #[arg(long, default_value_t = 30.0)]
    pub fps: f64,
    /// The yaw from the lane's tangent at the car from the first frame, instead of the
    /// boundaries' straight crossing until --tangent-yaw-after frames agree (a better yaw on
    /// long gentle bends, on Caltech's frames 0.1 degrees from the labels'; off by default:
    /// on short clips the trackers, adachi-mmpf most, do worse with its cameras).
    #[arg(long)]
    pub tangent_yaw: bool,
    /// The yaw switches from the boundaries' straight crossing to the lane's tangent at the
    /// car once this many frames that agree on the pose have a tangent (0 to 2000; 0: never)
    /// [default: 100].
    #[arg(long, conflicts_with = "tangent_yaw")]
    pub tangent_yaw_after: Option<usize>,
}

/// Options of `lanepf calibrate`.
#[derive(clap::Args)]
pub struct Args {
    /// Folder of PNG/JPEG frames, in file-name order.
    #[arg(long)]
    frames: PathBuf,
    #[command(flatten)]
    calibration: CalibrationArgs,
    /// Print the whole estimate (confidence, spreads, frames used) as JSON on stdout.
    #[arg(long)]
    json: bool,
    /// Output camera.json.
    #[arg(long)]
    out: PathBuf,
}

/// Runs the command.
pub fn run(args: Args) -> Result<()> {
    let files = frames::list(&args.frames)?;
    let estimate = calibrate(&files, &args.calibration)?;
    estimate.camera.write(&args.out)?;
    if args.json {
        let text =
            serde_json::to_string_pretty(&estimate).map_err(|e| Error::Config(e.to_string()))?;
        super::out(&format!("{text}\n"))
    } else {
        super::out(&format!("{}\n", summary(&estimate)))
    }
}

/// One line: the estimated pose, its spread and confidence.
pub fn summary(e: &CalibrationEstimate) -> String {
    let c = &e.camera;
    format!(
        "pitch {:.2} deg (sd {:.2}), yaw {:.2} deg (sd {:.2}, {}), height {:.2} m (sd {:.2}), \
         confidence {:.2}, {} of {} frames used, focal length {:.1} px ({})",
        c.pitch_deg,
        e.pitch_sd_deg,
        c.yaw_deg,
        e.yaw_sd_deg,
        if e.yaw_from_tangent {
            "the lane's tangent"
        } else {
            "the boundaries' crossing"
        },
        c.height_m,
        e.height_sd_m,
        e.confidence,
        e.frames_used,
        e.frames_seen,
        c.fx,
        if e.intrinsics_known {
            "given"
        } else {
            "from the field of view"
        }
    )
}

/// Feeds `files` (the first --seconds of them) to a calibrator and returns its estimate.
///
/// # Errors
/// Unreadable or mismatched frames, bad options, or no straight lane markings in any frame.
pub fn calibrate(files: &[PathBuf], args: &CalibrationArgs) -> Result<CalibrationEstimate> {
    let intrinsics = args
        .intrinsics
        .as_deref()
        .map(CameraFile::read)
        .transpose()?;
    let config = CalibratorConfig {
        lane_width_m: args.lane_width,
        hfov_deg: args.hfov,
        stable_frames: if args.stills {
            1
        } else {
            CalibratorConfig::default().stable_frames
        },
        tangent_yaw: args.tangent_yaw,
        tangent_yaw_after: args
            .tangent_yaw_after
            .unwrap_or(CalibratorConfig::default().tangent_yaw_after),
        ..CalibratorConfig::default()
    };
    let limit = match args.seconds {
        Some(s) => {
            lanepf::error::require_positive("--seconds", s)?;
            lanepf::error::require_within("--fps", args.fps, 1.0..=1000.0, "must be 1 to 1000")?;
            ((s * args.fps).ceil() as usize).max(1)
        }
        None => files.len(),
    };
    let mut calibrator: Option<Calibrator> = None;
    for path in files.iter().take(limit) {
        let frame = read_rgba(path)?;
        let cal = match &mut calibrator {
            Some(c) => c,
            None => calibrator.insert(Calibrator::new(
                frame.width,
                frame.height,
                intrinsics.as_ref(),
                config,
            )?),
        };
        let [w, h] = cal.size();
        if (frame.width, frame.height) != (w, h) {
            return Err(Error::Dimensions(format!(
                "{} is {}x{} but the first frame is {w}x{h}",
                path.display(),
                frame.width,
                frame.height
            )));
        }
        cal.feed_rgba(&frame.data, frame.width, frame.height)?;
    }
    let estimate = calibrator
        .and_then(|c| c.estimate())
        .ok_or_else(|| no_estimate(files, limit))?;
    if estimate.confidence < LOW_CONFIDENCE {
        eprintln!(
            "lanepf: warning: the camera estimate has a low confidence ({:.2}, {} of {} frames \
             used): few straight stretches with both lane boundaries were seen; check it, feed \
             more frames, or give a camera.json",
            estimate.confidence, estimate.frames_used, estimate.frames_seen
        );
    }
    Ok(estimate)
}

/// Below this confidence `calibrate` and `track --camera auto` warn on stderr.
pub const LOW_CONFIDENCE: f64 = 0.5;

fn no_estimate(files: &[PathBuf], limit: usize) -> Error {
    let dir = files
        .first()
        .and_then(|p| p.parent())
        .unwrap_or(Path::new("."));
    Error::Config(format!(
        "no straight lane markings found in the {} frames of {}: auto-calibration needs a \
         stretch of straight road with both lane boundaries visible; give a camera.json instead",
        limit.min(files.len()),
        dir.display()
    ))
}
