//! The Caltech Lanes benchmark (Aly 2008): its label reader and curve matching.
//!
//! **Labels** (`labels.json`): `image_size` [width, height] and `frames[i]` with `frame` (the
//! image file name, e.g. `f00088.png`, as in the `frames/` folder) and `lanes[j]` with
//! `bezier_xy`, the 4 control points of a cubic Bezier curve
//! B(t) = (1-t)^3 P0 + 3(1-t)^2 t P1 + 3(1-t) t^2 P2 + t^3 P3, t in [0, 1], in 0-based pixels,
//! and `kind` (`bw`, `sw`, `dy`). A prediction's `frame` matches the label's `frame` by file
//! name, so `f00088.png` and `frames/f00088.png` both find it.
//!
//! **Matching** a predicted boundary (its image polyline) with a labelled lane: both curves are
//! sampled every [`SAMPLE_SPACING_PX`] of arc length; d1 are the distances from the samples of
//! the prediction to the nearest point of the labelled curve (as a polyline through
//! [`BEZIER_SEGMENTS`] + 1 points of B), d2 those from the samples of the labelled curve to the
//! prediction's polyline. They match when min(median d1, median d2) <= 20 px **and**
//! min(mean d1, mean d2) <= 15 px (the median of an even count is the mean of the middle two).
//! The min lets a curve that is only part of the other (a short detection, or a label that
//! stops before the image edge) still match. Within a frame the matching is one-to-one and
//! exact: the most matched pairs, ties broken by the smaller mean distance (see `assign`).
//!
//! **Figures**, in two modes, summed over all frames:
//!
//! - *all lanes*: every labelled lane, every predicted boundary;
//! - *ego lanes* (Aly's "2 lanes"): of the labelled lanes only the nearest one left and the
//!   nearest one right of the image centre x = (width - 1) / 2 at the bottom row, where a lane's
//!   bottom position is the point where the lane, extended from its lowest end along the chord
//!   of its lowest [`END_DIRECTION_ARC_PX`] of arc length, meets the row y = height - 1 (lanes
//!   that leave through the side of the image lie far out); of the
//!   predictions only the `ego-left` and `ego-right` boundaries. Matching ignores the roles.
//!
//! correct rate = matched labelled lanes / labelled lanes; false-positive rate = unmatched
//! predictions / predictions (each `None` when its denominator is 0). Invalid estimates and
//! missing frames predict nothing.

use super::assign::match_pairs;
use super::percent;
use super::polyline::{distance_to_polyline, resample_into};
use crate::error::{Error, Result};
use crate::lane::{LaneEstimate, Role};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::Path;

/// Arc-length spacing of the samples taken on both curves, pixels.
pub const SAMPLE_SPACING_PX: f64 = 1.0;
/// Straight pieces used to stand for a Bezier curve as the target of distances.
pub const BEZIER_SEGMENTS: usize = 64;
/// Largest min(median d1, median d2) of a match, pixels.
pub const MEDIAN_THRESHOLD_PX: f64 = 20.0;
/// Largest min(mean d1, mean d2) of a match, pixels.
pub const MEAN_THRESHOLD_PX: f64 = 15.0;
/// Arc length over which a label's direction at its lowest end is taken when it is extended to
/// the bottom row (see [`bottom_x`]), pixels.
pub const END_DIRECTION_ARC_PX: f64 = 30.0;

/// One labelled lane.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct CaltechLane {
    /// Bezier control points P0..P3, [x, y] pixels.
    pub bezier_xy: [[f64; 2]; 4],
    /// Marking kind: `bw`, `sw` or `dy`.
    #[serde(default)]
    pub kind: String,
}

/// One labelled frame.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct CaltechFrame {
    /// Image file name.
    pub frame: String,
    /// Its lanes.
    #[serde(default)]
    pub lanes: Vec<CaltechLane>,
}

/// The contents of `labels.json`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct CaltechLabels {
    /// [width, height] of the frames.
    #[serde(default = "default_size")]
    pub image_size: [usize; 2],
    /// The labelled frames.
    pub frames: Vec<CaltechFrame>,
}

fn default_size() -> [usize; 2] {
    [640, 480]
}

