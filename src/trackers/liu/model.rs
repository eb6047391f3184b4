//! The partitioned model of Liu Sec. IV: the particle state, the random walks of its two
//! partitions (eqs. 18-19, 22-23), the measurement models of both partitions (PPF-Kernel eqs.
//! 20-21 and 24-25, PPF-NoKernel eqs. 26-27), the multiple-lane validity checks (Sec. IV-A) and
//! the default lane model the initialisation particles come from (Sec. IV-D).
//!
//! Stage 0 (linear part): weight = prod_k n_k^l p(z_k^l | x) = prod_k S_k^l with
//!
//! ```text
//! S_k^l = sum_{i near boundary k, y_i > y_m} K_ci K_theta(theta_k; theta_i, 1/|grad I|_i) G_li(rho_k, theta_k)
//! ```
//!
//! Stage 1 (parabolic part): weight = A prod_k n_k^p p(z_k^p | x) = prod_k S_k^p / n_k^l, with
//! A = prod_k 1 / n_k^l (Sec. IV-F: the paper replaces the weighted-resampling factor 1/w^l
//! by 1/n_k^l "to enforce the importance of the linear part"; we read it as the product over
//! the boundaries, the counts of the particle's own linear part, with n_k^l = 0 read as 1) and
//!
//! ```text
//! S_k^p = sum_{i near boundary k, y_i <= y_m} K_ci G_pi(c_k, d_k, e_k)      (eq. 17 for c, e)
//! ```
//!
//! PPF-NoKernel replaces the sums by sum_i K_ci over the same pixels (eqs. 26-27). "Near" is a
//! band of +-`band_px` columns around the boundary in each row (the paper does not give its
//! width). A boundary with no mask pixel near it gives S = 0 and the particle weight 0, as the
//! product of eq. 21 says; when that happens to every particle (a blackout) the core falls back
//! to equal weights and the random walk carries the cloud.
//!
//! Numerics (ours, tested against the reference kernels of [`super::kernels`] to 1e-3): exp by
//! the polynomial of [`super::neg_exp`] (an approximation within 8e-5 relative; 0 from an
//! exponent of 32 on, exp(-32) = 1.3e-14), its argument in base 2 (log2(e) folded into the
//! exponent's constant factors: log2(e) / (2 sigma_x^2) cos^2(theta) / (...) and
//! log2(e) / 2 |grad I|), the 3-node rule's outer weights as 1/4 of the middle one's (w_0
//! multiplies the sum once), in G_pi the curve's orientation per row by the polynomial
//! [`super::atan32`] (an approximation within 2e-7 rad) and at the quadrature nodes taken
//! to first order from the row's (the nodes are within 2 rows; the error is below 1e-6 rad),
//! orientation differences folded by d - pi round(d / pi), and both kernels in f32: a pixel's term (rounding 6e-8 each, the f32 column differences 1e-5
//! at most) is added into one of four f32 partial sums over up to 64 pixels (rounding below
//! 1e-6 relative), which go into the f64 sum. The pixels of both sums are gathered across
//! rows and run four per operation ([`super::lanes`]: SSE2 natively, `simd128` in
//! WebAssembly), with the same bits on every target.

//! Validity (Sec. IV-A, in metres): at the bottom row and at y_m, each boundary lies at least
//! `min_spacing_m` to the right of its left neighbour, and neighbouring spacings differ by less
//! than `max_spacing_difference_m`; other particles get weight 0 in stage 0.

use super::atan32::{atan32, Atan32Lanes};
use super::config::{LiuConfig, MAX_BOUNDARIES};
use super::descriptors::{wrap_half_turn, Descriptors, MaskPixel};
use super::kernels::GaussHermite;
use super::lanes::F32x4;
use super::neg_exp::{neg_exp, NegExp2Lanes};
use crate::calib::ego_on_road::EgoOnRoad;
use crate::filter::{InitialDistribution, PartitionedModel, Rng};
use crate::lane::LinearParabolic;
use crate::math;
use std::cell::RefCell;
use std::f64::consts::PI;
use std::ops::{Add, Div, Mul, Sub};

/// One particle: (rho, theta, d) of each boundary, left to right; only the first n_l are used.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaneParticle {
    /// (rho px, theta rad, d px/px) per boundary.
    pub boundaries: [[f64; 3]; MAX_BOUNDARIES],
}

/// The two partitions' motion and measurement, on one top view.
#[derive(Debug, Clone)]
pub struct PpfModel {
    n: usize,
    kernel: bool,
    width: usize,
    height: usize,
    y_m: f64,
    m_per_px: f64,
    var_x: f64,
    var_y: f64,
    band: usize,
    /// -band_px - 1 and width + band_px: the bounds of x -+ 1/2 for a band in the view.
    band_below: f64,
    band_above: f64,
    /// w_k / sqrt(pi) of the Gauss-Hermite rule (f32: the parabolic sums run in f32).
    node_weights: Vec<f32>,
    /// sqrt(2 sigma_y^2) t_k.
    node_offsets: Vec<f64>,
    /// log2(e) / (2 sigma_x^2) in f32: the position term of the kernels' exponent in base 2.
    position_log2: f32,
    sigma_rho: f64,
    sigma_theta: f64,
    sigma_d: f64,
    min_spacing: f64,
    max_difference: f64,
    /// n_k^l of the linear parts stage 0 weighed in the current frame (see [`CountMemo`]).
    counts: RefCell<CountMemo>,
}

