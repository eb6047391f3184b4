//! Evaluation: how well a tracker's [`LaneEstimate`]s agree with ground truth.
//!
//! Predictions are the JSON lines of `lanepf track` ([`read_predictions`]); the ground truth is
//! one of five formats ([`Format`]), each with its own metric:
//!
//! | format | ground truth (`--gt`) | metric |
//! |---|---|---|
//! | `synthetic` | the simulator's `gt.jsonl` (or its folder) | parameter errors ([`params`]) and boundary accuracy ([`synthetic`]) |
//! | `caltech` | Caltech Lanes `labels.json` (or its folder) | Aly 2008 correct and false-positive rates, all lanes and ego lanes ([`caltech`]) |
//! | `tusimple` | TuSimple label JSON lines (or a folder with `labels.json`) | official accuracy, FP, FN ([`tusimple`]) |
//! | `culane` | a folder of `NNNNN.lines.txt` (or one file) | IoU matching, precision, recall, F1 ([`culane`]) |
//! | `kitti-road` | KITTI road's `gt_image_2` folder of `*_lane_*.png` masks (or one mask) | the ego lane's pixels in the image: precision, recall, F1 ([`kitti_road`]) |
//!
//! **Frames.** A prediction belongs to the ground-truth frame named by its `frame` field:
//! names are compared by file name, without directories (`frames/f00088.png` finds
//! `f00088.png`, `0000.png` finds TuSimple's `image/0000.png`). Where several ground-truth
//! frames share a file name (TuSimple's `clips/.../20.jpg`), the prediction must give the full
//! name as the labels write it; a file name that is still ambiguous is an error, and so is a
//! second prediction for the same frame. A ground-truth frame without a prediction counts as a
//! frame where nothing was detected (no lanes, no valid estimate). A prediction for a frame the
//! ground truth does not have is ignored and listed in the report (`unknown_frames`).
//!
//! **Invalid estimates** (`"valid": false`) count as detecting nothing in every format, even if
//! they carry boundaries: the tracker itself says it has no confident estimate.

pub mod caltech;
pub mod culane;
pub mod kitti_road;
pub mod lane_changes;
pub mod lane_configuration;
pub mod params;
pub mod suite;
pub mod synthetic;
pub mod tusimple;

mod assign;
pub mod limits;
mod polyline;
mod sniff;

pub use sniff::guess_format;

use crate::error::{Error, Result};
use crate::lane::LaneEstimate;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// A ground-truth format, named on the command line
/// `synthetic|caltech|tusimple|culane|kitti-road`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// The simulator's `gt.jsonl`.
    Synthetic,
    /// Caltech Lanes (Aly 2008) `labels.json`.
    Caltech,
    /// TuSimple label JSON lines.
    Tusimple,
    /// CULane `.lines.txt` files.
    Culane,
    /// KITTI road ego-lane masks (`gt_image_2/*_lane_*.png`).
    #[serde(rename = "kitti-road")]
    KittiRoad,
}

impl Format {
    /// Every format, in command-line order.
    pub const ALL: [Format; 5] = [
        Format::Synthetic,
        Format::Caltech,
        Format::Tusimple,
        Format::Culane,
        Format::KittiRoad,
    ];

