//! The image-space cues of one frame (Sec. VI-A): the variable-width horizontal gradient HG,
//! the marking edges and their distance image DT^S, the road edges and their distance image
//! DT^E. Everything is computed on the rows below the horizon only (the road region), and the
//! distance images cover those rows.
//!
//! - **HG**: [`crate::vision::HGradient`], the marking's width on the road setting each row's
//!   kernel.
//! - **Markings** (the paper's ref. \[9\] extracts them from this same gradient): on each row, a
//!   dark-to-light run of the gradient (g > c) followed by a light-to-dark run (g < -c) whose
//!   extremes are between the smallest and largest marking width apart at that row's distance
//!   is a marking; both of its edges are marked. The stereo tracker adds the curbs' feet
//!   from the elevation map ([`super::elevation`]) to the same image before DT^S.
//! - **Road edges**: Canny edges of the grey image. The stereo tracker keeps those whose 3-D
//!   point is on the road (selected by the preliminary pitch, Sec. IV); the monocular one keeps
//!   all of them (it cannot tell the road from what stands on it).

use super::config::DanescuConfig;
use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::image::{rgba_to_gray, Image, ImageView};
use crate::vision::{Canny, DistanceTransform, HGradient, EDGE};

/// Distances are capped at this many pixels (the likelihoods are flat beyond it anyway).
pub const MAX_DISTANCE_PX: f32 = 50.0;

/// The cues of the last frame and the executors that make them.
#[derive(Debug, Clone)]
pub struct ImageCues {
    /// First row of the road region.
    top: usize,
    width: usize,
    height: usize,
    gray: Image<u8>,
    hgradient: HGradient,
    /// Per row of the image: smallest and largest marking width, pixels.
    marking_px: Vec<(f32, f32)>,
    contrast: f32,
    markings: Image<u8>,
    canny: Canny,
    edges: Image<u8>,
    dt: DistanceTransform,
    dt_marking: Image<f32>,
    dt_edge: Image<f32>,
    marking_count: usize,
    edge_count: usize,
}

impl ImageCues {
    /// The executors for `camera`'s frames.
    ///
    /// # Errors
    /// Option errors of the gradient and Canny; [`Error::Config`] when the camera does not
    /// see the road (the horizon at or below the bottom row).
    pub fn new(camera: &Camera, config: &DanescuConfig) -> Result<Self> {
        let (w, h) = (camera.width(), camera.height());
        let cx = camera.principal_point()[0];
        let horizon = camera.horizon_row(cx).unwrap_or(f64::INFINITY);
        // Two rows of margin below the horizon, where the road is a line of pixels.
        let top = (horizon.max(0.0) + 2.0).ceil();
        if top.is_nan() || top >= h as f64 - 8.0 {
            return Err(Error::Config(
                "the camera's horizon is at the bottom of the image: it does not see the road"
                    .into(),
            ));
        }
        let top = top as usize;
        let hgradient = HGradient::new(camera, config.hgradient)?;
        let fx = camera.focal()[0];
        let [w_min, w_max] = config.marking_width_range_m;
        let marking_px = (0..h)
            .map(|v| match camera.pixel_to_road(cx, v as f64) {
                Ok([x, _]) if x > 0.0 => ((fx * w_min / x) as f32, (fx * w_max / x) as f32 + 1.0),
                _ => (f32::INFINITY, 0.0),
            })
            .collect();
        let region = h - top;
        Ok(Self {
            top,
            width: w,
            height: h,
            gray: Image::new(w, h)?,
            hgradient,
            marking_px,
            contrast: config.marking_contrast,
            markings: Image::new(w, region)?,
            canny: Canny::new(config.canny)?,
            edges: Image::new(w, region)?,
            dt: DistanceTransform::new(),
            dt_marking: Image::new(w, region)?,
            dt_edge: Image::new(w, region)?,
            marking_count: 0,
            edge_count: 0,
        })
    }

    /// First image row of the road region.
    pub fn top(&self) -> usize {
        self.top
    }

    /// The grey image of the last frame.
    pub fn gray(&self) -> &Image<u8> {
        &self.gray
    }

    /// HG of the last frame.
    pub fn hgradient(&self) -> &Image<u8> {
        self.hgradient.image()
    }

