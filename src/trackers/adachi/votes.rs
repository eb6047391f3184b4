//! The measurement space of Adachi et al. (Sec. 3.2, Fig. 3): edge points of a road region,
//! each mapped onto the rho axis (across the road, positive to the right, rho = -y in ISO 8855)
//! through the camera's back-projection, voted into a histogram H_j of bins of `bin_m` metres;
//! and N_j, the same vote of every pixel of the region (the noise distribution).
//!
//! An edge point is a local maximum along its row of the horizontal Sobel response of the
//! chosen polarity, above a threshold, so each marking edge votes once per image row. With
//! `edge_response: "gradient"` (ours) the response is the Sobel gradient magnitude where g_x
//! has the polarity's sign (0 elsewhere): a line at lateral distance Y crosses the image at an
//! angle of tangent h / |Y| (camera height h), and g_x alone falls with that angle, so that a
//! neighbour lane's outer line (|Y| = 1.5 w) from a camera 1.1-1.6 m high hardly passes the
//! threshold that its gradient magnitude passes in 95-100 % of the rows (issue 20; CHANGELOG,
//! 2026-11-28, the known failures' lane-configuration row). The
//! pixel-to-bin table is built once; a frame converts and scans only the region's rows.
//!
//! With `lane_shape: "curved"` (not the paper's) each region pixel also keeps its road point
//! (x ahead, rho), and a frame's edge points are voted where [`road_shape`](super::road_shape)
//! straightens them.

use super::config::{
    AdachiConfig, EdgeResponse, LaneShape, Polarity, PAIRED_EDGE_MAX_M, THRESHOLD_WIDTH_PX,
};
use super::road_shape::{Shape, ShapeSearch};
use crate::camera::Camera;
use crate::error::Result;
use crate::image::luma;

/// The voting executor.
#[derive(Debug, Clone)]
pub struct Votes {
    width: usize,
    rows: std::ops::Range<usize>,
    /// Bin of each pixel of the region rows (u32::MAX outside the region).
    bins: Vec<u32>,
    gray: Vec<f32>,
    response: Vec<f32>,
    /// N_j normalised to sum 1.
    pub noise: Vec<f64>,
    /// The first and last bin of each region row that covers any (for [`Votes::rows_crossing`]).
    row_spans: Vec<(u32, u32)>,
    /// H_j of the last frame.
    pub histogram: Vec<f64>,
    /// Per bin, the road distance of the nearest row that voted into it in the last frame
    /// (infinite when none; `reacquire_near_m`).
    nearest_m: Vec<f64>,
    /// The road distance of each region row (at the image's middle column) and of the
    /// region's nearest row.
    row_m: Vec<f64>,
    near_m: f64,
    bin_m: f64,
    rho_min: f64,
    polarity: Polarity,
    edge_response: EdgeResponse,
    threshold: f32,
    /// `lane_shape: "curved"`: the road point (x ahead, rho) of each region pixel, the frame's
    /// edge points, the search, the followed shape (None before the first frame) and its gain.
    curved: Option<Curved>,
    /// `paired_edges`: the signed edge response of the row and, per region row, how many
    /// pixels [`PAIRED_EDGE_MAX_M`] spans there (empty when off).
    gx: Vec<f32>,
    pair_px: Vec<usize>,
}

#[derive(Debug, Clone)]
struct Curved {
    road: Vec<(f32, f32)>,
    points: Vec<(f32, f32)>,
    search: ShapeSearch,
    shape: Option<Shape>,
    gain: f64,
}

