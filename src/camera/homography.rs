//! The ground-plane homographies of a camera.
//!
//! For road points (x, y, 0) the camera coordinates are R (x, y, -h)^T = M (x, y, 1)^T with
//! M = [r1 | r2 | -h r3] (r_i the columns of the road-to-camera rotation R). With the
//! intrinsics K, the road-to-image homography is H = K M (pixels up to scale, no lens
//! distortion); the image-to-road one is H^-1. A homogeneous result with w <= 0 is behind the
//! camera (road to image) or above the horizon (image to road).

use super::Camera;
use nalgebra::{Matrix3, Vector3};

/// The pair of 3x3 homographies between the road plane (metres) and the undistorted image
/// (pixels).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundHomography {
    /// Road (x, y, 1) to pixel (u, v, 1), up to scale.
    pub road_to_image: Matrix3<f64>,
    /// Pixel (u, v, 1) to road (x, y, 1), up to scale.
    pub image_to_road: Matrix3<f64>,
}

impl GroundHomography {
    /// Builds both homographies of `camera`.
    pub fn new(camera: &Camera) -> Self {
        let r = camera.rotation();
        let h = camera.height_m();
        let m = Matrix3::from_columns(&[r.column(0).into(), r.column(1).into(), -h * r.column(2)]);
        let road_to_image = camera.intrinsics() * m;
        // M is invertible for h > 0 (det M = -h det R = -h) and K is invertible for fx, fy > 0,
        // which Camera guarantees; the fallback is never taken for a validated camera.
        let image_to_road = road_to_image.try_inverse().unwrap_or_else(Matrix3::zeros);
        Self {
            road_to_image,
            image_to_road,
        }
    }

    /// Undistorted pixel of the road point (x, y), or `None` behind the camera.
    pub fn to_image(&self, x: f64, y: f64) -> Option<[f64; 2]> {
        apply(&self.road_to_image, x, y)
    }

    /// Road point of the undistorted pixel (u, v), or `None` at or above the horizon.
    pub fn to_road(&self, u: f64, v: f64) -> Option<[f64; 2]> {
        apply(&self.image_to_road, u, v)
    }
}

fn apply(m: &Matrix3<f64>, a: f64, b: f64) -> Option<[f64; 2]> {
    let p = m * Vector3::new(a, b, 1.0);
    // Both maps are scaled so that w is the depth-like quantity: positive in front / below the
    // horizon. H^-1 inherits the sign convention: w = 1/Z > 0 for points on the road ahead.
    (p.z > 1e-12).then(|| [p.x / p.z, p.y / p.z])
}

#[cfg(test)]
mod tests {
    use crate::camera::tests::caltech;

    #[test]
    fn homographies_agree_with_the_camera_model() {
        let c = caltech();
        let g = c.ground_homography();
        for (x, y) in [(6.0, 0.0), (20.0, 1.8), (55.0, -5.0)] {
            let p = g.to_image(x, y).unwrap();
            let q = c.road_to_pixel(x, y).unwrap();
            assert!((p[0] - q[0]).abs() < 1e-9 && (p[1] - q[1]).abs() < 1e-9);
            let r = g.to_road(p[0], p[1]).unwrap();
            assert!((r[0] - x).abs() < 1e-9 && (r[1] - y).abs() < 1e-9);
        }
        assert!(g.to_image(-3.0, 0.0).is_none(), "behind the camera");
        assert!(g.to_road(320.0, 50.0).is_none(), "above the horizon");
    }
}
