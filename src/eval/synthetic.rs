//! The `synthetic` format: the simulator's exact ground truth.
//!
//! **Ground truth** is `gt.jsonl` (written by `lanepf synth`; a folder holding it also works):
//! one [`LaneEstimate`]-shaped JSON object per frame. It is read leniently: unknown keys are
//! ignored, a missing `valid` means true, missing numbers are NaN (then not compared),
//! non-numeric `state` entries and boundaries with a role this version does not know are
//! dropped. Frame names are the `frame` fields (e.g. `000000.png`); predictions match them by
//! file name.
//!
//! **Report** = the parameter errors of [`super::params`] plus a boundary-level image accuracy:
//! for each ground-truth boundary with at least 2 points, the prediction's boundary with the
//! same role (the first one if several; none when the prediction is missing or invalid) is
//! compared on the integer image rows both polylines cover. The boundary is *correct* when
//!
//! - those common rows are at least half of the ground-truth boundary's rows (a prediction
//!   that covers only a sliver does not count), and
//! - the mean |x_pred - x_gt| over the common rows is <= [`BOUNDARY_THRESHOLD_PX`] = 20 px.
//!
//! boundary accuracy = correct / ground-truth boundaries; the mean x error is averaged over the
//! boundaries that had common rows. Predicted boundaries whose role is not in the ground truth
//! are counted as extra.

use super::params::{parameter_errors, ParamErrors};
use super::polyline::{x_at_y, y_range};
use crate::error::{Error, Result};
use crate::lane::{Boundary, LaneEstimate, Role};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt;
use std::path::Path;

/// Largest mean |x_pred - x_gt| of a correct boundary, pixels.
pub const BOUNDARY_THRESHOLD_PX: f64 = 20.0;
/// Smallest share of the ground-truth rows the prediction must also cover.
pub const MIN_ROW_COVERAGE: f64 = 0.5;

#[derive(Deserialize)]
struct GtLine {
    #[serde(default)]
    frame: String,
    #[serde(default = "yes")]
    valid: bool,
    #[serde(default)]
    boundaries: Vec<GtBoundary>,
    lateral_offset_m: Option<f64>,
    heading_rad: Option<f64>,
    curvature_per_m: Option<f64>,
    lane_width_m: Option<f64>,
    #[serde(default)]
    state: BTreeMap<String, serde_json::Value>,
}

#[derive(Deserialize)]
struct GtBoundary {
    role: String,
    #[serde(default)]
    points: Vec<[f64; 2]>,
    #[serde(default)]
    road_points: Vec<[f64; 2]>,
}

fn yes() -> bool {
    true
}

/// Parses ground-truth JSON lines leniently (see the module docs); `source` names the text in
/// errors. Blank lines are skipped.
///
/// # Errors
/// [`Error::Config`] naming the line when a line is not a JSON object of that shape.
pub fn parse_ground_truth(text: &str, source: &str) -> Result<Vec<LaneEstimate>> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        super::limits::check_line(source, i + 1, line)?;
        let g: GtLine = serde_json::from_str(line)
            .map_err(|e| Error::Config(format!("{source} line {}: {e}", i + 1)))?;
        for (k, b) in g.boundaries.iter().enumerate() {
            let what = format!("{source} line {}: boundary {k}", i + 1);
            super::limits::check_points(&what, b.points.len())?;
        }
        let boundaries = g
            .boundaries
            .into_iter()
            .filter_map(|b| {
                let role: Role = serde_json::from_value(serde_json::Value::String(b.role)).ok()?;
                Some(Boundary {
                    role,
                    points: b.points,
                    road_points: b.road_points,
                })
            })
            .collect();
        out.push(LaneEstimate {
            frame: g.frame,
            valid: g.valid,
            ms: 0.0,
            boundaries,
            lateral_offset_m: g.lateral_offset_m.unwrap_or(f64::NAN),
            heading_rad: g.heading_rad.unwrap_or(f64::NAN),
            curvature_per_m: g.curvature_per_m.unwrap_or(f64::NAN),
            lane_width_m: g.lane_width_m.unwrap_or(f64::NAN),
            delimiters: Vec::new(),
            state: g
                .state
                .into_iter()
                .filter_map(|(k, v)| v.as_f64().map(|v| (k, v)))
                .collect(),
        });
    }
    Ok(out)
}

