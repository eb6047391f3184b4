//! Listing and reading a folder of frames, and the default synthetic camera.

use lanepf::camera::{Camera, CameraFile};
use lanepf::{Error, Result};
use std::path::{Path, PathBuf};

/// The PNG/JPEG files of `dir`, in file-name order.
pub fn list(dir: &Path) -> Result<Vec<PathBuf>> {
    let entries = std::fs::read_dir(dir).map_err(|e| Error::Io {
        path: dir.display().to_string(),
        reason: e.to_string(),
    })?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension()
                .and_then(|x| x.to_str())
                .is_some_and(|x| matches!(x.to_ascii_lowercase().as_str(), "png" | "jpg" | "jpeg"))
        })
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(Error::Io {
            path: dir.display().to_string(),
            reason: "no PNG or JPEG frames in this folder".into(),
        });
    }
    Ok(files)
}

/// The file name of `path` (for the `frame` field).
pub fn name(path: &Path) -> String {
    path.file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
}

/// The synthetic camera used when none is given: 60 degrees horizontal field of view,
/// principal point at the centre, 1.5 m above the road, pitched 4 degrees down, with a stereo
/// baseline of 0.3 m.
pub fn default_camera(width: usize, height: usize) -> Result<Camera> {
    let f = width as f64 / 2.0 / lanepf::math::tan(lanepf::math::deg_to_rad(30.0));
    Camera::from_file(&CameraFile {
        width,
        height,
        fx: f,
        fy: f,
        cx: (width as f64 - 1.0) / 2.0,
        cy: (height as f64 - 1.0) / 2.0,
        height_m: 1.5,
        pitch_deg: 4.0,
        yaw_deg: 0.0,
        roll_deg: 0.0,
        k1: 0.0,
        k2: 0.0,
        p1: 0.0,
        p2: 0.0,
        k3: 0.0,
        baseline_m: Some(0.3),
    })
}
