//! The TuSimple lane benchmark: its label reader and its official accuracy, FP and FN.
//!
//! **Labels** are JSON lines with `raw_file` (the clip frame), `h_samples` (the image rows) and
//! `lanes` (`lanes[k][i]` is the x of lane k at row `h_samples[i]`, negative, normally -2, where
//! the lane is absent). The frame name is `lanenet_image` when the line has it (the shared
//! copy names its image in `images/` this way), else the full `raw_file` path; predictions
//! match it by file name (see [`crate::eval`]), or by the full path where file names repeat, as
//! TuSimple's `.../20.jpg` do.
//!
//! **Predictions**: every boundary of a valid [`LaneEstimate`] becomes one TuSimple lane: its x
//! at each row of `h_samples` inside the polyline's y range, by linear interpolation between
//! the two polyline points around the row, and -2 outside that range ([`polyline_to_lane`]).
//! An invalid estimate, or a frame without a prediction, has no lanes.
//!
//! **Metric**, per frame, following the official `LaneEval.bench`:
//!
//! - every ground-truth lane gets an angle θ = atan(k), k the least-squares slope of x on y over
//!   its present points (x >= 0; θ = 0 with fewer than two), and a threshold 20 px / cos θ;
//! - the accuracy of a prediction against a ground-truth lane is the fraction of *all* rows
//!   where |x_pred - x_gt| < threshold, after replacing every negative x on either side by -100:
//!   a row absent from both counts as correct, a row present in one only counts as wrong;
//! - each ground-truth lane takes the best accuracy over all predictions (predictions may serve
//!   several lanes: the official metric is not one-to-one); it is matched when that is >= 0.85,
//!   otherwise it is a false negative;
//! - FP = (number of predictions - number of matched lanes) / number of predictions (0 without
//!   predictions; it can go negative when one prediction matches two lanes, as officially);
//! - with more than 4 ground-truth lanes one false negative is forgiven and the worst lane
//!   accuracy is left out of the sum;
//! - accuracy = sum of lane accuracies / max(min(4, gt lanes), 1),
//!   FN = false negatives / max(min(4, gt lanes), 1);
//! - a frame with more than gt lanes + 2 predictions scores accuracy 0, FP 0, FN 1, and so does
//!   a frame whose prediction took more than 200 ms (the `ms` field; see
//!   [`super::EvalOptions::tusimple_time_limit_ms`] to switch this off).
//!
//! The benchmark figures are the means of the per-frame scores over all ground-truth frames.

use super::polyline::{x_at_y, y_range};
use crate::error::{Error, Result};
use crate::lane::{Boundary, LaneEstimate};
use crate::math;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::Path;

/// Pixel threshold before the angle correction.
pub const PIXEL_THRESHOLD: f64 = 20.0;
/// Lane accuracy needed for a ground-truth lane to count as detected.
pub const LANE_MATCH_ACCURACY: f64 = 0.85;
/// The official limit on a frame's running time, milliseconds.
pub const TIME_LIMIT_MS: f64 = 200.0;
/// The value TuSimple uses for "no lane at this row".
pub const ABSENT: f64 = -2.0;

/// One labelled TuSimple frame.
#[derive(Debug, Clone, PartialEq)]
pub struct TusimpleFrame {
    /// The frame name predictions are matched against (`lanenet_image`, else `raw_file`).
    pub frame: String,
    /// The clip frame path as labelled.
    pub raw_file: String,
    /// Image rows of the samples.
    pub h_samples: Vec<f64>,
    /// x of each lane at each row; negative where absent.
    pub lanes: Vec<Vec<f64>>,
}

#[derive(Deserialize)]
struct LabelLine {
    raw_file: String,
    lanes: Vec<Vec<f64>>,
    h_samples: Vec<f64>,
    #[serde(default)]
    lanenet_image: Option<String>,
}