/// Reads `gt.jsonl`, or `gt.jsonl` inside the folder `path`.
///
/// # Errors
/// [`Error::Io`] when it cannot be read, otherwise as [`parse_ground_truth`].
pub fn read_ground_truth(path: &Path) -> Result<Vec<LaneEstimate>> {
    let file = if path.is_dir() {
        path.join("gt.jsonl")
    } else {
        path.to_path_buf()
    };
    let text = super::read_text(&file)?;
    parse_ground_truth(&text, &file.display().to_string())
}

/// How a predicted boundary compares with a ground-truth one.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BoundaryComparison {
    /// Integer rows the ground truth covers.
    pub gt_rows: usize,
    /// Of those, the rows the prediction covers too.
    pub common_rows: usize,
    /// Mean |x_pred - x_gt| over the common rows (`None` without any).
    pub mean_abs_dx_px: Option<f64>,
    /// Whether this counts as correct (see the module docs).
    pub correct: bool,
}

/// Compares two image polylines on the integer rows both cover.
pub fn compare_boundaries(pred: &[[f64; 2]], gt: &[[f64; 2]]) -> BoundaryComparison {
    let rows = |p: &[[f64; 2]]| y_range(p).map(|(lo, hi)| (lo.ceil(), hi.floor()));
    let count = |(lo, hi): (f64, f64)| if hi >= lo { (hi - lo) as usize + 1 } else { 0 };
    let gt_rows = rows(gt).map_or(0, count);
    let (mut n, mut sum) = (0usize, 0.0);
    if let (Some((glo, ghi)), Some((plo, phi))) = (rows(gt), rows(pred)) {
        let (lo, hi) = (glo.max(plo), ghi.min(phi));
        let mut y = lo;
        while y <= hi {
            if let (Some(a), Some(b)) = (x_at_y(pred, y), x_at_y(gt, y)) {
                n += 1;
                sum += (a - b).abs();
            }
            y += 1.0;
        }
    }
    let mean = (n > 0).then(|| sum / n as f64);
    let correct = gt_rows > 0
        && n as f64 >= MIN_ROW_COVERAGE * gt_rows as f64
        && mean.is_some_and(|m| m <= BOUNDARY_THRESHOLD_PX);
    BoundaryComparison {
        gt_rows,
        common_rows: n,
        mean_abs_dx_px: mean,
        correct,
    }
}

/// Boundary counts of one role.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RoleAccuracy {
    /// The role.
    pub role: Role,
    /// Ground-truth boundaries of this role.
    pub gt: usize,
    /// Of those, how many had a predicted boundary of the role with common rows.
    pub compared: usize,
    /// Of those, how many were correct.
    pub correct: usize,
    /// Mean of the per-boundary mean |dx| over the compared ones, pixels.
    pub mean_abs_dx_px: Option<f64>,
}

/// The boundary-level image accuracy.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BoundaryAccuracy {
    /// Ground-truth boundaries scored (with at least 2 points).
    pub gt: usize,
    /// Correct boundaries.
    pub correct: usize,
    /// correct / gt (`None` without boundaries).
    pub accuracy: Option<f64>,
    /// Mean of the per-boundary mean |dx| over the compared boundaries, pixels.
    pub mean_abs_dx_px: Option<f64>,
    /// Predicted boundaries whose role the frame's ground truth does not have.
    pub extra_predicted: usize,
    /// Per role, in role order.
    pub per_role: Vec<RoleAccuracy>,
    /// Each ground-truth frame's boundaries, in frame order (they sum to `gt` and `correct`).
    pub frames: Vec<FrameBoundaries>,
}

/// One ground-truth frame's boundary-level counts.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrameBoundaries {
    /// The ground-truth frame's name.
    pub frame: String,
    /// Ground-truth boundaries scored.
    pub gt: usize,
    /// Correct ones.
    pub correct: usize,
    /// Whether the prediction was there and valid.
    pub valid: bool,
}

