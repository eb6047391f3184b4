//! The CULane benchmark: its `.lines.txt` reader and its F1 measure.
//!
//! **Labels**: one file `NNNNN.lines.txt` per image `NNNNN.jpg`, one lane per line as
//! `x1 y1 x2 y2 ...` in pixels (points may lie outside the image). The frame name is
//! `NNNNN.jpg`; predictions match it by file name. The image is 1640x590 in CULane; the size
//! is read from the header of `NNNNN.jpg` beside the labels when it is there, else taken from
//! [`super::EvalOptions::image_size`], else 1640x590.
//!
//! **Metric**: every lane (a labelled line, or the image polyline of a predicted boundary) is
//! drawn [`LANE_WIDTH_PX`] = 30 px wide: the pixels whose centre lies within 15 px of the
//! polyline (round ends and joints), clipped to the image. The IoU of two lanes is
//! |A ∩ B| / |A ∪ B| over those pixels; a lane with fewer than 2 points has IoU 0 with
//! everything, as officially. Within a frame lanes are paired one-to-one, choosing the exact
//! matching with the most pairs of IoU > [`IOU_THRESHOLD`] = 0.5 (ties: the larger total IoU);
//! those pairs are true positives, the other predictions false positives and the other labels
//! false negatives. Summed over all frames: precision = TP / (TP + FP), recall = TP / (TP + FN),
//! F1 = 2 TP / (2 TP + FP + FN) (= 2PR / (P + R); each `None` when its denominator is 0).
//!
//! Two differences from the official C++ tool, both small on real data: it draws each lane
//! through a cubic spline of its points (ours joins them by straight segments: CULane points
//! are 10 px apart in y and trackers write theirs at most 10 px apart), and its Hungarian
//! matching maximises the total IoU of all pairs before thresholding (ours maximises the number
//! of pairs above the threshold, which can only give as many or more true positives). Invalid
//! estimates and missing frames predict nothing.
//!
//! The rasteriser keeps one bit per pixel and lane in buffers owned by [`CulaneScorer`], reused
//! from frame to frame; a lane only clears and counts the rows it touched.

use super::assign::match_pairs;
use super::{percent, ratio};
use crate::error::{Error, Result};
use crate::lane::LaneEstimate;
use crate::num_text::Fixed;
use serde::Serialize;
use std::fmt;
use std::path::Path;

/// Width of a drawn lane, pixels.
pub const LANE_WIDTH_PX: f64 = 30.0;
/// IoU a pair must exceed to count as a true positive.
pub const IOU_THRESHOLD: f64 = 0.5;
/// The CULane image size, [width, height].
pub const CULANE_SIZE: [usize; 2] = [1640, 590];
/// Largest image side accepted for rasterisation.
const MAX_SIDE: usize = 16384;

/// One labelled CULane frame.
#[derive(Debug, Clone, PartialEq)]
pub struct CulaneFrame {
    /// Frame name (`NNNNN.jpg`).
    pub frame: String,
    /// The lanes, each a list of [x, y] points.
    pub lanes: Vec<Vec<[f64; 2]>>,
    /// The image size [width, height] read from the image, if it was found.
    pub image_size: Option<[usize; 2]>,
}

/// Parses the text of a `.lines.txt` file; `source` names it in errors. Blank lines are
/// skipped.
///
/// # Errors
/// [`Error::Config`] naming the line for a value that is not a finite number or an odd count.
pub fn parse_lines(text: &str, source: &str) -> Result<Vec<Vec<[f64; 2]>>> {
    let mut lanes = Vec::new();
    for (i, line) in text.lines().enumerate() {
        super::limits::check_line(source, i + 1, line)?;
        let values: Vec<f64> = line
            .split_whitespace()
            .map(|v| {
                v.parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| {
                        Error::Config(format!("{source} line {}: `{v}` is not a number", i + 1))
                    })
            })
            .collect::<Result<_>>()?;
        if values.is_empty() {
            continue;
        }
        if values.len() % 2 != 0 {
            return Err(Error::Config(format!(
                "{source} line {}: {} values, expected x y pairs",
                i + 1,
                values.len()
            )));
        }
        lanes.push(values.chunks_exact(2).map(|c| [c[0], c[1]]).collect());
    }
    Ok(lanes)
}