impl Votes {
    /// Builds the table for `camera` and the region of `config`.
    ///
    /// # Errors
    /// None for a validated camera and configuration (kept fallible for future checks).
    pub fn new(camera: &Camera, config: &AdachiConfig) -> Result<Self> {
        let (w, h) = (camera.width(), camera.height());
        let bins_n = (2.0 * config.rho_range_m / config.bin_m).round() as usize;
        let rho_min = -config.rho_range_m;
        let curved = config.lane_shape == LaneShape::Curved;
        let mut table = vec![u32::MAX; w * h];
        let mut road = vec![(0.0f32, 0.0f32); if curved { w * h } else { 0 }];
        let (mut first, mut last) = (h, 0);
        for v in 0..h {
            for u in 0..w {
                let Ok([x, y]) = camera.pixel_to_road(u as f64, v as f64) else {
                    continue;
                };
                if x < config.near_m || x > config.far_m {
                    continue;
                }
                let bin = ((-y - rho_min) / config.bin_m).floor();
                if bin >= 0.0 && (bin as usize) < bins_n {
                    table[v * w + u] = bin as u32;
                    if curved {
                        road[v * w + u] = (x as f32, -y as f32);
                    }
                    first = first.min(v);
                    last = last.max(v);
                }
            }
        }
        let rows = if first <= last { first..last + 1 } else { 0..0 };
        let bins = table[rows.start * w..rows.end * w].to_vec();
        let curved = curved.then(|| Curved {
            road: road[rows.start * w..rows.end * w].to_vec(),
            points: Vec::with_capacity(rows.len() * 16),
            search: ShapeSearch::new(
                config.max_heading_rad,
                config.max_curvature_per_m,
                config.far_m,
                config.bin_m,
                rho_min,
                bins_n,
            ),
            shape: None,
            gain: config.shape_gain,
        });
        let mut noise = vec![0.0; bins_n];
        for &b in &bins {
            if b != u32::MAX {
                noise[b as usize] += 1.0;
            }
        }
        let row_spans = bins
            .chunks(w.max(1))
            .filter_map(|row| {
                let mut span = row.iter().filter(|&&b| b != u32::MAX);
                let first = *span.next()?;
                Some(span.fold((first, first), |(lo, hi), &b| (lo.min(b), hi.max(b))))
            })
            .collect();
        let total: f64 = noise.iter().sum();
        if total > 0.0 {
            noise.iter_mut().for_each(|n| *n /= total);
        }
        let row_m: Vec<f64> = rows
            .clone()
            .map(|v| {
                camera
                    .pixel_to_road(w as f64 / 2.0, v as f64)
                    .map_or(config.far_m, |[x, _]| {
                        crate::math::clamp(x, config.near_m, config.far_m)
                    })
            })
            .collect();
        let near_m = row_m.iter().copied().fold(config.far_m, f64::min);
        let pair_px = if config.paired_edges {
            rows.clone().map(|v| stripe_px(camera, v)).collect()
        } else {
            Vec::new()
        };
        Ok(Self {
            width: w,
            rows: rows.clone(),
            bins,
            gray: vec![0.0; (rows.len() + 2) * w],
            response: vec![0.0; w],
            noise,
            row_spans,
            histogram: vec![0.0; bins_n],
            nearest_m: vec![f64::INFINITY; bins_n],
            row_m,
            near_m,
            bin_m: config.bin_m,
            rho_min,
            polarity: config.polarity,
            edge_response: config.edge_response,
            threshold: if config.width_scaled_threshold {
                (config.edge_threshold * (THRESHOLD_WIDTH_PX / w.max(1) as f64).min(1.0)) as f32
            } else {
                config.edge_threshold as f32
            },
            curved,
            gx: vec![0.0; if config.paired_edges { w } else { 0 }],
            pair_px,
        })
    }

    /// The road shape (s1, s2) the last frame was straightened by (`lane_shape: "curved"`;
    /// (0, 0) for the paper's straight lanes): a boundary at rho_0 lies at
    /// rho_0 + s1 x + s2 x^2 at x metres ahead.
    pub fn shape(&self) -> Shape {
        self.curved
            .as_ref()
            .and_then(|c| c.shape)
            .unwrap_or([0.0, 0.0])
    }

    /// Forgets the followed road shape (the next frame starts from its own best).
    pub fn reset_shape(&mut self) {
        if let Some(c) = &mut self.curved {
            c.shape = None;
        }
    }

    /// Number of bins M.
    pub fn bins(&self) -> usize {
        self.histogram.len()
    }
    /// Centre of bin j on the rho axis, metres.
    pub fn rho(&self, j: usize) -> f64 {
        self.rho_min + (j as f64 + 0.5) * self.bin_m
    }
    /// The bin size, metres.
    pub fn bin_m(&self) -> f64 {
        self.bin_m
    }
    /// The lower end of the rho axis, metres.
    pub fn rho_min(&self) -> f64 {
        self.rho_min
    }
    /// The bin holding `rho`, clamped to the axis.
    pub fn bin_of(&self, rho: f64) -> usize {
        let j = ((rho - self.rho_min) / self.bin_m).floor();
        if j.is_nan() || j < 0.0 {
            0
        } else {
            (j as usize).min(self.bins().saturating_sub(1))
        }
    }