    /// The command-line name.
    pub fn as_str(self) -> &'static str {
        match self {
            Format::Synthetic => "synthetic",
            Format::Caltech => "caltech",
            Format::Tusimple => "tusimple",
            Format::Culane => "culane",
            Format::KittiRoad => "kitti-road",
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for Format {
    type Err = Error;

    fn from_str(s: &str) -> Result<Self> {
        Format::ALL
            .into_iter()
            .find(|f| f.as_str() == s)
            .ok_or_else(|| {
                Error::parameter(
                    "format",
                    s,
                    "expected synthetic, caltech, tusimple, culane or kitti-road",
                )
            })
    }
}

/// Settings of [`evaluate_with`] beyond the formats' own rules.
#[derive(Debug, Clone, PartialEq)]
pub struct EvalOptions {
    /// TuSimple: a frame whose prediction took longer than this many milliseconds (its `ms`)
    /// scores accuracy 0, FP 0, FN 1, as in the official benchmark. `None` switches the rule
    /// off (useful for debug builds). Default: `Some(200.0)`.
    pub tusimple_time_limit_ms: Option<f64>,
    /// [width, height] of the images. CULane: used for frames whose `.jpg` is not beside the
    /// labels (default 1640x590). Caltech: overrides the labels' `image_size` for the ego-lane
    /// choice.
    pub image_size: Option<[usize; 2]>,
}

impl Default for EvalOptions {
    fn default() -> Self {
        EvalOptions {
            tusimple_time_limit_ms: Some(tusimple::TIME_LIMIT_MS),
            image_size: None,
        }
    }
}

/// The figures of one format.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Metrics {
    /// Parameter errors and boundary accuracy.
    Synthetic(Box<synthetic::SyntheticReport>),
    /// Aly's rates.
    Caltech(caltech::CaltechReport),
    /// The official TuSimple figures.
    Tusimple(tusimple::TusimpleReport),
    /// CULane precision, recall, F1.
    Culane(culane::CulaneReport),
    /// KITTI road ego-lane pixels.
    #[serde(rename = "kitti-road")]
    KittiRoad(kitti_road::KittiRoadReport),
}

/// The result of an evaluation: frame bookkeeping and the format's figures. Serialises to JSON
/// for `--json`; `Display` is a readable table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EvalReport {
    /// The ground-truth format.
    pub format: Format,
    /// Ground-truth frames.
    pub frames: usize,
    /// Ground-truth frames that had a prediction.
    pub predicted_frames: usize,
    /// Of those, predictions marked invalid (they count as detecting nothing).
    pub invalid_predictions: usize,
    /// Ground-truth frames without a prediction (they count as detecting nothing).
    pub missing_frames: usize,
    /// Frames of predictions the ground truth does not have (ignored).
    pub unknown_frames: Vec<String>,
    /// The figures.
    pub metrics: Metrics,
}

impl fmt::Display for EvalReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{} evaluation: {} ground-truth frames, {} predicted ({} invalid), {} missing, {} \
             unknown predictions ignored",
            self.format,
            self.frames,
            self.predicted_frames,
            self.invalid_predictions,
            self.missing_frames,
            self.unknown_frames.len()
        )?;
        if !self.unknown_frames.is_empty() {
            let shown: Vec<&str> = self
                .unknown_frames
                .iter()
                .take(3)
                .map(String::as_str)
                .collect();
            let more = if self.unknown_frames.len() > 3 {
                ", ..."
            } else {
                ""
            };
            writeln!(f, "  unknown: {}{more}", shown.join(", "))?;
        }
        match &self.metrics {
            Metrics::Synthetic(r) => write!(f, "{r}"),
            Metrics::Caltech(r) => write!(f, "{r}"),
            Metrics::Tusimple(r) => write!(f, "{r}"),
            Metrics::Culane(r) => write!(f, "{r}"),
            Metrics::KittiRoad(r) => write!(f, "{r}"),
        }
    }
}

impl EvalReport {
    /// The format's per-frame table (`lanepf eval --per-frame`): one line a ground-truth frame,
    /// in the ground truth's order.
    pub fn frames_table(&self) -> String {
        match &self.metrics {
            Metrics::Synthetic(r) => r.boundaries.frames_table(),
            Metrics::Caltech(r) => r.frames_table(),
            Metrics::Tusimple(r) => r.frames_table(),
            Metrics::Culane(r) => r.frames_table(),
            Metrics::KittiRoad(r) => r.frames_table(),
        }
    }
}

/// `read` of the file `path`, or of every file of the folder `path` whose name passes `keep`,
/// in name order.
///
/// # Errors
/// [`Error::Io`] when the folder cannot be listed; [`Error::Config`] when it holds no such
/// file (`what` names them); `read`'s errors.
pub(crate) fn each_file<T>(
    path: &Path,
    keep: impl Fn(&str) -> bool,
    what: &str,
    read: impl Fn(&Path) -> Result<T>,
) -> Result<Vec<T>> {
    if !path.is_dir() {
        return Ok(vec![read(path)?]);
    }
    let mut files: Vec<PathBuf> = std::fs::read_dir(path)
        .map_err(|e| Error::Io {
            path: path.display().to_string(),
            reason: e.to_string(),
        })?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.file_name().is_some_and(|n| keep(&n.to_string_lossy())))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(Error::Config(format!("{}: no {what}", path.display())));
    }
    files.iter().map(|f| read(f)).collect()
}

/// Reads a whole text file of at most [`limits::MAX_FILE_BYTES`].
pub(crate) fn read_text(path: &Path) -> Result<String> {
    limits::read_text(path)
}

/// `num / den`, or `None` when `den` is 0 (precision, recall and F1 of pixel or lane counts).
pub(crate) fn ratio(num: usize, den: usize) -> Option<f64> {
    (den > 0).then(|| num as f64 / den as f64)
}

