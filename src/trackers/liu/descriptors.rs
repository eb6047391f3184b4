//! Pre-processing and local image descriptors (Liu Secs. II and IV-C).
//!
//! Per frame: grey levels -> IPM top view (bilinear, where the paper shows a cubic
//! interpolation, Fig. 1; a simplification) -> Sobel gradient (magnitude |grad I| and
//! orientation) -> the measurement mask |grad I| > threshold (10 in the paper) on pixels whose
//! 3 x 3 neighbourhood lies inside the camera's view (the IPM's fill value would otherwise make
//! an edge along the border of the visible area). For every mask pixel i the descriptors are:
//!
//! - its position (x_i, y_i) (column, row of the top view);
//! - the gradient orientation theta_i, taken modulo pi in (-pi/2, pi/2]: the two edges of a
//!   bright marking have opposite gradients and both belong to the boundary;
//! - the orientation's variance sigma_theta_i^2 = 1 / |grad I|_i (Sec. II), stored as its
//!   inverse, the precision;
//! - the intensity kernel K_ci = N(I_i / 255; mu_c, sigma_c^2) of the normalised grey level.
//!
//! `weight` holds what multiplies a pixel's position and orientation kernels in the sums of
//! eqs. 20 and 24: K_ci sqrt(|grad I|_i / 2 pi), the intensity kernel times the orientation
//! kernel's normaliser 1 / sqrt(2 pi sigma_theta_i^2). PPF-NoKernel (eqs. 26-27) uses K_ci alone.
//! Pixels outside the mask have weight 0.

use crate::camera::Camera;
use crate::error::Result;
use crate::image::{rgba_to_gray_rows, Image};
use crate::math;
use crate::vision::{Gradients, Ipm, TopViewConfig};
use std::f64::consts::PI;

impl MaskPixel {
    /// The four fields in their order (column, weight, orientation, precision) as one array.
    #[inline]
    pub fn as_array(&self) -> &[f32; 4] {
        // SAFETY: `MaskPixel` is `repr(C)` with four f32 fields and no padding, so it has the
        // size, alignment and layout of `[f32; 4]`.
        unsafe { &*(self as *const Self).cast::<[f32; 4]>() }
    }
}

/// The descriptors of one frame on the top view, reused from frame to frame.
#[derive(Debug, Clone)]
pub struct Descriptors {
    ipm: Ipm,
    inner: Image<u8>,
    grey: Image<u8>,
    top: Image<u8>,
    gradients: Gradients,
    threshold: f32,
    intensity_mean: f64,
    intensity_variance: f64,
    kernel: bool,
    /// Kernel-variant weight K_c sqrt(|grad I| / 2 pi) (or K_c for PPF-NoKernel), 0 off the
    /// mask; row-major, top-view width per row.
    pub weight: Vec<f32>,
    /// The mask pixels in row-major order (compact): column, weight, orientation, precision.
    pub pixels: Vec<MaskPixel>,
    /// before[y (W + 1) + x]: mask pixels before column x of row y in row-major order, so the
    /// mask pixels of row y in columns lo..=hi are `pixels[before(y, lo)..before(y, hi + 1)]`.
    before: Vec<u32>,
    /// Running sum of the weights over `pixels` (index j: the first j pixels).
    weight_sum: Vec<f64>,
    /// The id of the last frame computed (unique across all descriptors; 0 before the first).
    frame: u64,
}

/// The next frame id of [`Descriptors::frame`].
static NEXT_FRAME: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

/// One measurement pixel (four f32 in this order, so that the kernel sums load it as one
/// vector of four lanes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C)]
pub struct MaskPixel {
    /// Column x_i.
    pub x: f32,
    /// Weight (see [`Descriptors::weight`]).
    pub weight: f32,
    /// Orientation theta_i modulo pi.
    pub theta: f32,
    /// Precision |grad I|.
    pub precision: f32,
}

