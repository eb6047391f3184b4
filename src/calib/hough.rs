//! Straight lines through marking pixels.
//!
//! Lane lines are steep in the image, so a line is written x = a + b (y - y_ref), b = tan(phi),
//! with phi the angle from the vertical ([`MIN_ANGLE_DEG`] <= |phi| <= [`MAX_ANGLE_DEG`]). Each
//! point votes, with its ridge contrast as weight, for every (phi, a) it lies on (a Hough
//! transform with 0.75 degree and 1 pixel bins). Lines are
//! then taken strongest first: the peak's points (those within [`BAND_PX`] perpendicular
//! pixels) are refitted by least squares on x(y), the fit is repeated once on its own band,
//! and the points used are withdrawn from the accumulator, so that the next peak is another
//! line and not a neighbour of this one.
//!
//! The peak is the accumulator's largest cell (the last one on a tie). Each angle's row keeps
//! its own maximum; withdrawing votes only lowers cells, so after a withdrawal only the rows
//! where a lowered cell held the row's maximum are scanned again, and the peak is the largest
//! of the row maxima: the same cell as a scan of the whole accumulator, at a fraction of the
//! work (most rows' maxima lie on other lines).
//!
//! Each line also measures how far it bends: a parabola x = a + b t + c t^2, t = (y - y_mid) /
//! half extent in [-1, 1], grown from the line along the points within [`BEND_BAND_PX`] of it,
//! deviates from its chord by at most |c| pixels (c > 0: the middle lies left of the chord). On a straight road that is below a pixel; on a bend the far
//! markings leave the straight line (see the calibrator).

use crate::math;
use nalgebra::{Matrix3, Vector3};

/// Largest angle of a line from the vertical, degrees.
pub const MAX_ANGLE_DEG: f64 = 78.0;
/// Smallest angle of a line from the vertical, degrees: nearly vertical lines are poles,
/// trunks and building edges; a lane boundary is that steep only right under the camera.
pub const MIN_ANGLE_DEG: f64 = 8.0;
/// Angle bin, degrees.
pub const ANGLE_STEP_DEG: f64 = 0.75;
/// Largest vote of one point (its ridge contrast, capped: a white line on black asphalt
/// should not outvote a worn one by ten to one).
pub const MAX_WEIGHT: u32 = 64;
/// A peak needs `min_support` points of this mean weight.
pub const MIN_MEAN_WEIGHT: u32 = 12;
/// Perpendicular distance, pixels, within which a point belongs to a line.
pub const BAND_PX: f64 = 1.5;
/// Perpendicular distance, pixels, of the points the bend is measured on.
pub const BEND_BAND_PX: f64 = 4.0;

/// A fitted line x = x_ref + slope (y - y_ref), with its support.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LineFit {
    /// x at row `y_ref`.
    pub x_ref: f64,
    /// Reference row.
    pub y_ref: f64,
    /// dx / dy.
    pub slope: f64,
    /// Points within [`BAND_PX`] of the line.
    pub support: usize,
    /// Topmost row of those points.
    pub y_top: f64,
    /// Bottom row of those points.
    pub y_bottom: f64,
    /// Signed deviation of the best parabola from its chord at its middle, pixels (see
    /// [`bend`]; 0 until measured): positive when the middle lies left of the chord.
    pub bend: f64,
}

impl LineFit {
    /// x of the line at row y.
    pub fn x_at(&self, y: f64) -> f64 {
        self.x_ref + self.slope * (y - self.y_ref)
    }

    /// Perpendicular distance from (x, y) to the line.
    pub fn distance(&self, x: f64, y: f64) -> f64 {
        (x - self.x_at(y)).abs() / (1.0 + self.slope * self.slope).sqrt()
    }
}

/// The Hough accumulator and its scratch buffers (kept between frames).
#[derive(Debug, Clone, Default)]
pub struct Hough {
    tans: Vec<f64>,
    a_min: f64,
    a_bins: usize,
    acc: Vec<u32>,
    /// Per angle: the row's largest count and the last cell holding it, and whether a
    /// withdrawal may have lowered that maximum.
    row_max: Vec<(u32, usize)>,
    stale: Vec<bool>,
    used: Vec<bool>,
    band: Vec<usize>,
}

/// What [`Hough::detect`] looks for.
#[derive(Debug, Clone, Copy)]
pub struct HoughParams {
    /// Width of the image the points come from (sets the range of a).
    pub width: usize,
    /// Reference row (the middle of the rows searched).
    pub y_ref: f64,
    /// Fewest points on a line.
    pub min_support: usize,
    /// Least vertical extent of a line's points, rows.
    pub min_extent: f64,
    /// Most lines returned.
    pub max_lines: usize,
}