/// Parses TuSimple label JSON lines; `source` names the text in errors. Blank lines are
/// skipped.
///
/// # Errors
/// [`Error::Config`] naming the line for malformed JSON, a missing key, or a lane whose length
/// differs from `h_samples`.
pub fn parse_labels(text: &str, source: &str) -> Result<Vec<TusimpleFrame>> {
    let mut frames = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        super::limits::check_line(source, i + 1, line)?;
        let l: LabelLine = serde_json::from_str(line)
            .map_err(|e| Error::Config(format!("{source} line {}: {e}", i + 1)))?;
        super::limits::check_points(
            &format!("{source} line {}: h_samples", i + 1),
            l.h_samples.len(),
        )?;
        if let Some(k) = l.lanes.iter().position(|x| x.len() != l.h_samples.len()) {
            return Err(Error::Config(format!(
                "{source} line {}: lane {k} has {} values but there are {} h_samples",
                i + 1,
                l.lanes[k].len(),
                l.h_samples.len()
            )));
        }
        frames.push(TusimpleFrame {
            frame: l.lanenet_image.unwrap_or_else(|| l.raw_file.clone()),
            raw_file: l.raw_file,
            h_samples: l.h_samples,
            lanes: l.lanes,
        });
    }
    Ok(frames)
}

/// Reads a TuSimple label file (JSON lines).
///
/// # Errors
/// [`Error::Io`] when it cannot be read, otherwise as [`parse_labels`].
pub fn read_labels(path: &Path) -> Result<Vec<TusimpleFrame>> {
    let text = super::read_text(path)?;
    parse_labels(&text, &path.display().to_string())
}

/// The TuSimple lane of an image polyline: x at each of `h_samples` inside the polyline's y
/// range (linear interpolation), [`ABSENT`] elsewhere.
pub fn polyline_to_lane(points: &[[f64; 2]], h_samples: &[f64]) -> Vec<f64> {
    let Some((lo, hi)) = y_range(points) else {
        return vec![ABSENT; h_samples.len()];
    };
    h_samples
        .iter()
        .map(|&y| {
            if y < lo || y > hi {
                ABSENT
            } else {
                x_at_y(points, y).unwrap_or(ABSENT)
            }
        })
        .collect()
}

/// The TuSimple lanes of a prediction's boundaries (none for an invalid estimate).
pub fn estimate_to_lanes(estimate: &LaneEstimate, h_samples: &[f64]) -> Vec<Vec<f64>> {
    if !estimate.valid {
        return Vec::new();
    }
    boundaries_to_lanes(&estimate.boundaries, h_samples)
}

/// One TuSimple lane per boundary, in order.
pub fn boundaries_to_lanes(boundaries: &[Boundary], h_samples: &[f64]) -> Vec<Vec<f64>> {
    boundaries
        .iter()
        .map(|b| polyline_to_lane(&b.points, h_samples))
        .collect()
}

/// The angle θ (radians) of a ground-truth lane: atan of the least-squares slope dx/dy over
/// the rows where x >= 0; 0 with fewer than two such rows (or all on one row).
pub fn lane_angle(xs: &[f64], ys: &[f64]) -> f64 {
    let pts = || xs.iter().zip(ys).filter(|(x, _)| **x >= 0.0);
    let n = pts().count();
    if n < 2 {
        return 0.0;
    }
    let (sx, sy) = pts().fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
    let (mx, my) = (sx / n as f64, sy / n as f64);
    let (sxy, syy) = pts().fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + (x - mx) * (y - my), b + (y - my) * (y - my))
    });
    if syy > 0.0 {
        math::atan(sxy / syy)
    } else {
        0.0
    }
}

/// The point threshold of a lane with angle `angle`: 20 px / cos θ.
pub fn point_threshold(angle: f64) -> f64 {
    PIXEL_THRESHOLD / math::cos(angle)
}