impl Descriptors {
    /// Buffers for `camera`'s frames and the top view `config`; `kernel` selects PPF-Kernel's
    /// weights (otherwise PPF-NoKernel's).
    ///
    /// # Errors
    /// As [`Ipm::new`].
    pub fn new(
        camera: &Camera,
        config: TopViewConfig,
        threshold: f64,
        intensity: (f64, f64),
        kernel: bool,
    ) -> Result<Self> {
        let ipm = Ipm::new(camera, config)?;
        let (w, h) = (ipm.width(), ipm.height());
        let valid = ipm.valid();
        let mut inner = Image::new(w, h)?;
        for y in 0..h {
            for x in 0..w {
                let all = (y.saturating_sub(1)..(y + 2).min(h))
                    .all(|v| (x.saturating_sub(1)..(x + 2).min(w)).all(|u| valid.get(u, v) == 1));
                // Border pixels of the view have a replicated (flat) neighbourhood: keep them
                // out as well.
                let border = x == 0 || y == 0 || x + 1 == w || y + 1 == h;
                inner.set(x, y, u8::from(all && !border));
            }
        }
        Ok(Self {
            inner,
            grey: Image::new(camera.width(), camera.height())?,
            top: Image::new(w, h)?,
            gradients: Gradients::new(w, h)?,
            threshold: threshold as f32,
            intensity_mean: intensity.0,
            intensity_variance: intensity.1,
            kernel,
            weight: vec![0.0; w * h],
            pixels: Vec::with_capacity(w * h),
            before: vec![0; (w + 1) * h],
            weight_sum: Vec::with_capacity(w * h + 1),
            frame: 0,
            ipm,
        })
    }

    /// The IPM.
    pub fn ipm(&self) -> &Ipm {
        &self.ipm
    }
    /// Top-view width, pixels.
    pub fn width(&self) -> usize {
        self.ipm.width()
    }
    /// Top-view height, pixels.
    pub fn height(&self) -> usize {
        self.ipm.height()
    }
    /// The last frame's top view.
    pub fn top_view(&self) -> &Image<u8> {
        &self.top
    }

    /// Computes the descriptors of an RGBA frame of the camera's size.
    ///
    /// # Errors
    /// [`crate::Error::BufferSize`] / [`crate::Error::Dimensions`] for a wrong frame.
    pub fn compute(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<()> {
        // A new id before anything changes, so that no cache keeps the last frame's values.
        self.frame = NEXT_FRAME.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        // Grey only where the IPM reads (the road's rows; the rest of the frame is never used).
        rgba_to_gray_rows(rgba, width, height, self.ipm.source_rows(), &mut self.grey)?;
        self.ipm.apply(&self.grey.view(), 0, &mut self.top)?;
        self.gradients.compute(&self.top.view())?;
        let norm = 1.0 / (2.0 * PI * self.intensity_variance).sqrt();
        // K_c for each grey level.
        let mut kc = [0.0f64; 256];
        for (g, k) in kc.iter_mut().enumerate() {
            let z = g as f64 / 255.0 - self.intensity_mean;
            *k = norm * math::exp(-z * z / (2.0 * self.intensity_variance));
        }
        let (w, h) = (self.width(), self.height());
        let (gx, gy) = (self.gradients.gx.data(), self.gradients.gy.data());
        let magnitude = self.gradients.magnitude.data();
        self.pixels.clear();
        self.weight_sum.clear();
        self.weight_sum.push(0.0);
        let mut total = 0.0;
        for y in 0..h {
            for x in 0..w {
                let i = y * w + x;
                self.before[y * (w + 1) + x] = self.pixels.len() as u32;
                let m = magnitude[i];
                if self.inner.data()[i] == 0 || m <= self.threshold {
                    self.weight[i] = 0.0;
                    continue;
                }
                let k = kc[self.top.data()[i] as usize];
                let weight = if self.kernel {
                    (k * (f64::from(m) / (2.0 * PI)).sqrt()) as f32
                } else {
                    k as f32
                };
                let theta = orientation_mod_pi(gy[i], gx[i]);
                self.weight[i] = weight;
                self.pixels.push(MaskPixel {
                    x: x as f32,
                    weight,
                    theta,
                    precision: m,
                });
                total += f64::from(weight);
                self.weight_sum.push(total);
            }
            self.before[y * (w + 1) + w] = self.pixels.len() as u32;
        }
        Ok(())
    }
}

impl Descriptors {
    /// The id of the last frame computed: unique across all descriptors of the process, so
    /// that values cached for one frame's pixels are never read for another's (0 before the
    /// first frame).
    pub fn frame(&self) -> u64 {
        self.frame
    }

    /// Mask pixels in the last frame.
    pub fn count(&self) -> usize {
        self.pixels.len()
    }