/// n_k^l by linear part: stage 0 counts the band pixels of every boundary it weighs as it sums
/// their kernels, and stage 1 (whose particles are stage 0's, resampled: copies, with the
/// same (rho, theta) bits, only d moved) reads them here instead of counting again. Keyed by
/// the bits of (rho, theta) and valid for one frame of descriptors ([`Descriptors::frame`]);
/// a value is exactly what [`PpfModel::linear_count`] gives for that line, so a miss (a
/// particle stage 0 did not weigh, e.g. an invalid one after a blackout) just counts.
#[derive(Debug, Clone, Default)]
struct CountMemo {
    /// The frame the entries belong to.
    frame: u64,
    /// Open addressing (linear probing), a power of two long: (rho bits, theta bits, count +
    /// 1), count + 1 = 0 for an empty slot.
    slots: Vec<(u64, u64, u32)>,
    used: usize,
}

impl CountMemo {
    fn slot(&self, rho: u64, theta: u64) -> usize {
        let h = (rho ^ theta.rotate_left(29)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        (h >> 40) as usize & (self.slots.len() - 1)
    }

    /// The entries of `frame` (emptied when they were another frame's).
    fn for_frame(&mut self, frame: u64) -> &mut Self {
        if self.frame != frame {
            self.frame = frame;
            self.slots.fill((0, 0, 0));
            self.used = 0;
        }
        self
    }

    fn get(&self, rho: u64, theta: u64) -> Option<usize> {
        if self.used == 0 {
            return None;
        }
        let mut i = self.slot(rho, theta);
        loop {
            let (r, t, c) = self.slots[i];
            if c == 0 {
                return None;
            }
            if r == rho && t == theta {
                return Some(c as usize - 1);
            }
            i = (i + 1) & (self.slots.len() - 1);
        }
    }

    fn insert(&mut self, rho: u64, theta: u64, count: usize) {
        if 2 * (self.used + 1) > self.slots.len() {
            let old = std::mem::take(&mut self.slots);
            self.slots = vec![(0, 0, 0); (2 * old.len()).max(1024)];
            self.used = 0;
            for (r, t, c) in old {
                if c != 0 {
                    self.insert(r, t, c as usize - 1);
                }
            }
        }
        let mut i = self.slot(rho, theta);
        loop {
            let (r, t, c) = self.slots[i];
            if c == 0 {
                self.slots[i] = (rho, theta, count as u32 + 1);
                self.used += 1;
                return;
            }
            if r == rho && t == theta {
                return;
            }
            i = (i + 1) & (self.slots.len() - 1);
        }
    }
}

impl PpfModel {
    /// The model of `config` on a top view of `width` x `height` pixels; `kernel` selects
    /// PPF-Kernel (otherwise PPF-NoKernel).
    pub fn new(config: &LiuConfig, width: usize, height: usize, kernel: bool) -> Self {
        let rule = GaussHermite::new(config.quadrature_nodes);
        let var_y = config.position_variance_px2;
        let node_weights = rule
            .weights
            .iter()
            .map(|w| (w / PI.sqrt()) as f32)
            .collect();
        let node_offsets = rule
            .nodes
            .iter()
            .map(|t| (2.0 * var_y).sqrt() * t)
            .collect();
        Self {
            n: config.boundaries,
            kernel,
            width,
            height,
            y_m: config.split_row(height),
            m_per_px: config.top_view.m_per_px,
            var_x: config.position_variance_px2,
            var_y,
            band: config.band_px,
            band_below: -(config.band_px as f64) - 1.0,
            band_above: (width + config.band_px) as f64,
            node_weights,
            node_offsets,
            position_log2: (std::f64::consts::LOG2_E * 0.5 / config.position_variance_px2) as f32,
            sigma_rho: config.sigma_rho_px,
            sigma_theta: config.sigma_theta,
            sigma_d: config.sigma_d,
            min_spacing: config.min_spacing_m,
            max_difference: config.max_spacing_difference_m,
            counts: RefCell::new(CountMemo::default()),
        }
    }

    /// Number of boundaries n_l.
    pub fn boundaries(&self) -> usize {
        self.n
    }
    /// The split row y_m.
    pub fn split_row(&self) -> f64 {
        self.y_m
    }
    /// Boundary k of a particle as a model.
    pub fn boundary(&self, p: &LaneParticle, k: usize) -> LinearParabolic {
        let [rho, theta, d] = p.boundaries[k];
        LinearParabolic {
            rho,
            theta,
            d,
            y_m: self.y_m,
        }
    }

    /// First near row (the rows y > y_m) and the last far row (y <= y_m).
    fn near_rows(&self) -> std::ops::Range<usize> {
        let first = (self.y_m.floor() as usize + 1).min(self.height);
        first..self.height
    }
    fn far_rows(&self) -> std::ops::Range<usize> {
        0..(self.y_m.floor() as usize + 1).min(self.height)
    }

    /// Columns of the band around x in a row, clipped to the view: the band is centred on x
    /// rounded half away from zero (as `f64::round`); `None` when none of its columns is in
    /// the view, and for NaN and infinities.
    #[inline]
    fn band(&self, x: f64) -> Option<std::ops::RangeInclusive<usize>> {
        // x rounded half away from zero is the integer part of x + 1/2 for x >= 0 and of
        // x - 1/2 below (-0 gives 0 either way).
        let r = x + 0.5f64.copysign(x);
        // The band c -+ band_px meets columns 0..=width - 1 exactly when -band_px <= c <=
        // width - 1 + band_px, i.e. -band_px - 1 < r < width + band_px (false for NaN).
        if !(r > self.band_below && r < self.band_above) {
            return None;
        }
        let centre = r as i64;
        let lo = (centre - self.band as i64).max(0);
        let hi = (centre + self.band as i64).min(self.width as i64 - 1);
        Some(lo as usize..=hi as usize)
    }