/// Reads one `.lines.txt` file as a frame (its image size from `NNNNN.jpg` beside it if that
/// exists and can be read).
///
/// # Errors
/// [`Error::Io`] when it cannot be read, otherwise as [`parse_lines`].
pub fn read_frame(path: &Path) -> Result<CulaneFrame> {
    let text = super::read_text(path)?;
    let lanes = parse_lines(&text, &path.display().to_string())?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let stem = name.strip_suffix(".lines.txt").unwrap_or(&name);
    let frame = format!("{stem}.jpg");
    let image = path.with_file_name(&frame);
    let image_size = ::image::image_dimensions(&image)
        .ok()
        .map(|(w, h)| [w as usize, h as usize]);
    Ok(CulaneFrame {
        frame,
        lanes,
        image_size,
    })
}

/// Reads every `*.lines.txt` file of a folder (in file-name order), or the one file `path`.
///
/// # Errors
/// [`Error::Io`] when the folder or a file cannot be read; [`Error::Config`] when the folder
/// has no `.lines.txt` file or a file is malformed.
pub fn read_labels(path: &Path) -> Result<Vec<CulaneFrame>> {
    super::each_file(
        path,
        |name| name.ends_with(".lines.txt"),
        ".lines.txt files",
        read_frame,
    )
}

/// A binary mask of one drawn lane: one bit per pixel, rows of `words` u64.
#[derive(Debug, Clone, Default)]
pub struct LaneMask {
    width: usize,
    height: usize,
    words: usize,
    bits: Vec<u64>,
    /// Rows that may hold set bits, [first, last).
    rows: (usize, usize),
}

impl LaneMask {
    /// An empty mask of the given size.
    ///
    /// # Errors
    /// [`Error::Dimensions`] for a zero or huge size.
    pub fn new(width: usize, height: usize) -> Result<Self> {
        let mut m = LaneMask::default();
        m.reset(width, height)?;
        Ok(m)
    }

    /// Clears the mask and sets its size (keeping the buffer when it is large enough).
    ///
    /// # Errors
    /// [`Error::Dimensions`] for a zero or huge size.
    pub fn reset(&mut self, width: usize, height: usize) -> Result<()> {
        if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
            return Err(Error::Dimensions(format!(
                "lane mask {width}x{height}: each side must be 1..={MAX_SIDE}"
            )));
        }
        if (width, height) == (self.width, self.height) {
            self.clear();
            return Ok(());
        }
        self.width = width;
        self.height = height;
        self.words = width.div_ceil(64);
        self.bits.clear();
        self.bits.resize(self.words * height, 0);
        self.rows = (0, 0);
        Ok(())
    }

    /// Clears the rows that were drawn on.
    pub fn clear(&mut self) {
        let (a, b) = self.rows;
        self.bits[a * self.words..b * self.words].fill(0);
        self.rows = (0, 0);
    }

    /// Whether pixel (x, y) is set.
    pub fn get(&self, x: usize, y: usize) -> bool {
        x < self.width && y < self.height && self.bits[y * self.words + x / 64] >> (x % 64) & 1 == 1
    }

    /// Sets every pixel whose centre is within `radius` of the polyline.
    pub fn draw_polyline(&mut self, points: &[[f64; 2]], radius: f64) {
        match points {
            [] => {}
            [p] => self.draw_segment(*p, *p, radius),
            _ => {
                for s in points.windows(2) {
                    self.draw_segment(s[0], s[1], radius);
                }
            }
        }
    }

    /// Sets every pixel whose centre is within `radius` of the segment a-b (a capsule).
    pub fn draw_segment(&mut self, a: [f64; 2], b: [f64; 2], radius: f64) {
        if !(a.iter().chain(&b).all(|v| v.is_finite()) && radius >= 0.0) {
            return;
        }
        let top = (a[1].min(b[1]) - radius).ceil().max(0.0);
        let bottom = (a[1].max(b[1]) + radius)
            .floor()
            .min(self.height as f64 - 1.0);
        if top > bottom {
            return;
        }
        let (y0, y1) = (top as usize, bottom as usize);
        for y in y0..=y1 {
            if let Some((lo, hi)) = capsule_row(a, b, radius, y as f64) {
                let lo = lo.ceil().max(0.0);
                let hi = hi.floor().min(self.width as f64 - 1.0);
                if lo <= hi {
                    self.set_run(y, lo as usize, hi as usize);
                }
            }
        }
    }

    fn set_run(&mut self, y: usize, x0: usize, x1: usize) {
        if self.rows.0 == self.rows.1 {
            self.rows = (y, y + 1);
        } else {
            self.rows = (self.rows.0.min(y), self.rows.1.max(y + 1));
        }
        let row = &mut self.bits[y * self.words..(y + 1) * self.words];
        let (w0, w1) = (x0 / 64, x1 / 64);
        let first = u64::MAX << (x0 % 64);
        let last = u64::MAX >> (63 - x1 % 64);
        if w0 == w1 {
            row[w0] |= first & last;
        } else {
            row[w0] |= first;
            row[w0 + 1..w1].fill(u64::MAX);
            row[w1] |= last;
        }
    }

    /// Number of set pixels.
    pub fn count(&self) -> u64 {
        let (a, b) = self.rows;
        self.bits[a * self.words..b * self.words]
            .iter()
            .map(|w| u64::from(w.count_ones()))
            .sum()
    }

    /// Number of pixels set in both masks (0 when the sizes differ).
    pub fn intersection(&self, other: &LaneMask) -> u64 {
        if (self.width, self.height) != (other.width, other.height) {
            return 0;
        }
        let a = self.rows.0.max(other.rows.0);
        let b = self.rows.1.min(other.rows.1);
        if a >= b {
            return 0;
        }
        let r = a * self.words..b * self.words;
        self.bits[r.clone()]
            .iter()
            .zip(&other.bits[r])
            .map(|(x, y)| u64::from((x & y).count_ones()))
            .sum()
    }
}