    /// The road distance of the region's nearest row, metres.
    pub fn near_m(&self) -> f64 {
        self.near_m
    }

    /// How far beyond the region's nearest row the nearest vote into the bins `lo..=hi` of the
    /// last frame lies, metres (infinite when none voted there).
    pub fn reach(&self, lo: usize, hi: usize) -> f64 {
        let nearest = self.nearest_m[lo..=hi]
            .iter()
            .fold(f64::INFINITY, |a, &b| a.min(b));
        (nearest - self.near_m).max(0.0)
    }

    /// Number of region rows that cover any of the bins `lo..=hi`: a solid marking edge lying
    /// in those bins can give at most that many votes (one per row).
    pub fn rows_crossing(&self, lo: usize, hi: usize) -> usize {
        self.row_spans
            .iter()
            .filter(|&&(a, b)| (a as usize) <= hi && (b as usize) >= lo)
            .count()
    }
    /// Whether the region covers any pixel.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Votes the edge points of an RGBA frame (of the camera's size) into H_j; returns the
    /// number of votes n.
    pub fn vote(&mut self, rgba: &[u8]) -> usize {
        self.histogram.fill(0.0);
        self.nearest_m.fill(f64::INFINITY);
        let w = self.width;
        if self.rows.is_empty() || w < 3 {
            return 0;
        }
        let height = rgba.len() / (4 * w);
        // Grey rows rows.start - 1 ..= rows.end (clamped).
        let top = self.rows.start.saturating_sub(1);
        let bottom = (self.rows.end + 1).min(height);
        for (k, v) in (top..bottom).enumerate() {
            for u in 0..w {
                let p = &rgba[(v * w + u) * 4..(v * w + u) * 4 + 3];
                self.gray[k * w + u] = luma(p[0], p[1], p[2]) as f32;
            }
        }
        let mut n = 0;
        if let Some(c) = &mut self.curved {
            c.points.clear();
        }
        for v in self.rows.clone() {
            let k = v - top;
            let up = k.saturating_sub(1);
            let down = (k + 1).min(bottom - top - 1);
            let g = |row: usize, u: usize| self.gray[row * w + u];
            let paired = !self.pair_px.is_empty();
            for u in 1..w - 1 {
                let gx = (g(up, u + 1) + 2.0 * g(k, u + 1) + g(down, u + 1))
                    - (g(up, u - 1) + 2.0 * g(k, u - 1) + g(down, u - 1));
                let gradient = || {
                    let gy = (g(down, u - 1) + 2.0 * g(down, u) + g(down, u + 1))
                        - (g(up, u - 1) + 2.0 * g(up, u) + g(up, u + 1));
                    (gx * gx + gy * gy).sqrt()
                };
                // g_x signed by the polarity: positive where the edge has the polarity's sign.
                let signed = match self.polarity {
                    Polarity::LeftEdge => gx,
                    Polarity::RightEdge => -gx,
                    Polarity::Both => gx.abs(),
                };
                self.response[u] = match self.edge_response {
                    EdgeResponse::Horizontal => signed,
                    EdgeResponse::Gradient if signed > 0.0 => gradient(),
                    EdgeResponse::Gradient => 0.0,
                };
                // `paired_edges`: the response of either sign, g_x or the gradient's magnitude
                // signed by g_x, where a partner edge is looked for.
                if paired {
                    self.gx[u] = match self.edge_response {
                        EdgeResponse::Horizontal => gx,
                        EdgeResponse::Gradient => gradient().copysign(gx),
                    };
                }
            }
            self.response[0] = 0.0;
            self.response[w - 1] = 0.0;
            if paired {
                self.gx[0] = 0.0;
                self.gx[w - 1] = 0.0;
            }
            let row_bins = &self.bins[(v - self.rows.start) * w..(v - self.rows.start + 1) * w];
            for (u, &b) in row_bins.iter().enumerate().take(w - 1).skip(1) {
                let r = self.response[u];
                let mut peak =
                    r > self.threshold && r >= self.response[u - 1] && r > self.response[u + 1];
                if peak && paired {
                    let reach = self.pair_px[v - self.rows.start];
                    peak = has_partner(&self.gx, u, reach, self.threshold);
                }
                if peak && b != u32::MAX {
                    match &mut self.curved {
                        None => {
                            self.histogram[b as usize] += 1.0;
                            let x = self.row_m[v - self.rows.start];
                            let nearest = &mut self.nearest_m[b as usize];
                            *nearest = nearest.min(x);
                            n += 1;
                        }
                        Some(c) => c.points.push(c.road[(v - self.rows.start) * w + u]),
                    }
                }
            }
        }
        match &mut self.curved {
            None => n,
            Some(c) => vote_straightened(c, &mut self.histogram, &mut self.nearest_m),
        }
    }
}

