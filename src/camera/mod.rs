//! Camera geometry: a pinhole camera with lens distortion, mounted at a height above a flat
//! road with pitch, yaw and roll; projection of road points to pixels and back, the
//! ground-plane homographies, and the stereo rig.
//!
//! Frames (see the crate docs): the road frame is ISO 8855 (x forward, y left, z up, origin on
//! the road under the camera); the camera frame is the computer-vision one (X right, Y down,
//! Z along the optical axis). The camera's optical centre is at C = (0, 0, h). Its orientation
//! is R = Rz(yaw) Ry(pitch) Rx(roll): forward F = R e_x, left L = R e_y, up U = R e_z, so a
//! positive pitch (a positive rotation about the left axis) tilts the optical axis down. A road
//! point P has camera coordinates
//!
//! ```text
//! X = -L . (P - C),   Y = -U . (P - C),   Z = F . (P - C)
//! ```
//!
//! and, with the normalised point (X/Z, Y/Z) passed through the lens [`Distortion`], pixel
//! u = cx + fx x_d, v = cy + fy y_d. On the road plane (z = 0) the undistorted map is the
//! homography H = K [-L | -U | F]^T [e_x | e_y | -h e_z] of [`GroundHomography`].

mod distortion;
mod file;
mod homography;
mod stereo;

pub use distortion::Distortion;
pub use file::CameraFile;
pub use homography::GroundHomography;
pub use stereo::StereoRig;

use crate::error::{require_finite, require_positive, Error, Result};
use crate::image::check_dimensions;
use crate::math;
use crate::num_text::{Fixed, Num};
use nalgebra::{Matrix3, Vector3};

/// Largest accepted |pitch|, |yaw|, |roll| in degrees: beyond it the camera does not see the
/// road ahead in any useful way.
pub const MAX_ANGLE_DEG: f64 = 80.0;
/// Largest accepted camera height above the road, metres.
pub const MAX_HEIGHT_M: f64 = 100.0;

/// A validated camera: intrinsics, distortion and mounting.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    file: CameraFile,
    distortion: Distortion,
    /// Rows: camera X, Y, Z axes expressed in the road frame (-L, -U, F).
    rotation: Matrix3<f64>,
    /// Squared normalised radius beyond which the lens model folds over
    /// ([`Distortion::monotonic_r2`]): nothing beyond it is projected.
    fold_r2: f64,
}

impl Camera {
    /// Validates a camera file.
    ///
    /// # Errors
    /// [`Error::Dimensions`] for a zero or oversized image; [`Error::Parameter`] naming the
    /// field for a NaN/infinite value, a non-positive focal length or height, an angle beyond
    /// ±[`MAX_ANGLE_DEG`], or a non-positive stereo baseline.
    pub fn from_file(file: &CameraFile) -> Result<Self> {
        check_dimensions(file.width, file.height)?;
        require_positive("fx", file.fx)?;
        require_positive("fy", file.fy)?;
        for (name, v) in [("cx", file.cx), ("cy", file.cy)] {
            require_finite(name, v)?;
        }
        require_positive("height_m", file.height_m)?;
        if file.height_m > MAX_HEIGHT_M {
            return Err(Error::parameter(
                "height_m",
                Num(file.height_m),
                &format!("must be at most {} m", Num(MAX_HEIGHT_M)),
            ));
        }
        for (name, v) in [
            ("pitch_deg", file.pitch_deg),
            ("yaw_deg", file.yaw_deg),
            ("roll_deg", file.roll_deg),
        ] {
            require_finite(name, v)?;
            if v.abs() > MAX_ANGLE_DEG {
                return Err(Error::parameter(
                    name,
                    Num(v),
                    &format!("must be between -{0} and {0} degrees", Num(MAX_ANGLE_DEG)),
                ));
            }
        }
        for (name, v) in [
            ("k1", file.k1),
            ("k2", file.k2),
            ("p1", file.p1),
            ("p2", file.p2),
            ("k3", file.k3),
        ] {
            require_finite(name, v)?;
        }
        if let Some(b) = file.baseline_m {
            require_positive("baseline_m", b)?;
        }
        let distortion = Distortion {
            k1: file.k1,
            k2: file.k2,
            p1: file.p1,
            p2: file.p2,
            k3: file.k3,
        };
        Ok(Self {
            file: file.clone(),
            fold_r2: distortion.monotonic_r2(),
            distortion,
            rotation: road_to_camera_rotation(
                math::deg_to_rad(file.pitch_deg),
                math::deg_to_rad(file.yaw_deg),
                math::deg_to_rad(file.roll_deg),
            ),
        })
    }

