//! The one error type of lanepf.
//!
//! Every fallible public function returns [`Result<T>`]. Messages are written for a person: they
//! say what was wrong, with the offending value, and what is accepted. The wasm binding turns
//! them into thrown JavaScript `Error`s unchanged.

use crate::num_text::Num;
use thiserror::Error;

/// Everything that can go wrong in lanepf.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// An image or buffer dimension is zero, too large, or inconsistent with its data.
    #[error("invalid image dimensions: {0}")]
    Dimensions(String),
    /// A buffer has the wrong number of elements for the stated dimensions.
    #[error("buffer has {actual} elements but {what} needs {expected}")]
    BufferSize {
        /// What the buffer was meant to hold, e.g. "a 640x480 RGBA frame".
        what: String,
        /// Elements required.
        expected: usize,
        /// Elements given.
        actual: usize,
    },
    /// A numeric parameter is NaN, infinite or outside its valid range.
    #[error("invalid parameter `{name}` = {value}: {reason}")]
    Parameter {
        /// Parameter name as the user wrote it.
        name: String,
        /// The offending value, formatted.
        value: String,
        /// What is accepted.
        reason: String,
    },
    /// A configuration (camera file, tracker config) could not be parsed or is inconsistent.
    #[error("invalid configuration: {0}")]
    Config(String),
    /// A file could not be read or written.
    #[error("{path}: {reason}")]
    Io {
        /// The file.
        path: String,
        /// What went wrong.
        reason: String,
    },
    /// An image file could not be decoded.
    #[error("cannot decode image {path}: {reason}")]
    Decode {
        /// The file or source name.
        path: String,
        /// The decoder's complaint.
        reason: String,
    },
    /// A tracker id that does not exist.
    #[error("unknown tracker `{id}`; available: {available}")]
    UnknownTracker {
        /// The id asked for.
        id: String,
        /// Comma-separated list of registered ids (or "none yet").
        available: String,
    },
    /// A point cannot be mapped (e.g. a pixel above the horizon has no road point).
    #[error("cannot map point: {0}")]
    Geometry(String),
    /// A call the object cannot take in its state or at all (no frame in progress, a stereo
    /// step without its right frame, a right frame for a one-camera tracker).
    #[error("{0}")]
    State(String),
}

/// `Result` with lanepf's [`enum@Error`].
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// Shorthand for a [`Error::Parameter`] error. Give an `f64` value as
    /// [`Num`]`(value)`: an `f64`'s own `Display` brings core's float formatting (24 kB raw) into
    /// the wasm.
    pub fn parameter(name: &str, value: impl std::fmt::Display, reason: &str) -> Self {
        Error::Parameter {
            name: name.to_string(),
            value: value.to_string(),
            reason: reason.to_string(),
        }
    }
}

/// Checks that `value` is finite, naming it in the error otherwise.
pub fn require_finite(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::parameter(
            name,
            Num(value),
            "must be a finite number",
        ))
    }
}

/// Checks that `value` is finite and in `range`, naming it with `reason` otherwise.
pub fn require_within(
    name: &str,
    value: f64,
    range: std::ops::RangeInclusive<f64>,
    reason: &str,
) -> Result<f64> {
    require_finite(name, value)?;
    if range.contains(&value) {
        Ok(value)
    } else {
        Err(Error::parameter(name, Num(value), reason))
    }
}

/// Checks that `value` is finite and strictly positive.
pub fn require_positive(name: &str, value: f64) -> Result<f64> {
    require_finite(name, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(Error::parameter(
            name,
            Num(value),
            "must be greater than zero",
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_the_value_and_the_rule() {
        let e = require_positive("fx", f64::NAN).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid parameter `fx` = NaN: must be a finite number"
        );
        let e = require_positive("height_m", -1.0).unwrap_err();
        assert!(e.to_string().contains("must be greater than zero"));
        assert_eq!(require_positive("x", 2.5), Ok(2.5));
        let e = require_within("split", 0.95, 0.1..=0.9, "must be 0.1 to 0.9").unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid parameter `split` = 0.95: must be 0.1 to 0.9"
        );
        let e = require_within("split", f64::INFINITY, 0.1..=0.9, "-").unwrap_err();
        assert!(e.to_string().contains("must be a finite number"));
        assert_eq!(require_within("split", 0.9, 0.1..=0.9, "-"), Ok(0.9));
    }
}
