//! Canny edges: Gaussian smoothing, Sobel gradients, non-maximum suppression, hysteresis.
//!
//! 1. smooth with a Gaussian of `sigma` pixels ([`super::GaussianBlur`]);
//! 2. Sobel gx, gy and |grad I| ([`super::Gradients`]);
//! 3. non-maximum suppression: keep a pixel whose magnitude is at least that of both
//!    neighbours along the gradient direction, quantised to 0, 45, 90 or 135 degrees (ties
//!    broken towards the earlier pixel so that a plateau yields one line);
//! 4. hysteresis: pixels above `high` are edges; pixels above `low` are edges when
//!    8-connected to an edge (a depth-first flood fill with a preallocated stack).
//!
//! Thresholds are on the unnormalised Sobel magnitude of the smoothed image (a step of
//! height 1 gives 4).

use super::blur::GaussianBlur;
use super::gradient::Gradients;
use crate::error::{require_finite, require_positive, Error, Result};
use crate::image::{Image, ImageView};
use crate::num_text::Num;
use serde::{Deserialize, Serialize};

/// A Canny edge detector: smoothing and the two hysteresis thresholds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CannyConfig {
    /// Gaussian smoothing, pixels.
    pub sigma: f64,
    /// Lower hysteresis threshold on |grad I|.
    pub low: f32,
    /// Upper hysteresis threshold on |grad I|.
    pub high: f32,
}

impl Default for CannyConfig {
    fn default() -> Self {
        Self {
            sigma: 1.0,
            low: 40.0,
            high: 100.0,
        }
    }
}

/// Edge pixel value in the output map.
pub const EDGE: u8 = 255;

const CANDIDATE: u8 = 1;

/// The Canny executor with its scratch images.
#[derive(Debug, Clone)]
pub struct Canny {
    config: CannyConfig,
    blur: GaussianBlur,
    smooth: Image<f32>,
    gradients: Gradients,
    stack: Vec<u32>,
}

impl Canny {
    /// A Canny detector.
    ///
    /// # Errors
    /// [`Error::Parameter`] for a bad sigma, a negative or NaN threshold, or low > high.
    pub fn new(config: CannyConfig) -> Result<Self> {
        require_finite("low", config.low as f64)?;
        require_positive("high", config.high as f64)?;
        if config.low < 0.0 || config.low > config.high {
            return Err(Error::parameter(
                "low",
                Num(f64::from(config.low)),
                "must be between 0 and high",
            ));
        }
        Ok(Self {
            config,
            blur: GaussianBlur::new(config.sigma)?,
            smooth: Image::new(1, 1)?,
            gradients: Gradients::new(1, 1)?,
            stack: Vec::new(),
        })
    }

    /// The gradients of the last frame (of the smoothed image).
    pub fn gradients(&self) -> &Gradients {
        &self.gradients
    }