/// Parses `labels.json` text; `source` names it in errors.
///
/// # Errors
/// [`Error::Config`] for malformed JSON or a lane without 4 control points.
pub fn parse_labels(text: &str, source: &str) -> Result<CaltechLabels> {
    serde_json::from_str(text).map_err(|e| Error::Config(format!("{source}: {e}")))
}

/// Reads `labels.json`.
///
/// # Errors
/// [`Error::Io`] when it cannot be read, otherwise as [`parse_labels`].
pub fn read_labels(path: &Path) -> Result<CaltechLabels> {
    let text = super::read_text(path)?;
    parse_labels(&text, &path.display().to_string())
}

/// B(t) of the cubic Bezier curve with control points `p`.
pub fn bezier_point(p: &[[f64; 2]; 4], t: f64) -> [f64; 2] {
    let s = 1.0 - t;
    let (b0, b1, b2, b3) = (s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t);
    [
        b0 * p[0][0] + b1 * p[1][0] + b2 * p[2][0] + b3 * p[3][0],
        b0 * p[0][1] + b1 * p[1][1] + b2 * p[2][1] + b3 * p[3][1],
    ]
}

/// The curve as a polyline through B(k / segments), k = 0..=segments.
pub fn bezier_polyline(p: &[[f64; 2]; 4], segments: usize) -> Vec<[f64; 2]> {
    let n = segments.max(1);
    (0..=n)
        .map(|k| bezier_point(p, k as f64 / n as f64))
        .collect()
}

/// x where the lane, extended from its lowest end along the direction of its lowest
/// [`END_DIRECTION_ARC_PX`] of arc length (the whole curve when it is shorter), crosses the row
/// `bottom_y`; the lowest end's own x when that direction does not go down.
///
/// The direction is a chord, not the Bezier end tangent P3 - P2: on a short label the end
/// tangent spans a few pixels and a pixel of labelling noise turns it. cordova1's 214 and 215
/// label a solid line that starts 15 m ahead, 1.0 m left of the camera, 22 rows tall: its end
/// tangent (0.9 px right over 7.9 rows) put it right of the image centre at the bottom row, and
/// so the ego-right lane, where its chord (4.4 px left over 22 rows) puts it left.
pub fn bottom_x(p: &[[f64; 2]; 4], bottom_y: f64) -> f64 {
    let lowest_first = p[3][1] >= p[0][1];
    let at = |k: usize| {
        let t = k as f64 / BEZIER_SEGMENTS as f64;
        bezier_point(p, if lowest_first { 1.0 - t } else { t })
    };
    let end = at(0);
    // Walk up the curve from its lowest end until END_DIRECTION_ARC_PX of arc length.
    let mut from = end;
    let mut arc = 0.0;
    for k in 1..=BEZIER_SEGMENTS {
        let q = at(k);
        arc += crate::math::hypot(q[0] - from[0], q[1] - from[1]);
        from = q;
        if arc >= END_DIRECTION_ARC_PX {
            break;
        }
    }
    let (dx, dy) = (end[0] - from[0], end[1] - from[1]);
    if dy > 1e-9 * (dx.abs() + dy.abs()) {
        end[0] + (bottom_y - end[1]) * dx / dy
    } else {
        end[0]
    }
}

/// Indices of the ego lanes among `lanes`: the nearest left and the nearest right of the image
/// centre at the bottom row (see the module docs).
pub fn ego_lanes(lanes: &[CaltechLane], image_size: [usize; 2]) -> [Option<usize>; 2] {
    let centre = (image_size[0] as f64 - 1.0) / 2.0;
    let bottom = image_size[1] as f64 - 1.0;
    let mut left: Option<(usize, f64)> = None;
    let mut right: Option<(usize, f64)> = None;
    for (i, lane) in lanes.iter().enumerate() {
        let x = bottom_x(&lane.bezier_xy, bottom);
        if !x.is_finite() {
            continue;
        }
        if x < centre {
            if left.is_none_or(|(_, lx)| x > lx) {
                left = Some((i, x));
            }
        } else if right.is_none_or(|(_, rx)| x < rx) {
            right = Some((i, x));
        }
    }
    [left.map(|l| l.0), right.map(|r| r.0)]
}

/// The distance statistics of two curves.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AlyDistances {
    /// min(median d1, median d2), pixels.
    pub median: f64,
    /// min(mean d1, mean d2), pixels.
    pub mean: f64,
}