    /// The mask pixels in the band around column x of one row, `before` being the row's
    /// [`Descriptors::row_before`]: [`PpfModel::band`] then [`Descriptors::span`], empty where
    /// there is no band.
    #[inline]
    fn band_span(&self, before: &[u32], x: f64) -> std::ops::Range<usize> {
        match self.band(x) {
            Some(cols) => before[*cols.start()] as usize..before[*cols.end() + 1] as usize,
            None => 0..0,
        }
    }

    /// The band spans of the `n <= ROW_CHUNK` rows from `first` around the curve x(y) (as
    /// [`PpfModel::band_span`] row by row) into `spans`, with x(y) in f32. A pass of its own
    /// before the rows' pixels are batched: the loop keeps its few values in registers.
    #[inline]
    fn spans(
        &self,
        cues: &Descriptors,
        first: usize,
        n: usize,
        x_at: impl Fn(f64) -> f64,
        spans: &mut Spans,
    ) {
        let (band, last) = (self.band as i32, self.width as i32 - 1);
        let (below, above) = (self.band_below, self.band_above);
        let mut y = first as f64;
        let rows = cues.rows_before(first..first + n);
        for (((before, start), len), x32) in rows
            .zip(&mut spans.start)
            .zip(&mut spans.len)
            .zip(&mut spans.x)
        {
            let x = x_at(y);
            y += 1.0;
            // As `band`: the centre column is x + 1/2 sign(x) truncated.
            let r = x + 0.5f64.copysign(x);
            let (s, e) = if r > below && r < above {
                // SAFETY: -band_px - 1 < r < width + band_px, so r is a number and its
                // integer part fits an i32 (band_px <= 50, the view's width far below 2^31).
                let centre = unsafe { r.to_int_unchecked::<i32>() };
                // 0 <= lo <= width - 1 and 1 <= hi + 1 <= width (the bounds above): within
                // the row's width + 1 counts.
                let lo = (centre - band).max(0) as usize;
                let hi = (centre + band).min(last) as usize;
                (before[lo], before[hi + 1])
            } else {
                (0, 0)
            };
            *start = s;
            *len = e - s;
            *x32 = x as f32;
        }
    }

    /// Sec. IV-A: spacings at the bottom row and at y_m.
    pub fn is_valid(&self, p: &LaneParticle) -> bool {
        // Each boundary's coefficients once for both rows (`x_at` computes them per call).
        let mut coefficients = [[0.0; 4]; MAX_BOUNDARIES];
        for (k, co) in coefficients.iter_mut().enumerate().take(self.n) {
            *co = self.boundary(p, k).coefficients();
        }
        for y in [self.height as f64 - 1.0, self.y_m] {
            let mut previous: Option<(f64, Option<f64>)> = None;
            for (k, &[a, b, c, e]) in coefficients.iter().enumerate().take(self.n) {
                // As `LinearParabolic::x_at`.
                let x = if y > self.y_m {
                    a + b * y
                } else {
                    c + p.boundaries[k][2] * y + e * y * y
                };
                if let Some((x_left, spacing_left)) = previous {
                    let spacing = (x - x_left) * self.m_per_px;
                    if spacing.is_nan() || spacing <= self.min_spacing {
                        return false;
                    }
                    if let Some(s) = spacing_left {
                        if (spacing - s).abs() >= self.max_difference {
                            return false;
                        }
                    }
                    previous = Some((x, Some(spacing)));
                } else {
                    previous = Some((x, None));
                }
            }
        }
        true
    }

    /// S_k^l of boundary `b` over the near rows: eq. 20 times n_k^l (PPF-Kernel) or eq. 26 times
    /// n_k^l (PPF-NoKernel).
    pub fn linear_sum(&self, b: &LinearParabolic, cues: &Descriptors) -> f64 {
        self.linear_sum_count(b, cues).0
    }

    /// [`PpfModel::linear_sum`] and [`PpfModel::linear_count`] of boundary `b` in one pass
    /// over the near rows (the same line, a = rho / cos(theta) and slope -sin / cos, so the
    /// same bands).
    // Out of line (one call per boundary): each loop keeps its own registers.
    #[inline(never)]
    pub fn linear_sum_count(&self, b: &LinearParabolic, cues: &Descriptors) -> (f64, usize) {
        let (s, c) = (math::sin(b.theta), math::cos(b.theta));
        let (a, slope) = (b.rho / c, -s / c);
        let mut count = 0;
        // Eq. 5's variance of the distance along the normal.
        let var = self.var_x * c * c + self.var_y * s * s;
        let line = Line {
            theta: b.theta as f32,
            // The exponent's position term (cos (xc - x))^2 / (2 var) in base 2, as one factor
            // of (xc - x)^2.
            position_log2: (std::f64::consts::LOG2_E * c * c * 0.5 / var) as f32,
        };
        let mut sum = 0.0;
        let near = self.near_rows();
        if !self.kernel {
            let mut y = near.start as f64;
            for before in cues.rows_before(near) {
                let span = self.band_span(before, a + slope * y);
                y += 1.0;
                count += span.len();
                sum += cues.weight_of(span);
            }
            return (sum, count);
        }
        let mut batch = Batch::<1>::new(&cues.pixels);
        let mut spans = Spans::default();
        let mut exponents = [[F32x4::splat(0.0); 2]; BATCH_QUADS];
        for first in near.clone().step_by(ROW_CHUNK) {
            let n = (near.end - first).min(ROW_CHUNK);
            self.spans(cues, first, n, |y| a + slope * y, &mut spans);
            count += spans.len[..n].iter().map(|&l| l as usize).sum::<usize>();
            batch.push_rows(&spans, [&spans.x], n, |b| {
                sum += line.batch(b, &mut exponents);
            });
        }
        if batch.used > 0 {
            sum += line.batch(&batch, &mut exponents);
        }
        sum /= (2.0 * PI * var).sqrt();
        (sum, count)
    }