/// How many pixels [`PAIRED_EDGE_MAX_M`] spans across the road at image row `v`, measured at
/// the middle column (at least 2: the Sobel responses of a line one pixel wide lie 2 apart).
fn stripe_px(camera: &Camera, v: usize) -> usize {
    let u = camera.width() as f64 / 2.0;
    let (Ok([_, y0]), Ok([_, y1])) = (
        camera.pixel_to_road(u, v as f64),
        camera.pixel_to_road(u + 1.0, v as f64),
    ) else {
        return 2;
    };
    let metres_per_px = (y1 - y0).abs();
    if metres_per_px > 0.0 && metres_per_px.is_finite() {
        ((PAIRED_EDGE_MAX_M / metres_per_px).ceil() as usize).clamp(2, camera.width())
    } else {
        2
    }
}

/// Whether the edge at `u` (signed response `gx`) is one side of a bright stripe: a rising edge
/// (dark to light going right) needs a falling peak within `reach` pixels to its right, a
/// falling one a rising peak within `reach` to its left, each above `threshold`.
fn has_partner(gx: &[f32], u: usize, reach: usize, threshold: f32) -> bool {
    let falling = |i: usize| -gx[i] > threshold && -gx[i] >= -gx[i - 1] && -gx[i] > -gx[i + 1];
    let rising = |i: usize| gx[i] > threshold && gx[i] >= gx[i - 1] && gx[i] > gx[i + 1];
    let last = gx.len() - 2;
    if gx[u] > 0.0 {
        (u + 1..=(u + reach).min(last)).any(falling)
    } else {
        (u.saturating_sub(reach).max(1)..u).any(rising)
    }
}

