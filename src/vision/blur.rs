//! Separable Gaussian smoothing.
//!
//! G_sigma(k) = exp(-k^2 / (2 sigma^2)) / sum_j exp(-j^2 / (2 sigma^2)) for |k| <= ceil(3 sigma),
//! applied along rows then columns, with the border replicated. Used by [`super::Canny`].

use crate::error::{require_positive, Error, Result};
use crate::image::{Image, ImageView};
use crate::math;
use crate::num_text::Num;

/// Largest accepted sigma, pixels.
pub const MAX_SIGMA: f64 = 50.0;

/// A Gaussian blur with its kernel and scratch row buffer.
#[derive(Debug, Clone)]
pub struct GaussianBlur {
    kernel: Vec<f32>,
    tmp: Image<f32>,
    /// One source row as f32.
    line: Vec<f32>,
}

impl GaussianBlur {
    /// A blur of standard deviation `sigma` pixels.
    ///
    /// # Errors
    /// [`Error::Parameter`] unless 0 < sigma <= [`MAX_SIGMA`].
    pub fn new(sigma: f64) -> Result<Self> {
        require_positive("sigma", sigma)?;
        if sigma > MAX_SIGMA {
            return Err(Error::parameter(
                "sigma",
                Num(sigma),
                "must be at most 50 pixels",
            ));
        }
        let radius = (3.0 * sigma).ceil() as i64;
        let raw: Vec<f64> = (-radius..=radius)
            .map(|k| math::exp(-((k * k) as f64) / (2.0 * sigma * sigma)))
            .collect();
        let sum: f64 = raw.iter().sum();
        Ok(Self {
            kernel: raw.iter().map(|v| (v / sum) as f32).collect(),
            tmp: Image::new(1, 1)?,
            line: Vec::new(),
        })
    }

    /// Kernel radius (half width), pixels.
    pub fn radius(&self) -> usize {
        self.kernel.len() / 2
    }

    /// Blurs `src` into `dst` (resized to `src`'s size).
    ///
    /// # Errors
    /// Only if resizing fails (it cannot for a valid view).
    pub fn apply<T: Copy + Into<f32>>(
        &mut self,
        src: &ImageView<'_, T>,
        dst: &mut Image<f32>,
    ) -> Result<()> {
        let (w, h) = (src.width(), src.height());
        let r = self.radius();
        self.tmp.resize(w, h)?;
        dst.resize(w, h)?;
        // Every output is 0 + g_0 v_0 + g_1 v_1 + ... in kernel order, the border replicated;
        // the loops below only choose the memory order (rows of the image), not the sums.
        for y in 0..h {
            let row = src.row(y);
            let out = self.tmp.row_mut(y);
            if w > 2 * r {
                // Interior: the window lies inside the row, no clamping; tap by tap along the
                // row (each pixel still sums its taps in kernel order).
                self.line.clear();
                self.line.extend(row.iter().map(|&p| p.into()));
                let inner = &mut out[r..w - r];
                inner.fill(0.0);
                for (k, &g) in self.kernel.iter().enumerate() {
                    for (o, &p) in inner.iter_mut().zip(&self.line[k..]) {
                        *o += g * p;
                    }
                }
            }
            for x in (0..r.min(w)).chain(w.saturating_sub(r).max(r.min(w))..w) {
                let mut acc = 0.0f32;
                for (k, &g) in self.kernel.iter().enumerate() {
                    let xi = (x + k).saturating_sub(r).min(w - 1);
                    acc += g * row[xi].into();
                }
                out[x] = acc;
            }
        }
        // Columns, a row at a time: out(x, y) accumulates g_k tmp(x, y + k - r) over k.
        for y in 0..h {
            let out = dst.row_mut(y);
            out.fill(0.0);
            for (k, &g) in self.kernel.iter().enumerate() {
                let yi = (y + k).saturating_sub(r).min(h - 1);
                for (o, &t) in out.iter_mut().zip(self.tmp.row(yi)) {
                    *o += g * t;
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kernel_is_normalised_and_constant_images_stay_constant() {
        let mut blur = GaussianBlur::new(1.4).unwrap();
        assert_eq!(blur.radius(), 5);
        assert!((blur.kernel.iter().sum::<f32>() - 1.0).abs() < 1e-6);
        let img = Image::from_vec(9, 7, vec![100u8; 63]).unwrap();
        let mut out = Image::new(1, 1).unwrap();
        blur.apply(&img.view(), &mut out).unwrap();
        assert!(out.data().iter().all(|&v| (v - 100.0).abs() < 1e-3));
    }

    /// The definition, one pixel at a time with clamped indices.
    fn reference(kernel: &[f32], img: &Image<u8>) -> Vec<f32> {
        let (w, h) = (img.width() as isize, img.height() as isize);
        let r = (kernel.len() / 2) as isize;
        let mut tmp = vec![0.0f32; (w * h) as usize];
        for y in 0..h {
            for x in 0..w {
                let mut acc = 0.0f32;
                for (k, &g) in kernel.iter().enumerate() {
                    let xi = (x + k as isize - r).clamp(0, w - 1);
                    acc += g * f32::from(img.get(xi as usize, y as usize));
                }
                tmp[(y * w + x) as usize] = acc;
            }
        }
        let mut out = vec![0.0f32; (w * h) as usize];
        for y in 0..h {
            for x in 0..w {
                let mut acc = 0.0f32;
                for (k, &g) in kernel.iter().enumerate() {
                    let yi = (y + k as isize - r).clamp(0, h - 1);
                    acc += g * tmp[(yi * w + x) as usize];
                }
                out[(y * w + x) as usize] = acc;
            }
        }
        out
    }

    #[test]
    fn equals_the_definition_bit_for_bit() {
        let mut state = 7u32;
        for (w, h, sigma) in [
            (40, 30, 1.0),
            (7, 5, 1.0),
            (3, 9, 1.4),
            (1, 1, 2.0),
            (64, 3, 0.6),
        ] {
            let data = (0..w * h)
                .map(|_| {
                    state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                    (state >> 24) as u8
                })
                .collect();
            let img = Image::from_vec(w, h, data).unwrap();
            let mut blur = GaussianBlur::new(sigma).unwrap();
            let mut out = Image::new(1, 1).unwrap();
            blur.apply(&img.view(), &mut out).unwrap();
            let want = reference(&blur.kernel, &img);
            let same = out
                .data()
                .iter()
                .zip(&want)
                .all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "{w}x{h} sigma {sigma}");
        }
    }

    #[test]
    fn an_impulse_spreads_with_the_right_variance() {
        let mut img = Image::<u8>::new(41, 41).unwrap();
        img.set(20, 20, 255);
        let mut blur = GaussianBlur::new(2.0).unwrap();
        let mut out = Image::new(1, 1).unwrap();
        blur.apply(&img.view(), &mut out).unwrap();
        let (mut mass, mut var) = (0.0, 0.0);
        for x in 0..41 {
            let v = out.get(x, 20) as f64;
            mass += v;
            var += v * ((x as f64 - 20.0).powi(2));
        }
        // Along one row the mass is 255 * g(0) (the column factor); the variance is sigma^2,
        // slightly less because the kernel is truncated at 3 sigma.
        assert!((var / mass - 4.0).abs() < 0.15, "{}", var / mass);
        assert!(GaussianBlur::new(0.0).is_err() && GaussianBlur::new(f64::NAN).is_err());
    }
}