    /// Mask pixels near boundary `b` in the near rows (n_k^l), without the kernels.
    pub fn linear_count(&self, b: &LinearParabolic, cues: &Descriptors) -> usize {
        // The line of `linear_sum_count` (a = b.a(); the slope -sin / cos, not b.b()'s -tan).
        let [a, slope, _, _] = b.coefficients();
        self.near_rows()
            .filter_map(|y| {
                let cols = self.band(a + slope * y as f64)?;
                Some(cues.span(y, *cols.start(), *cols.end()).len())
            })
            .sum()
    }

    /// S_k^p of boundary `b` over the far rows: eq. 24 times n_k^p (PPF-Kernel, G_pi by
    /// Gauss-Hermite) or eq. 27 times n_k^p (PPF-NoKernel).
    pub fn parabolic_sum(&self, b: &LinearParabolic, cues: &Descriptors) -> f64 {
        let [_, _, c, e] = b.coefficients();
        let d = b.d;
        let nodes = self.node_offsets.len();
        if self.kernel && nodes == 3 {
            return self.parabolic_sum_3(c, d, e, cues);
        }
        let mut sum = 0.0;
        let mut node_x = [0.0f32; 20];
        let mut node_theta = [0.0f32; 20];
        let far = self.far_rows();
        let mut yf = far.start as f64;
        for before in cues.rows_before(far) {
            let xc = c + d * yf + e * yf * yf;
            yf += 1.0;
            let span = self.band_span(before, xc);
            if span.is_empty() {
                continue;
            }
            if !self.kernel {
                sum += cues.weight_of(span);
                continue;
            }
            // Other rules than the default 3-node one: one pixel at a time. The curve and its
            // gradient orientation (eq. 7) at the row's nodes y_k: the orientation at y, in
            // f32 as the kernels use it, by the polynomial atan32 (an approximation within
            // 2e-7 rad), and its first-order change across the nodes (|dtheta/dy| = 2|e| / (1
            // + slope^2) over +-2 rows: below 1e-6 rad off).
            let yf = yf - 1.0;
            let slope = d + 2.0 * e * yf;
            let theta = atan32(-slope as f32);
            let dtheta_dy = -2.0 * e / (1.0 + slope * slope);
            for k in 0..nodes {
                let yk = yf + self.node_offsets[k];
                node_x[k] = (c + d * yk + e * yk * yk) as f32;
                // The change of the curve's orientation from the row to node k.
                node_theta[k] = (dtheta_dy * self.node_offsets[k]) as f32;
            }
            sum = self.parabolic_pixels(
                sum,
                &cues.pixels[span],
                theta,
                &node_x[..nodes],
                &node_theta[..nodes],
            );
        }
        if self.kernel {
            sum /= (2.0 * PI * self.var_x).sqrt();
        }
        sum
    }

