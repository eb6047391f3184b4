//! The likelihood map D of the near range (Lee et al., "approximated measurement model"): a
//! grid on the road plane in which the marking candidates are marked, turned into a
//! probabilistic map by the distance transform,
//!
//! ```text
//! D(x, y) = exp(-d(x, y)^2 / (2 sigma_D^2)),   d = distance to the nearest candidate (m)
//! ```
//!
//! The paper says only that the binary candidate map is turned into a "probabilistic
//! distribution" by a distance transform; the Gaussian of the distance is our choice (D = 1 on
//! a candidate, exp(-1/2) at sigma_D). Cells are square (`cell_m`), x from the near distance to
//! the split distance, y over +-`lateral_range_m`; outside the grid D = 0.

use crate::error::Result;
use crate::image::Image;
use crate::math;
use crate::vision::DistanceTransform;

/// The grid, its candidate marks and D.
#[derive(Debug, Clone)]
pub struct LikelihoodMap {
    x0: f64,
    y_max: f64,
    cell: f64,
    sigma: f64,
    /// Candidate marks (1 where a marking candidate lies), rows along x, columns from left
    /// (+y) to right.
    pub marks: Image<u8>,
    distance: Image<f32>,
    /// D, same layout as `marks`.
    pub likelihood: Vec<f32>,
    transform: DistanceTransform,
}

impl LikelihoodMap {
    /// A grid over x in [`x0`, `x1`], y in [-`lateral`, `lateral`] with square cells of `cell`
    /// metres, and the spread `sigma` of D (metres).
    ///
    /// # Errors
    /// Image-size errors for an empty or huge grid (the configuration is validated first).
    pub fn new(x0: f64, x1: f64, lateral: f64, cell: f64, sigma: f64) -> Result<Self> {
        let rows = ((x1 - x0) / cell).ceil().max(1.0) as usize;
        let cols = (2.0 * lateral / cell).ceil().max(1.0) as usize;
        let mut distance = Image::new(cols, rows)?;
        distance.fill(f32::INFINITY);
        Ok(Self {
            x0,
            y_max: lateral,
            cell,
            sigma,
            marks: Image::new(cols, rows)?,
            distance,
            likelihood: vec![0.0; rows * cols],
            transform: DistanceTransform::new(),
        })
    }

    /// Near edge of row 0 (x, metres), left edge of column 0 (y, metres) and the cell size.
    pub fn geometry(&self) -> (f64, f64, f64) {
        (self.x0, self.y_max, self.cell)
    }

    /// Clears the marks.
    pub fn clear(&mut self) {
        self.marks.fill(0);
    }

    /// Cell (column, row) of road point (x, y), if inside the grid.
    #[inline]
    fn cell(&self, x: f64, y: f64) -> Option<(usize, usize)> {
        let r = (x - self.x0) / self.cell;
        let c = (self.y_max - y) / self.cell;
        if r >= 0.0 && c >= 0.0 {
            let (r, c) = (r as usize, c as usize);
            if r < self.marks.height() && c < self.marks.width() {
                return Some((c, r));
            }
        }
        None
    }

    /// Marks the road segment from `a` to `b` (the footprint of a candidate's image row).
    pub fn mark_segment(&mut self, a: [f64; 2], b: [f64; 2]) {
        let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        let n = (len / (0.5 * self.cell)).ceil().min(10_000.0) as usize + 1;
        for k in 0..n {
            let t = if n == 1 {
                0.5
            } else {
                k as f64 / (n - 1) as f64
            };
            let (x, y) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
            if let Some((c, r)) = self.cell(x, y) {
                self.marks.set(c, r, 1);
            }
        }
    }

    /// Distance transform of the marks and D (eq. 31's map).
    ///
    /// # Errors
    /// None in practice (the buffers have the grid's size).
    pub fn finish(&mut self) -> Result<()> {
        self.transform
            .apply(&self.marks.view(), &mut self.distance)?;
        let k = -0.5 * (self.cell / self.sigma).powi(2);
        for (l, &d) in self.likelihood.iter_mut().zip(self.distance.data()) {
            // d is in cells; an empty map gives infinity and D = 0.
            *l = math::exp(k * (d as f64) * (d as f64)) as f32;
        }
        Ok(())
    }

    /// D(x, y), 0 outside the grid.
    #[inline]
    pub fn at(&self, x: f64, y: f64) -> f64 {
        match self.cell(x, y) {
            Some((c, r)) => self.likelihood[r * self.marks.width() + c] as f64,
            None => 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn d_is_one_on_a_mark_and_falls_as_a_gaussian_of_the_distance() {
        let mut map = LikelihoodMap::new(5.0, 20.0, 4.0, 0.1, 0.2).unwrap();
        map.clear();
        // A marking 1.8 m to the left along the whole range.
        map.mark_segment([5.0, 1.85], [20.0, 1.85]);
        map.finish().unwrap();
        assert_eq!(map.at(10.0, 1.85), 1.0);
        let d = map.at(10.0, 1.45);
        let expected = math::exp(-0.5 * (0.4f64 / 0.2).powi(2));
        assert!((d - expected).abs() < 1e-6, "{d} vs {expected}");
        assert_eq!(map.at(30.0, 1.85), 0.0, "beyond the grid");
        assert_eq!(map.at(10.0, -5.0), 0.0, "beside the grid");
        // No marks: D = 0 everywhere.
        map.clear();
        map.finish().unwrap();
        assert_eq!(map.at(10.0, 1.85), 0.0);
    }
}
