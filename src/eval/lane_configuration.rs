//! Lane-configuration accuracy: whether an output knows which neighbouring lanes exist.
//!
//! The configuration of a frame is the pair (a lane on the left, a lane on the right), read
//! from the boundaries present: a `left-adjacent` boundary means a lane on the left, a
//! `right-adjacent` one a lane on the right (the simulator's truth writes them exactly when
//! those lanes exist; they are Adachi's models r = 1 + left + 2 right). Over the frames with
//! a valid estimate, accuracy = frames whose configuration equals the truth's / those frames.
//!
//! A tracker that never reports an adjacent boundary does not model the configuration: the
//! count says so ([`LaneConfigurationCounts::reports_neighbours`]) and tables show "n/a". An
//! output that states its configuration model (`adachi.r`, Adachi's model number, the key the
//! truth writes too) models it on every frame, even one of model 1 (no neighbour, so no
//! adjacent boundary): until 2026-11-26 an adachi-mmpf run that said model 1 on every frame
//! (`night`, where the truth has a neighbour on every frame) was shown as "n/a" instead of 0 %.

use crate::lane::{LaneEstimate, Role};
use serde::Serialize;

/// Counts of one or more sequences.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct LaneConfigurationCounts {
    /// Frames with a valid estimate.
    pub frames: usize,
    /// Of those, frames whose configuration is right.
    pub correct: usize,
    /// Whether any valid estimate had an adjacent boundary.
    pub reports_neighbours: bool,
}

impl LaneConfigurationCounts {
    /// correct / frames, `None` without frames or when the output never reports neighbours.
    pub fn accuracy(&self) -> Option<f64> {
        (self.frames > 0 && self.reports_neighbours)
            .then(|| self.correct as f64 / self.frames as f64)
    }
}

/// (lane on the left, lane on the right) of an estimate.
pub fn configuration(e: &LaneEstimate) -> (bool, bool) {
    let has = |role: Role| e.boundaries.iter().any(|b| b.role == role);
    (has(Role::LeftAdjacent), has(Role::RightAdjacent))
}

/// Whether `e` says which neighbours exist: it reports an adjacent boundary, or states its
/// configuration model (`adachi.r`; model 1 has no adjacent boundary to report).
pub fn models_configuration(e: &LaneEstimate) -> bool {
    let (left, right) = configuration(e);
    left || right || e.state.contains_key(CONFIGURATION_MODEL_KEY)
}

/// The state key of Adachi's configuration model r (1: ego lane only, 2: a lane on the left,
/// 3: on the right, 4: both), in the truth and in adachi-mmpf's output.
pub const CONFIGURATION_MODEL_KEY: &str = "adachi.r";

/// The counts of one sequence; `preds[i]` belongs to `gt[i]`.
pub fn lane_configuration_counts(
    gt: &[LaneEstimate],
    preds: &[Option<&LaneEstimate>],
) -> LaneConfigurationCounts {
    let mut c = LaneConfigurationCounts::default();
    for (g, p) in gt.iter().zip(preds) {
        let Some(p) = p.filter(|p| p.valid) else {
            continue;
        };
        let predicted = configuration(p);
        c.frames += 1;
        c.correct += usize::from(predicted == configuration(g));
        c.reports_neighbours |= models_configuration(p);
    }
    c
}

/// Pools the counts of two sequences.
impl std::ops::Add for LaneConfigurationCounts {
    type Output = Self;
    fn add(self, other: Self) -> Self {
        Self {
            frames: self.frames + other.frames,
            correct: self.correct + other.correct,
            reports_neighbours: self.reports_neighbours || other.reports_neighbours,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lane::Boundary;

    fn with(roles: &[Role], valid: bool) -> LaneEstimate {
        LaneEstimate {
            valid,
            boundaries: roles
                .iter()
                .map(|&role| Boundary {
                    role,
                    points: vec![],
                    road_points: vec![],
                })
                .collect(),
            ..LaneEstimate::default()
        }
    }

    #[test]
    fn configurations_are_compared_on_valid_frames() {
        use Role::*;
        let gt = vec![
            with(&[EgoLeft, EgoRight, LeftAdjacent, RightAdjacent], true),
            with(&[EgoLeft, EgoRight, RightAdjacent], true),
            with(&[EgoLeft, EgoRight], true),
        ];
        let preds = [
            with(&[EgoLeft, EgoRight, LeftAdjacent, RightAdjacent], true),
            with(&[EgoLeft, EgoRight, LeftAdjacent], true),
            with(&[EgoLeft, EgoRight], false),
        ];
        let refs: Vec<Option<&LaneEstimate>> = preds.iter().map(Some).collect();
        let c = lane_configuration_counts(&gt, &refs);
        assert_eq!((c.frames, c.correct), (2, 1));
        assert_eq!(c.accuracy(), Some(0.5));
        // Never a neighbour: not modelled.
        let ego_only = [with(&[EgoLeft, EgoRight], true)];
        let c = lane_configuration_counts(&gt[..1], &[Some(&ego_only[0])]);
        assert_eq!((c.frames, c.accuracy()), (1, None));
    }

    /// An output that states Adachi's model r models the configuration even when it says
    /// model 1 (no neighbour) on every frame: scored, not "n/a" (adachi-mmpf at `night`).
    #[test]
    fn model_one_on_every_frame_is_scored() {
        use Role::*;
        let gt = vec![
            with(&[EgoLeft, EgoRight, LeftAdjacent], true),
            with(&[EgoLeft, EgoRight], true),
        ];
        let mut model_one = with(&[EgoLeft, EgoRight], true);
        model_one.state.insert(CONFIGURATION_MODEL_KEY.into(), 1.0);
        let c = lane_configuration_counts(&gt, &[Some(&model_one), Some(&model_one)]);
        assert_eq!((c.frames, c.correct), (2, 1));
        assert_eq!(c.accuracy(), Some(0.5));
        // Wrong on every frame: 0 %, not "n/a".
        let c = lane_configuration_counts(&gt[..1], &[Some(&model_one)]);
        assert_eq!(c.accuracy(), Some(0.0));
    }
}
