//! What the evaluation reads, at most: no input file, line or polyline can exhaust memory or
//! time (`--pred /dev/zero`, a prediction zigzagging between x = 0 and x = 1e7).

use crate::error::{Error, Result};
use std::io::Read;
use std::path::Path;

/// Largest input file (predictions, labels), bytes: 256 MiB (CULane's whole test set of
/// predictions is about 70 MB).
pub const MAX_FILE_BYTES: u64 = 256 << 20;
/// Longest line of a JSON-lines file, bytes (a frame's prediction is a few kilobytes).
pub const MAX_LINE_BYTES: usize = 1 << 20;
/// Most points of one polyline (a boundary, a labelled lane, `h_samples`).
pub const MAX_POINTS: usize = 5_000;
/// Most points one polyline is resampled to (Caltech's 1 px arc-length samples): 50 000 px of
/// arc length, many times any lane inside an image.
pub const MAX_RESAMPLED: usize = 50_000;

/// Reads a whole text file of at most [`MAX_FILE_BYTES`].
///
/// # Errors
/// [`Error::Io`] when it cannot be read, is larger, or is not UTF-8.
pub(crate) fn read_text(path: &Path) -> Result<String> {
    let io = |reason: String| Error::Io {
        path: path.display().to_string(),
        reason,
    };
    let file = std::fs::File::open(path).map_err(|e| io(e.to_string()))?;
    let mut bytes = Vec::new();
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| io(e.to_string()))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(io(format!(
            "larger than {} MiB, more than an evaluation input can be",
            MAX_FILE_BYTES >> 20
        )));
    }
    String::from_utf8(bytes).map_err(|_| io("not UTF-8 text".into()))
}

/// Checks one line of a JSON-lines file (`number` 1-based) against [`MAX_LINE_BYTES`].
///
/// # Errors
/// [`Error::Config`] naming the source and the line.
pub(crate) fn check_line(source: &str, number: usize, line: &str) -> Result<()> {
    if line.len() > MAX_LINE_BYTES {
        return Err(Error::Config(format!(
            "{source} line {number}: {} bytes long, more than the {} KiB a line may have",
            line.len(),
            MAX_LINE_BYTES >> 10
        )));
    }
    Ok(())
}

/// Checks a polyline's point count against [`MAX_POINTS`]; `what` names it.
///
/// # Errors
/// [`Error::Config`] naming it.
pub(crate) fn check_points(what: &str, count: usize) -> Result<()> {
    if count > MAX_POINTS {
        return Err(Error::Config(format!(
            "{what} has {count} points, more than the {MAX_POINTS} a polyline may have"
        )));
    }
    Ok(())
}