impl AlyDistances {
    /// Whether these distances make a match (median <= 20 px and mean <= 15 px).
    pub fn matched(&self) -> bool {
        self.median <= MEDIAN_THRESHOLD_PX && self.mean <= MEAN_THRESHOLD_PX
    }
}

/// Aly's distances between two polylines (the first is sampled every
/// [`SAMPLE_SPACING_PX`] and measured to the second, and the other way round); `None` when
/// either is empty. `scratch` is reused for the samples.
///
/// # Errors
/// [`Error::Config`] when a polyline would take more than
/// [`super::limits::MAX_RESAMPLED`] samples.
pub fn aly_distances(
    a: &[[f64; 2]],
    b: &[[f64; 2]],
    scratch: &mut (Vec<[f64; 2]>, Vec<f64>),
) -> Result<Option<AlyDistances>> {
    let (Some((da_med, da_mean)), Some((db_med, db_mean))) =
        (one_way(a, b, scratch)?, one_way(b, a, scratch)?)
    else {
        return Ok(None);
    };
    Ok(Some(AlyDistances {
        median: da_med.min(db_med),
        mean: da_mean.min(db_mean),
    }))
}

/// (median, mean) of the distances from samples of `from` to the polyline `to`.
fn one_way(
    from: &[[f64; 2]],
    to: &[[f64; 2]],
    (samples, d): &mut (Vec<[f64; 2]>, Vec<f64>),
) -> Result<Option<(f64, f64)>> {
    if from.is_empty() || to.is_empty() {
        return Ok(None);
    }
    resample_into(from, SAMPLE_SPACING_PX, samples)?;
    d.clear();
    d.extend(samples.iter().map(|p| distance_to_polyline(*p, to)));
    let mean = d.iter().sum::<f64>() / d.len() as f64;
    d.sort_unstable_by(f64::total_cmp);
    let mid = d.len() / 2;
    let median = if d.len() % 2 == 1 {
        d[mid]
    } else {
        0.5 * (d[mid - 1] + d[mid])
    };
    Ok(Some((median, mean)))
}

/// Counts of one mode.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct AlyCounts {
    /// Labelled lanes.
    pub gt_lanes: usize,
    /// Predicted boundaries.
    pub predicted: usize,
    /// Matched pairs.
    pub matched: usize,
    /// matched / gt_lanes.
    pub correct_rate: Option<f64>,
    /// (predicted - matched) / predicted.
    pub false_positive_rate: Option<f64>,
}

impl AlyCounts {
    fn add(&mut self, gt: usize, predicted: usize, matched: usize) {
        self.gt_lanes += gt;
        self.predicted += predicted;
        self.matched += matched;
    }

    fn finish(mut self) -> Self {
        self.correct_rate = (self.gt_lanes > 0).then(|| self.matched as f64 / self.gt_lanes as f64);
        self.false_positive_rate = (self.predicted > 0)
            .then(|| (self.predicted - self.matched) as f64 / self.predicted as f64);
        self
    }
}

/// One frame's counts in one mode: labelled lanes, predicted boundaries, matched pairs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct FrameCounts {
    /// Labelled lanes.
    pub gt_lanes: usize,
    /// Predicted boundaries (none when the prediction is missing or invalid).
    pub predicted: usize,
    /// Matched pairs.
    pub matched: usize,
}

/// One labelled frame's counts, all lanes and ego lanes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaltechFrameScore {
    /// The labelled frame's name.
    pub frame: String,
    /// All lanes.
    pub all_lanes: FrameCounts,
    /// Ego lanes.
    pub ego_lanes: FrameCounts,
}

/// The Caltech figures of a prediction set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaltechReport {
    /// All lanes.
    pub all_lanes: AlyCounts,
    /// Ego lanes ("2 lanes" mode).
    pub ego_lanes: AlyCounts,
    /// Each labelled frame's counts, in label order (they sum to the two above).
    pub frames: Vec<CaltechFrameScore>,
}