/// Fraction of rows where |pred - gt| < `threshold`, every negative value on either side read
/// as -100 (so rows absent from both agree). 0 for empty lanes.
pub fn line_accuracy(pred: &[f64], gt: &[f64], threshold: f64) -> f64 {
    if gt.is_empty() {
        return 0.0;
    }
    let norm = |v: f64| if v >= 0.0 { v } else { -100.0 };
    let correct = pred
        .iter()
        .zip(gt)
        .filter(|(p, g)| (norm(**p) - norm(**g)).abs() < threshold)
        .count();
    correct as f64 / gt.len() as f64
}

/// The score of one frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FrameScore {
    /// Accuracy (official definition, see the module docs).
    pub accuracy: f64,
    /// False-positive rate of the frame.
    #[serde(rename = "fp")]
    pub false_positive: f64,
    /// False-negative rate of the frame.
    #[serde(rename = "fn")]
    pub false_negative: f64,
}

impl FrameScore {
    /// The score of a rejected frame (too many lanes, too slow): accuracy 0, FP 0, FN 1.
    pub const REJECTED: FrameScore = FrameScore {
        accuracy: 0.0,
        false_positive: 0.0,
        false_negative: 1.0,
    };
}

/// Scores one frame as the official `LaneEval.bench` does (without its running-time rule,
/// which [`evaluate`] applies).
///
/// # Errors
/// [`Error::Parameter`] when a predicted or ground-truth lane's length differs from
/// `h_samples`.
pub fn bench_frame(pred: &[Vec<f64>], gt: &[Vec<f64>], h_samples: &[f64]) -> Result<FrameScore> {
    for (what, lanes) in [("predicted", pred), ("ground-truth", gt)] {
        if let Some(l) = lanes.iter().find(|l| l.len() != h_samples.len()) {
            return Err(Error::parameter(
                &format!("{what} lane length"),
                l.len(),
                &format!("must equal the number of h_samples ({})", h_samples.len()),
            ));
        }
    }
    if gt.len() + 2 < pred.len() {
        return Ok(FrameScore::REJECTED);
    }
    let mut accs = Vec::with_capacity(gt.len());
    let (mut matched, mut missed) = (0usize, 0usize);
    for g in gt {
        let threshold = point_threshold(lane_angle(g, h_samples));
        let best = pred
            .iter()
            .map(|p| line_accuracy(p, g, threshold))
            .fold(0.0, f64::max);
        if best < LANE_MATCH_ACCURACY {
            missed += 1;
        } else {
            matched += 1;
        }
        accs.push(best);
    }
    let mut sum: f64 = accs.iter().sum();
    if gt.len() > 4 {
        missed = missed.saturating_sub(1);
        sum -= accs.iter().copied().fold(f64::INFINITY, f64::min);
    }
    let denom = gt.len().clamp(1, 4) as f64;
    let false_positive = if pred.is_empty() {
        0.0
    } else {
        (pred.len() as f64 - matched as f64) / pred.len() as f64
    };
    Ok(FrameScore {
        accuracy: sum / denom,
        false_positive,
        false_negative: missed as f64 / denom,
    })
}

/// A frame's score with its name.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NamedScore {
    /// Ground-truth frame name.
    pub frame: String,
    /// Its score.
    #[serde(flatten)]
    pub score: FrameScore,
    /// Number of ground-truth lanes.
    pub gt_lanes: usize,
    /// Number of predicted lanes.
    pub pred_lanes: usize,
}

/// The TuSimple figures of a prediction set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TusimpleReport {
    /// Mean accuracy over the ground-truth frames.
    pub accuracy: f64,
    /// Mean false-positive rate.
    pub fp: f64,
    /// Mean false-negative rate.
    #[serde(rename = "fn")]
    pub fn_rate: f64,
    /// Frames scored 0/0/1 because the prediction took longer than the time limit.
    pub slow_frames: usize,
    /// Frames scored 0/0/1 because they had more than gt + 2 predicted lanes.
    pub too_many_lanes_frames: usize,
    /// Per-frame scores, in label order.
    pub frames: Vec<NamedScore>,
}

