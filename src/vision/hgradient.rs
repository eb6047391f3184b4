//! The horizontal gradient with a variable-width kernel (Danescu & Nedevschi 2011, Sec. VI-A c,
//! after their ref. \[9\]).
//!
//! Each row v has its own kernel half-width k(v): half the width in pixels of a lane marking
//! of `marking_width_m` on the flat road at that row's distance, between 1 and
//! `max_half_width`.
//! The gradient is the difference of the means of the k pixels right and left of a pixel,
//!
//! ```text
//! g(u, v)  = 1/k sum_{j=1..k} I(u + j, v) - 1/k sum_{j=1..k} I(u - j, v)
//! HG(u, v) = clamp(128 + gain g(u, v), 0, 255)
//! ```
//!
//! so near rows, where a marking is many pixels wide, average the asphalt texture away while
//! far rows keep a one-pixel kernel and their detail. A dark-to-light transition (the left side
//! of a marking) is above 128, a light-to-dark one below, 128 is flat (the paper's "centred in
//! 128", eqs. 9-10). The response falls off linearly over k pixels on both sides of an edge,
//! the continuous transitions the paper weighs particles on without a distance transform. Its
//! extremes are centred on the edge as long as the kernel fits inside the marking (k <= M - 1
//! for a marking M pixels wide): hence half the marking's width. A kernel as wide as the
//! marking would put each extreme half a pixel outside it and widen every marking by a pixel. Pixels closer than k to the left or right
//! border, and rows at or above the horizon, are 128. Means come from a prefix sum per row, so
//! the cost does not depend on k.

use crate::camera::Camera;
use crate::error::{require_positive, Error, Result};
use crate::image::{Image, ImageView};
use serde::{Deserialize, Serialize};

/// Danescu's variable-width horizontal gradient: the kernel follows a marking's width.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct HGradientConfig {
    /// Width on the road the kernel half-width follows, metres.
    pub marking_width_m: f64,
    /// Largest half-width k, pixels.
    pub max_half_width: usize,
    /// Gain from grey levels to HG units (a step of 128 / gain grey levels saturates).
    pub gain: f32,
}

impl Default for HGradientConfig {
    fn default() -> Self {
        Self {
            marking_width_m: 0.15,
            max_half_width: 12,
            gain: 2.0,
        }
    }
}

/// The variable-width gradient executor: per-row half-widths fixed by the camera at
/// construction, the output reused between frames.
#[derive(Debug, Clone)]
pub struct HGradient {
    config: HGradientConfig,
    half_width: Vec<usize>,
    prefix: Vec<u32>,
    out: Image<u8>,
    difference: Image<f32>,
}

impl HGradient {
    /// The executor for `camera`'s frames.
    ///
    /// # Errors
    /// [`Error::Parameter`] for a non-positive or NaN width or gain, or a half-width of 0 or
    /// above 256.
    pub fn new(camera: &Camera, config: HGradientConfig) -> Result<Self> {
        require_positive("marking_width_m", config.marking_width_m)?;
        require_positive("gain", config.gain as f64)?;
        if config.max_half_width == 0 || config.max_half_width > 256 {
            return Err(Error::parameter(
                "max_half_width",
                config.max_half_width,
                "must be between 1 and 256 pixels",
            ));
        }
        let (w, h) = (camera.width(), camera.height());
        let cx = camera.principal_point()[0];
        let fx = camera.focal()[0];
        let half_width = (0..h)
            .map(|v| match camera.pixel_to_road(cx, v as f64) {
                // Width in pixels of the marking at this row's distance x (the camera's height
                // above the point projects along the optical axis at roughly x).
                Ok([x, _]) if x > 0.0 => {
                    let px = fx * config.marking_width_m / x;
                    ((px / 2.0).round() as usize).clamp(1, config.max_half_width)
                }
                _ => 0,
            })
            .collect();
        Ok(Self {
            config,
            half_width,
            prefix: vec![0; w + 1],
            out: Image::new(w, h)?,
            difference: Image::new(w, h)?,
        })
    }

    /// The half-width k(v) of each row (0 above the horizon: not computed).
    pub fn half_widths(&self) -> &[usize] {
        &self.half_width
    }

    /// HG of the last frame.
    pub fn image(&self) -> &Image<u8> {
        &self.out
    }

    /// The unscaled difference g(u, v) of the last frame, grey levels (0 where HG is not
    /// computed).
    pub fn difference(&self) -> &Image<f32> {
        &self.difference
    }

