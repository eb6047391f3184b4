//! The stereo cues of `danescu-stereo` (Sec. IV, VI-A a, VI-B): disparity of the road rows,
//! 3-D points, the preliminary pitch, the road points, the road-edge selection and the density
//! image DT^D.
//!
//! 1. **Disparity** of the rows below the horizon ([`crate::vision::StereoMatcher`], census
//!    block matching), searched up to the disparity of the nearest visible road point.
//! 2. **3-D points**: each valid pixel triangulated through the rig and expressed in the road
//!    frame of the calibrated camera (x ahead, z up).
//! 3. **Preliminary pitch** (Sec. IV; the authors' ref. \[8\] detects it per frame from the
//!    lateral projection of the points): a histogram of the slopes z / x of the points between
//!    the blind spot and D_3D, in bins of `pitch_bin_rad` over +- `pitch_range_rad`; the
//!    fullest bin is the road plane's apparent tilt m, the pitch change of the car. (Obstacles
//!    stand above the road and spread over steeper slopes; the road fills one bin.)
//! 4. **Road points**: the points within `road_tolerance_m` of the line z = m x. As the paper
//!    says, this detected pitch only selects the road data; the tracked pitch and Y_0 come from
//!    the particles.
//! 5. **Road edges** (DT^E): the Canny edges whose 3-D point is a road point. Edges without a
//!    disparity (the matcher rejects ambiguous pixels) are kept: the selection removes what is
//!    known to stand off the road, not what could not be measured (our choice; the paper's
//!    dense stereo hardware measured the edges themselves).
//! 6. **Density** (Sec. VI-B): the road points in the lateral plane, [`crate::vision::Density`].
//! 7. **Curbs** (Sec. VI-A b): every point's height above the road line z = m x goes into the
//!    elevation map ([`super::elevation`]); the curbs' feet found there are projected at road
//!    height into the marking-edge image, which becomes DT^S.
//!
//! A frame whose road points are fewer than `min_road_share` of the road region's pixels
//! (a blackout, a lens covered: the matcher's few matches are noise) has no usable 3-D data
//! ([`StereoCues::usable_density`] is `None`, no curbs are marked): the particles are then
//! weighed by the image cues alone, as `danescu-mono`'s are (ours, see the option).

use super::config::DanescuConfig;
use super::cues::ImageCues;
use super::elevation::ElevationMap;
use crate::camera::{Camera, StereoRig};
use crate::error::{Error, Result};
use crate::image::{rgba_to_gray, Image};
use crate::math;
use crate::num_text::Num;
use crate::vision::{Density, DisparityConfig, StereoMatcher, EDGE};
use nalgebra::{Matrix3, Vector3};

/// A triangulated pixel: its column, its row in the road region, its distance ahead, lateral
/// offset and height.
#[derive(Debug, Clone, Copy)]
struct Point {
    u: u32,
    row: u32,
    x: f64,
    y: f64,
    z: f64,
}

/// The stereo executors and the last frame's stereo results.
#[derive(Debug, Clone)]
pub struct StereoCues {
    rig: StereoRig,
    /// Camera-to-road rotation (the transpose of the calibrated camera's).
    to_road: Matrix3<f64>,
    height: f64,
    right_gray: Image<u8>,
    matcher: StereoMatcher,
    density: Density,
    elevation: Option<ElevationMap>,
    camera: Camera,
    points: Vec<Point>,
    histogram: Vec<u32>,
    bin: f64,
    range: f64,
    near: f64,
    far: f64,
    tolerance: f64,
    min_road_share: f64,
    pitch_change: f64,
    road_points: usize,
    /// Whether the last frame's 3-D data counts (see `min_road_share`).
    usable: bool,
}

impl StereoCues {
    /// The executors for `camera`, whose file must give the baseline.
    ///
    /// # Errors
    /// [`Error::Config`] without a baseline; option errors of the matcher and the density.
    pub fn new(camera: &Camera, config: &DanescuConfig) -> Result<Self> {
        let rig = StereoRig::from_camera(camera.clone())?;
        let (w, h) = (camera.width(), camera.height());
        let [cx, _] = camera.principal_point();
        // The nearest visible road point bounds the disparities to search.
        let near = camera
            .pixel_to_road(cx, h as f64 - 1.0)
            .map_or(1.0, |[x, _]| x)
            .max(0.5);
        let d_max = rig.disparity_for_depth(near * 0.8).unwrap_or(64.0).ceil() as usize + 2;
        let matcher = StereoMatcher::new(
            w,
            h,
            DisparityConfig {
                max_disparity: d_max.min(crate::vision::MAX_DISPARITY).min(w - 1),
                ..config.disparity
            },
        )?;
        let bins = (2.0 * config.pitch_range_rad / config.pitch_bin_rad).ceil() as usize + 1;
        if bins > 100_000 {
            return Err(Error::parameter(
                "pitch_bin_rad",
                Num(config.pitch_bin_rad),
                "is too small for pitch_range_rad (over 100 000 bins)",
            ));
        }
        Ok(Self {
            to_road: camera.rotation().transpose(),
            height: camera.height_m(),
            right_gray: Image::new(w, h)?,
            matcher,
            density: Density::new(config.density)?,
            elevation: if config.curbs.enabled {
                Some(ElevationMap::new(config.curbs)?)
            } else {
                None
            },
            camera: camera.clone(),
            points: Vec::with_capacity(w * h),
            histogram: vec![0; bins],
            bin: config.pitch_bin_rad,
            range: config.pitch_range_rad,
            near,
            far: config.range_3d_m,
            tolerance: config.road_tolerance_m,
            min_road_share: config.min_road_share,
            pitch_change: 0.0,
            road_points: 0,
            usable: false,
            rig,
        })
    }