    /// Parses and validates `camera.json` text.
    ///
    /// # Errors
    /// As [`CameraFile::from_json_str`] and [`Camera::from_file`].
    pub fn from_json_str(text: &str) -> Result<Self> {
        Self::from_file(&CameraFile::from_json_str(text)?)
    }

    /// Reads and validates a `camera.json` file.
    ///
    /// # Errors
    /// As [`CameraFile::read`] and [`Camera::from_file`].
    pub fn load(path: &std::path::Path) -> Result<Self> {
        Self::from_file(&CameraFile::read(path)?)
    }

    /// The camera as a file description.
    pub fn to_file(&self) -> CameraFile {
        self.file.clone()
    }

    /// Image width, pixels.
    pub fn width(&self) -> usize {
        self.file.width
    }
    /// Image height, pixels.
    pub fn height(&self) -> usize {
        self.file.height
    }
    /// Height of the optical centre above the road, metres.
    pub fn height_m(&self) -> f64 {
        self.file.height_m
    }
    /// Pitch, radians (positive looking down).
    pub fn pitch(&self) -> f64 {
        math::deg_to_rad(self.file.pitch_deg)
    }
    /// Yaw, radians (positive to the left).
    pub fn yaw(&self) -> f64 {
        math::deg_to_rad(self.file.yaw_deg)
    }
    /// Roll, radians.
    pub fn roll(&self) -> f64 {
        math::deg_to_rad(self.file.roll_deg)
    }
    /// Focal lengths (fx, fy), pixels.
    pub fn focal(&self) -> [f64; 2] {
        [self.file.fx, self.file.fy]
    }
    /// Principal point (cx, cy), pixels.
    pub fn principal_point(&self) -> [f64; 2] {
        [self.file.cx, self.file.cy]
    }
    /// The lens distortion.
    pub fn distortion(&self) -> &Distortion {
        &self.distortion
    }
    /// The stereo baseline, if the file gives one.
    pub fn baseline_m(&self) -> Option<f64> {
        self.file.baseline_m
    }
    /// Intrinsic matrix K.
    pub fn intrinsics(&self) -> Matrix3<f64> {
        let f = &self.file;
        Matrix3::new(f.fx, 0.0, f.cx, 0.0, f.fy, f.cy, 0.0, 0.0, 1.0)
    }
    /// Rotation from road-frame directions to camera-frame directions (rows -L, -U, F).
    pub fn rotation(&self) -> &Matrix3<f64> {
        &self.rotation
    }

    /// Camera coordinates (X right, Y down, Z forward) of the road-frame point `p`.
    pub fn road_to_camera(&self, p: [f64; 3]) -> [f64; 3] {
        let d = Vector3::new(p[0], p[1], p[2] - self.file.height_m);
        let c = self.rotation * d;
        [c.x, c.y, c.z]
    }

