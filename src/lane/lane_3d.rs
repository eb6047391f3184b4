//! The 11-parameter 3-D lane of Danescu & Nedevschi 2011 (Sec. II, eqs. 1-4) and its
//! projection through a camera whose pose the lane's own parameters set.
//!
//! The paper's frame: X lateral (to the right), Y vertical (up), Z ahead, origin on the road
//! under the camera. With the lateral offset X_CW, the yaw psi and the horizontal curvature
//! C_H, the lane centre is X_C(Z) = X_CW + psi Z + C_H Z^2 / 2 (the clothoid of the authors'
//! earlier model, their ref. \[8\], to second order), and
//!
//! ```text
//! W(Z)      = W_0 + W_l Z                                   (eq. 1)
//! X_LIn(Z)  = X_C(Z) - W(Z)/2,   X_RIn(Z) = X_C(Z) + W(Z)/2  (eq. 2)
//! X_LOut(Z) = X_LIn(Z) - W_L,    X_ROut(Z) = X_RIn(Z) + W_R  (eq. 3)
//! Y_C(Z)    = Y_0 + alpha Z + C_V Z^2 / 2                    (eq. 4)
//! ```
//!
//! Signs: X_CW > 0 when the lane centre is to the right of the camera, psi > 0 when the lane
//! heads to the right, C_H > 0 when it curves to the right, C_V > 0 when the road bends up.
//! W is the width between the inner edges of the markings; W_L, W_R the marking widths.
//!
//! **Vertical profile as a camera pose.** Eq. 4 describes the road height in a frame fixed to
//! the car: the pitch alpha tilts it and the offset Y_0 lifts it. Seen from the camera this is
//! the same as the camera being at height h + Y_0 above the road (which itself rises by
//! C_V Z^2 / 2) and pitched by alpha, rolled by gamma. We project exactly that: each lane
//! builds the camera of its own pose (calibrated intrinsics, distortion and yaw; pitch alpha,
//! roll gamma, height h + Y_0), so alpha is the camera's absolute pitch (the calibrated pitch
//! when the car is at rest) and Y_0 the change of its height. To first order in alpha this is
//! eq. 4; it stays exact for the larger angles of a steep camera. [`Lane3d::road_height`]
//! gives eq. 4 itself (heights relative to the calibrated camera pose), which the discrete
//! 3-D space of eqs. 5-8 uses.

use crate::camera::{road_to_camera_rotation, Camera};
use nalgebra::{Matrix3, Vector3};

/// The 11 lane parameters of Danescu & Nedevschi 2011 (Sec. II), metres and radians.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Lane3d {
    /// W_0: lane width at Z = 0 between the inner marking edges.
    pub w0: f64,
    /// C_H: horizontal curvature, 1/m, positive to the right.
    pub ch: f64,
    /// W_l: width change per metre ahead (eq. 1).
    pub wl: f64,
    /// C_V: vertical curvature, 1/m, positive upwards.
    pub cv: f64,
    /// Y_0: change of the camera's height above the road, metres.
    pub y0: f64,
    /// X_CW: lateral offset of the lane centre, metres, positive to the right.
    pub xcw: f64,
    /// alpha: the camera's pitch over the road, radians, positive looking down.
    pub alpha: f64,
    /// gamma: the camera's roll over the road, radians.
    pub gamma: f64,
    /// psi: the lane's yaw relative to the car, radians, positive to the right.
    pub psi: f64,
    /// W_L: width of the left marking (0 for no marking).
    pub wl_mark: f64,
    /// W_R: width of the right marking.
    pub wr_mark: f64,
}

/// The four delimiter edges of eqs. 2-3.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Edge {
    /// X_LOut: the left marking's outer (left) edge.
    LeftOuter,
    /// X_LIn: the left marking's inner (right) edge.
    LeftInner,
    /// X_RIn: the right marking's inner (left) edge.
    RightInner,
    /// X_ROut: the right marking's outer (right) edge.
    RightOuter,
}

impl Lane3d {
    /// Parameter names in the order of [`Lane3d::to_array`] (the `danescu.*` ground-truth keys).
    pub const NAMES: [&'static str; 11] = [
        "w0", "ch", "wl", "cv", "y0", "xcw", "alpha", "gamma", "psi", "wl_mark", "wr_mark",
    ];

    /// The parameters as an array, in the order of [`Lane3d::NAMES`].
    pub fn to_array(&self) -> [f64; 11] {
        [
            self.w0,
            self.ch,
            self.wl,
            self.cv,
            self.y0,
            self.xcw,
            self.alpha,
            self.gamma,
            self.psi,
            self.wl_mark,
            self.wr_mark,
        ]
    }

    /// The lane of an array in the order of [`Lane3d::NAMES`].
    pub fn from_array(a: [f64; 11]) -> Self {
        Self {
            w0: a[0],
            ch: a[1],
            wl: a[2],
            cv: a[3],
            y0: a[4],
            xcw: a[5],
            alpha: a[6],
            gamma: a[7],
            psi: a[8],
            wl_mark: a[9],
            wr_mark: a[10],
        }
    }

