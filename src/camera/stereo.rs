//! A rectified stereo rig: two identical cameras, the right one displaced by the baseline B
//! along the left camera's X axis (to its right), image planes coplanar and rows aligned.
//!
//! A point at depth Z (camera frame) has disparity d = u_left - u_right = fx B / Z, so
//! Z = fx B / d. Lens distortion is assumed removed by rectification (the rig uses the
//! undistorted pinhole model).

use super::Camera;
use crate::error::{require_positive, Error, Result};

/// The left camera and the baseline.
#[derive(Debug, Clone, PartialEq)]
pub struct StereoRig {
    left: Camera,
    baseline_m: f64,
}

impl StereoRig {
    /// A rig from a camera whose file gives `baseline_m`.
    ///
    /// # Errors
    /// [`Error::Config`] when the camera has no baseline.
    pub fn from_camera(left: Camera) -> Result<Self> {
        let baseline_m = left.baseline_m().ok_or_else(|| {
            Error::Config(
                "a stereo rig needs `baseline_m` in the camera file (metres between the cameras)"
                    .to_string(),
            )
        })?;
        Ok(Self { left, baseline_m })
    }

    /// A rig from a camera and an explicit baseline.
    ///
    /// # Errors
    /// [`Error::Parameter`] for a baseline that is not a positive finite number.
    pub fn new(left: Camera, baseline_m: f64) -> Result<Self> {
        require_positive("baseline_m", baseline_m)?;
        Ok(Self { left, baseline_m })
    }

    /// The left (reference) camera.
    pub fn left(&self) -> &Camera {
        &self.left
    }
    /// The baseline B, metres.
    pub fn baseline_m(&self) -> f64 {
        self.baseline_m
    }

    /// Disparity (pixels) of a point at depth `z` metres; `None` for z <= 0.
    pub fn disparity_for_depth(&self, z: f64) -> Option<f64> {
        (z > 0.0).then(|| self.left.focal()[0] * self.baseline_m / z)
    }

    /// Depth (metres) of a disparity `d` pixels; `None` for d <= 0 (at infinity or invalid).
    pub fn depth_for_disparity(&self, d: f64) -> Option<f64> {
        (d > 0.0).then(|| self.left.focal()[0] * self.baseline_m / d)
    }

    /// Pixels of the road-frame point `p` in the left and right images (undistorted), or
    /// `None` when it is behind the rig.
    pub fn project(&self, p: [f64; 3]) -> Option<([f64; 2], [f64; 2])> {
        let [x, y, z] = self.left.road_to_camera(p);
        if z <= 1e-9 {
            return None;
        }
        let [fx, fy] = self.left.focal();
        let [cx, cy] = self.left.principal_point();
        let left = [cx + fx * x / z, cy + fy * y / z];
        let right = [cx + fx * (x - self.baseline_m) / z, left[1]];
        Some((left, right))
    }

    /// Camera-frame point (X, Y, Z) of left pixel (u, v) with disparity `d`; `None` for d <= 0.
    pub fn triangulate(&self, u: f64, v: f64, d: f64) -> Option<[f64; 3]> {
        let z = self.depth_for_disparity(d)?;
        let [fx, fy] = self.left.focal();
        let [cx, cy] = self.left.principal_point();
        Some([(u - cx) * z / fx, (v - cy) * z / fy, z])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::tests::caltech;

    #[test]
    fn disparity_and_depth_are_inverse_and_triangulation_recovers_points() {
        let rig = StereoRig::new(caltech(), 0.3).unwrap();
        let d = rig.disparity_for_depth(15.0).unwrap();
        assert!((d - 309.4362 * 0.3 / 15.0).abs() < 1e-12);
        assert!((rig.depth_for_disparity(d).unwrap() - 15.0).abs() < 1e-12);
        assert!(rig.depth_for_disparity(0.0).is_none());
        let p = [18.0, -1.7, 0.0];
        let (l, r) = rig.project(p).unwrap();
        assert_eq!(l[1], r[1], "rectified rows");
        let c = rig.triangulate(l[0], l[1], l[0] - r[0]).unwrap();
        let want = rig.left().road_to_camera(p);
        for k in 0..3 {
            assert!((c[k] - want[k]).abs() < 1e-9);
        }
    }

    #[test]
    fn a_rig_needs_a_baseline() {
        let e = StereoRig::from_camera(caltech()).unwrap_err();
        assert!(e.to_string().contains("baseline_m"), "{e}");
        assert!(StereoRig::new(caltech(), f64::NAN).is_err());
        let mut f = caltech().to_file();
        f.baseline_m = Some(0.24);
        let rig = StereoRig::from_camera(Camera::from_file(&f).unwrap()).unwrap();
        assert_eq!(rig.baseline_m(), 0.24);
    }
}