    /// Pixel of a camera-frame point, or `None` when it is not in front of the camera or lies
    /// beyond the radius where the lens model folds over (where it would be drawn back inside
    /// the image although it is far outside the field of view).
    pub fn camera_to_pixel(&self, c: [f64; 3]) -> Option<[f64; 2]> {
        if c[2] <= 1e-9 {
            return None;
        }
        let (x, y) = (c[0] / c[2], c[1] / c[2]);
        if x * x + y * y > self.fold_r2 {
            return None;
        }
        let [xd, yd] = self.distortion.distort(x, y);
        Some([
            self.file.cx + self.file.fx * xd,
            self.file.cy + self.file.fy * yd,
        ])
    }

    /// Pixel of the 3-D road-frame point `p`, or `None` when it is behind the camera.
    pub fn project(&self, p: [f64; 3]) -> Option<[f64; 2]> {
        self.camera_to_pixel(self.road_to_camera(p))
    }

    /// Pixel of the road-plane point (x, y, 0), or `None` when it is behind the camera.
    pub fn road_to_pixel(&self, x: f64, y: f64) -> Option<[f64; 2]> {
        self.project([x, y, 0.0])
    }

    /// Undistorted normalised coordinates of a pixel (the direction (x, y, 1) in the camera
    /// frame).
    ///
    /// # Errors
    /// [`Error::Geometry`] where the lens model cannot be inverted.
    pub fn pixel_to_normalised(&self, u: f64, v: f64) -> Result<[f64; 2]> {
        let f = &self.file;
        self.distortion
            .undistort((u - f.cx) / f.fx, (v - f.cy) / f.fy)
    }

    /// Direction, in the road frame, of the ray through pixel (u, v) (not unit length).
    ///
    /// # Errors
    /// As [`Camera::pixel_to_normalised`].
    pub fn pixel_ray(&self, u: f64, v: f64) -> Result<[f64; 3]> {
        let [x, y] = self.pixel_to_normalised(u, v)?;
        let r = self.rotation.transpose() * Vector3::new(x, y, 1.0);
        Ok([r.x, r.y, r.z])
    }

    /// Road-plane point (x, y) seen at pixel (u, v).
    ///
    /// # Errors
    /// [`Error::Geometry`] when the pixel's ray does not meet the road ahead (at or above the
    /// horizon) or the lens model cannot be inverted there.
    pub fn pixel_to_road(&self, u: f64, v: f64) -> Result<[f64; 2]> {
        self.ray_to_road(self.pixel_ray(u, v)?, u, v)
    }

    /// Road-plane point (x, y) seen at the undistorted pixel (u, v) (a pixel of the pinhole
    /// image, lens distortion already removed, as the calibrator's lines are).
    ///
    /// # Errors
    /// [`Error::Geometry`] at or above the horizon.
    pub fn undistorted_pixel_to_road(&self, u: f64, v: f64) -> Result<[f64; 2]> {
        let f = &self.file;
        let n = Vector3::new((u - f.cx) / f.fx, (v - f.cy) / f.fy, 1.0);
        let r = self.rotation.transpose() * n;
        self.ray_to_road([r.x, r.y, r.z], u, v)
    }

    /// Where the ray `r` from the camera, seen at pixel (u, v), meets the road.
    fn ray_to_road(&self, r: [f64; 3], u: f64, v: f64) -> Result<[f64; 2]> {
        // The ray C + t r meets z = 0 at t = h / -r_z; it must descend, and not so slowly
        // that the point is absurdly far (beyond 1e6 camera heights).
        if r[2] >= -1e-6 * (r[0] * r[0] + r[1] * r[1]).sqrt() {
            return Err(Error::Geometry(format!(
                "pixel ({}, {}) is at or above the horizon: its ray never meets the road",
                Fixed(u, 1),
                Fixed(v, 1)
            )));
        }
        let t = self.file.height_m / -r[2];
        Ok([t * r[0], t * r[1]])
    }