impl CaltechReport {
    /// One line a frame: ego and all lanes as matched / predicted / labelled, and a mark where
    /// a labelled ego lane was missed or a predicted one is a false positive.
    pub fn frames_table(&self) -> String {
        let mut out = String::from("  frame                 ego m/p/gt   all m/p/gt\n");
        for f in &self.frames {
            let (e, a) = (f.ego_lanes, f.all_lanes);
            let mark = if e.matched < e.gt_lanes || e.matched < e.predicted {
                "  <- ego"
            } else {
                ""
            };
            out.push_str(&format!(
                "  {:<20} {:>3}/{}/{}   {:>5}/{}/{}{mark}\n",
                f.frame, e.matched, e.predicted, e.gt_lanes, a.matched, a.predicted, a.gt_lanes
            ));
        }
        out
    }
}

/// Scores predictions (`preds[i]` belongs to `labels.frames[i]`); `image_size` overrides the
/// labels' size for the ego-lane choice.
///
/// # Errors
/// [`Error::Config`] when there are no labelled frames.
pub fn evaluate(
    labels: &CaltechLabels,
    preds: &[Option<&LaneEstimate>],
    image_size: Option<[usize; 2]>,
) -> Result<CaltechReport> {
    if labels.frames.is_empty() {
        return Err(Error::Config("no Caltech frames to evaluate".into()));
    }
    let size = image_size.unwrap_or(labels.image_size);
    let mut all = AlyCounts::default();
    let mut ego = AlyCounts::default();
    let mut frames = Vec::with_capacity(labels.frames.len());
    let mut scratch = (Vec::new(), Vec::new());
    for (i, frame) in labels.frames.iter().enumerate() {
        let gt: Vec<Vec<[f64; 2]>> = frame
            .lanes
            .iter()
            .map(|l| bezier_polyline(&l.bezier_xy, BEZIER_SEGMENTS))
            .collect();
        let boundaries = match preds.get(i).copied().flatten() {
            Some(p) if p.valid => p.boundaries.as_slice(),
            _ => &[],
        };
        // Distances of every (gt, prediction) pair, shared by both modes.
        let dist: Vec<Vec<Option<AlyDistances>>> = gt
            .iter()
            .map(|g| {
                boundaries
                    .iter()
                    .map(|b| aly_distances(&b.points, g, &mut scratch))
                    .collect::<Result<_>>()
            })
            .collect::<Result<_>>()
            .map_err(|e| Error::Config(format!("frame {}: {e}", frame.frame)))?;
        let quality = |i: usize, j: usize| -> Option<f64> {
            let d = dist[i][j].filter(AlyDistances::matched)?;
            Some(1.0 - d.mean / MEAN_THRESHOLD_PX)
        };
        let matched = match_pairs(gt.len(), boundaries.len(), quality).len();
        all.add(gt.len(), boundaries.len(), matched);
        let all_lanes = FrameCounts {
            gt_lanes: gt.len(),
            predicted: boundaries.len(),
            matched,
        };

        let gt_ego: Vec<usize> = ego_lanes(&frame.lanes, size)
            .into_iter()
            .flatten()
            .collect();
        let pred_ego: Vec<usize> = boundaries
            .iter()
            .enumerate()
            .filter(|(_, b)| matches!(b.role, Role::EgoLeft | Role::EgoRight))
            .map(|(j, _)| j)
            .collect();
        let matched = match_pairs(gt_ego.len(), pred_ego.len(), |i, j| {
            quality(gt_ego[i], pred_ego[j])
        })
        .len();
        ego.add(gt_ego.len(), pred_ego.len(), matched);
        frames.push(CaltechFrameScore {
            frame: frame.frame.clone(),
            all_lanes,
            ego_lanes: FrameCounts {
                gt_lanes: gt_ego.len(),
                predicted: pred_ego.len(),
                matched,
            },
        });
    }
    Ok(CaltechReport {
        all_lanes: all.finish(),
        ego_lanes: ego.finish(),
        frames,
    })
}