impl Hough {
    fn bin(&self, k: usize, x: f64, y: f64, y_ref: f64) -> Option<usize> {
        let a = x - self.tans[k] * (y - y_ref) - self.a_min;
        if a < 0.0 || a >= self.a_bins as f64 {
            return None;
        }
        Some(k * self.a_bins + a as usize)
    }

    fn vote(&mut self, p: [f32; 2], weight: u32, y_ref: f64, add: bool) {
        let (x, y) = (p[0] as f64, p[1] as f64);
        for k in 0..self.tans.len() {
            if let Some(i) = self.bin(k, x, y, y_ref) {
                self.acc[i] = if add {
                    self.acc[i] + weight
                } else {
                    self.lowering(k, i);
                    self.acc[i].saturating_sub(weight)
                };
            }
        }
    }

    /// Notes that cell `i` of angle `k` is about to be lowered: if it holds the row's maximum,
    /// the row must be scanned again.
    fn lowering(&mut self, k: usize, i: usize) {
        if self.acc[i] == self.row_max[k].0 {
            self.stale[k] = true;
        }
    }

    /// Sets cell `i` to zero (a peak that withdrew no point, so that it cannot come back).
    fn clear_cell(&mut self, i: usize) {
        self.lowering(i / self.a_bins, i);
        self.acc[i] = 0;
    }

    /// The largest count of angle `k`'s row and the last cell holding it (the maximum first,
    /// a loop the compiler vectorises, then its last position from the end).
    fn scan_row(&self, k: usize) -> (u32, usize) {
        let start = k * self.a_bins;
        let row = &self.acc[start..start + self.a_bins];
        let max = row.iter().copied().max().unwrap_or(0);
        let last = row.iter().rposition(|&v| v == max).unwrap_or(0);
        (max, start + last)
    }

    /// The accumulator's largest cell (the last one on a tie) and its count, rescanning the
    /// rows a withdrawal may have lowered.
    fn peak(&mut self) -> Option<(usize, u32)> {
        for k in 0..self.row_max.len() {
            if self.stale[k] {
                self.row_max[k] = self.scan_row(k);
                self.stale[k] = false;
            }
        }
        self.row_max
            .iter()
            .fold(None, |best: Option<(usize, u32)>, &(v, i)| match best {
                Some((_, b)) if v < b => best,
                _ => Some((i, v)),
            })
    }

    /// Appends to `out` up to `params.max_lines` lines through `points` (x, y), strongest
    /// first; `weights[i]` is point i's vote (1 to [`MAX_WEIGHT`]; without weights every point
    /// votes [`MIN_MEAN_WEIGHT`]).
    pub fn detect(
        &mut self,
        points: &[[f32; 2]],
        weights: &[u8],
        params: &HoughParams,
        out: &mut Vec<LineFit>,
    ) {
        if self.tans.is_empty() {
            let per_side = ((MAX_ANGLE_DEG - MIN_ANGLE_DEG) / ANGLE_STEP_DEG) as usize + 1;
            for sign in [-1.0, 1.0] {
                for k in 0..per_side {
                    let phi = MIN_ANGLE_DEG + k as f64 * ANGLE_STEP_DEG;
                    self.tans.push(sign * math::tan(math::deg_to_rad(phi)));
                }
            }
        }
        let n_angles = self.tans.len();
        let w = params.width as f64;
        self.a_min = -w;
        self.a_bins = 3 * params.width.max(1);
        self.acc.clear();
        self.acc.resize(n_angles * self.a_bins, 0);
        self.used.clear();
        self.used.resize(points.len(), false);
        let y_ref = params.y_ref;
        let weight =
            |i: usize| (weights.get(i).map_or(MIN_MEAN_WEIGHT, |&w| w as u32)).clamp(1, MAX_WEIGHT);
        for (i, &p) in points.iter().enumerate() {
            self.vote(p, weight(i), y_ref, true);
        }
        self.row_max.clear();
        self.row_max.resize(n_angles, (0, 0));
        self.stale.clear();
        self.stale.resize(n_angles, true);
        let min_votes = params.min_support as u32 * MIN_MEAN_WEIGHT;
        let mut found = 0;
        for _ in 0..4 * params.max_lines {
            if found >= params.max_lines {
                break;
            }
            let Some((peak, votes)) = self.peak() else {
                break;
            };
            if votes < min_votes {
                break;
            }
            let k = peak / self.a_bins;
            let seed = LineFit {
                x_ref: self.a_min + (peak % self.a_bins) as f64 + 0.5,
                y_ref,
                slope: self.tans[k],
                support: 0,
                y_top: 0.0,
                y_bottom: 0.0,
                bend: 0.0,
            };
            let fit = self
                .refine(points, seed, 2.0 * BAND_PX)
                .and_then(|f| self.refine(points, f, BAND_PX));
            // Withdraw the points of the peak and of its fit, so the peak cannot come back.
            let mut withdrawn = 0;
            for (i, &p) in points.iter().enumerate() {
                let (x, y) = (p[0] as f64, p[1] as f64);
                let near = seed.distance(x, y) <= 2.0 * BAND_PX
                    || fit.is_some_and(|f| f.distance(x, y) <= BAND_PX);
                if near && !self.used[i] {
                    self.used[i] = true;
                    self.vote(p, weight(i), y_ref, false);
                    withdrawn += 1;
                }
            }
            if withdrawn == 0 {
                self.clear_cell(peak);
            }
            let Some(fit) = fit else { continue };
            if fit.support >= params.min_support && fit.y_bottom - fit.y_top >= params.min_extent {
                out.push(fit);
                found += 1;
            }
        }
    }

