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
//! the polynomial of [`super::neg_exp`] (within 5e-6 relative; 0 from an exponent of 32 on,
//! exp(-32) = 1.3e-14), in G_pi the curve's orientation at the quadrature nodes taken to
//! first order from the row's (the nodes are within 2 rows; the error is below 1e-6 rad), and
//! both kernels in f32: a pixel's term (rounding 6e-8 each, the f32 column differences 1e-5
//! at most) is added into one of four f32 partial sums over up to 64 pixels (rounding below
//! 1e-6 relative), which go into the f64 sum. The pixels of both sums are gathered across
//! rows and run four per operation ([`super::lanes`]: SSE2 natively, `simd128` in
//! WebAssembly), with the same bits on every target.

//! Validity (Sec. IV-A, in metres): at the bottom row and at y_m, each boundary lies at least
//! `min_spacing_m` to the right of its left neighbour, and neighbouring spacings differ by less
//! than `max_spacing_difference_m`; other particles get weight 0 in stage 0.

use super::config::{LiuConfig, MAX_BOUNDARIES};
use super::descriptors::{wrap_half_turn, Descriptors, MaskPixel};
use super::kernels::GaussHermite;
use super::lanes::F32x4;
use super::neg_exp::{neg_exp, neg_exp_x4};
use crate::calib::ego_on_road::EgoOnRoad;
use crate::filter::{InitialDistribution, PartitionedModel, Rng};
use crate::lane::LinearParabolic;
use crate::math;
use std::cell::RefCell;
use std::f64::consts::PI;
use std::ops::{Add, Mul, Sub};

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
    /// w_k / sqrt(pi) of the Gauss-Hermite rule (f32: the parabolic sums run in f32).
    node_weights: Vec<f32>,
    /// sqrt(2 sigma_y^2) t_k.
    node_offsets: Vec<f64>,
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
            node_weights,
            node_offsets,
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

    /// Columns of the band around x in a row, clipped to the view.
    fn band(&self, x: f64) -> Option<std::ops::RangeInclusive<usize>> {
        self.band_around(band_centre(x)?)
    }

    /// Columns of the band around column `centre` ([`band_centre`]), clipped to the view.
    #[inline]
    fn band_around(&self, centre: i64) -> Option<std::ops::RangeInclusive<usize>> {
        let lo = (centre - self.band as i64).max(0);
        let hi = (centre + self.band as i64).min(self.width as i64 - 1);
        (lo <= hi).then_some(lo as usize..=hi as usize)
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
    /// over the near rows. (The count's rows are those of `linear_count`, whose line has the
    /// slope -tan(theta) where the sum's has -sin / cos: the two round to the same band centre
    /// in nearly every row, and where they do not the count takes its own band.)
    pub fn linear_sum_count(&self, b: &LinearParabolic, cues: &Descriptors) -> (f64, usize) {
        let (s, c) = (math::sin(b.theta), math::cos(b.theta));
        let (a, slope) = (b.rho / c, -s / c);
        // As `linear_count`'s b.a(), b.b(); the same line when the slopes have the same bits.
        let slope_n = b.b();
        let same_line = slope_n == slope;
        let mut count = 0;
        // Eq. 5's variance of the distance along the normal.
        let var = self.var_x * c * c + self.var_y * s * s;
        let line = Line {
            theta: b.theta as f32,
            cos: c as f32,
            inv_2var: (0.5 / var) as f32,
        };
        let mut sum = 0.0;
        let mut batch = Batch::<1>::new(&cues.pixels);
        for y in self.near_rows() {
            let xc = a + slope * y as f64;
            let centre = band_centre(xc);
            // Whether the count's line has the band centre of the sum's in this row (checked
            // without a second conversion; `false` only costs the count its own band).
            let same_band = same_line || {
                let xn = a + slope_n * y as f64;
                let same = centre.is_some_and(|c| rounds_to(xn, c));
                if !same {
                    if let Some(cols) = band_centre(xn).and_then(|x| self.band_around(x)) {
                        count += cues.span(y, *cols.start(), *cols.end()).len();
                    }
                }
                same
            };
            let Some(cols) = centre.and_then(|x| self.band_around(x)) else {
                continue;
            };
            let span = cues.span(y, *cols.start(), *cols.end());
            if same_band {
                count += span.len();
            }
            if !self.kernel {
                sum += cues.weight_of(span);
                continue;
            }
            batch.push_row(span, [xc as f32], |b| {
                sum += line.batch(b);
            });
        }
        if batch.used > 0 {
            sum += line.batch(&batch);
        }
        if self.kernel {
            sum /= (2.0 * PI * var).sqrt();
        }
        (sum, count)
    }

    /// Mask pixels near boundary `b` in the near rows (n_k^l), without the kernels.
    pub fn linear_count(&self, b: &LinearParabolic, cues: &Descriptors) -> usize {
        let (a, slope) = (b.a(), b.b());
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
        let mut sum = 0.0;
        let nodes = self.node_offsets.len();
        let mut node_x = [0.0f32; 20];
        let mut node_theta = [0.0f32; 20];
        // The default 3-node rule (nodes y - h, y, y + h) four pixels at a time; other rules
        // one at a time.
        let lanes = self.kernel && nodes == 3;
        let h = self.node_offsets[nodes - 1];
        let mut batch = Batch::<4>::new(&cues.pixels);
        for y in self.far_rows() {
            let yf = y as f64;
            let xc = c + d * yf + e * yf * yf;
            let Some(cols) = self.band(xc) else { continue };
            let span = cues.span(y, *cols.start(), *cols.end());
            if span.is_empty() {
                continue;
            }
            if !self.kernel {
                sum += cues.weight_of(span);
                continue;
            }
            // The curve and its gradient orientation (eq. 7) at the row's nodes y_k: the
            // orientation by atan (f32) at y and its first-order change across the nodes
            // (|dtheta/dy| = 2|e| / (1 + slope^2) over +-2 rows: below 1e-6 rad off).
            let slope = d + 2.0 * e * yf;
            // In f32, as the kernels use it (within an f32 rounding of the f64 atan's).
            let theta = math::atanf(-slope as f32);
            let dtheta_dy = -2.0 * e / (1.0 + slope * slope);
            if lanes {
                // The default 3-node rule: the pixels are batched across rows and go four at
                // a time, each with its row's curve: at the nodes y -+ h the column is
                // xc -+ slope h + e h^2 and the orientation theta -+ h dtheta/dy.
                let row = [xc as f32, theta, (slope * h) as f32, (dtheta_dy * h) as f32];
                let e_h2 = (e * h * h) as f32;
                batch.push_row(span, row, |b| {
                    sum += self.parabolic_batch(b, e_h2);
                });
                continue;
            }
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
        if batch.used > 0 {
            sum += self.parabolic_batch(&batch, (e * h * h) as f32);
        }
        if self.kernel {
            sum /= (2.0 * PI * self.var_x).sqrt();
        }
        sum
    }
}

/// The line of a linear sum (eqs. 5, 20): its orientation theta, cos(theta) and
/// 1 / (2 var) with eq. 5's variance, in f32.
struct Line {
    theta: f32,
    cos: f32,
    inv_2var: f32,
}

impl Line {
    /// The orientation and line kernels of the `used` pixels of `batch` (each with its row's
    /// line column first in its row record), four at a time, summed: per lane in f32, the four
    /// lanes then in f64 in lane order.
    fn batch(&self, batch: &Batch<1>) -> f64 {
        let (theta, cos) = (F32x4::splat(self.theta), F32x4::splat(self.cos));
        let inv_2var = F32x4::splat(self.inv_2var);
        let half = F32x4::splat(0.5);
        let mut acc = F32x4::splat(0.0);
        for j in (0..batch.used).step_by(4) {
            let [x, weight, theta_i, precision] = batch.pixels(j);
            let [xc] = batch.rows(j);
            let dtheta = fold_x4(theta.sub(theta_i));
            let orientation = half.mul(dtheta).mul(dtheta).mul(precision);
            let dist = cos.mul(xc.sub(x));
            let arg = dist.mul(dist).mul(inv_2var).add(orientation);
            let term = weight.mul(neg_exp_x4(arg));
            acc = acc.add(only_used(term, batch.used - j));
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
    /// then in f64 in lane order.
    fn parabolic_batch(&self, batch: &Batch<4>, e_h2: f32) -> f64 {
        let inv_2var = F32x4::splat((0.5 / self.var_x) as f32);
        let half = F32x4::splat(0.5);
        let e_h2 = F32x4::splat(e_h2);
        let [w_minus, w_0, w_plus] = [0, 1, 2].map(|k| F32x4::splat(self.node_weights[k]));
        let mut acc = F32x4::splat(0.0);
        for j in (0..batch.used).step_by(4) {
            let [x, weight, theta_i, precision] = batch.pixels(j);
            // Row record: the curve's column and orientation at the row, slope h, h dtheta/dy.
            let [xc, theta, slope_h, dtheta_h] = batch.rows(j);
            // The orientation difference at the row, folded once (see `parabolic_pixels`).
            let dtheta = fold_x4(theta.sub(theta_i));
            let dx = xc.sub(x);
            let node = |dx: F32x4, dt: F32x4| {
                let arg = dx
                    .mul(dx)
                    .mul(inv_2var)
                    .add(half.mul(dt).mul(dt).mul(precision));
                neg_exp_x4(arg)
            };
            let g = w_minus
                .mul(node(dx.sub(slope_h).add(e_h2), dtheta.sub(dtheta_h)))
                .add(w_0.mul(node(dx, dtheta)))
                .add(w_plus.mul(node(dx.add(slope_h).add(e_h2), dtheta.add(dtheta_h))));
            acc = acc.add(only_used(weight.mul(g), batch.used - j));
        }
        lane_sum(acc)
    }
}

/// The column a band is centred on: x rounded half away from zero (as f64::round) by
/// saturating casts, without the libm call; `None` for NaN and infinities.
#[inline]
fn band_centre(x: f64) -> Option<i64> {
    if !x.is_finite() {
        return None;
    }
    Some(if x >= 0.0 {
        (x + 0.5) as i64
    } else {
        (x - 0.5) as i64
    })
}

/// Whether [`band_centre`] of x is `centre`, by comparisons alone (no conversion: WebAssembly
/// engines emulate the saturating one in several instructions). Never true when it is not;
/// false also for a `centre` beyond 2^53, where the comparisons cannot tell.
#[inline]
fn rounds_to(x: f64, centre: i64) -> bool {
    let c = centre as f64;
    if x >= 0.0 {
        let t = x + 0.5;
        c <= t && t < c + 1.0
    } else if x < 0.0 {
        let t = x - 0.5;
        c - 1.0 < t && t <= c
    } else {
        false
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

/// [`fold32`] lane by lane (its branches as lane selects).
#[inline]
fn fold_x4(d: F32x4) -> F32x4 {
    let (half_pi, pi) = (F32x4::splat(FRAC_PI_2_32), F32x4::splat(PI_32));
    d.gt(half_pi).select(
        d.sub(pi),
        d.le(F32x4::splat(-FRAC_PI_2_32)).select(d.add(pi), d),
    )
}

/// Pixels per [`Batch`] (a multiple of 4).
const BATCH: usize = 64;
/// Pixels a [`Batch`] copies from a row at once: a whole band of the default 7 columns.
const ROW_COPY: usize = 8;

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

    /// Adds the pixels `all[span]` of one row with the row's record `row`, calling `full` with
    /// the batch (then emptied) each time it fills up.
    #[inline]
    fn push_row(
        &mut self,
        span: std::ops::Range<usize>,
        row: [f32; R],
        mut full: impl FnMut(&Self),
    ) {
        let mut start = span.start;
        loop {
            let n = (span.end - start).min(ROW_COPY);
            let j = self.used;
            // Room: used < BATCH before every write.
            if start + ROW_COPY <= self.all.len() {
                for k in 0..ROW_COPY {
                    self.index[j + k] = (start + k) as u32;
                }
            } else {
                for k in 0..n {
                    self.index[j + k] = (start + k) as u32;
                }
            }
            for (to, &v) in self.rows.iter_mut().zip(&row) {
                to[j..j + ROW_COPY].fill(v);
            }
            self.used = j + n;
            start += n;
            if self.used >= BATCH {
                full(self);
                self.used = 0;
            }
            if start == span.end {
                break;
            }
        }
    }

    /// The pixels j..j + 4 as lanes: column, weight, orientation, precision.
    #[inline]
    fn pixels(&self, j: usize) -> [F32x4; 4] {
        let index = &self.index[j..j + 4];
        F32x4::transpose(
            [0, 1, 2, 3].map(|k| F32x4::load_array(self.all[index[k] as usize].as_array())),
        )
    }

    /// The row records of pixels j..j + 4 as lanes (number r of the four in lane r).
    #[inline]
    fn rows(&self, j: usize) -> [F32x4; R] {
        std::array::from_fn(|r| F32x4::load(&self.rows[r], j))
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounds_to_agrees_with_band_centre() {
        let mut xs = vec![0.0, -0.0, 0.5, -0.5, 1.5, -1.5, 2.5, 1e300, -1e300, 9.3e18];
        for k in -400..400 {
            let x = f64::from(k) * 0.25;
            // x and its neighbouring floats.
            let bits = x.to_bits();
            xs.push(x);
            if x != 0.0 {
                xs.extend([f64::from_bits(bits + 1), f64::from_bits(bits - 1)]);
            }
        }
        for x in xs {
            let centre = band_centre(x).unwrap();
            for c in [centre.saturating_sub(1), centre, centre.saturating_add(1)] {
                if rounds_to(x, c) {
                    assert_eq!(c, centre, "{x}");
                }
            }
            if centre.unsigned_abs() < 1 << 52 {
                assert!(rounds_to(x, centre), "{x}");
            }
        }
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(band_centre(x), None);
            assert!(!rounds_to(x, 0) && !rounds_to(x, i64::MAX));
        }
    }
}
