//! Errors of the lane parameters against ground truth, detection rate and recovery time.
//!
//! For predicted and ground-truth [`LaneEstimate`]s of the same frames, the error of a
//! parameter in a frame is e = predicted - ground truth; over the N frames where both are
//! valid and both values are finite:
//!
//! - RMSE = sqrt(Σ e² / N), MAE = Σ |e| / N, bias = Σ e / N, and the largest |e|;
//! - for `lateral_offset_m`, `heading_rad`, `curvature_per_m`, `lane_width_m`, and for every
//!   key of the tracker-specific `state` present in both maps (names must agree exactly: the
//!   simulator writes e.g. `lee.psi`). Heading errors are wrapped into (-π, π]; state values
//!   are compared as plain numbers;
//! - detection rate = frames with a valid prediction / ground-truth frames (a missing
//!   prediction counts as not detected).
//!
//! **Recovery time** ([`recovery_frames`]): for a per-frame error series (e.g. from
//! [`error_series`]: NaN where there is no valid estimate), a threshold and the frames where
//! disturbances end, the number of frames from the end of each disturbance to the first frame
//! at or after it whose |error| is below the threshold (0 if it already is; `None` if it never
//! gets there before the series ends). NaN is never below the threshold. Later disturbances do
//! not cut the search short.

use crate::error::{Error, Result};
use crate::lane::LaneEstimate;
use serde::Serialize;
use std::collections::BTreeMap;
use std::f64::consts::{PI, TAU};
use std::fmt;

/// Summary of an error series.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ErrorStats {
    /// Number of frames compared.
    pub n: usize,
    /// Root-mean-square error.
    pub rmse: f64,
    /// Mean absolute error.
    pub mae: f64,
    /// Mean signed error (predicted - ground truth).
    pub bias: f64,
    /// Largest absolute error.
    pub max_abs: f64,
}

/// Statistics of signed errors (non-finite values are skipped); `None` when none is left.
pub fn error_stats(errors: &[f64]) -> Option<ErrorStats> {
    let mut n = 0usize;
    let (mut sq, mut abs, mut sum, mut max_abs) = (0.0, 0.0, 0.0, 0.0f64);
    for &e in errors.iter().filter(|e| e.is_finite()) {
        n += 1;
        sq += e * e;
        abs += e.abs();
        sum += e;
        max_abs = max_abs.max(e.abs());
    }
    (n > 0).then(|| {
        let nf = n as f64;
        ErrorStats {
            n,
            rmse: (sq / nf).sqrt(),
            mae: abs / nf,
            bias: sum / nf,
            max_abs,
        }
    })
}

/// An angle difference wrapped into (-π, π].
pub fn wrap_angle(d: f64) -> f64 {
    let w = (d + PI).rem_euclid(TAU) - PI;
    if w == -PI {
        PI
    } else {
        w
    }
}

/// Parameter errors of a prediction set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParamErrors {
    /// Ground-truth frames.
    pub frames: usize,
    /// Frames with a valid prediction.
    pub valid_predictions: usize,
    /// valid_predictions / frames (`None` without frames).
    pub detection_rate: Option<f64>,
    /// Lateral offset, metres.
    pub lateral_offset_m: Option<ErrorStats>,
    /// Heading, radians.
    pub heading_rad: Option<ErrorStats>,
    /// Curvature, 1/m.
    pub curvature_per_m: Option<ErrorStats>,
    /// Lane width, metres.
    pub lane_width_m: Option<ErrorStats>,
    /// Tracker-specific parameters present in both state maps.
    pub state: BTreeMap<String, ErrorStats>,
}

/// The prediction of a frame if it is there and valid (and the ground truth is valid).
fn both_valid<'a>(
    gt: &'a LaneEstimate,
    pred: Option<&'a LaneEstimate>,
) -> Option<(&'a LaneEstimate, &'a LaneEstimate)> {
    pred.filter(|p| p.valid && gt.valid).map(|p| (gt, p))
}