/// A rate as a percentage, or "n/a".
pub(crate) fn percent(rate: Option<f64>) -> String {
    rate.map_or_else(|| "n/a".to_string(), |r| format!("{:.1} %", 100.0 * r))
}

/// The last component of a `/`- or `\`-separated name.
pub(crate) fn file_name(name: &str) -> &str {
    name.rsplit(['/', '\\']).next().unwrap_or(name)
}

/// Parses prediction JSON lines (one [`LaneEstimate`] per line, blank lines skipped);
/// `source` names the text in errors.
///
/// # Errors
/// [`Error::Config`] naming the (1-based) line that is not a lane estimate, is longer than
/// [`limits::MAX_LINE_BYTES`] or has a polyline of more than [`limits::MAX_POINTS`] points.
pub fn parse_predictions(text: &str, source: &str) -> Result<Vec<LaneEstimate>> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        limits::check_line(source, i + 1, line)?;
        let e: LaneEstimate = serde_json::from_str(line).map_err(|e| {
            Error::Config(format!("{source} line {}: not a lane estimate: {e}", i + 1))
        })?;
        for (k, b) in e.boundaries.iter().enumerate() {
            limits::check_points(
                &format!("{source} line {}: boundary {k}", i + 1),
                b.points.len(),
            )?;
        }
        out.push(e);
    }
    Ok(out)
}

/// Reads the JSON lines written by `lanepf track`.
///
/// # Errors
/// [`Error::Io`] when the file cannot be read; [`Error::Config`] naming the first bad line.
pub fn read_predictions(path: &Path) -> Result<Vec<LaneEstimate>> {
    let text = read_text(path)?;
    parse_predictions(&text, &path.display().to_string())
}

/// Predictions assigned to ground-truth frames.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameMatch<'a> {
    /// The prediction of each ground-truth frame, in ground-truth order.
    pub per_gt: Vec<Option<&'a LaneEstimate>>,
    /// Prediction frames that matched no ground-truth frame, in input order.
    pub unknown: Vec<String>,
}

/// Assigns predictions to the ground-truth frames named `gt_names` (see the module docs for
/// the rules).
///
/// # Errors
/// [`Error::Config`] for a prediction whose file name fits several ground-truth frames, or two
/// predictions for one frame.
pub fn match_frames<'a, S: AsRef<str>>(
    gt_names: &[S],
    preds: &'a [LaneEstimate],
) -> Result<FrameMatch<'a>> {
    let mut exact: HashMap<&str, usize> = HashMap::new();
    let mut by_file: HashMap<&str, Vec<usize>> = HashMap::new();
    for (i, name) in gt_names.iter().enumerate() {
        let name = name.as_ref();
        exact.entry(name).or_insert(i);
        by_file.entry(file_name(name)).or_default().push(i);
    }
    let mut per_gt: Vec<Option<&LaneEstimate>> = vec![None; gt_names.len()];
    let mut unknown = Vec::new();
    for p in preds {
        let idx = match exact.get(p.frame.as_str()) {
            Some(&i) => Some(i),
            None => match by_file.get(file_name(&p.frame)).map(Vec::as_slice) {
                None | Some([]) => None,
                Some([i]) => Some(*i),
                Some(many) => {
                    let names: Vec<&str> =
                        many.iter().take(3).map(|&i| gt_names[i].as_ref()).collect();
                    return Err(Error::Config(format!(
                        "prediction frame `{}` fits {} ground-truth frames ({}, ...): give the \
                         full name",
                        p.frame,
                        many.len(),
                        names.join(", ")
                    )));
                }
            },
        };
        match idx {
            None => unknown.push(p.frame.clone()),
            Some(i) if per_gt[i].is_some() => {
                return Err(Error::Config(format!(
                    "two predictions for ground-truth frame `{}`",
                    gt_names[i].as_ref()
                )));
            }
            Some(i) => per_gt[i] = Some(p),
        }
    }
    Ok(FrameMatch { per_gt, unknown })
}

/// `path` itself, or `path/name` when `path` is a folder.
fn file_or_in_dir(path: &Path, name: &str) -> std::path::PathBuf {
    if path.is_dir() {
        path.join(name)
    } else {
        path.to_path_buf()
    }
}

/// Ground truth loaded in one of the formats.
enum GroundTruth {
    Synthetic(Vec<LaneEstimate>),
    Caltech(caltech::CaltechLabels),
    Tusimple(Vec<tusimple::TusimpleFrame>),
    Culane(Vec<culane::CulaneFrame>),
    KittiRoad(Vec<kitti_road::KittiRoadFrame>),
}

