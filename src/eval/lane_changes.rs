//! Lane-change events: the ones the ground truth has against the ones an output shows.
//!
//! **Truth**: a frame i with `state.lane_change` = 1 is an event towards the right when the
//! camera's lane index `state.ego_lane` grew from frame i-1 (lanes count from the left),
//! towards the left otherwise.
//!
//! **Output**: trackers report lane changes in their own ways (a flag, a re-labelled lane), but
//! what every consumer of the output sees is the lateral offset o (camera left of the ego-lane
//! centre) jumping by a lane width as the ego lane is re-assigned: crossing to the right lane,
//! o goes from about -W/2 to +W/2. So a frame i with a valid estimate is a predicted event when
//! the previous valid estimate, at most [`MAX_GAP_FRAMES`] before it, differs in offset by more
//! than half a lane width: o_i - o_prev > W/2 is a change to the right, < -W/2 to the left
//! (W: the mean of the two estimates' widths, [`FALLBACK_WIDTH_M`] when neither is finite).
//!
//! **Matching**: in frame order, each truth event takes the earliest unmatched predicted event
//! in the same direction within [`TOLERANCE_FRAMES`] of it: *right*. Truth events left over
//! are *missed*; predicted events left over (including those in the wrong direction) are
//! *spurious*.

use crate::lane::LaneEstimate;
use serde::Serialize;

/// Largest distance in frames between a truth event and the predicted event that matches it
/// (0.5 s at 30 fps).
pub const TOLERANCE_FRAMES: usize = 15;
/// Largest run of frames without a valid estimate across which an offset jump still counts.
pub const MAX_GAP_FRAMES: usize = 15;
/// Lane width used when the estimates give none, metres.
pub const FALLBACK_WIDTH_M: f64 = 3.6;

/// One lane change: its frame and direction (+1 to the right, -1 to the left).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct LaneChange {
    /// Frame index.
    pub frame: usize,
    /// +1: into the lane on the right; -1: on the left.
    pub direction: i8,
}

/// Counts of matched, missed and spurious lane changes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct LaneChangeCounts {
    /// Truth events.
    pub truth: usize,
    /// Truth events matched by a predicted one in the same direction.
    pub right: usize,
    /// Truth events without a match.
    pub missed: usize,
    /// Predicted events without a match.
    pub spurious: usize,
}

impl LaneChangeCounts {}

/// The lane changes of the ground truth (see the module docs).
pub fn truth_lane_changes(gt: &[LaneEstimate]) -> Vec<LaneChange> {
    let lane = |e: &LaneEstimate| e.state.get("ego_lane").copied().unwrap_or(f64::NAN);
    (1..gt.len())
        .filter(|&i| gt[i].state.get("lane_change").is_some_and(|&c| c > 0.5))
        .map(|i| LaneChange {
            frame: i,
            direction: if lane(&gt[i]) > lane(&gt[i - 1]) {
                1
            } else {
                -1
            },
        })
        .collect()
}

/// The lane changes an output shows (see the module docs); `preds[i]` is frame i.
pub fn predicted_lane_changes(preds: &[Option<&LaneEstimate>]) -> Vec<LaneChange> {
    let mut out = Vec::new();
    let mut previous: Option<(usize, &LaneEstimate)> = None;
    for (i, p) in preds.iter().enumerate() {
        let Some(p) = p.filter(|p| p.valid && p.lateral_offset_m.is_finite()) else {
            continue;
        };
        if let Some((_, q)) = previous.filter(|(j, _)| i - j <= MAX_GAP_FRAMES + 1) {
            let widths = [p.lane_width_m, q.lane_width_m];
            let finite: Vec<f64> = widths.into_iter().filter(|w| w.is_finite()).collect();
            let width = if finite.is_empty() {
                FALLBACK_WIDTH_M
            } else {
                finite.iter().sum::<f64>() / finite.len() as f64
            };
            let jump = p.lateral_offset_m - q.lateral_offset_m;
            if jump.abs() > width / 2.0 {
                out.push(LaneChange {
                    frame: i,
                    direction: if jump > 0.0 { 1 } else { -1 },
                });
            }
        }
        previous = Some((i, p));
    }
    out
}