    /// Computes HG of the grey image `src`.
    ///
    /// # Errors
    /// [`Error::Dimensions`] when `src` is not the camera's size.
    pub fn apply(&mut self, src: &ImageView<'_, u8>) -> Result<()> {
        let (w, h) = (self.out.width(), self.out.height());
        if (src.width(), src.height()) != (w, h) {
            return Err(Error::Dimensions(format!(
                "the horizontal gradient was built for {w}x{h} images but got {}x{}",
                src.width(),
                src.height()
            )));
        }
        let gain = self.config.gain;
        for v in 0..h {
            let k = self.half_width[v];
            let row = src.row(v);
            let out = self.out.row_mut(v);
            out.fill(128);
            let diff = self.difference.row_mut(v);
            diff.fill(0.0);
            if k == 0 || w < 2 * k + 1 {
                continue;
            }
            self.prefix[0] = 0;
            for (u, &p) in row.iter().enumerate() {
                self.prefix[u + 1] = self.prefix[u] + p as u32;
            }
            let inv = 1.0 / k as f32;
            for u in k..w - k {
                // Right mean over u+1..=u+k, left mean over u-k..=u-1.
                let right = self.prefix[u + k + 1] - self.prefix[u + 1];
                let left = self.prefix[u] - self.prefix[u - k];
                let g = (right as f32 - left as f32) * inv;
                diff[u] = g;
                out[u] = (128.0 + gain * g).clamp(0.0, 255.0) as u8;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::default_camera;

    #[test]
    fn kernels_shrink_with_distance_and_a_marking_shows_as_a_plus_minus_pair() {
        let camera = default_camera(640, 480).unwrap();
        let mut hg = HGradient::new(&camera, HGradientConfig::default()).unwrap();
        let k = hg.half_widths().to_vec();
        let horizon = camera.horizon_row(320.0).unwrap() as usize;
        assert!(k[..horizon].iter().all(|&k| k == 0));
        assert!(k[horizon + 2..].windows(2).all(|p| p[0] <= p[1]));
        assert!(k[479] > 3 && k[horizon + 2] == 1, "{:?}", &k[470..]);
        // A bright 10-pixel marking (u in 300..310) on grey asphalt in every row.
        let mut img = Image::<u8>::new(640, 480).unwrap();
        img.fill(80);
        for v in 0..480 {
            for u in 300..310 {
                img.set(u, v, 200);
            }
        }
        hg.apply(&img.view()).unwrap();
        let out = hg.image();
        for v in [horizon + 5, 400, 479] {
            let row = out.row(v);
            let kk = k[v];
            // Saturated dark-to-light response just left of the marking, light-to-dark just
            // right of it; the responses reach exactly k pixels out.
            assert_eq!((row[299], row[310]), (255, 0), "row {v} k {kk}");
            assert!(
                row[300 - kk] > 128 && row[299 - kk] == 128,
                "row {v} k {kk}"
            );
            assert!(
                row[309 + kk] < 128 && row[310 + kk] == 128,
                "row {v} k {kk}"
            );
            // Flat far from the marking.
            assert_eq!(row[100], 128);
            assert_eq!(row[500], 128);
        }
        // Above the horizon nothing is computed.
        assert!(out.row(horizon - 1).iter().all(|&p| p == 128));
    }

    #[test]
    fn the_response_follows_the_definition() {
        let camera = default_camera(64, 48).unwrap();
        let mut hg = HGradient::new(&camera, HGradientConfig::default()).unwrap();
        let mut img = Image::<u8>::new(64, 48).unwrap();
        for v in 0..48 {
            for u in 0..64 {
                img.set(u, v, ((u * 7 + v * 3) % 50) as u8);
            }
        }
        hg.apply(&img.view()).unwrap();
        let v = 47;
        let k = hg.half_widths()[v];
        assert!(k >= 1);
        for u in k..64 - k {
            let r: f32 = (1..=k).map(|j| img.get(u + j, v) as f32).sum::<f32>() / k as f32;
            let l: f32 = (1..=k).map(|j| img.get(u - j, v) as f32).sum::<f32>() / k as f32;
            let want = (128.0 + 2.0 * (r - l)).clamp(0.0, 255.0);
            assert!((hg.image().get(u, v) as f32 - want).abs() <= 1.0, "u {u}");
            assert!((hg.difference().get(u, v) - (r - l)).abs() < 1e-3, "u {u}");
        }
    }

    #[test]
    fn bad_input_is_refused() {
        let camera = default_camera(64, 48).unwrap();
        let bad = |c: HGradientConfig| HGradient::new(&camera, c).unwrap_err().to_string();
        let d = HGradientConfig::default();
        assert!(bad(HGradientConfig {
            gain: f32::NAN,
            ..d
        })
        .contains("gain"));
        assert!(bad(HGradientConfig {
            max_half_width: 0,
            ..d
        })
        .contains("max_half_width"));
        assert!(bad(HGradientConfig {
            marking_width_m: -1.0,
            ..d
        })
        .contains("marking_width_m"));
        let mut hg = HGradient::new(&camera, d).unwrap();
        let img = Image::<u8>::new(32, 48).unwrap();
        assert!(hg.apply(&img.view()).is_err());
    }
}
