//! [`SuiteCell`]: the scores of one tracker on one scenario family, pooled over seeds.
//!
//! Pooling treats the frames of all seeds as one sequence, per seed for what needs a
//! sequence: for a parameter with per-seed (n_i, RMSE_i, MAE_i), RMSE = sqrt(Σ n_i RMSE_i² /
//! Σ n_i) and MAE = Σ n_i MAE_i / Σ n_i; detection rate, point (boundary) accuracy and
//! lane-configuration accuracy are ratios of summed counts; lane-change counts are summed;
//! recovery lists every blackout of every seed (mean and worst frames to recover, and how many
//! never did); ms is the mean over every tracked frame.

use crate::eval::lane_changes::LaneChangeCounts;
use crate::eval::lane_configuration::LaneConfigurationCounts;
use crate::eval::params::ErrorStats;
use crate::eval::synthetic::SyntheticReport;
use serde::Serialize;

/// The scores of one tracker on one seed.
#[derive(Debug, Clone, PartialEq)]
pub struct SeedScore {
    /// Parameter errors, boundary accuracy and recovery.
    pub report: SyntheticReport,
    /// Lane-change events.
    pub lane_changes: LaneChangeCounts,
    /// Lane-configuration counts.
    pub configuration: LaneConfigurationCounts,
    /// Sum of the per-frame step times, ms.
    pub ms_sum: f64,
    /// Frames timed.
    pub ms_frames: usize,
}

/// Pooled (n, Σ e², Σ |e|) of one parameter.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Pooled {
    n: usize,
    squares: f64,
    absolutes: f64,
}

impl Pooled {
    fn add(&mut self, s: Option<ErrorStats>) {
        if let Some(s) = s {
            self.n += s.n;
            self.squares += s.rmse * s.rmse * s.n as f64;
            self.absolutes += s.mae * s.n as f64;
        }
    }
    fn rmse(&self) -> Option<f64> {
        (self.n > 0).then(|| (self.squares / self.n as f64).sqrt())
    }
    fn mae(&self) -> Option<f64> {
        (self.n > 0).then(|| self.absolutes / self.n as f64)
    }
}

/// One tracker on one scenario family, over seeds.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SuiteCell {
    seeds: usize,
    frames: usize,
    valid: usize,
    offset: Pooled,
    heading: Pooled,
    curvature: Pooled,
    width: Pooled,
    boundaries: usize,
    correct_boundaries: usize,
    configuration: LaneConfigurationCounts,
    recoveries: Vec<Option<usize>>,
    lane_changes: LaneChangeCounts,
    ms_sum: f64,
    ms_frames: usize,
}

/// A [`SuiteCell`] as one row of the table (JSON field names as written).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CellRow {
    /// Seeds pooled.
    pub seeds: usize,
    /// Frames scored.
    pub frames: usize,
    /// Frames with a valid estimate / frames.
    pub detection_rate: Option<f64>,
    /// Lateral offset RMSE, metres.
    pub offset_rmse_m: Option<f64>,
    /// Heading RMSE, degrees.
    pub heading_rmse_deg: Option<f64>,
    /// Curvature RMSE, 1/m.
    pub curvature_rmse_per_m: Option<f64>,
    /// Lane width MAE, metres.
    pub width_mae_m: Option<f64>,
    /// Correct boundaries / ground-truth boundaries (the `synthetic` boundary accuracy).
    pub point_accuracy: Option<f64>,
    /// Lane-configuration accuracy (`None`: no valid frame, or the output never models the
    /// configuration: [`crate::eval::lane_configuration::models_configuration`]).
    pub lane_configuration_accuracy: Option<f64>,
    /// Blackouts scored.
    pub blackouts: usize,
    /// Mean frames to recover over the blackouts recovered from.
    pub recovery_mean_frames: Option<f64>,
    /// Most frames to recover.
    pub recovery_max_frames: Option<usize>,
    /// Blackouts never recovered from within the sequence.
    pub not_recovered: usize,
    /// Lane-change events.
    pub lane_changes: LaneChangeCounts,
    /// Mean step time, ms.
    pub ms: Option<f64>,
}