impl fmt::Display for CaltechReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "  Caltech (Aly)   gt lanes  predicted  matched  correct rate  false pos. rate"
        )?;
        for (name, c) in [
            ("all lanes", &self.all_lanes),
            ("ego lanes", &self.ego_lanes),
        ] {
            writeln!(
                f,
                "  {name:<14} {:>9} {:>10} {:>8} {:>13} {:>16}",
                c.gt_lanes,
                c.predicted,
                c.matched,
                percent(c.correct_rate),
                percent(c.false_positive_rate)
            )?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lane::Boundary;

    /// A straight vertical lane from y = 450 up to y = 250 at x, as control points.
    fn vertical(x: f64) -> CaltechLane {
        CaltechLane {
            bezier_xy: [[x, 250.0], [x, 316.0], [x, 383.0], [x, 450.0]],
            kind: "sw".into(),
        }
    }

    /// A bottom-up polyline 10 px apart in y along the curve x(y) from y0 down... up to y1.
    fn polyline(x: impl Fn(f64) -> f64, y0: f64, y1: f64) -> Vec<[f64; 2]> {
        let n = ((y0 - y1) / 10.0).ceil() as usize;
        (0..=n)
            .map(|k| {
                let y = y0 - (y0 - y1) * k as f64 / n as f64;
                [x(y), y]
            })
            .collect()
    }

    fn estimate(boundaries: Vec<(Role, Vec<[f64; 2]>)>) -> LaneEstimate {
        LaneEstimate {
            frame: "f.png".into(),
            valid: true,
            boundaries: boundaries
                .into_iter()
                .map(|(role, points)| Boundary {
                    role,
                    points,
                    road_points: vec![],
                })
                .collect(),
            ..Default::default()
        }
    }

    #[test]
    fn bezier_ends_at_its_control_points() {
        let p = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [20.0, 10.0]];
        assert_eq!(bezier_point(&p, 0.0), [0.0, 0.0]);
        assert_eq!(bezier_point(&p, 1.0), [20.0, 10.0]);
        assert_eq!(bezier_point(&p, 0.5), [10.0, 5.0]);
        assert_eq!(bezier_polyline(&p, 4).len(), 5);
    }

    #[test]
    fn parallel_curve_at_10_px_matches_and_at_25_px_does_not() {
        let g = bezier_polyline(&vertical(300.0).bezier_xy, BEZIER_SEGMENTS);
        let mut s = (Vec::new(), Vec::new());
        let near = aly_distances(&polyline(|_| 310.0, 450.0, 250.0), &g, &mut s)
            .unwrap()
            .unwrap();
        assert!((near.median - 10.0).abs() < 1e-9 && (near.mean - 10.0).abs() < 1e-9);
        assert!(near.matched());
        let far = aly_distances(&polyline(|_| 325.0, 450.0, 250.0), &g, &mut s)
            .unwrap()
            .unwrap();
        assert!((far.median - 25.0).abs() < 1e-9, "{far:?}");
        assert!(!far.matched());
        // 18 px: the median passes (<= 20) but the mean fails (> 15).
        let mid = aly_distances(&polyline(|_| 318.0, 450.0, 250.0), &g, &mut s)
            .unwrap()
            .unwrap();
        assert!(mid.median <= 20.0 && !mid.matched(), "{mid:?}");
    }

    #[test]
    fn a_short_detection_of_a_long_lane_still_matches() {
        // Half the lane, exactly on it: d1 (detection -> lane) is 0, d2 is large for half.
        let g = bezier_polyline(&vertical(300.0).bezier_xy, BEZIER_SEGMENTS);
        let mut s = (Vec::new(), Vec::new());
        let d = aly_distances(&polyline(|_| 300.0, 450.0, 350.0), &g, &mut s)
            .unwrap()
            .unwrap();
        assert!(d.matched() && d.median < 1e-9, "{d:?}");
    }

    #[test]
    fn ego_lanes_are_the_nearest_either_side_at_the_bottom() {
        let lanes = vec![
            vertical(100.0),
            vertical(250.0),
            vertical(400.0),
            vertical(560.0),
            // Leaves through the left side at y = 300, heading left and down: far left.
            CaltechLane {
                bezier_xy: [[300.0, 200.0], [200.0, 240.0], [100.0, 270.0], [0.0, 300.0]],
                kind: "bw".into(),
            },
        ];
        assert_eq!(ego_lanes(&lanes, [640, 480]), [Some(1), Some(2)]);
        assert!(bottom_x(&lanes[4].bezier_xy, 479.0) < -500.0);
        assert_eq!(ego_lanes(&lanes[..1], [640, 480]), [Some(0), None]);
    }

    #[test]
    fn a_short_label_is_placed_by_its_chord_not_its_end_tangent() {
        // cordova1 f00214's solid line: 22 rows tall, 4.4 px left from top to bottom, but its
        // last control segment turns 0.9 px right. Extended by the end tangent it would cross
        // the bottom row right of the centre (about 327) and be the ego-right lane.
        let short = CaltechLane {
            bezier_xy: [
                [301.9, 199.5],
                [300.2, 206.5],
                [296.6, 213.6],
                [297.5, 221.5],
            ],
            kind: "sw".into(),
        };
        let x = bottom_x(&short.bezier_xy, 479.0);
        assert!((240.0..260.0).contains(&x), "{x}");
        let lanes = vec![vertical(100.0), short, vertical(480.0)];
        assert_eq!(ego_lanes(&lanes, [640, 480]), [Some(1), Some(2)]);
        // A long curve keeps the direction of its lowest 30 px, not its whole chord: a lane
        // bending from x = 300 at the top to straight down at x = 200 meets the bottom row
        // within a pixel of 200 (its whole chord would give 188.4).
        let bend = [
            [300.0, 200.0],
            [200.0, 250.0],
            [200.0, 300.0],
            [200.0, 450.0],
        ];
        let x = bottom_x(&bend, 479.0);
        assert!((x - 200.0).abs() < 1.0, "{x}");
    }

    #[test]
    fn rates_in_both_modes() {
        let labels = CaltechLabels {
            image_size: [640, 480],
            frames: vec![
                CaltechFrame {
                    frame: "f1.png".into(),
                    lanes: vec![vertical(100.0), vertical(250.0), vertical(400.0)],
                },
                CaltechFrame {
                    frame: "f2.png".into(),
                    lanes: vec![vertical(250.0), vertical(400.0)],
                },
            ],
        };
        let p1 = estimate(vec![
            (Role::EgoLeft, polyline(|_| 255.0, 450.0, 250.0)),
            (Role::EgoRight, polyline(|_| 440.0, 450.0, 250.0)), // 40 px off
            (Role::LeftAdjacent, polyline(|_| 98.0, 450.0, 250.0)),
        ]);
        let r = evaluate(&labels, &[Some(&p1), None], None).unwrap();
        assert_eq!(
            (
                r.all_lanes.gt_lanes,
                r.all_lanes.predicted,
                r.all_lanes.matched
            ),
            (5, 3, 2)
        );
        assert_eq!(r.all_lanes.correct_rate, Some(0.4));
        assert_eq!(r.all_lanes.false_positive_rate, Some(1.0 / 3.0));
        assert_eq!(
            (
                r.ego_lanes.gt_lanes,
                r.ego_lanes.predicted,
                r.ego_lanes.matched
            ),
            (4, 2, 1)
        );
        assert_eq!(r.ego_lanes.false_positive_rate, Some(0.5));
        // Nothing predicted anywhere: no false-positive rate at all.
        let r = evaluate(&labels, &[None, None], None).unwrap();
        assert_eq!(r.all_lanes.false_positive_rate, None);
        assert_eq!(r.all_lanes.correct_rate, Some(0.0));
        // One prediction cannot match two labels.
        let twin = CaltechLabels {
            image_size: [640, 480],
            frames: vec![CaltechFrame {
                frame: "f.png".into(),
                lanes: vec![vertical(300.0), vertical(305.0)],
            }],
        };
        let one = estimate(vec![(Role::EgoLeft, polyline(|_| 302.0, 450.0, 250.0))]);
        let r = evaluate(&twin, &[Some(&one)], None).unwrap();
        assert_eq!(r.all_lanes.matched, 1);
    }

    #[test]
    fn labels_parse_with_and_without_size() {
        let text = r#"{"frames": [{"frame": "f00001.png", "lanes": [
            {"bezier_xy": [[1, 2], [3, 4], [5, 6], [7, 8]], "kind": "dy"}]}]}"#;
        let l = parse_labels(text, "l").unwrap();
        assert_eq!(l.image_size, [640, 480]);
        assert_eq!(l.frames[0].lanes[0].bezier_xy[3], [7.0, 8.0]);
        let bad = r#"{"frames": [{"frame": "f", "lanes": [{"bezier_xy": [[1, 2]]}]}]}"#;
        assert!(parse_labels(bad, "l").is_err());
    }
}