    /// [`PpfModel::parabolic_sum`] of the curve x = c + d y + e y^2 with the default 3-node
    /// rule (nodes y - h, y, y + h): the pixels are batched across rows and go four at a time,
    /// each with its row's curve: at the nodes y -+ h the column is xc -+ slope h + e h^2 and
    /// the orientation theta -+ h dtheta/dy.
    // Out of line (one call per boundary): each loop keeps its own registers.
    #[inline(never)]
    fn parabolic_sum_3(&self, c: f64, d: f64, e: f64, cues: &Descriptors) -> f64 {
        let h = self.node_offsets[2];
        let (h32, e_h2) = (h as f32, (e * h * h) as f32);
        // -2 e h: h dtheta/dy = -2 e h / (1 + slope^2).
        let minus_2eh = (-2.0 * e * h) as f32;
        let mut batch = Batch::<4>::new(&cues.pixels);
        // The per-row orientation records, ROW_CHUNK rows at a time ([`RowCurve::orientations`]).
        let curve = RowCurve {
            minus_d: -d as f32,
            two_e: (2.0 * e) as f32,
            minus_h: -h32,
            minus_2eh,
        };
        let mut records = [[0.0f32; ROW_CHUNK]; 3];
        let mut spans = Spans::default();
        let mut exponents = [[F32x4::splat(0.0); 4]; BATCH_QUADS];
        let far = self.far_rows();
        let mut sum = 0.0;
        for first in far.clone().step_by(ROW_CHUNK) {
            let n = (far.end - first).min(ROW_CHUNK);
            curve.orientations(first as f32, n, &mut records);
            self.spans(cues, first, n, |y| c + d * y + e * y * y, &mut spans);
            let [theta, slope_h, dtheta_h] = &records;
            batch.push_rows(&spans, [&spans.x, theta, slope_h, dtheta_h], n, |b| {
                sum += self.parabolic_batch(b, e_h2, &mut exponents);
            });
        }
        if batch.used > 0 {
            sum += self.parabolic_batch(&batch, e_h2, &mut exponents);
        }
        // The middle node's weight w_0 / sqrt(pi), which `parabolic_batch` leaves out.
        sum *= f64::from(self.node_weights[1]);
        sum / (2.0 * PI * self.var_x).sqrt()
    }
}

/// Rows per [`RowCurve::orientations`] and [`PpfModel::spans`] call (a multiple of 4).
const ROW_CHUNK: usize = 64;

/// The band spans of up to ROW_CHUNK rows ([`PpfModel::spans`]): the first mask pixel of
/// each row's band, their number, and the curve's column there in f32.
struct Spans {
    start: [u32; ROW_CHUNK],
    len: [u32; ROW_CHUNK],
    x: [f32; ROW_CHUNK],
}

impl Default for Spans {
    fn default() -> Self {
        Self {
            start: [0; ROW_CHUNK],
            len: [0; ROW_CHUNK],
            x: [0.0; ROW_CHUNK],
        }
    }
}

/// A far part's curve x = c + d y + e y^2 (eq. 6) for the 3-node rule's row records, in f32:
/// -d, 2 e, -h and -2 e h (h the outer nodes' offset).
struct RowCurve {
    minus_d: f32,
    two_e: f32,
    minus_h: f32,
    minus_2eh: f32,
}

impl RowCurve {
    /// For the ROW_CHUNK rows from `y0` (the first `rows` of them at least), four per
    /// operation: the curve's gradient orientation theta = atan(-slope) (eq. 7, slope = d + 2 e
    /// y; by the polynomial [`atan32_x4`], within 2e-7 rad), slope h and h dtheta/dy = -2 e h /
    /// (1 + slope^2), into `records[0..3]`. The atan runs in a pass of its own over the stored
    /// -slope: its twelve constant lanes and the rows' values in one loop are more than x86's
    /// 16 vector registers, and V8 spilled them (a tenth of the frame in Chromium).
    // Out of line (one call per 64 rows): each loop keeps its own registers.
    #[inline(never)]
    fn orientations(&self, y0: f32, rows: usize, records: &mut [[f32; ROW_CHUNK]; 3]) {
        let (minus_d, two_e) = (F32x4::splat(self.minus_d), F32x4::splat(self.two_e));
        let (minus_h, minus_2eh) = (F32x4::splat(self.minus_h), F32x4::splat(self.minus_2eh));
        let one = F32x4::splat(1.0);
        let quad = F32x4::from_array([0.0, 1.0, 2.0, 3.0]);
        let rows = rows.min(ROW_CHUNK).next_multiple_of(4);
        for q in (0..rows).step_by(4) {
            let y = F32x4::splat(y0 + q as f32).add(quad);
            // -slope = -d - 2 e y (theta's argument, made theta in the pass below).
            let minus_slope = minus_d.sub(two_e.mul(y));
            let [theta, slope_h, dtheta_h] = [
                minus_slope,
                minus_slope.mul(minus_h),
                minus_2eh.div(one.add(minus_slope.mul(minus_slope))),
            ];
            for (to, v) in records.iter_mut().zip([theta, slope_h, dtheta_h]) {
                let mut four = [0.0; 4];
                v.store(&mut four);
                to[q..q + 4].copy_from_slice(&four);
            }
        }
        // theta = atan(-slope) in place.
        let atan = Atan32Lanes::opaque();
        for four in records[0][..rows].chunks_exact_mut(4) {
            if let Ok(four) = <&mut [f32; 4]>::try_from(four) {
                atan.eval(F32x4::load_array(four)).store(four);
            }
        }
    }
}

/// The line of a linear sum (eqs. 5, 20) in f32: its orientation theta and log2(e) cos^2(theta)
/// / (2 var) with eq. 5's variance (the normal distance is cos(theta) times the column
/// difference in a row).
struct Line {
    theta: f32,
    position_log2: f32,
}

impl Line {
    /// The orientation and line kernels of the `used` pixels of `batch` (each with its row's
    /// line column first in its row record), four at a time, summed: per lane in f32, the four
    /// lanes then in f64 in lane order. Two passes through `exponents`, as
    /// [`PpfModel::parabolic_batch`].
    // Out of line (one call per 64 pixels): each loop keeps its own registers.
    #[inline(never)]
    fn batch(&self, batch: &Batch<1>, exponents: &mut [[F32x4; 2]; BATCH_QUADS]) -> f64 {
        let quads = batch.quads();
        {
            let theta = F32x4::splat(self.theta);
            let position = F32x4::splat(self.position_log2);
            let orientation = F32x4::splat(HALF_LOG2_E);
            let k = NegExp2Lanes::opaque();
            for (q, to) in exponents[..quads].iter_mut().enumerate() {
                let [x, weight, theta_i, precision] = batch.pixels(q);
                let [xc] = batch.rows(q);
                // K_theta G_li = exp(-(dtheta^2 |grad I| / 2 + dist^2 / (2 var))) = 2^(-y), y
                // the same exponent times log2(e).
                let dtheta = fold_x4(theta.sub(theta_i), &k);
                let dx = xc.sub(x);
                let y = dx
                    .mul(dx)
                    .mul(position)
                    .add(dtheta.mul(dtheta).mul(precision.mul(orientation)));
                *to = [y, weight];
            }
        }
        let k = NegExp2Lanes::opaque();
        let mut acc = F32x4::splat(0.0);
        for (q, &[y, weight]) in exponents[..quads].iter().enumerate() {
            let term = weight.mul(k.eval(y));
            acc = acc.add(only_used(term, batch.used - 4 * q));
        }
        lane_sum(acc)
    }
}

impl PpfModel {
    /// The parabolic kernels of one row's band `pixels` added to `sum`, one pixel at a time in
    /// order, with the quadrature rule's nodes (`node_x`, `node_theta`: the curve's column and
    /// orientation change at each node; `theta`: its orientation at the row). A pixel's kernel
    /// is computed in f32 and added to the f64 sum. (The default 3-node rule goes four pixels
    /// at a time instead: [`PpfModel::parabolic_batch`].)
    #[inline]
    fn parabolic_pixels(
        &self,
        mut sum: f64,
        pixels: &[MaskPixel],
        theta: f32,
        node_x: &[f32],
        node_theta: &[f32],
    ) -> f64 {
        let inv_2var = (0.5 / self.var_x) as f32;
        for px in pixels {
            // The orientation difference at the row, folded once: across the nodes it
            // changes by dtheta_dy * offset (below 1e-3 rad), too little to cross a fold.
            let dtheta = fold32(theta - px.theta);
            let mut g = 0.0f32;
            for (k, (&x, &t)) in node_x.iter().zip(node_theta).enumerate() {
                let dx = x - px.x;
                let dt = dtheta + t;
                let arg = dx * dx * inv_2var + 0.5 * dt * dt * px.precision;
                g += self.node_weights[k] * neg_exp(arg);
            }
            sum += f64::from(px.weight * g);
        }
        sum
    }

