//! Listing and reading a folder of frames, and the default synthetic camera.

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
