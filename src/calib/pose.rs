//! Camera pose from the vanishing point of the lane lines, and height from the lane width.
//!
//! With no roll, [F L U] = Rz(psi) Ry(theta) (see [`crate::camera`]): the road's forward
//! direction e_x has camera coordinates (sin psi, -cos psi sin theta, cos psi cos theta), so its
//! vanishing point in undistorted pixels is
//!
//! ```text
//! u = cx + fx tan(psi) / cos(theta),   v = cy - fy tan(theta)
//! theta = atan((cy - v) / fy),         psi = atan((u - cx) cos(theta) / fx)
//! ```
//!
//! Height: the ray through a pixel, r = R^T (x_n, y_n, 1), meets the road z = 0 at t = h / -r_z,
//! so every road point scales with the camera height h. A boundary through the vanishing point
//! is parallel to e_x and has one lateral position y; at h = 1 the ego boundaries are w_1
//! apart, and a lane W metres wide gives h = W / w_1.

use crate::camera::road_to_camera_rotation;
use crate::math;
use nalgebra::Vector3;

/// Pinhole intrinsics in undistorted pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pinhole {
    /// Focal length along x, pixels.
    pub fx: f64,
    /// Focal length along y, pixels.
    pub fy: f64,
    /// Principal point x.
    pub cx: f64,
    /// Principal point y.
    pub cy: f64,
}

/// (pitch, yaw) in radians of a camera whose straight road vanishes at `vp` (undistorted
/// pixels), with no roll.
pub fn pose_from_vanishing_point(k: &Pinhole, vp: [f64; 2]) -> [f64; 2] {
    let pitch = math::atan((k.cy - vp[1]) / k.fy);
    let yaw = math::atan((vp[0] - k.cx) * math::cos(pitch) / k.fx);
    [pitch, yaw]
}

/// Undistorted pixel of the vanishing point of e_x for (pitch, yaw) in radians.
pub fn vanishing_point(k: &Pinhole, pitch: f64, yaw: f64) -> [f64; 2] {
    [
        k.cx + k.fx * math::tan(yaw) / math::cos(pitch),
        k.cy - k.fy * math::tan(pitch),
    ]
}

/// Lateral road position y (metres, left positive) of the road point seen at the undistorted
/// pixel `px` by a camera one metre above the road; `None` at or above the horizon.
pub fn lateral_at_unit_height(k: &Pinhole, pitch: f64, yaw: f64, px: [f64; 2]) -> Option<f64> {
    let rt = road_to_camera_rotation(pitch, yaw, 0.0).transpose();
    let r = rt * Vector3::new((px[0] - k.cx) / k.fx, (px[1] - k.cy) / k.fy, 1.0);
    if r.z >= -1e-9 {
        return None;
    }
    Some(r.y / -r.z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::{Camera, CameraFile};

    fn camera(pitch_deg: f64, yaw_deg: f64, height_m: f64) -> Camera {
        Camera::from_file(&CameraFile {
            fy: 510.0,
            cx: 321.0,
            cy: 236.0,
            height_m,
            pitch_deg,
            yaw_deg,
            ..CameraFile::pinhole(640, 480, 520.0)
        })
        .unwrap()
    }

    #[test]
    fn pose_and_height_come_back_from_projected_lane_lines() {
        let k = Pinhole {
            fx: 520.0,
            fy: 510.0,
            cx: 321.0,
            cy: 236.0,
        };
        for (pitch, yaw, h) in [(4.0, 0.0, 1.5), (-1.5, 2.5, 1.2), (9.0, -3.0, 2.3)] {
            let cam = camera(pitch, yaw, h);
            // Two boundaries 3.6 m apart, seen 8 m and 40 m ahead.
            let line = |y: f64| {
                [
                    cam.road_to_pixel(8.0, y).unwrap(),
                    cam.road_to_pixel(40.0, y).unwrap(),
                ]
            };
            let (l, r) = (line(1.7), line(-1.9));
            let cross = |a: [[f64; 2]; 2], b: [[f64; 2]; 2]| {
                let sa = (a[1][0] - a[0][0]) / (a[1][1] - a[0][1]);
                let sb = (b[1][0] - b[0][0]) / (b[1][1] - b[0][1]);
                let y = (b[0][0] - a[0][0] + sa * a[0][1] - sb * b[0][1]) / (sa - sb);
                [a[0][0] + sa * (y - a[0][1]), y]
            };
            let vp = cross(l, r);
            let [p, y] = pose_from_vanishing_point(&k, vp);
            assert!(
                (math::rad_to_deg(p) - pitch).abs() < 1e-9,
                "pitch {p} vs {pitch}"
            );
            assert!((math::rad_to_deg(y) - yaw).abs() < 1e-9, "yaw {y} vs {yaw}");
            let back = vanishing_point(&k, p, y);
            assert!((back[0] - vp[0]).abs() < 1e-6 && (back[1] - vp[1]).abs() < 1e-6);
            let yl = lateral_at_unit_height(&k, p, y, l[0]).unwrap();
            let yr = lateral_at_unit_height(&k, p, y, r[1]).unwrap();
            let est_h = 3.6 / (yl - yr);
            assert!((est_h - h).abs() < 1e-9, "height {est_h} vs {h}");
        }
        assert!(lateral_at_unit_height(&k, 0.0, 0.0, [300.0, 100.0]).is_none());
    }
}
