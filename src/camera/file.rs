//! The `camera.json` file format (see `../shared/data/README.md`).
//!
//! ```json
//! { "width": 640, "height": 480, "fx": 309.44, "fy": 344.22, "cx": 317.90, "cy": 256.54,
//!   "height_m": 2.18, "pitch_deg": 14.0, "yaw_deg": 0.0, "roll_deg": 0.0 }
//! ```
//!
//! `yaw_deg`, `roll_deg`, the distortion coefficients `k1 k2 p1 p2 k3` and the stereo
//! `baseline_m` are optional. Unknown fields are rejected, so that a typo (`pitch` for
//! `pitch_deg`) is an error and not a silently ignored value.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// A camera as written in a `camera.json` file: plain numbers, checked when a camera, scene
/// or tracker is built from them ([`super::Camera::from_file`]). Unknown fields are refused.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraFile {
    /// Image width, pixels (1 to 16384; width x height at most 2^26).
    pub width: usize,
    /// Image height, pixels (1 to 16384).
    pub height: usize,
    /// Focal length along x, pixels (> 0).
    pub fx: f64,
    /// Focal length along y, pixels (> 0).
    pub fy: f64,
    /// Principal point x, pixels.
    pub cx: f64,
    /// Principal point y, pixels.
    pub cy: f64,
    /// Height of the optical centre above the road, metres (> 0, at most 100).
    pub height_m: f64,
    /// Pitch, degrees, positive when the camera looks down at the road (|pitch| <= 80).
    pub pitch_deg: f64,
    /// Yaw, degrees, positive when the camera looks left of the car's forward axis (|yaw| <=
    /// 80; 0 when left out).
    #[serde(default)]
    pub yaw_deg: f64,
    /// Roll, degrees, positive when the camera's right side dips (ISO 8855; |roll| <= 80; 0
    /// when left out).
    #[serde(default)]
    pub roll_deg: f64,
    /// Radial distortion k1 (0 when left out).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub k1: f64,
    /// Radial distortion k2 (0 when left out).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub k2: f64,
    /// Tangential distortion p1 (0 when left out).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub p1: f64,
    /// Tangential distortion p2 (0 when left out).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub p2: f64,
    /// Radial distortion k3 (0 when left out).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub k3: f64,
    /// Stereo baseline (distance from the left to the right camera), metres (> 0); needed by
    /// danescu-stereo.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub baseline_m: Option<f64>,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

impl CameraFile {
    /// A `width` x `height` camera with square pixels of focal length `f`, the principal point
    /// at the image centre, no distortion, level (pitch, yaw and roll 0) and 1.5 m above the
    /// road, no stereo baseline: set the rest with struct update syntax,
    /// `CameraFile { pitch_deg: 4.0, ..CameraFile::pinhole(640, 480, 520.0) }`.
    pub fn pinhole(width: usize, height: usize, f: f64) -> Self {
        Self {
            width,
            height,
            fx: f,
            fy: f,
            cx: (width as f64 - 1.0) / 2.0,
            cy: (height as f64 - 1.0) / 2.0,
            height_m: 1.5,
            pitch_deg: 0.0,
            yaw_deg: 0.0,
            roll_deg: 0.0,
            k1: 0.0,
            k2: 0.0,
            p1: 0.0,
            p2: 0.0,
            k3: 0.0,
            baseline_m: None,
        }
    }

    /// Parses the JSON text of a camera file.
    ///
    /// # Errors
    /// [`Error::Config`] naming the missing, mistyped or unknown field.
    pub fn from_json_str(text: &str) -> Result<Self> {
        serde_json::from_str(text).map_err(|e| Error::Config(format!("camera: {e}")))
    }

    /// The camera as pretty-printed JSON.
    pub fn to_json_string(&self) -> String {
        // Serialising plain numbers cannot fail; NaN would become `null`, which
        // `from_json_str` then rejects, so a round trip never invents a value.
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Reads a camera file.
    ///
    /// # Errors
    /// [`Error::Io`] when the file cannot be read, [`Error::Config`] when it does not parse.
    pub fn read(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
            path: path.display().to_string(),
            reason: e.to_string(),
        })?;
        Self::from_json_str(&text).map_err(|e| Error::Io {
            path: path.display().to_string(),
            reason: e.to_string(),
        })
    }

    /// Writes the camera file.
    ///
    /// # Errors
    /// [`Error::Io`] when the file cannot be written.
    pub fn write(&self, path: &Path) -> Result<()> {
        std::fs::write(path, self.to_json_string() + "\n").map_err(|e| Error::Io {
            path: path.display().to_string(),
            reason: e.to_string(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CALTECH: &str = r#"{ "width": 640, "height": 480,
        "fx": 309.4362, "fy": 344.2161, "cx": 317.9034, "cy": 256.5352,
        "height_m": 2.1798, "pitch_deg": 14.0, "yaw_deg": 0.0, "roll_deg": 0.0 }"#;

    #[test]
    fn parses_the_documented_format_and_round_trips() {
        let f = CameraFile::from_json_str(CALTECH).unwrap();
        assert_eq!((f.width, f.height), (640, 480));
        assert_eq!(f.pitch_deg, 14.0);
        assert_eq!((f.k1, f.baseline_m), (0.0, None));
        let back = CameraFile::from_json_str(&f.to_json_string()).unwrap();
        assert_eq!(back, f);
        assert!(
            !f.to_json_string().contains("k1"),
            "zero distortion is not written"
        );
    }

    #[test]
    fn rejects_unknown_and_missing_fields() {
        let e = CameraFile::from_json_str(&CALTECH.replace("pitch_deg", "pitch")).unwrap_err();
        assert!(e.to_string().contains("unknown field `pitch`"), "{e}");
        let e = CameraFile::from_json_str(r#"{"width": 640}"#).unwrap_err();
        assert!(e.to_string().contains("missing field"), "{e}");
    }

    #[test]
    fn reads_and_writes_files() {
        let dir = std::env::temp_dir().join(format!("lanepf-camera-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("camera.json");
        let mut f = CameraFile::from_json_str(CALTECH).unwrap();
        f.k1 = -0.25;
        f.baseline_m = Some(0.3);
        f.write(&path).unwrap();
        assert_eq!(CameraFile::read(&path).unwrap(), f);
        let e = CameraFile::read(&dir.join("missing.json")).unwrap_err();
        assert!(matches!(e, Error::Io { .. }), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