impl GroundTruth {
    /// Loads the ground truth; when it does not parse, the error says which format the file
    /// looks like if that is another one.
    fn load(format: Format, path: &Path) -> Result<Self> {
        Self::load_as(format, path).map_err(|e| match e {
            Error::Config(message) => {
                let file = match format {
                    Format::Caltech | Format::Tusimple => file_or_in_dir(path, "labels.json"),
                    _ => path.to_path_buf(),
                };
                let guess = file
                    .is_file()
                    .then(|| limits::read_text(&file).ok())
                    .flatten()
                    .and_then(|text| guess_format(&text))
                    .filter(|&g| g != format);
                match guess {
                    Some(g) => Error::Config(format!(
                        "{message}; the file looks like {}: try --format {g}",
                        sniff::describe(g)
                    )),
                    None => Error::Config(message),
                }
            }
            other => other,
        })
    }

    fn load_as(format: Format, path: &Path) -> Result<Self> {
        Ok(match format {
            Format::Synthetic => GroundTruth::Synthetic(synthetic::read_ground_truth(path)?),
            Format::Caltech => {
                GroundTruth::Caltech(caltech::read_labels(&file_or_in_dir(path, "labels.json"))?)
            }
            Format::Tusimple => {
                GroundTruth::Tusimple(tusimple::read_labels(&file_or_in_dir(path, "labels.json"))?)
            }
            Format::Culane => GroundTruth::Culane(culane::read_labels(path)?),
            Format::KittiRoad => GroundTruth::KittiRoad(kitti_road::read_labels(path)?),
        })
    }

    fn frame_names(&self) -> Vec<&str> {
        match self {
            GroundTruth::Synthetic(gt) => gt.iter().map(|g| g.frame.as_str()).collect(),
            GroundTruth::Caltech(l) => l.frames.iter().map(|f| f.frame.as_str()).collect(),
            GroundTruth::Tusimple(l) => l.iter().map(|f| f.frame.as_str()).collect(),
            GroundTruth::Culane(l) => l.iter().map(|f| f.frame.as_str()).collect(),
            GroundTruth::KittiRoad(l) => l.iter().map(|f| f.frame.as_str()).collect(),
        }
    }

    fn score(&self, preds: &[Option<&LaneEstimate>], options: &EvalOptions) -> Result<Metrics> {
        Ok(match self {
            GroundTruth::Synthetic(gt) => {
                Metrics::Synthetic(Box::new(synthetic::evaluate(gt, preds)?))
            }
            GroundTruth::Caltech(l) => {
                Metrics::Caltech(caltech::evaluate(l, preds, options.image_size)?)
            }
            GroundTruth::Tusimple(l) => Metrics::Tusimple(tusimple::evaluate(
                l,
                preds,
                options.tusimple_time_limit_ms,
            )?),
            GroundTruth::Culane(l) => {
                Metrics::Culane(culane::evaluate(l, preds, options.image_size)?)
            }
            GroundTruth::KittiRoad(l) => Metrics::KittiRoad(kitti_road::evaluate(l, preds)?),
        })
    }
}

/// Evaluates `predictions` against the ground truth at `gt_path` with the default options.
///
/// # Errors
/// As [`evaluate_with`].
pub fn evaluate(
    format: Format,
    predictions: &[LaneEstimate],
    gt_path: &Path,
) -> Result<EvalReport> {
    evaluate_with(format, predictions, gt_path, &EvalOptions::default())
}

/// Evaluates `predictions` against the ground truth at `gt_path`.
///
/// # Errors
/// [`Error::Io`] when the ground truth cannot be read; [`Error::Config`] when it is malformed
/// or empty, or frames cannot be matched (see [`match_frames`]).
pub fn evaluate_with(
    format: Format,
    predictions: &[LaneEstimate],
    gt_path: &Path,
    options: &EvalOptions,
) -> Result<EvalReport> {
    let gt = GroundTruth::load(format, gt_path)?;
    let names = gt.frame_names();
    let matched = match_frames(&names, predictions)?;
    let metrics = gt.score(&matched.per_gt, options)?;
    let predicted = matched.per_gt.iter().flatten().count();
    Ok(EvalReport {
        format,
        frames: names.len(),
        predicted_frames: predicted,
        invalid_predictions: matched.per_gt.iter().flatten().filter(|p| !p.valid).count(),
        missing_frames: names.len() - predicted,
        unknown_frames: matched.unknown,
        metrics,
    })
}

#[cfg(test)]
mod tests;
