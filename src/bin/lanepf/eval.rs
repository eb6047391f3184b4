//! `lanepf eval`: score a `track` output against ground truth in one of the supported formats.

use lanepf::eval::{evaluate_with, read_predictions, EvalOptions, Format};
use lanepf::{Error, Result};
use std::path::PathBuf;

/// Options of `lanepf eval`.
#[derive(clap::Args)]
pub struct Args {
    /// The tracker's output (JSON lines, one per frame).
    #[arg(long)]
    pred: PathBuf,
    /// Ground truth: gt.jsonl (synthetic), labels.json (caltech, tusimple), a folder of
    /// .lines.txt files (culane) or of *_lane_*.png masks (kitti-road, KITTI's gt_image_2).
    #[arg(long)]
    gt: PathBuf,
    /// synthetic, caltech, tusimple, culane or kitti-road.
    #[arg(long)]
    format: String,
    /// Print the report as JSON (it holds every frame's figures).
    #[arg(long)]
    json: bool,
    /// After the report, one line per ground-truth frame with its figures (which frames fail).
    #[arg(long)]
    per_frame: bool,
    /// Ignore TuSimple's 200 ms per frame rule (e.g. for debug builds).
    #[arg(long)]
    no_time_limit: bool,
}

/// Runs the command.
pub fn run(args: Args) -> Result<()> {
    let format: Format = args.format.parse()?;
    let predictions = read_predictions(&args.pred)?;
    let mut options = EvalOptions::default();
    if args.no_time_limit {
        options.tusimple_time_limit_ms = None;
    }
    let report = evaluate_with(format, &predictions, &args.gt, &options)?;
    if args.json {
        let text =
            serde_json::to_string_pretty(&report).map_err(|e| Error::Config(e.to_string()))?;
        super::out(&format!("{text}\n"))?;
    } else {
        let text = report.to_string();
        super::out(&text)?;
        if args.per_frame {
            let gap = if text.ends_with('\n') { "\n" } else { "\n\n" };
            super::out(&format!("{gap}{}", report.frames_table()))?;
        }
    }
    Ok(())
}