impl BoundaryAccuracy {
    /// One line a frame: correct / ground-truth boundaries and whether the prediction was valid.
    pub fn frames_table(&self) -> String {
        let mut out = String::from("  frame                 correct / gt   valid\n");
        for f in &self.frames {
            let mark = if f.correct < f.gt { "  <- missed" } else { "" };
            out.push_str(&format!(
                "  {:<20} {:>8} / {:<4} {:>6}{mark}\n",
                f.frame, f.correct, f.gt, f.valid
            ));
        }
        out
    }
}

/// Lateral-offset error under which a tracker counts as recovered, metres.
pub const RECOVERY_THRESHOLD_M: f64 = 0.3;

/// Recovery after one disturbance of the ground truth (a run of `blackout` frames).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Recovery {
    /// First frame after the disturbance.
    pub end: usize,
    /// Frames from `end` until the valid estimate's lateral-offset error is under
    /// [`RECOVERY_THRESHOLD_M`] (`None`: not within the sequence).
    pub frames: Option<usize>,
}

/// The `synthetic` report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SyntheticReport {
    /// Parameter errors and detection rate.
    pub params: ParamErrors,
    /// Boundary-level image accuracy.
    pub boundaries: BoundaryAccuracy,
    /// Recovery after each blackout of the ground truth.
    pub recovery: Vec<Recovery>,
}

/// Recovery times after the blackouts marked in the ground truth (`state.blackout` = 1): for
/// each first frame after a run of blackout frames, the frames until the lateral-offset error
/// is back under [`RECOVERY_THRESHOLD_M`] ([`super::params::recovery_frames`]).
pub fn recovery(gt: &[LaneEstimate], preds: &[Option<&LaneEstimate>]) -> Vec<Recovery> {
    let dark = |i: usize| gt[i].state.get("blackout").is_some_and(|&b| b > 0.5);
    let ends: Vec<usize> = (1..gt.len()).filter(|&i| dark(i - 1) && !dark(i)).collect();
    let errors = super::params::error_series(gt, preds, |e| e.lateral_offset_m);
    let frames = super::params::recovery_frames(&errors, RECOVERY_THRESHOLD_M, &ends)
        .unwrap_or_else(|_| vec![None; ends.len()]);
    ends.into_iter()
        .zip(frames)
        .map(|(end, frames)| Recovery { end, frames })
        .collect()
}

/// The boundary-level accuracy; `preds[i]` belongs to `gt[i]`.
pub fn boundary_accuracy(gt: &[LaneEstimate], preds: &[Option<&LaneEstimate>]) -> BoundaryAccuracy {
    // (gt, compared, correct, sum of mean dx) per role.
    let mut per: BTreeMap<Role, (usize, usize, usize, f64)> = BTreeMap::new();
    let mut extra = 0;
    let mut frames = Vec::with_capacity(gt.len());
    for (i, g) in gt.iter().enumerate() {
        let pred = preds.get(i).copied().flatten().filter(|p| p.valid);
        let mut frame = FrameBoundaries {
            frame: g.frame.clone(),
            gt: 0,
            correct: 0,
            valid: pred.is_some(),
        };
        for b in g.boundaries.iter().filter(|b| b.points.len() >= 2) {
            let e = per.entry(b.role).or_insert((0, 0, 0, 0.0));
            e.0 += 1;
            frame.gt += 1;
            let Some(pb) = pred.and_then(|p| p.boundaries.iter().find(|pb| pb.role == b.role))
            else {
                continue;
            };
            let c = compare_boundaries(&pb.points, &b.points);
            if let Some(m) = c.mean_abs_dx_px {
                e.1 += 1;
                e.3 += m;
            }
            e.2 += usize::from(c.correct);
            frame.correct += usize::from(c.correct);
        }
        frames.push(frame);
        if let Some(p) = pred {
            extra += p
                .boundaries
                .iter()
                .filter(|pb| !g.boundaries.iter().any(|b| b.role == pb.role))
                .count();
        }
    }
    let per_role: Vec<RoleAccuracy> = per
        .into_iter()
        .map(|(role, (gt, compared, correct, sum))| RoleAccuracy {
            role,
            gt,
            compared,
            correct,
            mean_abs_dx_px: (compared > 0).then(|| sum / compared as f64),
        })
        .collect();
    let total = per_role.iter().map(|r| r.gt).sum::<usize>();
    let correct = per_role.iter().map(|r| r.correct).sum::<usize>();
    let compared = per_role.iter().map(|r| r.compared).sum::<usize>();
    let dx_sum: f64 = per_role
        .iter()
        .filter_map(|r| r.mean_abs_dx_px.map(|m| m * r.compared as f64))
        .sum();
    BoundaryAccuracy {
        gt: total,
        correct,
        accuracy: (total > 0).then(|| correct as f64 / total as f64),
        mean_abs_dx_px: (compared > 0).then(|| dx_sum / compared as f64),
        extra_predicted: extra,
        per_role,
        frames,
    }
}