/// Signed errors (predicted - ground truth) of `value` per frame; NaN where the frame has no
/// valid prediction or a value is not finite.
pub fn error_series(
    gt: &[LaneEstimate],
    preds: &[Option<&LaneEstimate>],
    value: impl Fn(&LaneEstimate) -> f64,
) -> Vec<f64> {
    gt.iter()
        .enumerate()
        .map(
            |(i, g)| match both_valid(g, preds.get(i).copied().flatten()) {
                Some((g, p)) => {
                    let e = value(p) - value(g);
                    if e.is_finite() {
                        e
                    } else {
                        f64::NAN
                    }
                }
                None => f64::NAN,
            },
        )
        .collect()
}

/// The errors of every parameter; `preds[i]` is the prediction for `gt[i]` (`None` when
/// missing).
pub fn parameter_errors(gt: &[LaneEstimate], preds: &[Option<&LaneEstimate>]) -> ParamErrors {
    let pred_at = |i: usize| preds.get(i).copied().flatten();
    let valid_predictions = (0..gt.len())
        .filter(|&i| pred_at(i).is_some_and(|p| p.valid))
        .count();
    let stats = |f: fn(&LaneEstimate) -> f64| error_stats(&error_series(gt, preds, f));
    let heading: Vec<f64> = error_series(gt, preds, |e| e.heading_rad)
        .into_iter()
        .map(wrap_angle)
        .collect();
    let mut per_key: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    for (i, g) in gt.iter().enumerate() {
        if let Some((g, p)) = both_valid(g, pred_at(i)) {
            for (k, gv) in &g.state {
                if let Some(pv) = p.state.get(k) {
                    per_key.entry(k.clone()).or_default().push(pv - gv);
                }
            }
        }
    }
    ParamErrors {
        frames: gt.len(),
        valid_predictions,
        detection_rate: (!gt.is_empty()).then(|| valid_predictions as f64 / gt.len() as f64),
        lateral_offset_m: stats(|e| e.lateral_offset_m),
        heading_rad: error_stats(&heading),
        curvature_per_m: stats(|e| e.curvature_per_m),
        lane_width_m: stats(|e| e.lane_width_m),
        state: per_key
            .into_iter()
            .filter_map(|(k, v)| error_stats(&v).map(|s| (k, s)))
            .collect(),
    }
}

/// Frames from each disturbance end in `ends` until `errors` is below `threshold` (see the
/// module docs).
///
/// # Errors
/// [`Error::Parameter`] for a threshold that is not finite or an end beyond the series.
pub fn recovery_frames(
    errors: &[f64],
    threshold: f64,
    ends: &[usize],
) -> Result<Vec<Option<usize>>> {
    crate::error::require_finite("threshold", threshold)?;
    ends.iter()
        .map(|&end| {
            if end >= errors.len() {
                return Err(Error::parameter(
                    "disturbance end",
                    end,
                    &format!("must be a frame of the series (0..{})", errors.len()),
                ));
            }
            Ok(errors[end..].iter().position(|&e| e.abs() < threshold))
        })
        .collect()
}

