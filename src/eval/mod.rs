//! Evaluation metrics: how well a tracker's lane estimates agree with ground truth.
//!
//! One file per metric or ground-truth reader, each opening with its definition.

pub mod tusimple;

mod polyline;

use crate::error::{Error, Result};
use std::path::Path;

/// Reads a whole text file.
pub(crate) fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|e| Error::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    })
}
