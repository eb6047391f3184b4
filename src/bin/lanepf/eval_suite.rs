//! `lanepf eval-suite`: trackers x scenario families x seeds, rendered, tracked and scored
//! into one table, DIR/suite.md and DIR/suite.json (see `lanepf::eval::suite`).
//!
//! Each family member (scenario, seed) is rendered once at --width x --height through its own
//! drawn camera, and every tracker runs on it with its default options (or --options),
//! --tracker-seed and the true ego motion; rows pool the seeds of one tracker and scenario, and with more than one
//! scenario an `all` row pools every scenario of the tracker.

use lanepf::eval::suite::{markdown_table, run_member, score_run, CellRow, SuiteCell};
use lanepf::synth::{default_camera, draw_scenario, SCENARIOS};
use lanepf::trackers::{self, TrackerConfig, TRACKER_IDS};
use lanepf::{Error, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Options of `lanepf eval-suite`.
#[derive(clap::Args)]
pub struct Args {
    /// Tracker id, or `all`.
    #[arg(long)]
    tracker: String,
    /// Scene seeds, `A..B` (both included) or one seed `A`.
    #[arg(long)]
    seeds: String,
    /// Comma-separated scenario families (default: all twelve; `random` is accepted too).
    #[arg(long, value_delimiter = ',')]
    scenarios: Vec<String>,
    /// Image width.
    #[arg(long, default_value_t = 320)]
    width: usize,
    /// Image height.
    #[arg(long, default_value_t = 240)]
    height: usize,
    /// At most this many frames of each member (default: the member's own length).
    #[arg(long)]
    frames: Option<u32>,
    /// Seed of every tracker's particle filter.
    #[arg(long, default_value_t = 1)]
    tracker_seed: u64,
    /// Tracker options for every tracker of the run, a JSON object (e.g. `{"adjacent_lanes":
    /// true}`; an option a tracker does not have is refused); default: each tracker's own.
    #[arg(long)]
    options: Option<String>,
    /// Output folder (suite.md, suite.json).
    #[arg(long)]
    out: PathBuf,
}

/// Largest number of seeds one run accepts.
const MAX_SEEDS: u64 = 10_000;

/// Parses --options: a JSON object of tracker options (none: the defaults).
fn parse_options(text: Option<&str>) -> Result<BTreeMap<String, serde_json::Value>> {
    let Some(text) = text else {
        return Ok(BTreeMap::new());
    };
    serde_json::from_str(text).map_err(|e| {
        Error::Config(format!(
            "--options must be a JSON object of tracker options: {e}"
        ))
    })
}

/// Builds each tracker of `ids` once with `options` on the default camera, so that an option a
/// tracker does not take is refused before anything is rendered or written.
fn check_options(
    ids: &[String],
    options: &BTreeMap<String, serde_json::Value>,
    width: usize,
    height: usize,
) -> Result<()> {
    let config = TrackerConfig {
        camera: default_camera(width, height)?.to_file(),
        particles: None,
        seed: 1,
        options: trackers::Options::ByName(options.clone()),
    };
    for id in ids {
        trackers::create(id, &config)?;
    }
    Ok(())
}

/// Parses `A..B` (inclusive) or `A` into the seeds.
fn parse_seeds(text: &str) -> Result<std::ops::RangeInclusive<u64>> {
    let number = |s: &str| {
        s.trim().parse::<u64>().map_err(|_| {
            Error::Config(format!(
                "--seeds {text}: `{s}` is not a seed (a whole number); give A..B or A"
            ))
        })
    };
    let (a, b) = match text.split_once("..") {
        Some((a, b)) => (number(a)?, number(b.trim_start_matches('='))?),
        None => {
            let a = number(text)?;
            (a, a)
        }
    };
    if b < a {
        return Err(Error::Config(format!(
            "--seeds {text}: the range is empty; A..B needs B >= A (both are included)"
        )));
    }
    if b - a >= MAX_SEEDS {
        return Err(Error::Config(format!(
            "--seeds {text}: at most {MAX_SEEDS} seeds per run"
        )));
    }
    Ok(a..=b)
}

/// The tracker ids of `--tracker`.
fn tracker_ids(arg: &str) -> Result<Vec<String>> {
    if arg == "all" {
        return Ok(TRACKER_IDS.iter().map(|s| s.to_string()).collect());
    }
    if !TRACKER_IDS.contains(&arg) {
        return Err(Error::UnknownTracker {
            id: arg.to_string(),
            available: format!("{}, or all", TRACKER_IDS.join(", ")),
        });
    }
    Ok(vec![arg.to_string()])
}

/// The scenario names of `--scenarios`, each checked.
fn scenario_names(args: &[String]) -> Result<Vec<String>> {
    if args.is_empty() {
        return Ok(SCENARIOS.iter().map(|(n, _)| n.to_string()).collect());
    }
    for name in args {
        draw_scenario(name, 0)?;
    }
    Ok(args.to_vec())
}

fn io_error(path: &Path) -> impl Fn(std::io::Error) -> Error + '_ {
    move |e| Error::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    }
}