    /// Indices into [`Descriptors::pixels`] of row y's mask pixels in columns lo..=hi.
    pub fn span(&self, y: usize, lo: usize, hi: usize) -> std::ops::Range<usize> {
        let base = y * (self.width() + 1);
        self.before[base + lo] as usize..self.before[base + hi + 1] as usize
    }

    /// Row y's counts of [`Descriptors::span`]: entry x is the number of mask pixels before
    /// column x of row y in row-major order (W + 1 entries), so that the mask pixels of row y
    /// in columns lo..=hi are `row[lo]..row[hi + 1]`.
    #[inline]
    pub fn row_before(&self, y: usize) -> &[u32] {
        let w = self.width() + 1;
        &self.before[y * w..(y + 1) * w]
    }

    /// [`Descriptors::row_before`] of the rows `rows`, in order.
    #[inline]
    pub fn rows_before(&self, rows: std::ops::Range<usize>) -> std::slice::ChunksExact<'_, u32> {
        let w = self.width() + 1;
        self.before[rows.start * w..rows.end * w].chunks_exact(w)
    }

    /// The sum of the weights of the pixels `span`.
    pub fn weight_of(&self, span: std::ops::Range<usize>) -> f64 {
        self.weight_sum[span.end] - self.weight_sum[span.start]
    }
}

/// atan2(gy, gx) folded into (-pi/2, pi/2]: atan(gy / gx) folded, the same orientation
/// (gx = 0: +-pi/2, one orientation; 0 for a zero gradient), by the polynomial
/// [`super::atan32::atan32`] (an approximation within 2e-7 rad of atan).
pub fn orientation_mod_pi(gy: f32, gx: f32) -> f32 {
    if gx == 0.0 && gy == 0.0 {
        return 0.0;
    }
    let t = f64::from(super::atan32::atan32(gy / gx));
    wrap_half_turn(t) as f32
}

/// An angle folded into (-pi/2, pi/2] (orientations modulo pi), in constant time for any
/// angle (NaN and infinities give NaN). The remainder `t % pi` is exact, so an angle within a
/// few turns gives the same bits as subtracting pi step by step.
pub fn wrap_half_turn(t: f64) -> f64 {
    // `t % PI` is t itself for |t| < pi: skip the fmod call (the same bits; NaN and
    // infinities take the remainder).
    let t = if t.abs() < PI { t } else { t % PI };
    if t > PI / 2.0 {
        t - PI
    } else if t <= -PI / 2.0 {
        t + PI
    } else {
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientations_fold_onto_a_half_turn() {
        assert!((wrap_half_turn(PI) - 0.0).abs() < 1e-12);
        assert!((wrap_half_turn(-PI / 2.0) - PI / 2.0).abs() < 1e-12);
        assert!((wrap_half_turn(3.0) - (3.0 - PI)).abs() < 1e-12);
        assert!((orientation_mod_pi(0.0, -5.0)).abs() < 1e-6);
        assert!((f64::from(orientation_mod_pi(1.0, 1.0)) - PI / 4.0).abs() < 1e-6);
        // atan2 folded, within the polynomial's 2e-7 rad (and the f32 rounding), all round.
        for k in 0..3600 {
            let a = f64::from(k) * PI / 1800.0;
            let (gy, gx) = ((100.0 * math::sin(a)) as f32, (100.0 * math::cos(a)) as f32);
            let exact = wrap_half_turn(math::atan2(f64::from(gy), f64::from(gx)));
            let d = wrap_half_turn(f64::from(orientation_mod_pi(gy, gx)) - exact);
            assert!(d.abs() < 4e-7, "{a}: {d}");
        }
        assert_eq!(orientation_mod_pi(0.0, 0.0), 0.0);
        // Huge angles return at once (a loop of pi steps never ended at 1e17).
        for t in [1e9, -1e17, 1e300, f64::MAX, -f64::MAX] {
            let w = wrap_half_turn(t);
            assert!(w > -PI / 2.0 && w <= PI / 2.0, "{t}: {w}");
        }
        assert!(wrap_half_turn(f64::INFINITY).is_nan() && wrap_half_turn(f64::NAN).is_nan());
        // The same bits as the step-by-step fold within a few turns.
        for k in -4000..4000 {
            let t = f64::from(k) * 0.0031;
            let mut s = t;
            while s > PI / 2.0 {
                s -= PI;
            }
            while s <= -PI / 2.0 {
                s += PI;
            }
            assert_eq!(wrap_half_turn(t).to_bits(), s.to_bits(), "{t}");
        }
    }
}