/// The x interval [lo, hi] of row `y` within distance `r` of the segment a-b, if any. The
/// capsule is convex, so its row section is the hull of the sections of its three convex
/// parts: the discs at both ends and the band of points projecting inside the segment.
fn capsule_row(a: [f64; 2], b: [f64; 2], r: f64, y: f64) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    let mut take = |l: f64, h: f64| {
        if l <= h {
            lo = lo.min(l);
            hi = hi.max(h);
        }
    };
    for c in [a, b] {
        let dy = y - c[1];
        let h2 = r * r - dy * dy;
        if h2 >= 0.0 {
            let h = h2.sqrt();
            take(c[0] - h, c[0] + h);
        }
    }
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = (dx * dx + dy * dy).sqrt();
    if len > 0.0 {
        let (ux, uy) = (dx / len, dy / len);
        // Along the segment: t = (x - ax) ux + (y - ay) uy in [0, len];
        // across it: s = -(x - ax) uy + (y - ay) ux in [-r, r]. Both are linear in x.
        let ry = y - a[1];
        let (mut l, mut h) = (f64::NEG_INFINITY, f64::INFINITY);
        for (slope, offset, min, max) in [(ux, ry * uy, 0.0, len), (-uy, ry * ux, -r, r)] {
            // min <= offset + slope (x - ax) <= max
            if slope.abs() < 1e-12 {
                if offset < min || offset > max {
                    return (lo <= hi).then_some((lo, hi));
                }
            } else {
                let e1 = a[0] + (min - offset) / slope;
                let e2 = a[0] + (max - offset) / slope;
                l = l.max(e1.min(e2));
                h = h.min(e1.max(e2));
            }
        }
        take(l, h);
    }
    (lo <= hi).then_some((lo, hi))
}

/// IoU of two masks (0 when both are empty).
pub fn iou(a: &LaneMask, b: &LaneMask) -> f64 {
    let inter = a.intersection(b);
    let union = a.count() + b.count() - inter;
    if union == 0 {
        0.0
    } else {
        inter as f64 / union as f64
    }
}

/// True positives, false positives and false negatives.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct Counts {
    /// Matched pairs.
    pub tp: usize,
    /// Unmatched predictions.
    pub fp: usize,
    /// Unmatched labels.
    #[serde(rename = "fn")]
    pub fn_: usize,
}

/// Draws and matches the lanes of frames, owning its masks between frames.
#[derive(Debug, Clone, Default)]
pub struct CulaneScorer {
    gt: Vec<LaneMask>,
    pred: Vec<LaneMask>,
    ious: Vec<f64>,
}