impl fmt::Display for ParamErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "  detection rate {} ({} valid of {} frames)",
            super::percent(self.detection_rate),
            self.valid_predictions,
            self.frames
        )?;
        writeln!(
            f,
            "  parameter                    frames         RMSE          MAE         bias"
        )?;
        let row = |f: &mut fmt::Formatter<'_>, name: &str, s: &Option<ErrorStats>| match s {
            Some(s) => writeln!(
                f,
                "  {name:<26} {:>8} {:>12.5} {:>12.5} {:>12.5}",
                s.n, s.rmse, s.mae, s.bias
            ),
            None => writeln!(f, "  {name:<26} {:>8}", 0),
        };
        row(f, "lateral_offset_m", &self.lateral_offset_m)?;
        row(f, "heading_rad", &self.heading_rad)?;
        row(f, "curvature_per_m", &self.curvature_per_m)?;
        row(f, "lane_width_m", &self.lane_width_m)?;
        for (k, s) in &self.state {
            row(f, &format!("state {k}"), &Some(*s))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn est(valid: bool, offset: f64, heading: f64, state: &[(&str, f64)]) -> LaneEstimate {
        LaneEstimate {
            valid,
            lateral_offset_m: offset,
            heading_rad: heading,
            curvature_per_m: 0.001,
            lane_width_m: 3.5,
            state: state.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
            ..Default::default()
        }
    }

    #[test]
    fn rmse_mae_and_bias_of_a_known_series() {
        // Errors 1, -2, 3, -4 (and a NaN that is skipped):
        // RMSE = sqrt(30 / 4), MAE = 10 / 4, bias = -2 / 4, max 4.
        let s = error_stats(&[1.0, -2.0, f64::NAN, 3.0, -4.0]).unwrap();
        assert_eq!(s.n, 4);
        assert!((s.rmse - 7.5f64.sqrt()).abs() < 1e-12);
        assert_eq!((s.mae, s.bias, s.max_abs), (2.5, -0.5, 4.0));
        assert_eq!(error_stats(&[f64::NAN]), None);
    }

    #[test]
    fn parameter_errors_use_frames_where_both_are_valid() {
        let gt = vec![
            est(true, 0.0, 0.0, &[("lee.psi", 0.01), ("t", 0.0)]),
            est(true, 0.1, 0.0, &[("lee.psi", 0.02)]),
            est(true, 0.2, 0.0, &[]),
            est(true, 0.3, 0.0, &[]),
        ];
        let p0 = est(true, 0.5, 0.02, &[("lee.psi", 0.03), ("other", 1.0)]);
        let p1 = est(true, -0.1, -0.04, &[("lee.psi", 0.02)]);
        let p2 = est(false, 9.0, 9.0, &[]); // invalid: not compared
        let preds = [Some(&p0), Some(&p1), Some(&p2), None];
        let r = parameter_errors(&gt, &preds);
        assert_eq!((r.frames, r.valid_predictions), (4, 2));
        assert_eq!(r.detection_rate, Some(0.5));
        let off = r.lateral_offset_m.unwrap();
        // Errors 0.5 and -0.2.
        assert_eq!(off.n, 2);
        assert!((off.mae - 0.35).abs() < 1e-12);
        assert!((off.rmse - (0.29f64 / 2.0).sqrt()).abs() < 1e-12);
        assert!((off.bias - 0.15).abs() < 1e-12);
        let psi = r.state["lee.psi"];
        assert_eq!(psi.n, 2);
        assert!((psi.mae - 0.01).abs() < 1e-12);
        assert!(!r.state.contains_key("other") && !r.state.contains_key("t"));
        assert_eq!(r.lane_width_m.unwrap().rmse, 0.0);
    }

    #[test]
    fn heading_errors_wrap_around() {
        assert!((wrap_angle(2.0 * PI - 0.1) + 0.1).abs() < 1e-12);
        assert!((wrap_angle(-PI) - PI).abs() < 1e-12);
        let gt = vec![est(true, 0.0, PI - 0.05, &[])];
        let p = est(true, 0.0, -PI + 0.05, &[]);
        let r = parameter_errors(&gt, &[Some(&p)]);
        assert!((r.heading_rad.unwrap().mae - 0.1).abs() < 1e-9);
    }

    #[test]
    fn recovery_counts_frames_until_the_error_is_back_under_the_threshold() {
        let e = [0.1, 0.9, -0.8, f64::NAN, 0.6, -0.2, 0.1, 0.7, 0.9];
        // From frame 1: 0.9, -0.8, NaN, 0.6, then |-0.2| < 0.3 at frame 5: 4 frames.
        // From frame 6: already under: 0. From frame 7: never.
        let r = recovery_frames(&e, 0.3, &[1, 6, 7]).unwrap();
        assert_eq!(r, vec![Some(4), Some(0), None]);
        assert!(recovery_frames(&e, 0.3, &[9]).is_err());
        assert!(recovery_frames(&e, f64::NAN, &[0]).is_err());
    }
}