/// The full `synthetic` report; `preds[i]` belongs to `gt[i]`.
///
/// # Errors
/// [`Error::Config`] when there are no ground-truth frames.
pub fn evaluate(gt: &[LaneEstimate], preds: &[Option<&LaneEstimate>]) -> Result<SyntheticReport> {
    if gt.is_empty() {
        return Err(Error::Config("no synthetic ground-truth frames".into()));
    }
    Ok(SyntheticReport {
        params: parameter_errors(gt, preds),
        boundaries: boundary_accuracy(gt, preds),
        recovery: recovery(gt, preds),
    })
}

impl fmt::Display for SyntheticReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.params)?;
        let b = &self.boundaries;
        let dx = |m: Option<f64>| m.map_or_else(|| "n/a".to_string(), |m| format!("{m:.2}"));
        writeln!(
            f,
            "  boundary (<= 20 px mean |dx|)     gt  compared  correct  mean |dx| px"
        )?;
        for r in &b.per_role {
            writeln!(
                f,
                "  {:<30} {:>5} {:>9} {:>8} {:>13}",
                r.role.as_str(),
                r.gt,
                r.compared,
                r.correct,
                dx(r.mean_abs_dx_px)
            )?;
        }
        write!(
            f,
            "  boundary accuracy {} ({} of {}), mean |dx| {} px, {} extra predicted",
            super::percent(b.accuracy),
            b.correct,
            b.gt,
            dx(b.mean_abs_dx_px),
            b.extra_predicted
        )?;
        for r in &self.recovery {
            match r.frames {
                Some(n) => write!(
                    f,
                    "\n  recovery after the blackout ending at frame {}: {n} frames (|offset error| < {RECOVERY_THRESHOLD_M} m)",
                    r.end
                )?,
                None => write!(
                    f,
                    "\n  recovery after the blackout ending at frame {}: not within the sequence",
                    r.end
                )?,
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn column(x: f64, y0: f64, y1: f64) -> Vec<[f64; 2]> {
        let n = ((y0 - y1) / 10.0).ceil() as usize;
        (0..=n)
            .map(|k| [x, y0 - (y0 - y1) * k as f64 / n as f64])
            .collect()
    }

    fn with(boundaries: Vec<(Role, Vec<[f64; 2]>)>) -> LaneEstimate {
        LaneEstimate {
            valid: true,
            boundaries: boundaries
                .into_iter()
                .map(|(role, points)| Boundary {
                    role,
                    points,
                    road_points: vec![],
                })
                .collect(),
            lane_width_m: 3.5,
            ..Default::default()
        }
    }

    #[test]
    fn ground_truth_is_read_leniently() {
        let text = concat!(
            r#"{"frame": "000000.png", "valid": true, "ms": 0, "extra": {"a": 1},"#,
            r#" "boundaries": [{"role": "ego-left", "points": [[1, 2]]},"#,
            r#" {"role": "left-adjacent-2", "points": []}],"#,
            r#" "lateral_offset_m": 0.1, "heading_rad": 0, "curvature_per_m": 0,"#,
            r#" "lane_width_m": 3.5, "state": {"lee.psi": 0.01, "name": "x"}}"#,
            "\n",
            r#"{"frame": "000001.png", "boundaries": []}"#
        );
        let gt = parse_ground_truth(text, "gt").unwrap();
        assert_eq!(gt.len(), 2);
        assert_eq!(gt[0].boundaries.len(), 1, "unknown role dropped");
        assert_eq!(gt[0].state.len(), 1, "non-numeric state dropped");
        assert!(gt[1].valid && gt[1].lateral_offset_m.is_nan());
        let e = parse_ground_truth("\n[1]", "gt").unwrap_err().to_string();
        assert!(e.contains("gt line 2"), "{e}");
    }

    #[test]
    fn boundaries_within_20_px_on_enough_rows_are_correct() {
        let gt = column(300.0, 479.0, 279.0); // 201 rows
        let c = compare_boundaries(&column(315.0, 479.0, 279.0), &gt);
        assert_eq!((c.gt_rows, c.common_rows), (201, 201));
        assert_eq!(c.mean_abs_dx_px, Some(15.0));
        assert!(c.correct);
        assert!(!compare_boundaries(&column(321.0, 479.0, 279.0), &gt).correct);
        // Exact but only on the lowest 50 rows: a quarter of the rows is not enough.
        let c = compare_boundaries(&column(300.0, 479.0, 430.0), &gt);
        assert_eq!((c.common_rows, c.mean_abs_dx_px), (50, Some(0.0)));
        assert!(!c.correct);
        assert!(compare_boundaries(&column(300.0, 479.0, 379.0), &gt).correct);
    }

    #[test]
    fn report_counts_roles_missing_and_extra_boundaries() {
        let gt = vec![
            with(vec![
                (Role::EgoLeft, column(200.0, 479.0, 279.0)),
                (Role::EgoRight, column(400.0, 479.0, 279.0)),
            ]),
            with(vec![
                (Role::EgoLeft, column(200.0, 479.0, 279.0)),
                (Role::EgoRight, column(400.0, 479.0, 279.0)),
            ]),
        ];
        let p0 = with(vec![
            (Role::EgoLeft, column(205.0, 479.0, 279.0)),
            (Role::EgoRight, column(440.0, 479.0, 279.0)),
            (Role::RightAdjacent, column(600.0, 479.0, 279.0)),
        ]);
        let r = evaluate(&gt, &[Some(&p0), None]).unwrap();
        let b = &r.boundaries;
        assert_eq!((b.gt, b.correct, b.extra_predicted), (4, 1, 1));
        assert_eq!(b.accuracy, Some(0.25));
        assert_eq!(b.mean_abs_dx_px, Some(22.5));
        assert_eq!(b.per_role[0].role, Role::EgoLeft);
        assert_eq!((b.per_role[0].gt, b.per_role[0].compared), (2, 1));
        assert_eq!(r.params.detection_rate, Some(0.5));
        assert!(evaluate(&[], &[]).is_err());
    }

    #[test]
    fn recovery_is_counted_from_the_end_of_each_blackout() {
        let frame = |offset: f64, blackout: bool| LaneEstimate {
            valid: true,
            lateral_offset_m: offset,
            state: [("blackout".to_string(), f64::from(u8::from(blackout)))].into(),
            ..LaneEstimate::default()
        };
        // Blackouts on frames 2-3 and 7; truth offset 0 throughout.
        let gt: Vec<LaneEstimate> = (0..10)
            .map(|i| frame(0.0, matches!(i, 2 | 3 | 7)))
            .collect();
        // The estimate is off by 1 m from frame 2 to 5, back at frame 6, off again at 7-9.
        let preds: Vec<LaneEstimate> = (0..10)
            .map(|i| {
                frame(
                    if (2..6).contains(&i) || i >= 7 {
                        1.0
                    } else {
                        0.1
                    },
                    false,
                )
            })
            .collect();
        let refs: Vec<Option<&LaneEstimate>> = preds.iter().map(Some).collect();
        let r = evaluate(&gt, &refs).unwrap();
        assert_eq!(
            r.recovery,
            vec![
                Recovery {
                    end: 4,
                    frames: Some(2)
                },
                Recovery {
                    end: 8,
                    frames: None
                }
            ]
        );
        let text = r.to_string();
        assert!(text.contains("ending at frame 4: 2 frames"), "{text}");
        assert!(
            text.contains("ending at frame 8: not within the sequence"),
            "{text}"
        );
    }
}