/// Runs the command.
pub fn run(args: Args) -> Result<()> {
    let seeds = parse_seeds(&args.seeds)?;
    let ids = tracker_ids(&args.tracker)?;
    let scenarios = scenario_names(&args.scenarios)?;
    if args.frames == Some(0) {
        return Err(Error::parameter("--frames", 0, "must be at least 1"));
    }
    let options = parse_options(args.options.as_deref())?;
    check_options(&ids, &options, args.width, args.height)?;
    std::fs::create_dir_all(&args.out).map_err(io_error(&args.out))?;
    let mut cells: BTreeMap<(String, String), SuiteCell> = BTreeMap::new();
    let started = Instant::now();
    for scenario in &scenarios {
        for seed in seeds.clone() {
            let member = draw_scenario(scenario, seed)?;
            let run = run_member(
                &member,
                &ids,
                args.width,
                args.height,
                args.frames,
                args.tracker_seed,
                &options,
            )?;
            for (id, output) in &run.outputs {
                let score = score_run(&run.truth, output)?;
                cells
                    .entry((id.clone(), scenario.clone()))
                    .or_default()
                    .add(&score);
            }
            eprintln!(
                "lanepf eval-suite: {scenario} seed {seed} ({} frames) done, {:.0} s",
                run.truth.len(),
                started.elapsed().as_secs_f64()
            );
        }
    }
    let mut rows: Vec<(String, String, CellRow)> = Vec::new();
    for id in &ids {
        let mut all = SuiteCell::default();
        for scenario in &scenarios {
            if let Some(cell) = cells.get(&(id.clone(), scenario.clone())) {
                rows.push((id.clone(), scenario.clone(), cell.row()));
                all.merge(cell);
            }
        }
        if scenarios.len() > 1 {
            rows.push((id.clone(), "all".into(), all.row()));
        }
    }
    let table = markdown_table(&rows);
    let md = args.out.join("suite.md");
    std::fs::write(&md, &table).map_err(io_error(&md))?;
    let json = serde_json::json!({
        "trackers": ids,
        "scenarios": scenarios,
        "seeds": [seeds.start(), seeds.end()],
        "width": args.width,
        "height": args.height,
        "frames": args.frames,
        "tracker_seed": args.tracker_seed,
        "options": options,
        "rows": rows
            .iter()
            .map(|(tracker, scenario, row)| serde_json::json!({
                "tracker": tracker,
                "scenario": scenario,
                "scores": row,
            }))
            .collect::<Vec<_>>(),
    });
    let path = args.out.join("suite.json");
    let text = serde_json::to_string_pretty(&json).map_err(|e| Error::Config(e.to_string()))?;
    std::fs::write(&path, text + "\n").map_err(io_error(&path))?;
    super::out(&table)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seeds_parse_as_inclusive_ranges_with_clear_errors() {
        assert_eq!(parse_seeds("1000..1019").unwrap(), 1000..=1019);
        assert_eq!(parse_seeds("7").unwrap(), 7..=7);
        assert_eq!(parse_seeds("3..=4").unwrap(), 3..=4);
        let e = parse_seeds("5..2").unwrap_err().to_string();
        assert!(e.contains("--seeds 5..2: the range is empty"), "{e}");
        let e = parse_seeds("a..2").unwrap_err().to_string();
        assert!(e.contains("`a` is not a seed"), "{e}");
        assert!(parse_seeds("0..20000").is_err());
    }
}