    /// Road edges of the last frame (region rows: row 0 is image row [`ImageCues::top`]).
    pub fn edges_mut(&mut self) -> &mut Image<u8> {
        &mut self.edges
    }

    /// Marking-edge pixels and road-edge pixels found in the last frame.
    pub fn counts(&self) -> (usize, usize) {
        (self.marking_count, self.edge_count)
    }

    /// Converts the frame, computes HG, the markings and the road edges. The distance images
    /// follow in [`ImageCues::finish`], after the stereo tracker has filtered the edges.
    ///
    /// # Errors
    /// Buffer-size errors of the frame.
    pub fn begin(&mut self, rgba: &[u8]) -> Result<()> {
        rgba_to_gray(rgba, self.width, self.height, &mut self.gray)?;
        self.hgradient.apply(&self.gray.view())?;
        self.find_markings();
        let region = self.height - self.top;
        let data = &self.gray.data()[self.top * self.width..];
        let view = ImageView::new(data, self.width, region, self.width)?;
        self.canny.apply(&view, &mut self.edges)?;
        Ok(())
    }

    /// The distance images DT^S and DT^E of the markings and of the (filtered) road edges.
    ///
    /// # Errors
    /// Never for buffers built by [`ImageCues::new`].
    pub fn finish(&mut self) -> Result<()> {
        self.edge_count = self.edges.data().iter().filter(|&&e| e == EDGE).count();
        self.dt
            .apply_capped(&self.markings.view(), MAX_DISTANCE_PX, &mut self.dt_marking)?;
        self.dt
            .apply_capped(&self.edges.view(), MAX_DISTANCE_PX, &mut self.dt_edge)?;
        Ok(())
    }

    /// Marks the segment from image point `a` to `b` (pixels) as a delimiter edge in the
    /// marking-edge image (a curb's foot, [`super::elevation`]). Each of its pixels snaps to
    /// the nearest road edge on its row within `snap` pixels (interpolated from `a` to `b`),
    /// if there is one: the elevation map places a foot to a cell, the image edge of the
    /// face's foot to a pixel. Parts outside the road region are left out. Returns the pixels
    /// newly marked.
    pub fn mark_delimiter(&mut self, a: [f64; 2], b: [f64; 2], snap: [f64; 2]) -> usize {
        let steps = (b[0] - a[0]).abs().max((b[1] - a[1]).abs()).ceil().max(1.0);
        if !steps.is_finite() || steps > (self.width + self.height) as f64 * 4.0 {
            return 0;
        }
        let mut marked = 0;
        for k in 0..=steps as usize {
            let f = k as f64 / steps;
            let (u, v) = (
                (a[0] + (b[0] - a[0]) * f).round(),
                (a[1] + (b[1] - a[1]) * f).round(),
            );
            if u < 0.0 || u >= self.width as f64 || v < self.top as f64 || v >= self.height as f64 {
                continue;
            }
            let (u, row) = (u as usize, v as usize - self.top);
            let reach = (snap[0] + (snap[1] - snap[0]) * f).clamp(0.0, 64.0) as usize;
            let edges = self.edges.row(row);
            let u = (0..=reach)
                .flat_map(|d| [u.checked_sub(d), Some(u + d)])
                .flatten()
                .find(|&x| x < self.width && edges[x] == EDGE)
                .unwrap_or(u);
            if self.markings.get(u, row) == 0 {
                self.markings.set(u, row, 1);
                marked += 1;
            }
        }
        self.marking_count += marked;
        marked
    }

    fn find_markings(&mut self) {
        self.markings.fill(0);
        self.marking_count = 0;
        let c = self.contrast;
        let w = self.width;
        for v in self.top..self.height {
            let (lo, hi) = self.marking_px[v];
            let g = self.hgradient.difference().row(v);
            let out = self.markings.row_mut(v - self.top);
            let mut u = 0;
            while u < w {
                if g[u] <= c {
                    u += 1;
                    continue;
                }
                // A dark-to-light run: its strongest pixel (the first of a plateau) is the
                // left edge, between that pixel and the next.
                let mut best = u;
                while u < w && g[u] > c {
                    if g[u] > g[best] {
                        best = u;
                    }
                    u += 1;
                }
                // The light-to-dark run that follows within the largest width.
                let limit = (best as f32 + hi + 2.0).min(w as f32) as usize;
                let mut k = u;
                while k < limit && g[k] >= -c {
                    k += 1;
                }
                if k >= limit {
                    continue;
                }
                let mut worst = k;
                while k < w && g[k] < -c {
                    if g[k] < g[worst] {
                        worst = k;
                    }
                    k += 1;
                }
                let width = (worst - best) as f32;
                if width >= lo && width <= hi {
                    out[best + 1] = 1;
                    out[worst] = 1;
                    self.marking_count += 2;
                }
                u = k;
            }
        }
    }

