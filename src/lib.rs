//! # lanepf: particle-filter lane tracking
//!
//! The pipeline of one frame, in five lines:
//!
//! 1. an RGBA frame arrives (browser `ImageData`, a decoded file) and becomes a grey
//!    [`image::Image`];
//! 2. [`vision`] turns it into the cues a tracker weighs: a top view through the
//!    [`camera`], gradients, edges, dark-light-dark markings, distance maps;
//! 3. a tracker's motion model moves the particles of a [`filter`] (drift + diffusion);
//! 4. its measurement model gives each particle a log-likelihood from the cues;
//! 5. the filter normalises, estimates and resamples, and the estimate becomes lane boundaries.
//!
//! Notation: image pixels (x right, y down, origin top-left); road frame ISO 8855 (x forward,
//! y left, z up, metres, origin on the road under the camera); angles in radians.
//!
//! Start reading at [`filter`] (the generic particle filter) and [`camera`] (the geometry).
//! JavaScript users see only the `wasm` module's classes.
//!
//! Cargo features, both on by default: `wasm` (the JavaScript binding, `lanepf::wasm`: wasm-bindgen,
//! js-sys, web-sys, console_error_panic_hook; it is `wasm-track`, the package's main module with
//! the trackers and the calibrator, and `wasm-sim`, the simulator's module `lanepf/sim`, each of
//! which builds alone) and `cli` (the `lanepf` program: clap). With `default-features = false`
//! the crate is the trackers, the simulator and the evaluation alone.

#![deny(missing_docs)]
// A panic in wasm kills the module (and in the CLI, a batch run): library code returns errors
// instead. Tests may unwrap. Indexing is left to review: the image loops index by design.
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

pub mod baseline;
pub mod calib;
pub mod camera;
pub mod error;
pub mod eval;
pub mod filter;
pub mod image;
mod keypath;
pub mod lane;
pub mod math;
pub mod num_text;
pub mod synth;
pub mod trackers;
pub mod vision;
#[cfg(feature = "wasm-base")]
pub mod wasm;

pub use error::{Error, Result};

/// The crate version, as in Cargo.toml.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The golden values the native unit tests and the wasm tests both assert (not part of the API).
#[cfg(test)]
mod goldens {
    include!("../tests/common/goldens.rs");
}
