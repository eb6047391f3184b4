//! A tracker's own options, typed: [`TrackerOptions`] has one variant per tracker id, each
//! holding that tracker's config struct, so a Rust program configures a tracker without JSON
//! (and cannot give one tracker another's option). [`Options`] is what a [`TrackerConfig`]
//! carries: options by name (from JSON: a `--config` file, a JavaScript object) or typed.
//!
//! ```
//! use lanepf::trackers::{self, lee::config::{LeeConfig, Variant}, TrackerConfig, TrackerOptions};
//! let camera = lanepf::synth::default_camera(320, 240).unwrap().to_file();
//! let lee = LeeConfig { variant: Variant::FirstOrder, ..LeeConfig::default() };
//! let config = TrackerConfig::new(camera, TrackerOptions::LeeCpf(lee)).with_particles(300);
//! let tracker = trackers::build(&config).unwrap();
//! assert_eq!(tracker.id(), "lee-cpf");
//! ```
//!
//! [`TrackerConfig`]: super::TrackerConfig

use super::adachi::config::AdachiConfig;
use super::danescu::config::DanescuConfig;
use super::lee::config::LeeConfig;
use super::liu::config::LiuConfig;
use super::{adachi, danescu, lee, liu};
use crate::error::{Error, Result};
use serde::{Deserialize, Deserializer, Serialize};
use std::collections::BTreeMap;

/// The options of one tracker, tagged by its id (the variant); each variant holds the
/// tracker's config struct (all fields have defaults: `LeeConfig { variant: ..,
/// ..LeeConfig::default() }`). Serialises as the bare options object, as JSON gives them.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum TrackerOptions {
    /// `adachi-mmpf`.
    AdachiMmpf(AdachiConfig),
    /// `danescu-mono`.
    DanescuMono(DanescuConfig),
    /// `danescu-stereo`.
    DanescuStereo(DanescuConfig),
    /// `lee-cpf`.
    LeeCpf(LeeConfig),
    /// `liu-ppf`.
    LiuPpf(LiuConfig),
    /// `liu-ppf-nokernel`.
    LiuPpfNokernel(LiuConfig),
}

impl TrackerOptions {
    /// The id of the tracker these options build.
    pub fn id(&self) -> &'static str {
        match self {
            Self::AdachiMmpf(_) => adachi::ID,
            Self::DanescuMono(_) => danescu::ID_MONO,
            Self::DanescuStereo(_) => danescu::ID_STEREO,
            Self::LeeCpf(_) => lee::ID,
            Self::LiuPpf(_) => liu::ID,
            Self::LiuPpfNokernel(_) => liu::ID_NOKERNEL,
        }
    }

    /// The default options of tracker `id`.
    ///
    /// # Errors
    /// [`Error::UnknownTracker`] for an id not in [`super::TRACKER_IDS`].
    pub fn defaults(id: &str) -> Result<Self> {
        Ok((super::registry::entry(id)?.defaults)())
    }

    /// Checks every value (ranges and the limits that tie options together).
    ///
    /// # Errors
    /// [`Error::Parameter`] or [`Error::Config`] naming the first bad value.
    pub fn validate(&self) -> Result<()> {
        match self {
            Self::AdachiMmpf(c) => c.validate(),
            Self::DanescuMono(c) | Self::DanescuStereo(c) => c.validate(),
            Self::LeeCpf(c) => c.validate(),
            Self::LiuPpf(c) | Self::LiuPpfNokernel(c) => c.validate(),
        }
    }
}

/// A [`super::TrackerConfig`]'s tracker options: by name, as JSON gives them (checked when the
/// tracker is built, with the key path in the error), or typed.
#[derive(Debug, Clone)]
pub enum Options {
    /// Options by name (the JSON form); empty: every option at its default.
    ByName(BTreeMap<String, serde_json::Value>),
    /// Typed options, which also name the tracker.
    Typed(Box<TrackerOptions>),
}

impl Default for Options {
    fn default() -> Self {
        Self::ByName(BTreeMap::new())
    }
}

impl From<TrackerOptions> for Options {
    fn from(options: TrackerOptions) -> Self {
        Self::Typed(Box::new(options))
    }
}

impl<'de> Deserialize<'de> for Options {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> std::result::Result<Self, D::Error> {
        BTreeMap::deserialize(deserializer).map(Self::ByName)
    }
}

impl Options {
    /// The options of tracker `id` as its config `T`: parsed from the names (unknown ones
    /// refused, the key path in the error), or the typed ones `pick` takes for `id`.
    ///
    /// # Errors
    /// [`Error::Config`] for an unknown option or a wrong type, or typed options of another
    /// tracker.
    pub(crate) fn read<T: serde::de::DeserializeOwned + Clone>(
        &self,
        id: &str,
        pick: impl Fn(&TrackerOptions) -> Option<&T>,
    ) -> Result<T> {
        match self {
            Self::ByName(map) => super::parse_options(id, map),
            Self::Typed(typed) => pick(typed).cloned().ok_or_else(|| {
                Error::Config(format!(
                    "{id} cannot be built from the options of {}",
                    typed.id()
                ))
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::default_camera;
    use crate::trackers::{build, create, TrackerConfig, TRACKER_IDS};

    /// Typed options build the same tracker as the same options by name, for every id.
    #[test]
    fn typed_options_build_what_the_json_builds() {
        let camera = default_camera(160, 120).unwrap().to_file();
        for id in TRACKER_IDS {
            let typed = TrackerOptions::defaults(id).unwrap();
            assert_eq!(typed.id(), *id);
            let config = TrackerConfig::new(camera.clone(), typed.clone()).with_particles(20);
            let by_name = serde_json::to_value(&typed).unwrap();
            let mut json = by_name.as_object().unwrap().clone();
            json.insert("camera".into(), serde_json::to_value(&camera).unwrap());
            json.insert("particles".into(), 20.into());
            let from_json =
                TrackerConfig::from_json_str(&serde_json::Value::Object(json).to_string()).unwrap();
            let (a, b) = (build(&config).unwrap(), create(id, &from_json).unwrap());
            assert_eq!(a.id(), *id);
            assert_eq!(a.particles(), b.particles(), "{id}");
        }
    }

    #[test]
    fn typed_options_of_another_tracker_are_refused() {
        let camera = default_camera(160, 120).unwrap().to_file();
        let lee = TrackerConfig::new(camera, TrackerOptions::defaults("lee-cpf").unwrap());
        let e = create("adachi-mmpf", &lee).err().unwrap().to_string();
        assert!(
            e.contains("adachi-mmpf cannot be built from the options of lee-cpf"),
            "{e}"
        );
        let e = create("danescu-stereo", &{
            let mut c = lee.clone();
            c.options = TrackerOptions::defaults("danescu-mono").unwrap().into();
            c
        })
        .err()
        .unwrap()
        .to_string();
        assert!(e.contains("options of danescu-mono"), "{e}");
        // Typed options are checked like named ones.
        let bad = super::LeeConfig {
            ess_threshold: 2.0,
            ..Default::default()
        };
        let e = build(&TrackerConfig {
            options: TrackerOptions::LeeCpf(bad).into(),
            ..lee.clone()
        })
        .err()
        .unwrap()
        .to_string();
        assert!(e.contains("ess_threshold"), "{e}");
        // Options by name need the id.
        let e = build(&TrackerConfig {
            options: Options::default(),
            ..lee
        })
        .err()
        .unwrap()
        .to_string();
        assert!(e.contains("create(id"), "{e}");
    }
}