    /// W(Z), eq. 1.
    pub fn width(&self, z: f64) -> f64 {
        self.w0 + self.wl * z
    }

    /// X_C(Z): the lane centre Z metres ahead.
    pub fn centre(&self, z: f64) -> f64 {
        self.xcw + self.psi * z + self.ch * z * z / 2.0
    }

    /// X of `edge` Z metres ahead, eqs. 2-3.
    pub fn edge_x(&self, edge: Edge, z: f64) -> f64 {
        let half = self.width(z) / 2.0;
        let c = self.centre(z);
        match edge {
            Edge::LeftOuter => c - half - self.wl_mark,
            Edge::LeftInner => c - half,
            Edge::RightInner => c + half,
            Edge::RightOuter => c + half + self.wr_mark,
        }
    }

    /// X of the left (`right` false) or right marking's centre line Z metres ahead: the
    /// boundary reported as output (the middle of a marking, or the road edge when its width
    /// is 0).
    pub fn marking_centre_x(&self, right: bool, z: f64) -> f64 {
        let half = self.width(z) / 2.0;
        if right {
            self.centre(z) + half + self.wr_mark / 2.0
        } else {
            self.centre(z) - half - self.wl_mark / 2.0
        }
    }

    /// Y_C(Z) of eq. 4: the road height Z metres ahead in the road frame of the calibrated
    /// camera (`alpha0` its pitch), to first order in the pitch change: a camera raised by
    /// Y_0 sees the road Y_0 lower, and one pitched further down by alpha - alpha0 reads the
    /// road as rising by that slope.
    pub fn road_height(&self, alpha0: f64, z: f64) -> f64 {
        -self.y0 + (self.alpha - alpha0) * z + self.cv * z * z / 2.0
    }
}

/// The camera a [`Lane3d`] implies: the calibrated intrinsics and yaw with the lane's pitch,
/// roll and height offset. Building one costs a rotation matrix (six sines and cosines).
#[derive(Debug, Clone, Copy)]
pub struct LaneCamera<'a> {
    camera: &'a Camera,
    rotation: Matrix3<f64>,
    height: f64,
    cv: f64,
}

impl<'a> LaneCamera<'a> {
    /// The pose of `lane` on `camera`.
    pub fn new(camera: &'a Camera, lane: &Lane3d) -> Self {
        Self {
            camera,
            rotation: road_to_camera_rotation(lane.alpha, camera.yaw(), lane.gamma),
            height: camera.height_m() + lane.y0,
            cv: lane.cv,
        }
    }

    /// Pixel of the road point X metres to the right, Z metres ahead, on the lane's vertical
    /// profile; `None` when it is behind the camera.
    pub fn project(&self, x: f64, z: f64) -> Option<[f64; 2]> {
        let d = Vector3::new(z, -x, self.cv * z * z / 2.0 - self.height);
        let c = self.rotation * d;
        self.camera.camera_to_pixel([c.x, c.y, c.z])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::default_camera;

    fn lane() -> Lane3d {
        Lane3d {
            w0: 3.4,
            ch: 0.002,
            wl: 0.01,
            cv: 0.0005,
            y0: 0.02,
            xcw: 0.3,
            alpha: 0.1,
            gamma: 0.01,
            psi: -0.02,
            wl_mark: 0.15,
            wr_mark: 0.2,
        }
    }

    #[test]
    fn edges_follow_eqs_1_to_3() {
        let l = lane();
        let z = 20.0;
        let w = 3.4 + 0.01 * z;
        let c = 0.3 - 0.02 * z + 0.002 * z * z / 2.0;
        assert!((l.width(z) - w).abs() < 1e-12);
        assert!((l.edge_x(Edge::LeftInner, z) - (c - w / 2.0)).abs() < 1e-12);
        assert!((l.edge_x(Edge::RightInner, z) - (c + w / 2.0)).abs() < 1e-12);
        assert!((l.edge_x(Edge::LeftOuter, z) - (c - w / 2.0 - 0.15)).abs() < 1e-12);
        assert!((l.edge_x(Edge::RightOuter, z) - (c + w / 2.0 + 0.2)).abs() < 1e-12);
        assert!((l.marking_centre_x(true, z) - (c + w / 2.0 + 0.1)).abs() < 1e-12);
        assert_eq!(Lane3d::from_array(l.to_array()), l);
    }

    #[test]
    fn the_lane_camera_of_the_calibrated_pose_is_the_calibrated_camera() {
        let camera = default_camera(640, 480).unwrap();
        let flat = Lane3d {
            alpha: camera.pitch(),
            ..Lane3d::default()
        };
        let lc = LaneCamera::new(&camera, &flat);
        for (x, z) in [(0.0, 5.0), (-1.8, 12.0), (3.0, 40.0)] {
            let a = lc.project(x, z).unwrap();
            let b = camera.road_to_pixel(z, -x).unwrap();
            assert!((a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9);
        }
        assert!(lc.project(0.0, -3.0).is_none());
    }
}