impl CulaneScorer {
    /// A scorer with no buffers yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// The IoU of every (label, prediction) pair, row-major (labels are rows), for an image of
    /// `size` [width, height].
    ///
    /// # Errors
    /// [`Error::Dimensions`] for an unusable size.
    pub fn ious(
        &mut self,
        gt: &[&[[f64; 2]]],
        pred: &[&[[f64; 2]]],
        size: [usize; 2],
    ) -> Result<&[f64]> {
        let radius = LANE_WIDTH_PX / 2.0;
        for (masks, lanes) in [(&mut self.gt, gt), (&mut self.pred, pred)] {
            if masks.len() < lanes.len() {
                masks.resize_with(lanes.len(), LaneMask::default);
            }
            for (m, lane) in masks.iter_mut().zip(lanes) {
                m.reset(size[0], size[1])?;
                if lane.len() >= 2 {
                    m.draw_polyline(lane, radius);
                }
            }
        }
        self.ious.clear();
        for (g, gl) in self.gt.iter().zip(gt) {
            for (p, pl) in self.pred.iter().zip(pred) {
                let v = if gl.len() < 2 || pl.len() < 2 {
                    0.0
                } else {
                    iou(g, p)
                };
                self.ious.push(v);
            }
        }
        Ok(&self.ious)
    }

    /// Each of `predictions` predicted lanes' largest IoU with any label, from the last
    /// [`CulaneScorer::ious`] (0 for a frame without labels): how near a false positive came.
    pub fn best_ious(&self, predictions: usize) -> Vec<f64> {
        (0..predictions)
            .map(|j| {
                self.ious
                    .iter()
                    .skip(j)
                    .step_by(predictions)
                    .fold(0.0, |best, &v| v.max(best))
            })
            .collect()
    }

    /// TP, FP and FN of one frame.
    ///
    /// # Errors
    /// [`Error::Dimensions`] for an unusable size.
    pub fn score_frame(
        &mut self,
        gt: &[&[[f64; 2]]],
        pred: &[&[[f64; 2]]],
        size: [usize; 2],
    ) -> Result<Counts> {
        let cols = pred.len();
        let ious = self.ious(gt, pred, size)?;
        let tp = match_pairs(gt.len(), cols, |i, j| {
            let v = ious[i * cols + j];
            (v > IOU_THRESHOLD).then_some(v)
        })
        .len();
        Ok(Counts {
            tp,
            fp: pred.len() - tp,
            fn_: gt.len() - tp,
        })
    }
}

/// The CULane figures of a prediction set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CulaneReport {
    /// Summed counts.
    #[serde(flatten)]
    pub counts: Counts,
    /// TP / (TP + FP).
    pub precision: Option<f64>,
    /// TP / (TP + FN).
    pub recall: Option<f64>,
    /// 2 TP / (2 TP + FP + FN).
    pub f1: Option<f64>,
    /// Each labelled frame's counts, in label order (they sum to `counts`; empty for a report
    /// made by [`CulaneReport::from_counts`]).
    pub frames: Vec<CulaneFrameScore>,
}

/// One labelled frame's counts.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CulaneFrameScore {
    /// The labelled frame's name.
    pub frame: String,
    /// Its counts.
    #[serde(flatten)]
    pub counts: Counts,
    /// Each predicted lane's largest IoU with a label, in the prediction's boundary order
    /// (empty for a frame not valid or not predicted).
    pub best_iou: Vec<f64>,
}

impl CulaneReport {
    /// The rates of summed counts.
    pub fn from_counts(c: Counts) -> Self {
        CulaneReport {
            counts: c,
            precision: ratio(c.tp, c.tp + c.fp),
            recall: ratio(c.tp, c.tp + c.fn_),
            f1: ratio(2 * c.tp, 2 * c.tp + c.fp + c.fn_),
            frames: Vec::new(),
        }
    }

    /// One line a frame: TP, FP, FN and each predicted lane's best IoU.
    pub fn frames_table(&self) -> String {
        let mut out =
            String::from("  frame                  TP  FP  FN  best IoU of each predicted lane\n");
        for f in &self.frames {
            let c = f.counts;
            out.push_str(&format!(
                "  {:<20} {:>4} {:>3} {:>3} ",
                f.frame, c.tp, c.fp, c.fn_
            ));
            for v in &f.best_iou {
                out.push_str(&format!(" {}", Fixed(*v, 2)));
            }
            out.push('\n');
        }
        out
    }
}