/// Matches predicted events to truth events (see the module docs).
pub fn match_lane_changes(truth: &[LaneChange], predicted: &[LaneChange]) -> LaneChangeCounts {
    let mut used = vec![false; predicted.len()];
    let mut right = 0;
    for t in truth {
        let hit = predicted.iter().enumerate().position(|(k, p)| {
            !used[k] && p.direction == t.direction && p.frame.abs_diff(t.frame) <= TOLERANCE_FRAMES
        });
        if let Some(k) = hit {
            used[k] = true;
            right += 1;
        }
    }
    LaneChangeCounts {
        truth: truth.len(),
        right,
        missed: truth.len() - right,
        spurious: predicted.len() - right,
    }
}

/// Truth against output lane changes of one sequence; `preds[i]` belongs to `gt[i]`.
pub fn lane_change_counts(
    gt: &[LaneEstimate],
    preds: &[Option<&LaneEstimate>],
) -> LaneChangeCounts {
    match_lane_changes(&truth_lane_changes(gt), &predicted_lane_changes(preds))
}

/// Pools the counts of two sequences.
impl std::ops::Add for LaneChangeCounts {
    type Output = Self;
    fn add(self, other: Self) -> Self {
        Self {
            truth: self.truth + other.truth,
            right: self.right + other.right,
            missed: self.missed + other.missed,
            spurious: self.spurious + other.spurious,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn truth(lane: f64, change: bool) -> LaneEstimate {
        LaneEstimate {
            state: [
                ("ego_lane".to_string(), lane),
                ("lane_change".to_string(), f64::from(u8::from(change))),
            ]
            .into(),
            ..LaneEstimate::default()
        }
    }

    fn output(offset: f64, valid: bool) -> LaneEstimate {
        LaneEstimate {
            valid,
            lateral_offset_m: offset,
            lane_width_m: 3.6,
            ..LaneEstimate::default()
        }
    }

    #[test]
    fn events_are_matched_by_direction_within_the_tolerance() {
        // Truth: lane 1 -> 2 at frame 10 (right), back to 1 at frame 40 (left).
        let gt: Vec<LaneEstimate> = (0..60)
            .map(|i| {
                truth(
                    if (10..40).contains(&i) { 2.0 } else { 1.0 },
                    i == 10 || i == 40,
                )
            })
            .collect();
        assert_eq!(
            truth_lane_changes(&gt),
            vec![
                LaneChange {
                    frame: 10,
                    direction: 1
                },
                LaneChange {
                    frame: 40,
                    direction: -1
                }
            ]
        );
        // Output: jumps +3.6 at frame 12 (right, in time), +3.6 again at 30 (spurious), and
        // nothing at 40 (missed); invalid frames 20-25 in between do not hide the jump at 30.
        let preds: Vec<LaneEstimate> = (0..60)
            .map(|i| {
                let offset = if i < 12 {
                    -1.7
                } else if i < 30 {
                    1.8
                } else {
                    5.3
                };
                output(offset, !(20..26).contains(&i))
            })
            .collect();
        let refs: Vec<Option<&LaneEstimate>> = preds.iter().map(Some).collect();
        let c = lane_change_counts(&gt, &refs);
        assert_eq!(
            c,
            LaneChangeCounts {
                truth: 2,
                right: 1,
                missed: 1,
                spurious: 1
            }
        );
        // Small drifts are not events; a jump the wrong way is spurious, not right.
        let drift: Vec<LaneEstimate> = (0..60).map(|i| output(0.02 * i as f64, true)).collect();
        let refs: Vec<Option<&LaneEstimate>> = drift.iter().map(Some).collect();
        assert!(predicted_lane_changes(&refs).is_empty());
        let wrong = [LaneChange {
            frame: 11,
            direction: -1,
        }];
        let c = match_lane_changes(&truth_lane_changes(&gt)[..1], &wrong);
        assert_eq!((c.right, c.missed, c.spurious), (0, 1, 1));
    }
}
