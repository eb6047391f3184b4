//! What every tracker is built from ([`TrackerConfig`]) and the reader of a tracker's own
//! options by name.

use super::options::{Options, TrackerOptions};
use crate::camera::{Camera, CameraFile};
use crate::error::{Error, Result};
use serde::Deserialize;
use std::collections::BTreeMap;

/// Largest accepted particle count.
pub const MAX_PARTICLES: usize = 200_000;

/// What every tracker is built from: the camera, the particle budget, the seed, and the
/// tracker's own options (checked by the tracker itself). In JSON the options are keys beside
/// these; in Rust they may instead be typed, naming the tracker (`TrackerConfig::new`).
#[derive(Debug, Clone, Deserialize)]
pub struct TrackerConfig {
    /// The camera (the `camera.json` format); the frames given to `step` must have its size.
    pub camera: CameraFile,
    /// Number of particles N (1 to 200000); left out: the tracker's own default.
    #[serde(default)]
    pub particles: Option<usize>,
    /// Seed of the random generator: the same seed gives the same run natively and in the
    /// browser.
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// The tracker's own options: by name (JSON) or typed.
    #[serde(flatten)]
    pub options: Options,
}

/// The seed a config without one gets.
pub const DEFAULT_SEED: u64 = 1;

fn default_seed() -> u64 {
    DEFAULT_SEED
}

impl TrackerConfig {
    /// A configuration with typed options (which name the tracker: build it with
    /// [`super::build`]), the tracker's default particle count and seed 1.
    pub fn new(camera: CameraFile, options: TrackerOptions) -> Self {
        Self {
            camera,
            particles: None,
            seed: default_seed(),
            options: Options::Typed(Box::new(options)),
        }
    }

    /// The same configuration with `particles` particles.
    #[must_use]
    pub fn with_particles(mut self, particles: usize) -> Self {
        self.particles = Some(particles);
        self
    }

    /// The same configuration with seed `seed`.
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Parses a JSON configuration.
    ///
    /// # Errors
    /// [`Error::Config`] when the JSON is malformed or a field has the wrong type.
    pub fn from_json_str(text: &str) -> Result<Self> {
        serde_json::from_str(text).map_err(|e| Error::Config(format!("tracker config: {e}")))
    }

    /// Checks the configuration and returns the validated camera.
    ///
    /// # Errors
    /// Camera errors as [`Camera::from_file`] gives them; [`Error::Parameter`] for a particle
    /// count of 0 or above [`MAX_PARTICLES`].
    pub fn validate(&self) -> Result<Camera> {
        if let Some(n) = self.particles {
            if n == 0 || n > MAX_PARTICLES {
                return Err(Error::parameter(
                    "particles",
                    n,
                    &format!("must be between 1 and {MAX_PARTICLES}"),
                ));
            }
        }
        Camera::from_file(&self.camera)
    }

    /// The particle count: the configured one, or the tracker's `default`.
    pub fn particles_or(&self, default: usize) -> usize {
        self.particles.unwrap_or(default)
    }
}

/// Reads a tracker's own options (all optional, unknown ones refused) from the free-form part
/// of the [`TrackerConfig`].
///
/// # Errors
/// [`Error::Config`] naming the tracker and the option's key path for an unknown option or a
/// wrong type.
pub(crate) fn parse_options<T: serde::de::DeserializeOwned>(
    id: &str,
    options: &BTreeMap<String, serde_json::Value>,
) -> Result<T> {
    // Inserted, not collected (which sorts the pairs first: one more sort in the wasm).
    let mut map = serde_json::Map::new();
    for (k, v) in options {
        map.insert(k.clone(), v.clone());
    }
    crate::keypath::deserialize(&serde_json::Value::Object(map)).map_err(|(path, inner)| {
        if path == "." {
            Error::Config(format!("{id} options: {inner}"))
        } else {
            Error::Config(format!("{id} options: {path}: {inner}"))
        }
    })
}
