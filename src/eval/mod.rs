//! Evaluation metrics: how well a tracker's lane estimates agree with ground truth.
//!
//! One file per metric or ground-truth reader, each opening with its definition.

pub mod caltech;
pub mod culane;
pub mod params;
pub mod synthetic;
pub mod tusimple;

mod assign;
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

/// A rate as a percentage, or "n/a".
pub(crate) fn percent(rate: Option<f64>) -> String {
    rate.map_or_else(|| "n/a".to_string(), |r| format!("{:.1} %", 100.0 * r))
}