/// Scores predictions (`preds[i]` belongs to `labels[i]`); `image_size` is used for frames
/// whose image was not found (default 1640x590).
///
/// # Errors
/// [`Error::Config`] when there are no frames; [`Error::Dimensions`] for an unusable size.
pub fn evaluate(
    labels: &[CulaneFrame],
    preds: &[Option<&LaneEstimate>],
    image_size: Option<[usize; 2]>,
) -> Result<CulaneReport> {
    if labels.is_empty() {
        return Err(Error::Config("no CULane frames to evaluate".into()));
    }
    let mut scorer = CulaneScorer::new();
    let mut total = Counts::default();
    let mut frames = Vec::with_capacity(labels.len());
    for (i, frame) in labels.iter().enumerate() {
        let size = frame.image_size.or(image_size).unwrap_or(CULANE_SIZE);
        let gt: Vec<&[[f64; 2]]> = frame.lanes.iter().map(Vec::as_slice).collect();
        let pred: Vec<&[[f64; 2]]> = match preds.get(i).copied().flatten() {
            Some(p) if p.valid => p.boundaries.iter().map(|b| b.points.as_slice()).collect(),
            _ => Vec::new(),
        };
        let c = scorer.score_frame(&gt, &pred, size)?;
        let best_iou = scorer.best_ious(pred.len());
        total.tp += c.tp;
        total.fp += c.fp;
        total.fn_ += c.fn_;
        frames.push(CulaneFrameScore {
            frame: frame.frame.clone(),
            counts: c,
            best_iou,
        });
    }
    Ok(CulaneReport {
        frames,
        ..CulaneReport::from_counts(total)
    })
}

