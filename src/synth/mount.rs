//! [`CameraMount`]: the camera of a scenario family member, independent of the image size.
//!
//! A mount is a horizontal field of view and a pose; [`CameraMount::camera`] turns it into a
//! pinhole camera for any `width` x `height` (square pixels, principal point at the centre,
//! no distortion): f = (width / 2) / tan(hfov / 2). A family seed draws every mount value
//! uniformly within [`MOUNT_RANGES`]; the reference members keep [`CameraMount::REFERENCE`],
//! the simulator's default camera ([`super::default_camera`]).

use super::draw::Draw;
use super::simulator::DEFAULT_BASELINE_M;
use crate::camera::{Camera, CameraFile};
use crate::error::Result;
use crate::math;
use serde::{Deserialize, Serialize};

/// A camera's field of view and pose on the car.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraMount {
    /// Horizontal field of view, degrees.
    pub hfov_deg: f64,
    /// Height of the camera above the road, metres.
    pub height_m: f64,
    /// Pitch, degrees, positive looking down.
    pub pitch_deg: f64,
    /// Yaw, degrees, positive looking left.
    pub yaw_deg: f64,
    /// Roll, degrees.
    pub roll_deg: f64,
}

/// The range of each mount value a family draws: (name, low, high), uniform in [low, high).
pub const MOUNT_RANGES: [(&str, f64, f64); 5] = [
    ("hfov_deg", 50.0, 90.0),
    ("height_m", 1.1, 2.4),
    ("pitch_deg", -2.0, 8.0),
    ("yaw_deg", -2.0, 2.0),
    ("roll_deg", -1.0, 1.0),
];

/// Salt of the camera's draw stream.
const MOUNT_SALT: u64 = 0x6361_6d65_7261_0001;

impl CameraMount {
    /// The simulator's default camera: 60 degrees, 1.5 m high, pitched 4 degrees down.
    pub const REFERENCE: Self = Self {
        hfov_deg: 60.0,
        height_m: 1.5,
        pitch_deg: 4.0,
        yaw_deg: 0.0,
        roll_deg: 0.0,
    };

    /// The mount of family seed `seed`: each value uniform within [`MOUNT_RANGES`], drawn in
    /// that order from its own stream.
    pub fn draw(seed: u64) -> Self {
        let mut d = Draw::new(seed, MOUNT_SALT);
        let mut value = |k: usize| d.range(MOUNT_RANGES[k].1, MOUNT_RANGES[k].2);
        Self {
            hfov_deg: value(0),
            height_m: value(1),
            pitch_deg: value(2),
            yaw_deg: value(3),
            roll_deg: value(4),
        }
    }

    /// The mount as a `width` x `height` camera file with the default stereo baseline.
    pub fn camera_file(&self, width: usize, height: usize) -> CameraFile {
        let f = width as f64 / 2.0 / math::tan(math::deg_to_rad(self.hfov_deg / 2.0));
        CameraFile {
            height_m: self.height_m,
            pitch_deg: self.pitch_deg,
            yaw_deg: self.yaw_deg,
            roll_deg: self.roll_deg,
            baseline_m: Some(DEFAULT_BASELINE_M),
            ..CameraFile::pinhole(width, height, f)
        }
    }

    /// The mount as a `width` x `height` camera.
    ///
    /// # Errors
    /// [`crate::Error::Dimensions`] for an unusable size.
    pub fn camera(&self, width: usize, height: usize) -> Result<Camera> {
        Camera::from_file(&self.camera_file(width, height))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::default_camera;

    #[test]
    fn the_reference_mount_is_the_default_camera() {
        let a = CameraMount::REFERENCE.camera(320, 240).unwrap().to_file();
        let b = default_camera(320, 240).unwrap().to_file();
        assert_eq!(a, b);
    }

    #[test]
    fn drawn_mounts_stay_in_range_and_build_cameras() {
        for seed in 0..200 {
            let m = CameraMount::draw(seed);
            let values = [m.hfov_deg, m.height_m, m.pitch_deg, m.yaw_deg, m.roll_deg];
            for (v, (name, lo, hi)) in values.iter().zip(MOUNT_RANGES) {
                assert!((lo..hi).contains(v), "seed {seed}: {name} {v}");
            }
            m.camera(160, 120).unwrap();
        }
        assert_ne!(CameraMount::draw(1), CameraMount::draw(2));
    }
}