impl SuiteCell {
    /// Adds one seed's scores.
    pub fn add(&mut self, s: &SeedScore) {
        let p = &s.report.params;
        let pooled = |stats: Option<ErrorStats>| {
            let mut x = Pooled::default();
            x.add(stats);
            x
        };
        self.merge(&SuiteCell {
            seeds: 1,
            frames: p.frames,
            valid: p.valid_predictions,
            offset: pooled(p.lateral_offset_m),
            heading: pooled(p.heading_rad),
            curvature: pooled(p.curvature_per_m),
            width: pooled(p.lane_width_m),
            boundaries: s.report.boundaries.gt,
            correct_boundaries: s.report.boundaries.correct,
            configuration: s.configuration,
            recoveries: s.report.recovery.iter().map(|r| r.frames).collect(),
            lane_changes: s.lane_changes,
            ms_sum: s.ms_sum,
            ms_frames: s.ms_frames,
        });
    }

    /// Adds every seed of another cell (for the all-scenarios row).
    pub fn merge(&mut self, o: &SuiteCell) {
        self.seeds += o.seeds;
        self.frames += o.frames;
        self.valid += o.valid;
        for (a, b) in [
            (&mut self.offset, o.offset),
            (&mut self.heading, o.heading),
            (&mut self.curvature, o.curvature),
            (&mut self.width, o.width),
        ] {
            a.n += b.n;
            a.squares += b.squares;
            a.absolutes += b.absolutes;
        }
        self.boundaries += o.boundaries;
        self.correct_boundaries += o.correct_boundaries;
        self.configuration = self.configuration + o.configuration;
        self.recoveries.extend(&o.recoveries);
        self.lane_changes = self.lane_changes + o.lane_changes;
        self.ms_sum += o.ms_sum;
        self.ms_frames += o.ms_frames;
    }

    /// The pooled values.
    pub fn row(&self) -> CellRow {
        let recovered: Vec<usize> = self.recoveries.iter().flatten().copied().collect();
        let ratio = |a: usize, b: usize| (b > 0).then(|| a as f64 / b as f64);
        CellRow {
            seeds: self.seeds,
            frames: self.frames,
            detection_rate: ratio(self.valid, self.frames),
            offset_rmse_m: self.offset.rmse(),
            heading_rmse_deg: self.heading.rmse().map(f64::to_degrees),
            curvature_rmse_per_m: self.curvature.rmse(),
            width_mae_m: self.width.mae(),
            point_accuracy: ratio(self.correct_boundaries, self.boundaries),
            lane_configuration_accuracy: self.configuration.accuracy(),
            blackouts: self.recoveries.len(),
            recovery_mean_frames: (!recovered.is_empty())
                .then(|| recovered.iter().sum::<usize>() as f64 / recovered.len() as f64),
            recovery_max_frames: recovered.iter().max().copied(),
            not_recovered: self.recoveries.len() - recovered.len(),
            lane_changes: self.lane_changes,
            ms: (self.ms_frames > 0).then(|| self.ms_sum / self.ms_frames as f64),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eval::params::error_stats;

    #[test]
    fn pooled_rmse_is_the_rmse_of_all_frames() {
        let a = [0.1, -0.2, 0.3];
        let b = [0.5, 0.0];
        let mut p = Pooled::default();
        p.add(error_stats(&a));
        p.add(error_stats(&b));
        let all: Vec<f64> = a.iter().chain(&b).copied().collect();
        let want = error_stats(&all).unwrap();
        assert!((p.rmse().unwrap() - want.rmse).abs() < 1e-12);
        assert!((p.mae().unwrap() - want.mae).abs() < 1e-12);
        assert_eq!(Pooled::default().rmse(), None);
    }
}