    /// The parabolic kernels of the `used` pixels of `batch` with the 3-node rule (nodes y - h,
    /// y, y + h; `e_h2` = e h^2), four pixels at a time in the four lanes of each operation
    /// ([`F32x4`]), each lane with its own row's curve, summed: per lane in f32, the four lanes
    /// then in f64 in lane order. Two passes through `exponents`: the nodes' exponents, then
    /// their exp (one loop of both needs more constant lanes than x86 has vector registers,
    /// and V8 spilled them).
    // Out of line (one call per 64 pixels): each loop keeps its own registers.
    #[inline(never)]
    fn parabolic_batch(
        &self,
        batch: &Batch<4>,
        e_h2: f32,
        exponents: &mut [[F32x4; 4]; BATCH_QUADS],
    ) -> f64 {
        let quads = batch.quads();
        {
            let position = F32x4::splat(self.position_log2);
            let orientation = F32x4::splat(HALF_LOG2_E);
            let e_h2 = F32x4::splat(e_h2);
            let k = NegExp2Lanes::opaque();
            for (q, to) in exponents[..quads].iter_mut().enumerate() {
                let [x, weight, theta_i, precision] = batch.pixels(q);
                // Row record: the curve's column and orientation at the row, slope h, h
                // dtheta/dy.
                let [xc, theta, slope_h, dtheta_h] = batch.rows(q);
                // The orientation difference at the row, folded once (see `parabolic_pixels`).
                let dtheta = fold_x4(theta.sub(theta_i), &k);
                let dx = xc.sub(x);
                // K'_x K'_theta at a node (eqs. 13-14) = exp(-(dx^2 / (2 sigma_x^2) + dt^2
                // |grad I| / 2)) = 2^(-y), y the same exponent times log2(e).
                let precision = precision.mul(orientation);
                let exponent =
                    |dx: F32x4, dt: F32x4| dx.mul(dx).mul(position).add(dt.mul(dt).mul(precision));
                *to = [
                    exponent(dx, dtheta),
                    exponent(dx.sub(slope_h).add(e_h2), dtheta.sub(dtheta_h)),
                    exponent(dx.add(slope_h).add(e_h2), dtheta.add(dtheta_h)),
                    weight,
                ];
            }
        }
        // The outer nodes' weight relative to the middle one's (w_-+ / w_0 = 1/4 for 3
        // nodes); the caller multiplies the sum by w_0 / sqrt(pi).
        let outer_weight = F32x4::splat(self.node_weights[0] / self.node_weights[1]);
        let k = NegExp2Lanes::opaque();
        let mut acc = F32x4::splat(0.0);
        for (q, &[middle, minus, plus, weight]) in exponents[..quads].iter().enumerate() {
            let outer = k.eval(minus).add(k.eval(plus));
            let g = k.eval(middle).add(outer_weight.mul(outer));
            acc = acc.add(only_used(weight.mul(g), batch.used - 4 * q));
        }
        lane_sum(acc)
    }
}

/// `term` with the lanes from `left` on set to 0 (`left` pixels of the batch are left from
/// this quad on; lanes past them hold stale entries).
#[inline]
fn only_used(term: F32x4, left: usize) -> F32x4 {
    if left >= 4 {
        return term;
    }
    let lane = F32x4::from_array([0.0, 1.0, 2.0, 3.0]);
    lane.lt(F32x4::splat(left as f32))
        .select(term, F32x4::splat(0.0))
}

/// The four lanes added in f64, in lane order.
#[inline]
fn lane_sum(acc: F32x4) -> f64 {
    acc.to_array().iter().map(|&v| f64::from(v)).sum()
}

/// log2(e) / 2 in f32: the orientation term dtheta^2 |grad I| / 2 of the kernels' exponent
/// in base 2 is dtheta^2 (|grad I| HALF_LOG2_E).
const HALF_LOG2_E: f32 = 0.5 * super::neg_exp::LOG2_E;

/// A difference d of two orientations in (-pi/2, pi/2] each, folded into [-pi/2, pi/2] lane
/// by lane: d - k pi with k the integer nearest d / pi (ties to even; k is -1, 0 or 1). As
/// [`fold32`] but for d within an f32 rounding of -+pi/2, where either end is as good (the
/// kernels use the square, and the nodes' orientation changes by below 1e-3 rad).
#[inline]
fn fold_x4(d: F32x4, k: &NegExp2Lanes) -> F32x4 {
    let n = d.mul(k.frac_1_pi).round_small_by(k.rounder());
    d.sub(n.mul(k.pi))
}

/// Pixels per [`Batch`] (a multiple of 4).
const BATCH: usize = 64;
/// Pixels a [`Batch`] copies from a row at once: a whole band of the default 7 columns.
const ROW_COPY: usize = 8;
/// The most quads (four pixels) a [`Batch`] holds.
const BATCH_QUADS: usize = (BATCH + ROW_COPY) / 4;

/// Band pixels of a linear or parabolic sum gathered across rows, each with its row's record
/// of `R` numbers (the curve there): a row has few (about 3 in a 7-column band), too few to
/// fill the four lanes. The batch holds the pixels' indices; a row's are written eight at a
/// time whatever their number (the entries past the band are overwritten by the next row's or
/// never read), so that the writes do not branch on it. The pixels are then read four at a
/// time and transposed into lanes; the records are kept by number (record number r of pixel
/// j at `rows[r][j]`), so that four pixels' are one load each. (Copying the pixels themselves
/// became a `memory.copy` call per row in WebAssembly.)
#[derive(Debug, Clone, Copy)]
struct Batch<'a, const R: usize> {
    all: &'a [MaskPixel],
    used: usize,
    /// Indices into `all`, each valid (entries are written only with valid indices).
    index: [u32; BATCH + ROW_COPY],
    rows: [[f32; BATCH + ROW_COPY]; R],
}