    /// Least-squares fit of x(y) to the unused points within `band` of `line`.
    fn refine(&mut self, points: &[[f32; 2]], line: LineFit, band: f64) -> Option<LineFit> {
        self.band.clear();
        let (mut sy, mut sx, mut syy, mut sxy) = (0.0, 0.0, 0.0, 0.0);
        let (mut top, mut bottom) = (f64::INFINITY, f64::NEG_INFINITY);
        for (i, &p) in points.iter().enumerate() {
            let (x, y) = (p[0] as f64, p[1] as f64);
            if self.used[i] || line.distance(x, y) > band {
                continue;
            }
            self.band.push(i);
            let t = y - line.y_ref;
            sy += t;
            sx += x;
            syy += t * t;
            sxy += t * x;
            top = top.min(y);
            bottom = bottom.max(y);
        }
        let n = self.band.len() as f64;
        let det = n * syy - sy * sy;
        if self.band.len() < 3 || det <= 1e-9 * n * n {
            return None;
        }
        let slope = (n * sxy - sy * sx) / det;
        Some(LineFit {
            x_ref: (sx - slope * sy) / n,
            y_ref: line.y_ref,
            slope,
            support: self.band.len(),
            y_top: top,
            y_bottom: bottom,
            bend: 0.0,
        })
    }
}

