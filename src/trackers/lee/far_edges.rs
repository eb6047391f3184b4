//! Edges of the far range (Lee et al., "residual measurement model"): Canny edges of the image
//! rows that see the road between the split and far distances, kept as a binary map without
//! a distance transform ("to preserve accurate measurement for the long range").
//!
//! A far evaluation point hits when an edge lies on its image row within the half width of a
//! marking at that distance plus one pixel (both edges of a marking are then within reach of
//! its centre line); the paper leaves the matching rule open and this is our choice.

use crate::error::Result;
use crate::image::{Image, ImageView};
use crate::vision::{Canny, CannyConfig, EDGE};

/// The far-band edge detector.
#[derive(Debug, Clone)]
pub struct FarEdges {
    canny: Canny,
    rows: std::ops::Range<usize>,
    /// Canny edges of the band (row 0 = image row `rows.start`).
    pub edges: Image<u8>,
}

impl FarEdges {
    /// A detector for image rows `rows`.
    ///
    /// # Errors
    /// Canny parameter errors.
    pub fn new(config: CannyConfig, rows: std::ops::Range<usize>) -> Result<Self> {
        Ok(Self {
            canny: Canny::new(config)?,
            rows,
            edges: Image::new(1, 1)?,
        })
    }

    /// The image rows of the band.
    pub fn rows(&self) -> std::ops::Range<usize> {
        self.rows.clone()
    }

    /// Canny on the band of `gray`.
    ///
    /// # Errors
    /// None in practice (the band lies inside the frame).
    pub fn detect(&mut self, gray: &Image<u8>) -> Result<()> {
        if self.rows.is_empty() {
            self.edges.fill(0);
            return Ok(());
        }
        let w = gray.width();
        let band = ImageView::new(&gray.data()[self.rows.start * w..], w, self.rows.len(), w)?;
        self.canny.apply(&band, &mut self.edges)
    }

    /// Whether an edge lies on the image row of pixel `p` within `half` pixels of it.
    #[inline]
    pub fn hit(&self, p: [f64; 2], half: f64) -> Option<bool> {
        let v = p[1].round();
        if v < self.rows.start as f64 || v >= self.rows.end as f64 {
            return None;
        }
        let w = self.edges.width() as f64;
        if p[0] < 0.0 || p[0] > w - 1.0 {
            return None;
        }
        let row = self.edges.row(v as usize - self.rows.start);
        let lo = (p[0] - half).max(0.0).round() as usize;
        let hi = (p[0] + half).min(w - 1.0).round() as usize;
        Some(row[lo..=hi].contains(&EDGE))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_hits_an_edge_within_reach_on_its_row() {
        let mut img = Image::new(64, 40).unwrap();
        img.fill(50);
        for v in 0..40 {
            for u in 30..33 {
                img.set(u, v, 220);
            }
        }
        let mut far = FarEdges::new(CannyConfig::default(), 10..30).unwrap();
        far.detect(&img).unwrap();
        assert_eq!(far.hit([31.0, 20.0], 2.5), Some(true), "on the marking");
        assert_eq!(far.hit([40.0, 20.0], 2.5), Some(false), "beside it");
        assert_eq!(far.hit([31.0, 5.0], 2.5), None, "outside the band");
        assert_eq!(far.hit([-3.0, 20.0], 2.5), None, "outside the image");
    }
}