impl<'a, const R: usize> Batch<'a, R> {
    /// An empty batch of pixels of `all`.
    fn new(all: &'a [MaskPixel]) -> Self {
        Self {
            all,
            used: 0,
            index: [0; BATCH + ROW_COPY],
            rows: [[0.0; BATCH + ROW_COPY]; R],
        }
    }

    /// Adds the pixels of the first `n` rows of `spans`, row r with the record `records[.][r]`,
    /// calling `full` with the batch (then emptied) each time it fills up (a batch can end
    /// up to ROW_COPY - 1 pixels past BATCH: a row's first ROW_COPY pixels go in at once).
    #[inline]
    fn push_rows(
        &mut self,
        spans: &Spans,
        records: [&[f32; ROW_CHUNK]; R],
        n: usize,
        mut full: impl FnMut(&Self),
    ) {
        let mut used = self.used;
        for r in 0..n.min(ROW_CHUNK) {
            let (start, len) = (spans.start[r] as usize, spans.len[r] as usize);
            let k = len.min(ROW_COPY);
            self.write(used, start, k, records.map(|v| v[r]));
            used += k;
            if used >= BATCH {
                self.used = used;
                full(self);
                used = 0;
            }
            if k < len {
                self.used = used;
                self.push_rest(start + k..start + len, records.map(|v| v[r]), &mut full);
                used = self.used;
            }
        }
        self.used = used;
    }

    /// Writes the indices and records of `n <= ROW_COPY` pixels from `all[start]` at entry
    /// `j < BATCH` (eight entries, as [`Batch::push_copy`], which also counts them).
    #[inline]
    fn write(&mut self, j: usize, start: usize, n: usize, row: [f32; R]) {
        // Checked once here for the slices below.
        assert!(j < BATCH && n <= ROW_COPY);
        let index = &mut self.index[j..j + ROW_COPY];
        if start + ROW_COPY <= self.all.len() {
            for (k, to) in index.iter_mut().enumerate() {
                *to = (start + k) as u32;
            }
        } else {
            for (k, to) in index[..n].iter_mut().enumerate() {
                *to = (start + k) as u32;
            }
        }
        // The row's record in all eight entries, four per store (a plain `fill` became 32
        // scalar stores in WebAssembly).
        for (to, &v) in self.rows.iter_mut().zip(&row) {
            let (v, to) = (F32x4::splat(v), &mut to[j..j + ROW_COPY]);
            let (low, high) = to.split_at_mut(4);
            // Always both (four and four of the eight).
            if let (Ok(low), Ok(high)) = (low.try_into(), high.try_into()) {
                v.store(low);
                v.store(high);
            }
        }
    }

    /// [`Batch::push_rows`] of the pixels past a row's first ROW_COPY.
    #[cold]
    #[inline(never)]
    fn push_rest(
        &mut self,
        span: std::ops::Range<usize>,
        row: [f32; R],
        mut full: impl FnMut(&Self),
    ) {
        let mut start = span.start;
        while start < span.end {
            let n = (span.end - start).min(ROW_COPY);
            self.push_copy(start, n, row);
            start += n;
            if self.used >= BATCH {
                full(self);
                self.used = 0;
            }
        }
    }

    /// Adds the `n <= ROW_COPY` pixels from `all[start]` with the row record `row` (room:
    /// `used < BATCH` before, so that they fit).
    #[inline]
    fn push_copy(&mut self, start: usize, n: usize, row: [f32; R]) {
        self.write(self.used, start, n, row);
        self.used += n;
    }

    /// The number of quads (four pixels) to read: `used` rounded up to four (the lanes past
    /// `used` hold stale but valid entries), in quads.
    #[inline]
    fn quads(&self) -> usize {
        // At most (BATCH + ROW_COPY) / 4 (used < BATCH + ROW_COPY): said for the bounds.
        self.used.div_ceil(4).min((BATCH + ROW_COPY) / 4)
    }

    /// The pixels of quad q (pixels 4 q..4 q + 4) as lanes: column, weight, orientation,
    /// precision.
    #[inline]
    fn pixels(&self, q: usize) -> [F32x4; 4] {
        let index = &self.index[4 * q..4 * q + 4];
        F32x4::transpose([0, 1, 2, 3].map(|k| {
            let i = index[k] as usize;
            debug_assert!(i < self.all.len());
            // SAFETY: every entry of `index` is below `all.len()`: `write` writes only
            // indices of pixels of `all`, and the initial zeros are read only once a row has
            // been pushed, so when `all` is not empty.
            F32x4::load_array(unsafe { self.all.get_unchecked(i) }.as_array())
        }))
    }

    /// The row records of quad q as lanes (number r of the four in lane r).
    #[inline]
    fn rows(&self, q: usize) -> [F32x4; R] {
        std::array::from_fn(|r| F32x4::load(&self.rows[r], 4 * q))
    }
}

const PI_32: f32 = std::f32::consts::PI;
const FRAC_PI_2_32: f32 = std::f32::consts::FRAC_PI_2;

/// A difference of two orientations in (-pi/2, pi/2] each, folded into (-pi/2, pi/2].
#[inline]
fn fold32(d: f32) -> f32 {
    if d > FRAC_PI_2_32 {
        d - PI_32
    } else if d <= -FRAC_PI_2_32 {
        d + PI_32
    } else {
        d
    }
}

impl PartitionedModel<LaneParticle> for PpfModel {
    type Cues = Descriptors;