impl fmt::Display for CulaneReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let c = &self.counts;
        writeln!(f, "  CULane (IoU > 0.5, 30 px)   value")?;
        writeln!(
            f,
            "  TP / FP / FN                {} / {} / {}",
            c.tp, c.fp, c.fn_
        )?;
        writeln!(
            f,
            "  precision                   {}",
            percent(self.precision)
        )?;
        writeln!(f, "  recall                      {}", percent(self.recall))?;
        write!(f, "  F1                          {}", percent(self.f1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The slow reference: test every pixel centre against the distance to the polyline.
    fn slow_mask(points: &[[f64; 2]], r: f64, w: usize, h: usize) -> Vec<bool> {
        let mut out = vec![false; w * h];
        for y in 0..h {
            for x in 0..w {
                let d = super::super::polyline::distance_to_polyline([x as f64, y as f64], points);
                out[y * w + x] = d <= r;
            }
        }
        out
    }

    #[test]
    fn rasteriser_agrees_with_the_pixel_by_pixel_reference() {
        let (w, h) = (130, 90);
        let shapes: [&[[f64; 2]]; 5] = [
            &[[10.0, 80.0], [60.0, 10.0]],
            &[[65.3, 88.7], [64.1, 50.2], [70.0, 20.5], [100.4, 3.3]],
            &[[-20.0, 45.0], [150.0, 45.5]],
            &[[40.0, 40.0]],
            &[[120.0, 85.0], [128.9, 5.0], [90.0, 1.0]],
        ];
        let mut m = LaneMask::new(w, h).unwrap();
        for (k, pts) in shapes.iter().enumerate() {
            for r in [0.0, 3.5, 15.0] {
                m.reset(w, h).unwrap();
                m.draw_polyline(pts, r);
                let slow = slow_mask(pts, r, w, h);
                let mut n = 0;
                for y in 0..h {
                    for x in 0..w {
                        // Pixels within 1e-9 of the boundary may round either way.
                        let d =
                            super::super::polyline::distance_to_polyline([x as f64, y as f64], pts);
                        if (d - r).abs() > 1e-9 {
                            assert_eq!(m.get(x, y), slow[y * w + x], "shape {k} r {r} ({x},{y})");
                        }
                        n += usize::from(m.get(x, y));
                    }
                }
                assert_eq!(m.count(), n as u64);
            }
        }
    }

    #[test]
    fn identical_lanes_have_iou_1_and_lanes_40_px_apart_do_not_match() {
        let lane: Vec<[f64; 2]> = (0..19).map(|k| [800.0, 590.0 - 10.0 * k as f64]).collect();
        let moved: Vec<[f64; 2]> = lane.iter().map(|p| [p[0] + 40.0, p[1]]).collect();
        let mut s = CulaneScorer::new();
        let ious = s
            .ious(&[&lane], &[&lane, &moved], CULANE_SIZE)
            .unwrap()
            .to_vec();
        assert_eq!(ious[0], 1.0);
        // 30 px wide bands 40 px apart do not overlap at all.
        assert_eq!(ious[1], 0.0);
        let c = s.score_frame(&[&lane], &[&moved], CULANE_SIZE).unwrap();
        assert_eq!(
            c,
            Counts {
                tp: 0,
                fp: 1,
                fn_: 1
            }
        );
        // 10 px apart: overlap 21 of 31 columns in most rows, IoU ~ 21/41 > 0.5.
        let near: Vec<[f64; 2]> = lane.iter().map(|p| [p[0] + 10.0, p[1]]).collect();
        let v = s.ious(&[&lane], &[&near], CULANE_SIZE).unwrap()[0];
        assert!(v > 0.5 && v < 0.55, "{v}");
        // A one-point lane never matches.
        let c = s.score_frame(&[&lane], &[&lane[..1]], CULANE_SIZE).unwrap();
        assert_eq!(
            c,
            Counts {
                tp: 0,
                fp: 1,
                fn_: 1
            }
        );
    }

    #[test]
    fn each_prediction_keeps_its_best_iou_with_any_label() {
        let lane =
            |x: f64| -> Vec<[f64; 2]> { (0..19).map(|k| [x, 590.0 - 10.0 * k as f64]).collect() };
        let (a, b) = (lane(400.0), lane(800.0));
        // Predictions: on b, 20 px beside a (a near miss), far from both.
        let preds = [lane(800.0), lane(420.0), lane(1200.0)];
        let pred: Vec<&[[f64; 2]]> = preds.iter().map(Vec::as_slice).collect();
        let mut s = CulaneScorer::new();
        let c = s.score_frame(&[&a, &b], &pred, CULANE_SIZE).unwrap();
        assert_eq!((c.tp, c.fp, c.fn_), (1, 2, 1));
        let best = s.best_ious(pred.len());
        assert_eq!(best.len(), 3);
        assert_eq!(best[0], 1.0);
        // 30 px bands 20 px apart: about 11 / 51 of their union.
        assert!(best[1] > 0.15 && best[1] < 0.3, "{best:?}");
        assert_eq!(best[2], 0.0);
        // No labels: every prediction's best is 0; no predictions: nothing.
        s.score_frame(&[], &pred, CULANE_SIZE).unwrap();
        assert_eq!(s.best_ious(pred.len()), vec![0.0; 3]);
        s.score_frame(&[&a], &[], CULANE_SIZE).unwrap();
        assert!(s.best_ious(0).is_empty());
    }

    #[test]
    fn exact_assignment_finds_two_matches_where_greedy_finds_one() {
        // Vertical lanes in the order Q, A, P, B (x = 792, 800, 802, 810): two parallel
        // 30 px bands d px apart have IoU about (31 - d) / (31 + d), above 0.5 for d <= 10.
        let v =
            |x: f64| -> Vec<[f64; 2]> { (0..19).map(|k| [x, 580.0 - 10.0 * k as f64]).collect() };
        let (a, b) = (v(800.0), v(810.0));
        let (p, q) = (v(802.0), v(792.0));
        let mut s = CulaneScorer::new();
        let m = s.ious(&[&a, &b], &[&p, &q], CULANE_SIZE).unwrap().to_vec();
        let (ap, aq, bp, bq) = (m[0], m[1], m[2], m[3]);
        // The best pair is (A, P); taking it first (greedy) leaves B with Q only, below 0.5.
        assert!(ap > aq && ap > bp && ap > bq, "{m:?}");
        assert!(aq > 0.5 && bp > 0.5 && bq <= 0.5, "{m:?}");
        // The exact matching pairs (A, Q) and (B, P): two true positives.
        let c = s.score_frame(&[&a, &b], &[&p, &q], CULANE_SIZE).unwrap();
        assert_eq!(
            c,
            Counts {
                tp: 2,
                fp: 0,
                fn_: 0
            }
        );
    }

    #[test]
    fn lines_files_parse_and_f1_is_summed() {
        let lanes = parse_lines("1 2 3 4 \n\n5.5 6 7 8 9 10\n", "x").unwrap();
        assert_eq!(lanes.len(), 2);
        assert_eq!(lanes[1], vec![[5.5, 6.0], [7.0, 8.0], [9.0, 10.0]]);
        let e = parse_lines("1 2 3", "x").unwrap_err().to_string();
        assert!(e.contains("x line 1") && e.contains("3 values"), "{e}");
        assert!(parse_lines("1 nan", "x").is_err());
        let r = CulaneReport::from_counts(Counts {
            tp: 6,
            fp: 2,
            fn_: 4,
        });
        assert_eq!(r.precision, Some(0.75));
        assert_eq!(r.recall, Some(0.6));
        assert_eq!(r.f1, Some(12.0 / 18.0));
        let r = CulaneReport::from_counts(Counts::default());
        assert_eq!((r.precision, r.recall, r.f1), (None, None, None));
    }
}
