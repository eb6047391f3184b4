//! Marking candidates of the near range (Lee et al. Fig. 4, eqs. 21-26).
//!
//! On every image row of the near band, the DLD detector (eqs. 21-24, [`crate::vision::Dld`])
//! classifies pixels as rising edges e_r (I_d > gamma) or falling edges e_f (I_d < -gamma).
//! Each run of rising pixels is summarised by its strongest pixel u_r, each falling run by
//! its strongest u_f; a rising edge followed by a falling edge (with no other rising run in
//! between) is a dark-light-dark pattern. Both are mapped to the road by the camera's ground
//! homography (eq. 25, with the lens distortion removed), the pattern length
//! w = |x_f - x_r| (eq. 26) is compared with the largest marking width, and a pattern that
//! passes is a candidate. The candidate is marked at its centre on the road grid of the
//! [`LikelihoodMap`], over the road footprint of its image row (from v - 1/2 to v + 1/2), so
//! that far rows, which cover more than one cell, leave no gaps.

use super::likelihood_map::LikelihoodMap;
use crate::camera::Camera;
use crate::error::Result;
use crate::image::{Image, ImageView};
use crate::vision::{Dld, DldConfig, FALLING, RISING};

/// The candidate detector of the near band.
#[derive(Debug, Clone)]
pub struct Candidates {
    dld: Dld,
    rows: std::ops::Range<usize>,
    max_width: f64,
    /// Candidates found in the last frame.
    pub count: usize,
}

/// Strongest pixel of the run of `kind` starting at `u`, and the end of the run.
fn run_peak(edges: &[u8], diff: &[f32], u: usize, kind: u8) -> (usize, usize) {
    let mut best = u;
    let mut end = u;
    while end < edges.len() && edges[end] == kind {
        if diff[end].abs() > diff[best].abs() {
            best = end;
        }
        end += 1;
    }
    (best, end)
}

impl Candidates {
    /// A detector for image rows `rows` (the near band).
    ///
    /// # Errors
    /// DLD parameter errors.
    pub fn new(dld: DldConfig, rows: std::ops::Range<usize>, max_width: f64) -> Result<Self> {
        Ok(Self {
            dld: Dld::new(dld)?,
            rows,
            max_width,
            count: 0,
        })
    }

    /// Detects the candidates of `gray` (full frame; only the band is read) and marks them on
    /// `map` (which is cleared first).
    ///
    /// # Errors
    /// None in practice (the band lies inside the frame).
    pub fn detect(
        &mut self,
        gray: &Image<u8>,
        camera: &Camera,
        map: &mut LikelihoodMap,
    ) -> Result<()> {
        map.clear();
        self.count = 0;
        if self.rows.is_empty() {
            return Ok(());
        }
        let w = gray.width();
        let top = self.rows.start;
        let mut count = 0;
        let band = ImageView::new(&gray.data()[top * w..], w, self.rows.len(), w)?;
        self.dld.apply(&band)?;
        for r in 0..self.rows.len() {
            let v = (top + r) as f64;
            let edges = self.dld.edges.row(r);
            let diff = self.dld.difference.row(r);
            let mut rising: Option<usize> = None;
            let mut u = 0;
            while u < w {
                match edges[u] {
                    RISING => {
                        let (peak, end) = run_peak(edges, diff, u, RISING);
                        rising = Some(peak);
                        u = end;
                    }
                    FALLING => {
                        let (peak, end) = run_peak(edges, diff, u, FALLING);
                        if let Some(ur) = rising.take() {
                            let found =
                                pair(camera, map, self.max_width, ur as f64, peak as f64, v);
                            count += usize::from(found);
                        }
                        u = end;
                    }
                    _ => u += 1,
                }
            }
        }
        self.count = count;
        map.finish()
    }
}

/// Eqs. 25-26 for one rising / falling pair on row v; marks a candidate and says whether it
/// was one.
fn pair(
    camera: &Camera,
    map: &mut LikelihoodMap,
    max_width: f64,
    ur: f64,
    uf: f64,
    v: f64,
) -> bool {
    let (Ok(xr), Ok(xf)) = (camera.pixel_to_road(ur, v), camera.pixel_to_road(uf, v)) else {
        return false;
    };
    let width = ((xf[0] - xr[0]).powi(2) + (xf[1] - xr[1]).powi(2)).sqrt();
    if width > max_width {
        return false;
    }
    let um = (ur + uf) / 2.0;
    let (Ok(a), Ok(b)) = (
        camera.pixel_to_road(um, v - 0.5),
        camera.pixel_to_road(um, v + 0.5),
    ) else {
        return false;
    };
    map.mark_segment(a, b);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera::from_json_str(
            r#"{"width": 320, "height": 240, "fx": 256, "fy": 256, "cx": 160, "cy": 120,
                "height_m": 1.5, "pitch_deg": 4.0}"#,
        )
        .unwrap()
    }

    /// A grey frame with bright vertical stripes painted on the road at lateral positions `ys`
    /// (metres, y left) of width `widths`.
    fn road(camera: &Camera, stripes: &[(f64, f64)]) -> Image<u8> {
        let mut img = Image::new(320, 240).unwrap();
        for v in 0..240 {
            for u in 0..320 {
                let bright = camera
                    .pixel_to_road(u as f64, v as f64)
                    .map(|[x, y]| x > 0.0 && stripes.iter().any(|&(c, w)| (y - c).abs() < w / 2.0))
                    .unwrap_or(false);
                img.set(u, v, if bright { 200 } else { 60 });
            }
        }
        img
    }

    #[test]
    fn markings_become_candidates_and_wide_patterns_do_not() {
        let cam = camera();
        // Rows of the road from 6 to 15 m.
        let rows: Vec<usize> = (0..240)
            .filter(|&v| {
                cam.pixel_to_road(160.0, v as f64)
                    .map(|p| p[0] > 6.0 && p[0] < 15.0)
                    .unwrap_or(false)
            })
            .collect();
        let band = rows[0]..rows[rows.len() - 1] + 1;
        let mut map = LikelihoodMap::new(5.0, 20.0, 6.0, 0.1, 0.2).unwrap();
        let mut det = Candidates::new(DldConfig::default(), band.clone(), 0.45).unwrap();
        // A 0.15 m marking at +1.8 m and a 1.2 m wide bright patch at -2 m.
        let img = road(&cam, &[(1.8, 0.15), (-2.0, 1.2)]);
        det.detect(&img, &cam, &mut map).unwrap();
        assert!(det.count >= band.len() / 2, "{} candidates", det.count);
        for x in [7.0, 10.0, 14.0] {
            assert!(map.at(x, 1.8) > 0.6, "marking at x {x}: {}", map.at(x, 1.8));
            assert!(map.at(x, -2.0) < 0.01, "the wide patch is no marking");
        }
    }
}