    /// Detects the edges of `src` into `edges` ([`EDGE`] on edges, 0 elsewhere; resized to
    /// `src`'s size).
    ///
    /// # Errors
    /// Only if resizing fails (it cannot for a valid view).
    pub fn apply<T: Copy + Into<f32>>(
        &mut self,
        src: &ImageView<'_, T>,
        edges: &mut Image<u8>,
    ) -> Result<()> {
        let (w, h) = (src.width(), src.height());
        self.blur.apply(src, &mut self.smooth)?;
        self.gradients.compute(&self.smooth.view())?;
        edges.resize(w, h)?;
        edges.fill(0);
        self.stack.clear();
        self.stack.reserve(w * h);
        let (gx, gy, mag) = (
            &self.gradients.gx,
            &self.gradients.gy,
            &self.gradients.magnitude,
        );
        let (low, high) = (self.config.low, self.config.high);
        // tan(22.5 deg) and tan(67.5 deg) for the direction sectors.
        const T1: f32 = 0.414_213_57;
        const T2: f32 = 2.414_213_6;
        for y in 1..h.saturating_sub(1) {
            for x in 1..w.saturating_sub(1) {
                let m = mag.get(x, y);
                if m <= low {
                    continue;
                }
                let (dx, dy) = (gx.get(x, y), gy.get(x, y));
                let (ax, ay) = (dx.abs(), dy.abs());
                let (a, b) = if ay <= T1 * ax {
                    (mag.get(x - 1, y), mag.get(x + 1, y))
                } else if ay >= T2 * ax {
                    (mag.get(x, y - 1), mag.get(x, y + 1))
                } else if (dx > 0.0) == (dy > 0.0) {
                    (mag.get(x - 1, y - 1), mag.get(x + 1, y + 1))
                } else {
                    (mag.get(x + 1, y - 1), mag.get(x - 1, y + 1))
                };
                // Strictly greater than the earlier neighbour, at least the later one.
                if m > a && m >= b {
                    edges.set(x, y, CANDIDATE);
                    if m > high {
                        edges.set(x, y, EDGE);
                        self.stack.push((y * w + x) as u32);
                    }
                }
            }
        }
        let data = edges.data_mut();
        while let Some(i) = self.stack.pop() {
            let (x, y) = (i as usize % w, i as usize / w);
            for ny in y.saturating_sub(1)..=(y + 1).min(h - 1) {
                for nx in x.saturating_sub(1)..=(x + 1).min(w - 1) {
                    let j = ny * w + nx;
                    if data[j] == CANDIDATE {
                        data[j] = EDGE;
                        self.stack.push(j as u32);
                    }
                }
            }
        }
        for v in data.iter_mut() {
            if *v == CANDIDATE {
                *v = 0;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(w: usize, h: usize) -> Image<u8> {
        let data = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                if (10..30).contains(&x) && (8..24).contains(&y) {
                    200
                } else {
                    40
                }
            })
            .collect();
        Image::from_vec(w, h, data).unwrap()
    }

    #[test]
    fn a_square_gives_a_thin_closed_outline() {
        let mut canny = Canny::new(CannyConfig::default()).unwrap();
        let mut edges = Image::new(1, 1).unwrap();
        canny.apply(&square(40, 32).view(), &mut edges).unwrap();
        // Each side is crossed by exactly one edge pixel (thin), at the step.
        let row: Vec<usize> = (0..40).filter(|&x| edges.get(x, 16) == EDGE).collect();
        assert_eq!(row.len(), 2, "{row:?}");
        assert!(
            (9..=10).contains(&row[0]) && (29..=30).contains(&row[1]),
            "{row:?}"
        );
        let col: Vec<usize> = (0..32).filter(|&y| edges.get(20, y) == EDGE).collect();
        assert_eq!(col.len(), 2, "{col:?}");
        // Flat regions have none.
        assert_eq!(edges.get(20, 16), 0);
        assert_eq!(edges.get(2, 2), 0);
        assert!(edges.data().iter().all(|&v| v == 0 || v == EDGE));
    }

    #[test]
    fn hysteresis_keeps_weak_edges_only_when_connected_to_strong_ones() {
        // A vertical step whose contrast fades from strong (top) to weak (bottom), and a
        // separate weak step elsewhere.
        let (w, h) = (60, 40);
        let data = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .map(|(x, y)| {
                let strong = 40 + (160 - 3 * y as i32).max(20);
                if (20..40).contains(&x) {
                    strong as u8
                } else if x >= 50 {
                    60
                } else {
                    40
                }
            })
            .collect();
        let img = Image::from_vec(w, h, data).unwrap();
        let config = CannyConfig {
            sigma: 1.0,
            low: 30.0,
            high: 250.0,
        };
        let mut canny = Canny::new(config).unwrap();
        let mut edges = Image::new(1, 1).unwrap();
        canny.apply(&img.view(), &mut edges).unwrap();
        let edge_in_rows =
            |x0: usize, x1: usize, y: usize| (x0..x1).any(|x| edges.get(x, y) == EDGE);
        assert!(edge_in_rows(17, 23, 5), "strong part");
        assert!(edge_in_rows(17, 23, 35), "weak part, connected");
        assert!(!edge_in_rows(47, 53, 20), "weak and isolated");
    }

    #[test]
    fn bad_thresholds_are_errors() {
        let bad = CannyConfig {
            low: 50.0,
            high: 10.0,
            ..Default::default()
        };
        assert!(Canny::new(bad).unwrap_err().to_string().contains("`low`"));
        let nan = CannyConfig {
            high: f32::NAN,
            ..Default::default()
        };
        assert!(Canny::new(nan).is_err());
    }
}
