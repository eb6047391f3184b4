//! `lanepf`: the command-line tool (see ../shared/DESIGN.md, "The command-line contract").
//!
//! ```text
//! lanepf synth --scenario NAME --seed N [--reference] --frames N [--width W --height H] [--stereo] --out DIR
//! lanepf track --tracker ID --camera FILE --frames DIR [--right DIR] [--seed N] [--config FILE]
//!              [--preset paper|real-roads]
//!              [--still K] --out FILE.jsonl
//!     (--camera auto estimates the camera from the frames first, as `calibrate` does)
//! lanepf calibrate --frames DIR [--intrinsics FILE | --hfov DEG] [--lane-width M] [--stills]
//!              [--seconds N [--fps F]] [--json] --out camera.json
//! lanepf eval --pred FILE.jsonl --gt PATH --format synthetic|caltech|tusimple|culane|kitti-road [--json]
//! lanepf bench [--tracker ID|all] [--frames N] [--warmup N] [--motion] [--width W --height H]
//!              [--preset paper|real-roads] [--json]
//! lanepf eval-suite --tracker ID|all --seeds A..B [--scenarios a,b,...] [--width W --height H]
//!              [--frames N] [--tracker-seed N] --out DIR
//! ```
//!
//! Every error is one line on stderr (`lanepf: error: ...`) and exit status 1; usage errors
//! exit with 2 (clap's convention).

// Errors, not panics, for anything a user's files or flags can reach (tests may unwrap).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

mod bench;
mod calibrate;
mod eval;
mod eval_suite;
mod frames;
mod synth;
mod track;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Particle-filter lane tracking: synthetic scenes, tracking, evaluation and benchmarks.
#[derive(Parser)]
#[command(name = "lanepf", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a named synthetic scenario with its exact ground truth.
    Synth(synth::Args),
    /// Run a tracker on a folder of frames and write one JSON line per frame.
    Track(track::Args),
    /// Estimate the camera's pitch, yaw and height from the lane markings of a folder of frames.
    Calibrate(calibrate::Args),
    /// Score tracker output against ground truth (synthetic, Caltech, TuSimple, CULane).
    Eval(eval::Args),
    /// Time trackers on a standard synthetic sequence.
    Bench(bench::Args),
    /// Render, track and score trackers on scenario families over seeds: one table.
    EvalSuite(eval_suite::Args),
}

/// Writes `text` to standard output. A closed pipe (`lanepf eval ... | head`) ends the output
/// quietly instead of panicking as `println!` does; other write errors are reported.
pub(crate) fn out(text: &str) -> lanepf::Result<()> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
    {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(lanepf::Error::Io {
            path: "standard output".into(),
            reason: e.to_string(),
        }),
        _ => Ok(()),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Synth(args) => synth::run(args),
        Command::Track(args) => track::run(args),
        Command::Calibrate(args) => calibrate::run(args),
        Command::Eval(args) => eval::run(args),
        Command::Bench(args) => bench::run(args),
        Command::EvalSuite(args) => eval_suite::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("lanepf: error: {e}");
            ExitCode::FAILURE
        }
    }
}
