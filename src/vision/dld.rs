//! The dark-light-dark (DLD) marking detector of Lee et al. 2015 (eqs. 21-24).
//!
//! For every pixel, the means of the N pixels to its left and right on the same row,
//!
//! ```text
//! m_l(u, v) = 1/N sum_{k=1..N} I(u - k, v)      (Lee eq. 22)
//! m_r(u, v) = 1/N sum_{k=1..N} I(u + k, v)      (Lee eq. 23)
//! I_d(u, v) = m_r(u, v) - m_l(u, v)             (Lee eq. 21)
//! ```
//!
//! classify it as a rising edge e_r where I_d > gamma (the left side of a bright marking), a
//! falling edge e_f where I_d < -gamma (its right side), and none otherwise (Lee eq. 24).
//! Pixels closer than N to the left or right border have no full window and are none. The
//! means come from a running prefix sum per row, so the cost does not depend on N.
//!
//! The paper then pairs rising and falling edges into marking candidates by their width on the
//! road (eqs. 25-26); that step needs the camera and lives with the Lee tracker.

use crate::error::{require_finite, Error, Result};
use crate::image::{Image, ImageView};
use crate::num_text::Num;
use serde::{Deserialize, Serialize};

/// Edge-map value of a rising edge e_r.
pub const RISING: u8 = 1;
/// Edge-map value of a falling edge e_f.
pub const FALLING: u8 = 2;

/// Lee's dark-light-dark (DLD) marking detector (eqs. 21-24): averaging window and threshold.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DldConfig {
    /// Averaging window N, pixels.
    pub window: usize,
    /// Threshold gamma on I_d, grey levels.
    pub gamma: f32,
}

impl Default for DldConfig {
    fn default() -> Self {
        Self {
            window: 4,
            gamma: 20.0,
        }
    }
}

/// The DLD executor: the difference image I_d and the edge map E, reused between frames.
#[derive(Debug, Clone)]
pub struct Dld {
    config: DldConfig,
    prefix: Vec<u32>,
    /// I_d of the last frame.
    pub difference: Image<f32>,
    /// E of the last frame: [`RISING`], [`FALLING`] or 0.
    pub edges: Image<u8>,
}

impl Dld {
    /// A DLD detector.
    ///
    /// # Errors
    /// [`Error::Parameter`] for a window of 0 or above 1024, or a negative or NaN gamma.
    pub fn new(config: DldConfig) -> Result<Self> {
        if config.window == 0 || config.window > 1024 {
            return Err(Error::parameter(
                "window",
                config.window,
                "must be between 1 and 1024 pixels",
            ));
        }
        require_finite("gamma", config.gamma as f64)?;
        if config.gamma < 0.0 {
            return Err(Error::parameter(
                "gamma",
                Num(f64::from(config.gamma)),
                "must not be negative",
            ));
        }
        Ok(Self {
            config,
            prefix: Vec::new(),
            difference: Image::new(1, 1)?,
            edges: Image::new(1, 1)?,
        })
    }

    /// Computes I_d and E for `src`.
    ///
    /// # Errors
    /// Only if resizing fails (it cannot for a valid view).
    pub fn apply(&mut self, src: &ImageView<'_, u8>) -> Result<()> {
        let (w, h) = (src.width(), src.height());
        let n = self.config.window;
        self.difference.resize(w, h)?;
        self.edges.resize(w, h)?;
        self.prefix.resize(w + 1, 0);
        let gamma = self.config.gamma;
        let inv_n = 1.0 / n as f32;
        for y in 0..h {
            let row = src.row(y);
            // prefix[i] = sum of row[0..i].
            let mut acc = 0u32;
            self.prefix[0] = 0;
            for (i, &p) in row.iter().enumerate() {
                acc += p as u32;
                self.prefix[i + 1] = acc;
            }
            let diff = self.difference.row_mut(y);
            let edges = self.edges.row_mut(y);
            for u in 0..w {
                if u < n || u + n >= w {
                    diff[u] = 0.0;
                    edges[u] = 0;
                    continue;
                }
                // sum I(u-N..u-1) and sum I(u+1..u+N).
                let left = self.prefix[u] - self.prefix[u - n];
                let right = self.prefix[u + n + 1] - self.prefix[u + 1];
                let d = (right as f32 - left as f32) * inv_n;
                diff[u] = d;
                edges[u] = if d > gamma {
                    RISING
                } else if d < -gamma {
                    FALLING
                } else {
                    0
                };
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Straight from eqs. 21-23, no prefix sums.
    fn reference(row: &[u8], u: usize, n: usize) -> f32 {
        let ml: f32 = (1..=n).map(|k| row[u - k] as f32).sum::<f32>() / n as f32;
        let mr: f32 = (1..=n).map(|k| row[u + k] as f32).sum::<f32>() / n as f32;
        mr - ml
    }

    #[test]
    fn matches_the_equations_on_random_rows() {
        let mut state = 7u32;
        let data: Vec<u8> = (0..64 * 5)
            .map(|_| {
                state = state.wrapping_mul(1_103_515_245).wrapping_add(12_345);
                (state >> 23) as u8
            })
            .collect();
        let img = Image::from_vec(64, 5, data).unwrap();
        let mut dld = Dld::new(DldConfig {
            window: 5,
            gamma: 30.0,
        })
        .unwrap();
        dld.apply(&img.view()).unwrap();
        for y in 0..5 {
            for u in 5..59 {
                let want = reference(img.row(y), u, 5);
                let got = dld.difference.get(u, y);
                assert!((got - want).abs() < 1e-4, "({u}, {y})");
                let e = dld.edges.get(u, y);
                assert_eq!(e == RISING, want > 30.0);
                assert_eq!(e == FALLING, want < -30.0);
            }
            assert_eq!(dld.edges.get(4, y), 0, "no full window");
            assert_eq!(dld.edges.get(59, y), 0, "no full window");
        }
    }

    #[test]
    fn a_bright_marking_gives_rising_then_falling_edges() {
        let row: Vec<u8> = (0..40)
            .map(|x| if (18..23).contains(&x) { 220 } else { 60 })
            .collect();
        let img = Image::from_vec(40, 1, row).unwrap();
        let mut dld = Dld::new(DldConfig::default()).unwrap();
        dld.apply(&img.view()).unwrap();
        let kinds: Vec<u8> = (0..40).map(|u| dld.edges.get(u, 0)).collect();
        let first_rising = kinds.iter().position(|&k| k == RISING).unwrap();
        let first_falling = kinds.iter().position(|&k| k == FALLING).unwrap();
        assert!(
            first_rising < 18 && first_falling > first_rising,
            "{kinds:?}"
        );
        assert!(kinds[..10].iter().all(|&k| k == 0) && kinds[30..].iter().all(|&k| k == 0));
    }

    #[test]
    fn bad_parameters_are_errors() {
        assert!(Dld::new(DldConfig {
            window: 0,
            gamma: 1.0
        })
        .is_err());
        assert!(Dld::new(DldConfig {
            window: 3,
            gamma: f32::NAN
        })
        .is_err());
        assert!(Dld::new(DldConfig {
            window: 3,
            gamma: -1.0
        })
        .is_err());
    }
}