/// Scores predictions (`preds[i]` belongs to `labels[i]`, `None` when missing) with the
/// official rules; `time_limit_ms` is the running-time rule (`None` to switch it off).
///
/// # Errors
/// [`Error::Config`] when there are no labelled frames; as [`bench_frame`] for bad labels.
pub fn evaluate(
    labels: &[TusimpleFrame],
    preds: &[Option<&LaneEstimate>],
    time_limit_ms: Option<f64>,
) -> Result<TusimpleReport> {
    if labels.is_empty() {
        return Err(Error::Config("no TuSimple frames to evaluate".into()));
    }
    let mut frames = Vec::with_capacity(labels.len());
    let (mut slow, mut crowded) = (0, 0);
    for (i, label) in labels.iter().enumerate() {
        let pred = preds.get(i).copied().flatten();
        let lanes = pred.map_or_else(Vec::new, |p| estimate_to_lanes(p, &label.h_samples));
        let too_slow = match (pred, time_limit_ms) {
            (Some(p), Some(limit)) => p.ms > limit,
            _ => false,
        };
        let score = if too_slow {
            slow += 1;
            FrameScore::REJECTED
        } else {
            if label.lanes.len() + 2 < lanes.len() {
                crowded += 1;
            }
            bench_frame(&lanes, &label.lanes, &label.h_samples)?
        };
        frames.push(NamedScore {
            frame: label.frame.clone(),
            score,
            gt_lanes: label.lanes.len(),
            pred_lanes: lanes.len(),
        });
    }
    let n = frames.len() as f64;
    let mean = |f: fn(&FrameScore) -> f64| frames.iter().map(|s| f(&s.score)).sum::<f64>() / n;
    Ok(TusimpleReport {
        accuracy: mean(|s| s.accuracy),
        fp: mean(|s| s.false_positive),
        fn_rate: mean(|s| s.false_negative),
        slow_frames: slow,
        too_many_lanes_frames: crowded,
        frames,
    })
}

impl TusimpleReport {
    /// One line a frame: accuracy, FP and FN rates, labelled and predicted lanes.
    pub fn frames_table(&self) -> String {
        let mut out = String::from(
            "  frame                                   accuracy     FP     FN  gt  pred\n",
        );
        for f in &self.frames {
            let s = f.score;
            let mark = if s.false_positive > 0.0 || s.false_negative > 0.0 {
                "  <- FP / FN"
            } else {
                ""
            };
            out.push_str(&format!(
                "  {:<38} {:>9.3} {:>6.3} {:>6.3} {:>3} {:>5}{mark}\n",
                f.frame, s.accuracy, s.false_positive, s.false_negative, f.gt_lanes, f.pred_lanes
            ));
        }
        out
    }
}