    /// The density image and DT^D of the last frame.
    pub fn density(&self) -> &Density {
        &self.density
    }

    /// The density image of the last frame when its 3-D data counts (see `min_road_share`).
    pub fn usable_density(&self) -> Option<&Density> {
        self.usable.then_some(&self.density)
    }

    /// Whether the last frame's 3-D data counts (see `min_road_share`).
    pub fn usable(&self) -> bool {
        self.usable
    }

    /// The elevation map of the last frame and the curbs found in it (`None` with curbs
    /// disabled).
    pub fn elevation(&self) -> Option<&ElevationMap> {
        self.elevation.as_ref()
    }

    /// The disparity of the last frame.
    pub fn disparity(&self) -> &Image<f32> {
        self.matcher.disparity()
    }

    /// The preliminary pitch change (the road plane's apparent slope) of the last frame,
    /// radians, positive when the camera looks further down than calibrated.
    pub fn pitch_change(&self) -> f64 {
        self.pitch_change
    }

    /// Road points selected in the last frame.
    pub fn road_points(&self) -> usize {
        self.road_points
    }

    /// Road-frame point (x ahead, y left, z up) of left pixel (u, v) with disparity d.
    #[inline]
    fn point(&self, u: usize, v: usize, d: f32) -> Option<[f64; 3]> {
        let c = self.rig.triangulate(u as f64, v as f64, d as f64)?;
        let p = self.to_road * Vector3::new(c[0], c[1], c[2]);
        Some([p.x, p.y, p.z + self.height])
    }

    /// Runs the stereo steps on the left grey image in `cues` and the right RGBA frame,
    /// then filters `cues`' road edges. Returns the milliseconds spent matching.
    ///
    /// # Errors
    /// Buffer-size errors of the right frame.
    pub fn process(&mut self, right_rgba: &[u8], cues: &mut ImageCues) -> Result<f64> {
        let (w, h) = (self.right_gray.width(), self.right_gray.height());
        rgba_to_gray(right_rgba, w, h, &mut self.right_gray)?;
        let top = cues.top();
        let t0 = super::super::now();
        {
            let left = cues.gray().view();
            self.matcher.compute(&left, &self.right_gray.view(), top)?;
        }
        let matching = super::super::now() - t0;
        // The 3-D points of the road region, triangulated once.
        self.points.clear();
        for v in top..h {
            for u in 0..w {
                let d = self.matcher.disparity().get(u, v);
                if d <= 0.0 {
                    continue;
                }
                if let Some([x, y, z]) = self.point(u, v, d) {
                    self.points.push(Point {
                        u: u as u32,
                        row: (v - top) as u32,
                        x,
                        y,
                        z,
                    });
                }
            }
        }
        // Preliminary pitch: the fullest slope bin.
        self.histogram.fill(0);
        let bins = self.histogram.len();
        for p in self
            .points
            .iter()
            .filter(|p| p.x >= self.near && p.x <= self.far)
        {
            let k = ((p.z / p.x + self.range) / self.bin).round();
            if k >= 0.0 && (k as usize) < bins {
                self.histogram[k as usize] += 1;
            }
        }
        let best = (0..bins)
            .max_by_key(|&k| (self.histogram[k], std::cmp::Reverse(k.abs_diff(bins / 2))))
            .unwrap_or(bins / 2);
        let slope = best as f64 * self.bin - self.range;
        self.pitch_change = math::atan(slope);
        // Road points: density, and the road-edge selection.
        self.density.clear();
        self.road_points = 0;
        let dz_max = self.density.config().cols as f64 * self.density.config().dz_m;
        let edges = cues.edges_mut();
        for p in &self.points {
            if (p.z - slope * p.x).abs() <= self.tolerance {
                self.road_points += 1;
                if p.x < dz_max {
                    self.density.add(p.x, p.z);
                }
            } else if edges.get(p.u as usize, p.row as usize) == EDGE {
                edges.set(p.u as usize, p.row as usize, 0);
            }
        }
        self.density.finish()?;
        let region = (w * (h - top)) as f64;
        self.usable = self.road_points as f64 >= self.min_road_share * region;
        if let Some(map) = self.elevation.as_mut() {
            map.clear();
            if !self.usable {
                return Ok(matching);
            }
            for p in &self.points {
                map.add(p.x, p.y, p.z - slope * p.x);
            }
            let fx = self.camera.focal()[0];
            let reach = map.config().snap_m;
            for f in map.find().iter().filter(|f| f.x1 > self.near) {
                let foot = |x: f64| self.camera.project([x, f.y, slope * x]);
                let x0 = f.x0.max(self.near);
                if let (Some(a), Some(b)) = (foot(x0), foot(f.x1)) {
                    cues.mark_delimiter(a, b, [reach * fx / x0, reach * fx / f.x1]);
                }
            }
        }
        Ok(matching)
    }
}