    /// DT^S at image pixel (u, v) (rounded), capped; `None` outside the road region.
    #[inline]
    pub fn marking_distance(&self, u: f64, v: f64) -> Option<f32> {
        self.lookup(&self.dt_marking, u, v)
    }

    /// DT^E at image pixel (u, v).
    #[inline]
    pub fn edge_distance(&self, u: f64, v: f64) -> Option<f32> {
        self.lookup(&self.dt_edge, u, v)
    }

    /// HG at image pixel (u, v); `None` outside the road region.
    #[inline]
    pub fn gradient(&self, u: f64, v: f64) -> Option<u8> {
        let (u, v) = self.pixel(u, v)?;
        Some(self.hgradient.image().get(u, v + self.top))
    }

    #[inline]
    fn pixel(&self, u: f64, v: f64) -> Option<(usize, usize)> {
        // Nearest pixel; truncation is the floor for the non-negative values kept (and NaN
        // fails the comparisons).
        let (a, b) = (u + 0.5, v + 0.5 - self.top as f64);
        if !(a >= 0.0 && b >= 0.0) {
            return None;
        }
        let (u, v) = (a as usize, b as usize);
        (u < self.width && v < self.height - self.top).then_some((u, v))
    }

    #[inline]
    fn lookup(&self, img: &Image<f32>, u: f64, v: f64) -> Option<f32> {
        let (u, v) = self.pixel(u, v)?;
        Some(img.get(u, v))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{default_camera, scenario, Eye, Scene};

    #[test]
    fn marking_edges_lie_on_the_true_markings() {
        let camera = default_camera(640, 480).unwrap();
        let mut scene =
            Scene::new(scenario("highway-straight").unwrap(), camera.clone(), 1).unwrap();
        let mut rgba = vec![0; 640 * 480 * 4];
        scene.render(0, Eye::Left, &mut rgba, None).unwrap();
        let mut cues = ImageCues::new(&camera, &DanescuConfig::default()).unwrap();
        cues.begin(&rgba).unwrap();
        cues.finish().unwrap();
        let (markings, edges) = cues.counts();
        assert!(markings > 500 && edges > markings, "{markings} {edges}");
        // Every marking edge is within 0.2 m (half a marking and a pixel) of a true boundary.
        let pose = scene.pose(0);
        let mut off = 0;
        for r in 0..cues.markings.height() {
            for u in 0..640 {
                if cues.markings.get(u, r) == 0 {
                    continue;
                }
                let v = (r + cues.top()) as f64;
                let [x, y] = camera.pixel_to_road(u as f64, v).unwrap();
                let on = (0..=scene.road().lanes())
                    .filter_map(|k| scene.boundary_y(&pose, k, x))
                    .any(|t| (t - y).abs() < 0.2 + x / camera.focal()[0]);
                off += usize::from(!on);
            }
        }
        assert!(
            off * 50 < markings,
            "{off} of {markings} marking edges off the markings"
        );
        // Distance images: the true ego boundaries (dashed or solid) run along marking and
        // road edges for at least a fifth of their length.
        let truth = crate::trackers::scene_truth(&scene, 0);
        for b in &truth.boundaries[..2] {
            // Within half a near marking's width (the truth is the marking's centre line).
            let near = |d: Option<f32>| d.is_some_and(|d| d <= 5.0);
            let n = b.points.len();
            let on_marking = b
                .points
                .iter()
                .filter(|p| near(cues.marking_distance(p[0], p[1])));
            let on_edge = b
                .points
                .iter()
                .filter(|p| near(cues.edge_distance(p[0], p[1])));
            let (m, e) = (on_marking.count(), on_edge.count());
            assert!(m * 5 >= n && e * 5 >= n, "{:?}: {m} {e} of {n}", b.role);
        }
        let p = truth.boundaries[0].points[0];
        assert!(cues.marking_distance(p[0], 0.0).is_none());
    }
}