/// The bend of `line` over rows `rows` (see the module docs). The parabola starts as the line
/// and grows: three times, the points within [`BEND_BAND_PX`] of it in those rows are taken
/// and it is refitted over their rows, so that it follows a marking that curves away from the
/// straight fit. (Keep `rows` below the vanishing point, where other lines come close.)
pub fn bend(points: &[[f32; 2]], line: &LineFit, rows: (f64, f64)) -> f64 {
    // Parabola x = c0 + c1 t + c2 t^2 with t = (y - mid) / half.
    let (mut mid, mut half) = (line.y_ref, 1.0);
    let mut c = Vector3::new(line.x_ref, line.slope, 0.0);
    for _ in 0..3 {
        let at = |y: f64| {
            let t = (y - mid) / half;
            c[0] + c[1] * t + c[2] * t * t
        };
        let (mut top, mut bottom, mut n) = (f64::INFINITY, f64::NEG_INFINITY, 0);
        let near = |x: f64, y: f64| y >= rows.0 && y <= rows.1 && (x - at(y)).abs() <= BEND_BAND_PX;
        for p in points {
            let (x, y) = (p[0] as f64, p[1] as f64);
            if near(x, y) {
                top = top.min(y);
                bottom = bottom.max(y);
                n += 1;
            }
        }
        if n < 6 || bottom - top < 2.0 {
            break;
        }
        let (new_mid, new_half) = (0.5 * (top + bottom), 0.5 * (bottom - top));
        let mut m = Matrix3::zeros();
        let mut r = Vector3::zeros();
        for p in points {
            let (x, y) = (p[0] as f64, p[1] as f64);
            if near(x, y) {
                let t = (y - new_mid) / new_half;
                let basis = Vector3::new(1.0, t, t * t);
                m += basis * basis.transpose();
                r += basis * x;
            }
        }
        let Some(inv) = m.try_inverse() else { break };
        c = inv * r;
        (mid, half) = (new_mid, new_half);
    }
    c[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(width: usize) -> HoughParams {
        HoughParams {
            width,
            y_ref: 100.0,
            min_support: 10,
            min_extent: 20.0,
            max_lines: 4,
        }
    }

    #[test]
    fn two_lines_among_noise_are_found_with_their_slopes() {
        let mut pts = Vec::new();
        for y in 60..140 {
            let y = y as f32;
            pts.push([150.0 - 1.2 * (y - 100.0), y]); // left boundary
            pts.push([250.0 + 0.9 * (y - 100.0), y]); // right boundary
        }
        // Scattered clutter: a deterministic spray of points.
        for i in 0..60u32 {
            pts.push([((i * 97) % 400) as f32, 60.0 + ((i * 53) % 80) as f32]);
        }
        let mut hough = Hough::default();
        let mut out = Vec::new();
        hough.detect(&pts, &[], &params(400), &mut out);
        assert!(out.len() >= 2, "{out:?}");
        let mut slopes: Vec<f64> = out[..2].iter().map(|l| l.slope).collect();
        slopes.sort_by(f64::total_cmp);
        assert!(
            (slopes[0] + 1.2).abs() < 0.01 && (slopes[1] - 0.9).abs() < 0.01,
            "{out:?}"
        );
        for l in &out[..2] {
            assert!(l.support >= 78, "{l:?}");
            let b = bend(&pts, l, (60.0, 140.0));
            assert!(b < 0.2, "straight lines do not bend: {b} {l:?}");
        }
    }

    /// The row maxima give the cell a scan of the whole accumulator gives (the last of the
    /// largest), through withdrawals of random points and zeroed peaks, ties included.
    #[test]
    fn the_row_maxima_find_the_whole_accumulators_peak() {
        let mut rng = crate::filter::Rng::new(5);
        for round in 0..20 {
            let mut hough = Hough::default();
            let points: Vec<[f32; 2]> = (0..40 + 10 * round)
                .map(|_| {
                    // Integer positions and a few shared lines make ties common.
                    let y = 60.0 + rng.below(80) as f32;
                    match rng.below(3) {
                        0 => [150.0 - (y - 100.0), y],
                        1 => [250.0 + (y - 100.0) / 2.0, y],
                        _ => [rng.below(400) as f32, y],
                    }
                })
                .collect();
            let weights: Vec<u8> = points.iter().map(|_| 1 + rng.below(3) as u8).collect();
            // Vote and set up the row maxima as detect does, with no lines taken.
            let mut p = params(400);
            p.max_lines = 0;
            hough.detect(&points, &weights, &p, &mut Vec::new());
            for step in 0..points.len() {
                let full = hough
                    .acc
                    .iter()
                    .enumerate()
                    .max_by_key(|(_, &v)| v)
                    .map(|(i, &v)| (i, v));
                assert_eq!(hough.peak(), full, "round {round}, step {step}");
                if step % 7 == 3 {
                    let (i, _) = full.unwrap();
                    hough.clear_cell(i);
                } else {
                    hough.vote(points[step], u32::from(weights[step]), p.y_ref, false);
                }
            }
        }
    }

    #[test]
    fn a_curved_line_bends() {
        // x = 200 + 0.5 t + 3 t^2 with t = (y - 100) / 40 over rows 60..140: bend 3 px.
        let pts: Vec<[f32; 2]> = (60..140)
            .map(|y| {
                let t = (y as f64 - 100.0) / 40.0;
                [(200.0 + 20.0 * t + 3.0 * t * t) as f32, y as f32]
            })
            .collect();
        let mut out = Vec::new();
        Hough::default().detect(&pts, &[], &params(400), &mut out);
        assert!(!out.is_empty());
        let b = bend(&pts, &out[0], (60.0, 140.0));
        assert!((b - 3.0).abs() < 0.3, "{b} {:?}", out[0]);
        let half = bend(&pts, &out[0], (100.0, 140.0));
        assert!(
            half > 0.5 && half < 1.0,
            "half the rows bend a quarter as much: {half}"
        );
        let mirrored: Vec<[f32; 2]> = pts.iter().map(|p| [400.0 - p[0], p[1]]).collect();
        let mut out = Vec::new();
        Hough::default().detect(&mirrored, &[], &params(400), &mut out);
        let b = bend(&mirrored, &out[0], (60.0, 140.0));
        assert!(
            (b + 3.0).abs() < 0.3,
            "the mirrored curve bends the other way: {b}"
        );
    }
}
