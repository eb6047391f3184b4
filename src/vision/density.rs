//! The 3-D point density image of Danescu & Nedevschi 2011 (Sec. VI-B) and its distance image
//! DT^D.
//!
//! Road points are projected onto the lateral (YOZ) plane and counted in a grid of `rows` x
//! `cols` cells of `dy_m` (height) by `dz_m` (distance): cell (r, c) with c = Z / dZ (eq. 7)
//! and r = Y / dY + rows / 2 (eq. 8), so heights from -rows dY / 2 to +rows dY / 2 (the paper:
//! 200 x 300 cells of 1 cm x 10 cm). Instead of a plain count per cell, each point adds a
//! triangular kernel (the paper's ref. \[12\]): 11 x 11 cells, 6 at the centre and one less per
//! ring, 1 on the outer ring,
//!
//! ```text
//! D(r, c) = sum_points max(0, 6 - max(|r - r_p|, |c - c_p|))
//! ```
//!
//! (the rings are Chebyshev rings: "the neighbouring cells with values that decrease linearly
//! with the distance from the centre"). The kernel is added once per occupied cell, multiplied
//! by the cell's count, which gives the same image as adding it once per point. Then column
//! non-maximum suppression keeps the cells at least as dense as the cells above and below,
//! a low fixed threshold drops thin ones, and the exact distance transform of what remains is
//! DT^D, in cells.

use super::DistanceTransform;
use crate::error::{require_positive, Error, Result};
use crate::image::Image;
use serde::{Deserialize, Serialize};

/// Radius of the triangular kernel (11 x 11 cells).
pub const KERNEL_RADIUS: usize = 5;

/// Danescu's discrete lateral space (the 3-D density image) and its density threshold.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DensityConfig {
    /// Cells in height (h).
    pub rows: usize,
    /// Cells in distance (w).
    pub cols: usize,
    /// Cell height dY, metres.
    pub dy_m: f64,
    /// Cell length dZ, metres.
    pub dz_m: f64,
    /// Smallest density kept after the column non-maximum suppression.
    pub threshold: f32,
}

impl Default for DensityConfig {
    fn default() -> Self {
        Self {
            rows: 200,
            cols: 300,
            dy_m: 0.01,
            dz_m: 0.1,
            threshold: 30.0,
        }
    }
}

/// Density image, its edges and DT^D, reused between frames.
#[derive(Debug, Clone)]
pub struct Density {
    config: DensityConfig,
    counts: Vec<u32>,
    density: Image<f32>,
    edges: Image<u8>,
    distance: Image<f32>,
    transform: DistanceTransform,
}

impl Density {
    /// An empty density image.
    ///
    /// # Errors
    /// [`Error::Parameter`] for non-positive cell sizes or threshold, or a grid of fewer than
    /// 3 or more than 4096 cells a side.
    pub fn new(config: DensityConfig) -> Result<Self> {
        require_positive("dy_m", config.dy_m)?;
        require_positive("dz_m", config.dz_m)?;
        require_positive("threshold", config.threshold as f64)?;
        for (name, n) in [("rows", config.rows), ("cols", config.cols)] {
            if !(3..=4096).contains(&n) {
                return Err(Error::parameter(
                    name,
                    n,
                    "must be between 3 and 4096 cells",
                ));
            }
        }
        let (w, h) = (config.cols, config.rows);
        Ok(Self {
            config,
            counts: vec![0; w * h],
            density: Image::new(w, h)?,
            edges: Image::new(w, h)?,
            distance: Image::new(w, h)?,
            transform: DistanceTransform::new(),
        })
    }

    /// The grid.
    pub fn config(&self) -> &DensityConfig {
        &self.config
    }

    /// Forgets the points of the last frame.
    pub fn clear(&mut self) {
        self.counts.fill(0);
    }

    /// The (row, column) cell of height `y` at distance `z` (eqs. 7-8, rounded), or `None`
    /// outside the grid.
    pub fn cell(&self, z: f64, y: f64) -> Option<(usize, usize)> {
        let c = (z / self.config.dz_m).round();
        let r = (y / self.config.dy_m + (self.config.rows / 2) as f64).round();
        (c >= 0.0 && r >= 0.0 && (c as usize) < self.config.cols && (r as usize) < self.config.rows)
            .then_some((r as usize, c as usize))
    }

    /// Counts one road point of height `y` at distance `z` (ignored outside the grid).
    pub fn add(&mut self, z: f64, y: f64) {
        if let Some((r, c)) = self.cell(z, y) {
            self.counts[r * self.config.cols + c] += 1;
        }
    }