    fn stages(&self) -> usize {
        2
    }

    /// Eqs. 18-19 (stage 0: rho_k, theta_k) and 22-23 (stage 1: d_k): identity plus Gaussian
    /// noise.
    fn propagate(&self, stage: usize, p: &mut LaneParticle, rng: &mut Rng) {
        for b in p.boundaries.iter_mut().take(self.n) {
            if stage == 0 {
                b[0] += rng.gaussian(0.0, self.sigma_rho);
                b[1] = wrap_half_turn(b[1] + rng.gaussian(0.0, self.sigma_theta));
            } else {
                b[2] += rng.gaussian(0.0, self.sigma_d);
            }
        }
    }

    fn log_likelihood(&self, stage: usize, p: &LaneParticle, cues: &Descriptors) -> f64 {
        let mut l = 0.0;
        if stage == 0 {
            if !self.is_valid(p) {
                return f64::NEG_INFINITY;
            }
            let mut counts = self.counts.borrow_mut();
            let counts = counts.for_frame(cues.frame());
            for k in 0..self.n {
                // Eq. 21: prod_k n_k^l p(z_k^l | x) = prod_k S_k^l.
                let (sum, count) = self.linear_sum_count(&self.boundary(p, k), cues);
                l += math::ln(sum);
                let [rho, theta, _] = p.boundaries[k];
                counts.insert(rho.to_bits(), theta.to_bits(), count);
            }
        } else {
            let mut counts = self.counts.borrow_mut();
            let counts = counts.for_frame(cues.frame());
            for k in 0..self.n {
                let b = self.boundary(p, k);
                // Eq. 25 with A = prod_k 1 / n_k^l. A particle can reach this stage with
                // n_k^l = 0 only when the linear stage gave every particle weight 0 (its
                // weights then fell back to equal); A is undefined there and taken as 1,
                // not as an infinite weight. The count is stage 0's for the same line
                // (resampling copied it), or counted here.
                let [rho, theta, _] = p.boundaries[k];
                let n_l = counts
                    .get(rho.to_bits(), theta.to_bits())
                    .unwrap_or_else(|| self.linear_count(&b, cues))
                    .max(1);
                l += math::ln(self.parabolic_sum(&b, cues)) - math::ln(n_l as f64);
            }
        }
        if l.is_nan() {
            f64::NEG_INFINITY
        } else {
            l
        }
    }
}

/// The default lane model (Sec. IV-D): n_l straight (d = b), parallel boundaries one lane
/// width apart with a common heading, placed so that the car is inside the set, each jittered.
#[derive(Debug, Clone)]
pub struct DefaultLanes {
    n: usize,
    y_m: f64,
    width_m: [f64; 2],
    heading: f64,
    jitter_m: f64,
    view: crate::vision::TopViewConfig,
}

impl DefaultLanes {
    /// The default lane model of `config` on a top view of `height` rows.
    pub fn new(config: &LiuConfig, height: usize) -> Self {
        Self {
            n: config.boundaries,
            y_m: config.split_row(height),
            width_m: config.default_width_m,
            heading: config.default_heading_rad,
            jitter_m: config.default_jitter_m,
            view: config.top_view,
        }
    }

    /// The straight boundary at lateral position `y0` (m, left positive) at the car with
    /// heading tan = `slope`, in top-view pixels: column(r) = a + b r with b = slope.
    pub fn straight_boundary(&self, y0: f64, slope: f64) -> [f64; 3] {
        let v = &self.view;
        // y(x) = y0 + slope x; column = (y_left - y) / s - 1/2; x(r) = x_max - (r + 1/2) s.
        let s = v.m_per_px;
        let a = (v.y_left_m - y0 - slope * (v.x_max_m - 0.5 * s)) / s - 0.5;
        let b = slope;
        let m = LinearParabolic::from_line(a, b, b, self.y_m);
        [m.rho, m.theta, m.d]
    }
}

impl DefaultLanes {
    /// Default-model lanes on a detected ego pair: the lane width and heading of `ego`, its
    /// boundaries as the middle two of the n parallel ones (the left one of the middle pair
    /// for an odd n), each jittered by `default_jitter_m` (the `relock_share` proposal).
    pub fn on_ego_pair(&self, ego: &EgoOnRoad, rng: &mut Rng) -> LaneParticle {
        let w = ego.width();
        let slope = math::tan(ego.heading());
        let centre = (self.n as f64 - 1.0) / 2.0;
        // Boundary k lies at shift + (centre - k) w: the middle pair on the ego boundaries.
        let shift = if self.n % 2 == 0 {
            ego.centre()
        } else {
            ego.left.offset
        };
        let mut p = LaneParticle {
            boundaries: [[0.0; 3]; MAX_BOUNDARIES],
        };
        for k in 0..self.n {
            let y0 = shift + (centre - k as f64) * w + rng.gaussian(0.0, self.jitter_m);
            p.boundaries[k] = self.straight_boundary(y0, slope);
        }
        p
    }
}

impl InitialDistribution<LaneParticle> for DefaultLanes {
    fn sample(&self, rng: &mut Rng) -> LaneParticle {
        let [lo, hi] = self.width_m;
        let w = lo + (hi - lo) * rng.uniform();
        let shift = (rng.uniform() - 0.5) * w;
        let slope = math::tan((2.0 * rng.uniform() - 1.0) * self.heading);
        let mut p = LaneParticle {
            boundaries: [[0.0; 3]; MAX_BOUNDARIES],
        };
        let centre = (self.n as f64 - 1.0) / 2.0;
        for k in 0..self.n {
            let y0 = shift + (centre - k as f64) * w + rng.gaussian(0.0, self.jitter_m);
            p.boundaries[k] = self.straight_boundary(y0, slope);
        }
        p
    }
}