impl fmt::Display for TusimpleReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "  TuSimple (official rules)    value")?;
        writeln!(f, "  accuracy                    {:7.4}", self.accuracy)?;
        writeln!(f, "  FP                          {:7.4}", self.fp)?;
        writeln!(f, "  FN                          {:7.4}", self.fn_rate)?;
        writeln!(f, "  frames over 200 ms          {:7}", self.slow_frames)?;
        write!(
            f,
            "  frames with > gt+2 lanes    {:7}",
            self.too_many_lanes_frames
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lane::Role;

    fn rows() -> Vec<f64> {
        (0..20).map(|i| 300.0 + 10.0 * i as f64).collect()
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-12
    }

    #[test]
    fn vertical_lane_19_px_off_is_correct_21_px_is_not() {
        let h = rows();
        let gt = vec![vec![500.0; h.len()]];
        let s = bench_frame(&[vec![519.0; h.len()]], &gt, &h).unwrap();
        assert_eq!(
            s,
            FrameScore {
                accuracy: 1.0,
                false_positive: 0.0,
                false_negative: 0.0
            }
        );
        let s = bench_frame(&[vec![521.0; h.len()]], &gt, &h).unwrap();
        assert_eq!(
            s,
            FrameScore {
                accuracy: 0.0,
                false_positive: 1.0,
                false_negative: 1.0
            }
        );
        // Exactly 20 px is not "< 20".
        assert!(close(line_accuracy(&[520.0], &[500.0], 20.0), 0.0));
    }

    #[test]
    fn tilted_lane_widens_the_threshold_by_one_over_cos() {
        // x = 2 y: slope 2, cos(atan 2) = 1/sqrt 5, threshold 20 sqrt 5 = 44.72 px.
        let h = rows();
        let gt: Vec<f64> = h.iter().map(|y| 2.0 * y - 300.0).collect();
        let angle = lane_angle(&gt, &h);
        assert!(close(angle, math::atan(2.0)));
        assert!((point_threshold(angle) - 20.0 * 5f64.sqrt()).abs() < 1e-9);
        let shifted = |dx: f64| -> Vec<f64> { gt.iter().map(|x| x + dx).collect() };
        let s = bench_frame(&[shifted(40.0)], std::slice::from_ref(&gt), &h).unwrap();
        assert!(close(s.accuracy, 1.0), "40 px is inside 44.7 px: {s:?}");
        let s = bench_frame(&[shifted(45.0)], std::slice::from_ref(&gt), &h).unwrap();
        assert!(close(s.accuracy, 0.0), "45 px is outside: {s:?}");
        // Absent rows (-2) are left out of the fit: the angle is unchanged.
        let mut partial = gt.clone();
        partial[..5].fill(ABSENT);
        assert!(close(lane_angle(&partial, &h), angle));
    }

    #[test]
    fn absent_rows_agree_with_absent_rows_only() {
        let gt = [ABSENT, ABSENT, 100.0, 110.0];
        assert!(close(
            line_accuracy(&[ABSENT, -5.0, 101.0, ABSENT], &gt, 20.0),
            0.75
        ));
        assert!(close(
            line_accuracy(&[1.0, ABSENT, 101.0, 111.0], &gt, 20.0),
            0.75
        ));
    }

    #[test]
    fn five_gt_lanes_forgive_one_miss_and_drop_the_worst_accuracy() {
        let h = rows();
        let gt: Vec<Vec<f64>> = (0..5).map(|k| vec![100.0 + 200.0 * k as f64; 20]).collect();
        // Four lanes found exactly, the fifth not at all.
        let s = bench_frame(&gt[..4], &gt, &h).unwrap();
        assert!(close(s.accuracy, 1.0), "{s:?}");
        assert!(close(s.false_negative, 0.0), "{s:?}");
        assert!(close(s.false_positive, 0.0), "{s:?}");
        // Three found: one of the two misses is forgiven; sum 3 - min 0 = 3 over 4.
        let s = bench_frame(&gt[..3], &gt, &h).unwrap();
        assert!(
            close(s.accuracy, 0.75) && close(s.false_negative, 0.25),
            "{s:?}"
        );
        // Four lanes: no forgiveness.
        let s = bench_frame(&gt[..3], &gt[..4], &h).unwrap();
        assert!(
            close(s.accuracy, 0.75) && close(s.false_negative, 0.25),
            "{s:?}"
        );
        let s = bench_frame(&gt[..2], &gt[..4], &h).unwrap();
        assert!(
            close(s.accuracy, 0.5) && close(s.false_negative, 0.5),
            "{s:?}"
        );
    }

    #[test]
    fn empty_and_crowded_predictions() {
        let h = rows();
        let gt: Vec<Vec<f64>> = (0..2).map(|k| vec![100.0 + 300.0 * k as f64; 20]).collect();
        let s = bench_frame(&[], &gt, &h).unwrap();
        assert_eq!(s, FrameScore::REJECTED);
        // Five predictions for two lanes: more than gt + 2.
        let many: Vec<Vec<f64>> = (0..5).map(|k| vec![100.0 + 300.0 * k as f64; 20]).collect();
        assert_eq!(bench_frame(&many, &gt, &h).unwrap(), FrameScore::REJECTED);
        // Four is allowed: two match, two are false positives.
        let s = bench_frame(&many[..4], &gt, &h).unwrap();
        assert!(
            close(s.accuracy, 1.0) && close(s.false_positive, 0.5),
            "{s:?}"
        );
        // No lanes at all: accuracy 0 (as officially), no FP, no FN.
        let s = bench_frame(&[], &[], &h).unwrap();
        assert!(close(s.accuracy, 0.0) && close(s.false_positive + s.false_negative, 0.0));
        assert!(bench_frame(&[vec![1.0; 3]], &gt, &h).is_err());
    }

    #[test]
    fn polylines_become_lanes_by_row_interpolation() {
        let h = [400.0, 410.0, 420.0, 430.0, 440.0];
        // Bottom-up, 8 px apart in y, from y = 436 to y = 404.
        let pts: Vec<[f64; 2]> = (0..5)
            .map(|i| {
                let y = 436.0 - 8.0 * i as f64;
                [y * 0.5, y]
            })
            .collect();
        let lane = polyline_to_lane(&pts, &h);
        assert_eq!(lane, vec![ABSENT, 205.0, 210.0, 215.0, ABSENT]);
        assert_eq!(polyline_to_lane(&[], &h), vec![ABSENT; 5]);
        let est = LaneEstimate {
            valid: false,
            boundaries: vec![Boundary {
                role: Role::EgoLeft,
                points: pts,
                road_points: vec![],
            }],
            ..Default::default()
        };
        assert!(
            estimate_to_lanes(&est, &h).is_empty(),
            "invalid => no lanes"
        );
    }

    #[test]
    fn labels_are_parsed_and_checked() {
        let text = concat!(
            r#"{"raw_file": "clips/a/20.jpg", "lanes": [[-2, 5]], "h_samples": [1, 2]}"#,
            "\n\n",
            r#"{"raw_file": "clips/b/20.jpg", "lanes": [], "h_samples": [1], "lanenet_image": "image/0001.png"}"#,
        );
        let frames = parse_labels(text, "t").unwrap();
        assert_eq!(frames.len(), 2);
        assert_eq!(frames[0].frame, "clips/a/20.jpg");
        assert_eq!(frames[1].frame, "image/0001.png");
        assert_eq!(frames[0].lanes, vec![vec![-2.0, 5.0]]);
        let bad = r#"{"raw_file": "x", "lanes": [[1, 2, 3]], "h_samples": [1, 2]}"#;
        let e = parse_labels(&format!("\n{bad}"), "t")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("line 2") && e.contains("lane 0 has 3 values"),
            "{e}"
        );
        let e = parse_labels("{", "t").unwrap_err().to_string();
        assert!(e.contains("t line 1"), "{e}");
    }

    #[test]
    fn slow_frames_are_rejected_unless_the_rule_is_off() {
        let h = rows();
        let label = TusimpleFrame {
            frame: "0000.png".into(),
            raw_file: "clips/x/20.jpg".into(),
            h_samples: h.clone(),
            lanes: vec![vec![500.0; 20]],
        };
        let pred = LaneEstimate {
            frame: "0000.png".into(),
            valid: true,
            ms: 250.0,
            boundaries: vec![Boundary {
                role: Role::EgoLeft,
                points: vec![[500.0, 500.0], [500.0, 300.0]],
                road_points: vec![],
            }],
            ..Default::default()
        };
        let labels = [label];
        let r = evaluate(&labels, &[Some(&pred)], Some(TIME_LIMIT_MS)).unwrap();
        assert_eq!((r.accuracy, r.fn_rate, r.slow_frames), (0.0, 1.0, 1));
        let r = evaluate(&labels, &[Some(&pred)], None).unwrap();
        assert_eq!(
            (r.accuracy, r.fp, r.fn_rate, r.slow_frames),
            (1.0, 0.0, 0.0, 0)
        );
        let r = evaluate(&labels, &[None], None).unwrap();
        assert_eq!((r.accuracy, r.fp, r.fn_rate), (0.0, 0.0, 1.0));
    }
}
