//! Sobel gradients: gx, gy, magnitude and orientation.
//!
//! ```text
//!        [-1 0 1]            [-1 -2 -1]
//! gx  =  [-2 0 2] * I,  gy = [ 0  0  0] * I,  |grad I| = sqrt(gx^2 + gy^2),  theta = atan2(gy, gx)
//!        [-1 0 1]            [ 1  2  1]
//! ```
//!
//! Unnormalised, as is usual (a step of height 1 gives |grad I| = 4; Liu et al. threshold this
//! magnitude at 10 on 0-255 images), with the border replicated. gx grows to the right, gy
//! downwards, so theta is the image-frame angle of the gradient (pointing from dark to
//! light), in (-pi, pi]. Orientation costs an atan2 per pixel and is computed only on request.

use crate::error::Result;
use crate::image::{Image, ImageView};
use crate::math;

/// The gradient images of one frame, reused from frame to frame.
#[derive(Debug, Clone)]
pub struct Gradients {
    /// Horizontal derivative.
    pub gx: Image<f32>,
    /// Vertical derivative (positive when the image gets brighter downwards).
    pub gy: Image<f32>,
    /// Magnitude sqrt(gx^2 + gy^2).
    pub magnitude: Image<f32>,
    /// Orientation atan2(gy, gx), radians; only filled by [`Gradients::compute_orientation`].
    pub orientation: Image<f32>,
}

impl Gradients {
    /// Empty gradient images of size `width` x `height`.
    ///
    /// # Errors
    /// [`crate::Error::Dimensions`] for an unusable size.
    pub fn new(width: usize, height: usize) -> Result<Self> {
        Ok(Self {
            gx: Image::new(width, height)?,
            gy: Image::new(width, height)?,
            magnitude: Image::new(width, height)?,
            orientation: Image::new(width, height)?,
        })
    }

    /// Computes gx, gy and the magnitude of `src` (resizing the buffers if the size changed).
    ///
    /// # Errors
    /// [`crate::Error::Dimensions`] only if resizing fails (it cannot for a valid view).
    pub fn compute<T: Copy + Into<f32>>(&mut self, src: &ImageView<'_, T>) -> Result<()> {
        let (w, h) = (src.width(), src.height());
        self.gx.resize(w, h)?;
        self.gy.resize(w, h)?;
        self.magnitude.resize(w, h)?;
        self.orientation.resize(w, h)?;
        for y in 0..h {
            let up = src.row(y.saturating_sub(1));
            let mid = src.row(y);
            let down = src.row((y + 1).min(h - 1));
            let gx_row = self.gx.row_mut(y);
            let gy_row = self.gy.row_mut(y);
            let mag_row = self.magnitude.row_mut(y);
            let p = |row: &[T], i: usize| -> f32 { row[i].into() };
            // The same expression at every pixel; the border columns clamp their neighbours.
            let mut pixel = |x: usize, l: usize, r: usize| {
                let gx = (p(up, r) + 2.0 * p(mid, r) + p(down, r))
                    - (p(up, l) + 2.0 * p(mid, l) + p(down, l));
                let gy = (p(down, l) + 2.0 * p(down, x) + p(down, r))
                    - (p(up, l) + 2.0 * p(up, x) + p(up, r));
                gx_row[x] = gx;
                gy_row[x] = gy;
                mag_row[x] = (gx * gx + gy * gy).sqrt();
            };
            pixel(0, 0, 1.min(w - 1));
            if w > 1 {
                pixel(w - 1, w - 2, w - 1);
            }
            if w > 2 {
                let interior = gx_row[1..w - 1]
                    .iter_mut()
                    .zip(&mut gy_row[1..w - 1])
                    .zip(&mut mag_row[1..w - 1])
                    .zip(up.windows(3).zip(mid.windows(3)).zip(down.windows(3)));
                for (((gx_o, gy_o), mag_o), ((u, m), d)) in interior {
                    let q = |row: &[T], i: usize| -> f32 { row[i].into() };
                    let gx =
                        (q(u, 2) + 2.0 * q(m, 2) + q(d, 2)) - (q(u, 0) + 2.0 * q(m, 0) + q(d, 0));
                    let gy =
                        (q(d, 0) + 2.0 * q(d, 1) + q(d, 2)) - (q(u, 0) + 2.0 * q(u, 1) + q(u, 2));
                    *gx_o = gx;
                    *gy_o = gy;
                    *mag_o = (gx * gx + gy * gy).sqrt();
                }
            }
        }
        Ok(())
    }

    /// Fills [`Gradients::orientation`] from gx and gy.
    pub fn compute_orientation(&mut self) {
        let (gx, gy) = (self.gx.data(), self.gy.data());
        for ((o, &x), &y) in self.orientation.data_mut().iter_mut().zip(gx).zip(gy) {
            *o = math::atan2f(y, x);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(w: usize, h: usize, f: impl Fn(usize, usize) -> u8) -> Image<u8> {
        let data = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| f(x, y))
            .collect();
        Image::from_vec(w, h, data).unwrap()
    }

    #[test]
    fn a_ramp_has_the_textbook_response() {
        // I = 3x + 5y: gx = 8 * 3, gy = 8 * 5 away from the border.
        let img = image(12, 9, |x, y| (3 * x + 5 * y) as u8);
        let mut g = Gradients::new(1, 1).unwrap();
        g.compute(&img.view()).unwrap();
        g.compute_orientation();
        assert_eq!(g.gx.get(5, 4), 24.0);
        assert_eq!(g.gy.get(5, 4), 40.0);
        assert!((g.magnitude.get(5, 4) - (24.0f32 * 24.0 + 1600.0).sqrt()).abs() < 1e-4);
        assert!((g.orientation.get(5, 4) - math::atan2f(40.0, 24.0)).abs() < 1e-6);
        // Replicated border: half the interior response on the first column.
        assert_eq!(g.gx.get(0, 4), 12.0);
    }

    #[test]
    fn a_vertical_bright_bar_has_opposite_gradients_on_its_sides() {
        let img = image(20, 10, |x, _| if (8..12).contains(&x) { 200 } else { 50 });
        let mut g = Gradients::new(20, 10).unwrap();
        g.compute(&img.view()).unwrap();
        g.compute_orientation();
        assert!(g.gx.get(7, 5) > 0.0 && g.gx.get(12, 5) < 0.0);
        assert_eq!(g.gy.get(7, 5), 0.0);
        assert!(g.orientation.get(7, 5).abs() < 1e-6);
        assert!((g.orientation.get(12, 5).abs() - std::f32::consts::PI).abs() < 1e-6);
        assert_eq!(g.magnitude.get(2, 5), 0.0);
        assert_eq!(g.magnitude.get(7, 5), 600.0);
    }
}