    /// Builds the density image, its column maxima and DT^D from the points added since
    /// [`Density::clear`].
    pub fn finish(&mut self) -> Result<()> {
        let (w, h) = (self.config.cols, self.config.rows);
        self.density.fill(0.0);
        let rad = KERNEL_RADIUS as isize;
        for r in 0..h {
            for c in 0..w {
                let n = self.counts[r * w + c];
                if n == 0 {
                    continue;
                }
                let n = n as f32;
                for dr in -rad..=rad {
                    let rr = r as isize + dr;
                    if rr < 0 || rr >= h as isize {
                        continue;
                    }
                    let row = self.density.row_mut(rr as usize);
                    for dc in -rad..=rad {
                        let cc = c as isize + dc;
                        if cc < 0 || cc >= w as isize {
                            continue;
                        }
                        let v = (rad + 1 - dr.abs().max(dc.abs())) as f32;
                        row[cc as usize] += n * v;
                    }
                }
            }
        }
        let t = self.config.threshold;
        for r in 0..h {
            for c in 0..w {
                let d = self.density.get(c, r);
                let up = if r > 0 {
                    self.density.get(c, r - 1)
                } else {
                    0.0
                };
                let down = if r + 1 < h {
                    self.density.get(c, r + 1)
                } else {
                    0.0
                };
                let keep = d >= t && d >= up && d >= down;
                self.edges.set(c, r, u8::from(keep));
            }
        }
        self.transform
            .apply(&self.edges.view(), &mut self.distance)?;
        Ok(())
    }

    /// The density image (row r = height, column c = distance).
    pub fn density(&self) -> &Image<f32> {
        &self.density
    }

    /// The column maxima above the threshold (1) and the rest (0).
    pub fn edges(&self) -> &Image<u8> {
        &self.edges
    }

    /// DT^D: distance in cells to the nearest kept cell (infinite when none is kept).
    pub fn distance(&self) -> &Image<f32> {
        &self.distance
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_point_adds_the_triangular_kernel() {
        let mut d = Density::new(DensityConfig::default()).unwrap();
        d.add(10.0, 0.0); // cell (100, 100)
        d.finish().unwrap();
        let img = d.density();
        assert_eq!(img.get(100, 100), 6.0);
        assert_eq!(img.get(101, 100), 5.0);
        assert_eq!(img.get(103, 98), 3.0);
        assert_eq!(img.get(105, 95), 1.0);
        assert_eq!(img.get(106, 100), 0.0);
        let total: f32 = img.data().iter().sum();
        // 6 + 8*5 + 16*4 + 24*3 + 32*2 + 40*1.
        assert_eq!(total, 286.0);
        // One point is below the threshold: nothing survives.
        assert!(d.edges().data().iter().all(|&e| e == 0));
    }

    #[test]
    fn a_road_line_survives_suppression_and_the_distance_image_measures_from_it() {
        let mut d = Density::new(DensityConfig::default()).unwrap();
        // Road points along y = -0.3 + 0.01 z (a pitched road), 20 per 10 cm, plus scattered
        // points above it (an obstacle's thin cloud) that must not survive.
        for k in 0..2000 {
            let z = 2.0 + 0.01 * k as f64;
            d.add(z, -0.3 + 0.01 * z);
        }
        for k in 0..10 {
            d.add(15.0 + 0.5 * k as f64, 0.5);
        }
        d.finish().unwrap();
        let cell_of = |z: f64| d.cell(z, -0.3 + 0.01 * z).unwrap();
        for z in [3.0, 10.0, 20.0] {
            let (r, c) = cell_of(z);
            assert_eq!(d.edges().get(c, r), 1, "z {z}");
            // One maximum in the column (two where the line steps from row to row).
            let kept: usize = (0..200).map(|rr| d.edges().get(c, rr) as usize).sum();
            assert!((1..=2).contains(&kept), "z {z}: {kept}");
            assert_eq!(d.distance().get(c, r), 0.0);
            assert_eq!(d.distance().get(c, r + 7), 7.0);
        }
        let (r, c) = d.cell(16.0, 0.5).unwrap();
        assert_eq!(
            d.edges().get(c, r),
            0,
            "the sparse points are below the threshold"
        );
        d.clear();
        d.finish().unwrap();
        assert!(d.distance().data().iter().all(|v| v.is_infinite()));
    }

    #[test]
    fn bad_grids_are_refused() {
        let bad = |c: DensityConfig| Density::new(c).unwrap_err().to_string();
        let d = DensityConfig::default();
        assert!(bad(DensityConfig { rows: 0, ..d }).contains("rows"));
        assert!(bad(DensityConfig {
            dz_m: f64::NAN,
            ..d
        })
        .contains("dz_m"));
        assert!(bad(DensityConfig {
            threshold: 0.0,
            ..d
        })
        .contains("threshold"));
        let g = Density::new(d).unwrap();
        assert_eq!(g.cell(-1.0, 0.0), None);
        assert_eq!(g.cell(10.0, 5.0), None);
    }
}