    /// Image row of the horizon at column `u` (where rays become parallel to the road),
    /// ignoring lens distortion; `None` when the horizon is parallel to the image columns
    /// (impossible within the accepted angles).
    pub fn horizon_row(&self, u: f64) -> Option<f64> {
        // Ray z-component: x (-L_z) + y (-U_z) + F_z = 0 with x = (u - cx) / fx.
        let rt = self.rotation.transpose();
        let (a, b, c) = (rt[(2, 0)], rt[(2, 1)], rt[(2, 2)]);
        if b.abs() < 1e-12 {
            return None;
        }
        let x = (u - self.file.cx) / self.file.fx;
        Some(self.file.cy + self.file.fy * (-(a * x + c) / b))
    }

    /// The ground-plane homographies of this camera (ignoring lens distortion).
    pub fn ground_homography(&self) -> GroundHomography {
        GroundHomography::new(self)
    }
}

/// R (road to camera): rows are the camera's X = -L, Y = -U, Z = F axes in road coordinates,
/// with [F L U] = Rz(yaw) Ry(pitch) Rx(roll).
pub(crate) fn road_to_camera_rotation(pitch: f64, yaw: f64, roll: f64) -> Matrix3<f64> {
    let (sp, cp) = (math::sin(pitch), math::cos(pitch));
    let (sy, cy) = (math::sin(yaw), math::cos(yaw));
    let (sr, cr) = (math::sin(roll), math::cos(roll));
    let rz = Matrix3::new(cy, -sy, 0.0, sy, cy, 0.0, 0.0, 0.0, 1.0);
    let ry = Matrix3::new(cp, 0.0, sp, 0.0, 1.0, 0.0, -sp, 0.0, cp);
    let rx = Matrix3::new(1.0, 0.0, 0.0, 0.0, cr, -sr, 0.0, sr, cr);
    let body = rz * ry * rx; // columns F, L, U
    let (f, l, u) = (body.column(0), body.column(1), body.column(2));
    Matrix3::from_rows(&[(-l).transpose(), (-u).transpose(), f.transpose()])
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The Caltech Cordova camera of ../shared/data (camera.json).
    pub(crate) fn caltech() -> Camera {
        Camera::from_json_str(
            r#"{ "width": 640, "height": 480, "fx": 309.4362, "fy": 344.2161,
                 "cx": 317.9034, "cy": 256.5352, "height_m": 2.1798, "pitch_deg": 14.0 }"#,
        )
        .unwrap()
    }

    fn with(edit: impl FnOnce(&mut CameraFile)) -> Result<Camera> {
        let mut f = caltech().to_file();
        edit(&mut f);
        Camera::from_file(&f)
    }

    #[test]
    fn level_camera_matches_the_textbook_formulas() {
        let c = with(|f| f.pitch_deg = 0.0).unwrap();
        // u = cx - fx y / x, v = cy + fy h / x.
        let [u, v] = c.road_to_pixel(20.0, 1.5).unwrap();
        assert!((u - (317.9034 - 309.4362 * 1.5 / 20.0)).abs() < 1e-9);
        assert!((v - (256.5352 + 344.2161 * 2.1798 / 20.0)).abs() < 1e-9);
        assert!((c.horizon_row(100.0).unwrap() - 256.5352).abs() < 1e-9);
    }

    #[test]
    fn pitched_camera_sees_the_horizon_above_the_centre() {
        let c = caltech();
        // Horizon at v = cy - fy tan(pitch).
        let want = 256.5352 - 344.2161 * math::tan(math::deg_to_rad(14.0));
        assert!((c.horizon_row(317.9).unwrap() - want).abs() < 1e-9);
        // A far road point approaches the horizon from below.
        let [_, v] = c.road_to_pixel(1e4, 0.0).unwrap();
        assert!(v > want && v - want < 0.1);
        // The optical axis meets the road at distance h / tan(pitch), at the principal point.
        let d = 2.1798 / math::tan(math::deg_to_rad(14.0));
        let [u, v] = c.road_to_pixel(d, 0.0).unwrap();
        assert!((u - 317.9034).abs() < 1e-9 && (v - 256.5352).abs() < 1e-9);
        assert!(c.road_to_pixel(-5.0, 0.0).is_none(), "behind the camera");
    }

    #[test]
    fn back_projection_inverts_projection_for_every_mounting() {
        for (pitch, yaw, roll) in [(14.0, 0.0, 0.0), (3.0, 2.0, -1.5), (25.0, -4.0, 3.0)] {
            let c = with(|f| {
                f.pitch_deg = pitch;
                f.yaw_deg = yaw;
                f.roll_deg = roll;
                f.k1 = -0.1;
                f.p2 = 0.001;
            })
            .unwrap();
            for (x, y) in [(8.0, 0.0), (15.0, 3.5), (40.0, -6.0), (12.0, -1.8)] {
                let [u, v] = c.road_to_pixel(x, y).unwrap();
                let [xr, yr] = c.pixel_to_road(u, v).unwrap();
                assert!(
                    (xr - x).abs() < 1e-6 && (yr - y).abs() < 1e-6,
                    "{pitch} {yaw} {roll}"
                );
            }
        }
    }

    #[test]
    fn signs_follow_iso_8855() {
        let c = caltech();
        // A point to the left (y > 0) appears left of centre; further points appear higher.
        let [ul, _] = c.road_to_pixel(20.0, 2.0).unwrap();
        let [ur, _] = c.road_to_pixel(20.0, -2.0).unwrap();
        assert!(ul < 317.9 && ur > 317.9);
        let [_, v_near] = c.road_to_pixel(10.0, 0.0).unwrap();
        let [_, v_far] = c.road_to_pixel(30.0, 0.0).unwrap();
        assert!(v_near > v_far);
        // Yawing left moves the scene right in the image.
        let yawed = with(|f| f.yaw_deg = 5.0).unwrap();
        assert!(
            yawed.road_to_pixel(20.0, 0.0).unwrap()[0] > c.road_to_pixel(20.0, 0.0).unwrap()[0]
        );
        // Rolling right side down (clockwise seen from behind) turns the scene anticlockwise
        // in the image: the horizon rises (smaller v) on the right.
        let rolled = with(|f| f.roll_deg = 5.0).unwrap();
        assert!(rolled.horizon_row(600.0).unwrap() < rolled.horizon_row(40.0).unwrap());
    }

    #[test]
    fn pixels_above_the_horizon_have_no_road_point() {
        let c = caltech();
        let e = c.pixel_to_road(320.0, 100.0).unwrap_err();
        assert!(e.to_string().contains("horizon"), "{e}");
        assert!(c.pixel_to_road(320.0, 400.0).is_ok());
    }

    #[test]
    fn bad_files_are_rejected_with_the_field_named() {
        type Edit = Box<dyn Fn(&mut CameraFile)>;
        let cases: [(&str, Edit); 8] = [
            ("fx", Box::new(|f| f.fx = f64::NAN)),
            ("fy", Box::new(|f| f.fy = 0.0)),
            ("cy", Box::new(|f| f.cy = f64::INFINITY)),
            ("height_m", Box::new(|f| f.height_m = -2.0)),
            ("pitch_deg", Box::new(|f| f.pitch_deg = 95.0)),
            ("roll_deg", Box::new(|f| f.roll_deg = f64::NAN)),
            ("k2", Box::new(|f| f.k2 = f64::NAN)),
            ("baseline_m", Box::new(|f| f.baseline_m = Some(0.0))),
        ];
        for (name, edit) in cases {
            let e = with(|f| edit(f)).unwrap_err().to_string();
            assert!(e.contains(&format!("`{name}`")), "{name}: {e}");
        }
        assert!(matches!(with(|f| f.width = 0), Err(Error::Dimensions(_))));
        assert!(matches!(
            with(|f| f.height = 1 << 20),
            Err(Error::Dimensions(_))
        ));
    }
}