/// Finds and follows the road shape of the frame's edge points, then votes each one where the
/// shape straightens it; returns the number of votes.
fn vote_straightened(c: &mut Curved, histogram: &mut [f64], nearest_m: &mut [f64]) -> usize {
    let best = c.search.best(&c.points);
    let shape = match c.shape {
        None => best,
        Some(prev) => [
            prev[0] + c.gain * (best[0] - prev[0]),
            prev[1] + c.gain * (best[1] - prev[1]),
        ],
    };
    c.shape = Some(shape);
    let mut n = 0;
    for &(x, rho) in &c.points {
        if let Some(j) = c.search.bin(x, rho, shape) {
            histogram[j] += 1.0;
            nearest_m[j] = nearest_m[j].min(x as f64);
            n += 1;
        }
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::default_camera;

    /// A grey road with the stripe rho = 1.50-1.65 m (y = -1.5 .. -1.65) painted white, seen
    /// through the 320x240 default camera.
    fn stripe_frame(cam: &Camera) -> Vec<u8> {
        stripe_at(cam, 1.5, 230)
    }

    /// A grey road (90) with a stripe of grey `paint` 0.15 m wide from rho = `rho` to the right.
    fn stripe_at(cam: &Camera, rho: f64, paint: u8) -> Vec<u8> {
        let mut rgba = vec![90u8; 320 * 240 * 4];
        for v in 0..240 {
            for u in 0..320 {
                if let Ok([_, y]) = cam.pixel_to_road(u as f64, v as f64) {
                    if (-rho - 0.15..=-rho).contains(&y) {
                        rgba[(v * 320 + u) * 4..(v * 320 + u) * 4 + 3]
                            .copy_from_slice(&[paint, paint, paint]);
                    }
                }
            }
        }
        rgba
    }

    /// Votes in the bins whose centres lie in [lo, hi).
    fn between(votes: &Votes, lo: f64, hi: f64) -> f64 {
        (0..votes.bins())
            .filter(|&j| (lo..hi).contains(&votes.rho(j)))
            .map(|j| votes.histogram[j])
            .sum()
    }

    #[test]
    fn a_painted_stripe_votes_into_the_bin_of_its_left_edge() {
        let cam = default_camera(320, 240).unwrap();
        let config = AdachiConfig::default();
        let mut votes = Votes::new(&cam, &config).unwrap();
        assert_eq!(votes.bins(), 320);
        assert!((votes.noise.iter().sum::<f64>() - 1.0).abs() < 1e-9);
        let n = votes.vote(&stripe_frame(&cam));
        assert!(n > 20, "{n} votes");
        let peak = (0..votes.bins())
            .max_by(|&a, &b| votes.histogram[a].total_cmp(&votes.histogram[b]))
            .unwrap();
        assert!(
            (votes.rho(peak) - 1.5).abs() <= 0.1,
            "peak at {}",
            votes.rho(peak)
        );
        // Left edges only: nothing near the right edge at 1.65 + a bin.
        let j = ((1.75 - votes.rho_min()) / votes.bin_m()) as usize;
        assert_eq!(votes.histogram[j], 0.0);
        // Every vote is at the left edge, once per region row the stripe crosses.
        let rows = votes.rows_crossing(votes.bin_of(1.45), votes.bin_of(1.55));
        assert_eq!(between(&votes, 1.4, 1.6), n as f64);
        assert!(
            n <= rows && n as f64 >= 0.8 * rows as f64,
            "{n} of {rows} rows"
        );
    }

    /// A stripe far to the side crosses the image nearly flat, so its g_x is a fraction of
    /// its gradient: with `edge_response: "horizontal"` a stripe 40 grey levels brighter than
    /// the road (g_x of a vertical edge 160, twice the threshold) votes in few rows 5.5 m out,
    /// with `"gradient"` in about half (a neighbour lane's outer line, issue 20; in the far rows
    /// this stripe is under a pixel thick and the 3x3 Sobel cancels it either way). A stripe
    /// 1.5 m out votes alike with both.
    #[test]
    fn the_gradient_response_passes_flat_lines() {
        let cam = default_camera(320, 240).unwrap();
        let rows_voted = |rho: f64, edge_response| {
            let config = AdachiConfig {
                edge_response,
                ..AdachiConfig::default()
            };
            let mut votes = Votes::new(&cam, &config).unwrap();
            votes.vote(&stripe_at(&cam, rho, 130));
            let (lo, hi) = (votes.bin_of(rho - 0.1), votes.bin_of(rho + 0.1));
            let n: f64 = votes.histogram[lo..=hi].iter().sum();
            n / votes.rows_crossing(lo, hi) as f64
        };
        let (near_h, near_g) = (
            rows_voted(1.5, EdgeResponse::Horizontal),
            rows_voted(1.5, EdgeResponse::Gradient),
        );
        let (far_h, far_g) = (
            rows_voted(5.5, EdgeResponse::Horizontal),
            rows_voted(5.5, EdgeResponse::Gradient),
        );
        println!("rows voted: 1.5 m {near_h:.2} / {near_g:.2}, 5.5 m {far_h:.2} / {far_g:.2}");
        assert!(near_h > 0.8 && near_g > 0.8, "{near_h} {near_g}");
        assert!(far_g > 0.4, "gradient at 5.5 m: {far_g}");
        assert!(far_h < 0.1, "g_x at 5.5 m: {far_h}");
    }

    #[test]
    fn the_polarity_option_chooses_the_edge_that_votes() {
        let cam = default_camera(320, 240).unwrap();
        let rgba = stripe_frame(&cam);
        let with = |polarity| {
            let config = AdachiConfig {
                polarity,
                ..AdachiConfig::default()
            };
            let mut votes = Votes::new(&cam, &config).unwrap();
            let n = votes.vote(&rgba) as f64;
            // Split at the stripe's middle, 1.575 m: an edge point can fall a pixel (up to
            // 1.5 bins in the far rows) to either side of its edge.
            (n, between(&votes, 1.35, 1.575), between(&votes, 1.575, 1.8))
        };
        let (n_left, left_at_left, left_at_right) = with(Polarity::LeftEdge);
        let (n_right, right_at_left, right_at_right) = with(Polarity::RightEdge);
        let (n_both, both_at_left, both_at_right) = with(Polarity::Both);
        assert!(n_left > 20.0 && left_at_left == n_left && left_at_right == 0.0);
        // The right edge at 1.65 m votes, the left one at 1.5 m does not.
        assert!(
            n_right > 20.0 && right_at_right == n_right && right_at_left == 0.0,
            "{n_right} votes: {right_at_left} at 1.5 m, {right_at_right} at 1.65 m"
        );
        // Both: each edge as often as alone, nothing else.
        assert_eq!(
            (both_at_left, both_at_right, n_both),
            (n_left, n_right, n_left + n_right)
        );
    }

    /// A grey road (90) painted by `paint(y)` (Some grey level for the road point's lateral y).
    fn painted_frame(cam: &Camera, paint: impl Fn(f64) -> Option<u8>) -> Vec<u8> {
        let (w, h) = (cam.width(), cam.height());
        let mut rgba = vec![90u8; w * h * 4];
        for v in 0..h {
            for u in 0..w {
                let at = cam.pixel_to_road(u as f64, v as f64).ok();
                if let Some(grey) = at.and_then(|p| paint(p[1])) {
                    rgba[(v * w + u) * 4..(v * w + u) * 4 + 3].fill(grey);
                }
            }
        }
        rgba
    }

    #[test]
    fn a_width_scaled_threshold_halves_at_twice_640_pixels_and_holds_below() {
        // A faint marking: 15 grey levels over the road, a Sobel response of 60, under the
        // default threshold of 80 and over its half.
        let faint = |y: f64| (-1.65..=-1.5).contains(&y).then_some(105u8);
        let count = |width, height, width_scaled_threshold| {
            let cam = default_camera(width, height).unwrap();
            let config = AdachiConfig {
                width_scaled_threshold,
                ..AdachiConfig::default()
            };
            let mut votes = Votes::new(&cam, &config).unwrap();
            votes.vote(&painted_frame(&cam, faint))
        };
        assert_eq!(count(1280, 720, false), 0);
        let scaled = count(1280, 720, true);
        assert!(
            scaled > 50,
            "{scaled} votes at 1280x720 with the scaled threshold"
        );
        assert_eq!((count(320, 240, false), count(320, 240, true)), (0, 0));
    }

    #[test]
    fn with_paired_edges_only_a_bright_stripe_votes_not_a_seam_or_a_dark_stripe() {
        let cam = default_camera(320, 240).unwrap();
        // Across the road (rho = -y, to the right): light road (140) up to a dark strip of crack
        // sealant (40) at rho -2.2 .. -2.0, asphalt (90) to the seam at -0.5, lighter concrete
        // (140) beyond it, and on it a white marking (230) at 1.5 .. 1.65 m. Rising edges
        // (dark to light going right): the strip's right side, the seam and the marking.
        let rgba = painted_frame(&cam, |y| {
            let rho = -y;
            if (1.5..=1.65).contains(&rho) {
                Some(230)
            } else if (-2.2..=-2.0).contains(&rho) {
                Some(40)
            } else if !(-2.2..-0.5).contains(&rho) {
                Some(140)
            } else {
                None
            }
        });
        let with = |paired_edges| {
            let config = AdachiConfig {
                paired_edges,
                ..AdachiConfig::default()
            };
            let mut votes = Votes::new(&cam, &config).unwrap();
            let n = votes.vote(&rgba) as f64;
            (
                n,
                between(&votes, 1.35, 1.575),
                between(&votes, -0.7, -0.3),
                between(&votes, -2.2, -1.8),
            )
        };
        let (n, marking, seam, sealant) = with(false);
        // Every rising edge votes: the marking's, the seam's and the sealant strip's right side.
        assert!(
            marking > 20.0 && seam > 20.0 && sealant > 20.0,
            "{n}: {marking} {seam} {sealant}"
        );
        let (n_paired, marking_paired, seam_paired, sealant_paired) = with(true);
        assert_eq!(
            marking_paired, marking,
            "the marking's left edge has its right edge beside it"
        );
        assert_eq!(
            (seam_paired, sealant_paired),
            (0.0, 0.0),
            "single edges and dark stripes"
        );
        assert_eq!(n_paired, marking_paired, "nothing else votes");
    }
}
