//! The one table of trackers: each id with how to build it, its default options and the
//! ranges of its options. [`create`], [`super::default_options`] and [`super::option_ranges`]
//! look an id up here, so a new tracker is one entry.

use super::ranges::{ADACHI, DANESCU, LEE, LIU};
use super::TrackerOptions;
use super::{adachi, danescu, lee, liu, OptionRange, Options, Tracker, TrackerConfig};
use crate::error::{Error, Result};

/// One tracker of the registry.
pub(crate) struct Entry {
    /// The id (see ../shared/DESIGN.md).
    pub id: &'static str,
    /// Builds the tracker from a checked configuration.
    pub build: fn(&TrackerConfig) -> Result<Box<dyn Tracker>>,
    /// The default particle count.
    pub particles: usize,
    /// The tracker's options with their defaults.
    pub defaults: fn() -> TrackerOptions,
    /// The ranges of its numeric options, in groups.
    pub ranges: &'static [&'static [OptionRange]],
}

/// Every tracker, in the order the menus list them.
pub(crate) const REGISTRY: [Entry; 6] = [
    Entry {
        id: adachi::ID,
        build: |c| Ok(Box::new(adachi::AdachiTracker::new(c)?)),
        particles: adachi::DEFAULT_PARTICLES,
        defaults: || TrackerOptions::AdachiMmpf(Default::default()),
        ranges: ADACHI,
    },
    Entry {
        id: danescu::ID_MONO,
        build: |c| Ok(Box::new(danescu::DanescuTracker::new(c, danescu::ID_MONO)?)),
        particles: danescu::DEFAULT_PARTICLES,
        defaults: || TrackerOptions::DanescuMono(Default::default()),
        ranges: DANESCU,
    },
    Entry {
        id: danescu::ID_STEREO,
        build: |c| {
            Ok(Box::new(danescu::DanescuTracker::new(
                c,
                danescu::ID_STEREO,
            )?))
        },
        particles: danescu::DEFAULT_PARTICLES,
        defaults: || TrackerOptions::DanescuStereo(Default::default()),
        ranges: DANESCU,
    },
    Entry {
        id: lee::ID,
        build: |c| Ok(Box::new(lee::LeeTracker::new(c)?)),
        particles: lee::DEFAULT_PARTICLES,
        defaults: || TrackerOptions::LeeCpf(Default::default()),
        ranges: LEE,
    },
    Entry {
        id: liu::ID,
        build: |c| Ok(Box::new(liu::LiuTracker::new(c, true)?)),
        particles: liu::DEFAULT_PARTICLES,
        defaults: || TrackerOptions::LiuPpf(Default::default()),
        ranges: LIU,
    },
    Entry {
        id: liu::ID_NOKERNEL,
        build: |c| Ok(Box::new(liu::LiuTracker::new(c, false)?)),
        particles: liu::DEFAULT_PARTICLES,
        defaults: || TrackerOptions::LiuPpfNokernel(Default::default()),
        ranges: LIU,
    },
];

const fn ids<const N: usize>(entries: &[Entry; N]) -> [&'static str; N] {
    let mut out = [""; N];
    let mut i = 0;
    while i < N {
        out[i] = entries[i].id;
        i += 1;
    }
    out
}

const IDS: [&str; REGISTRY.len()] = ids(&REGISTRY);

/// The ids of the trackers, in the registry's order.
pub const TRACKER_IDS: &[&str] = &IDS;

/// The registry's entry for `id`.
///
/// # Errors
/// [`Error::UnknownTracker`] listing the ids there are.
pub(crate) fn entry(id: &str) -> Result<&'static Entry> {
    REGISTRY
        .iter()
        .find(|e| e.id == id)
        .ok_or_else(|| Error::UnknownTracker {
            id: id.to_string(),
            available: TRACKER_IDS.join(", "),
        })
}

/// Builds the tracker `id` from `config`.
///
/// # Errors
/// Configuration errors as [`TrackerConfig::validate`] gives them (checked first, so they are
/// reported whatever the id); [`Error::UnknownTracker`] for an id not in [`TRACKER_IDS`]; the
/// tracker's own option errors.
pub fn create(id: &str, config: &TrackerConfig) -> Result<Box<dyn Tracker>> {
    config.validate()?;
    (entry(id)?.build)(config)
}

/// Builds the tracker that `config`'s typed options name ([`TrackerConfig::new`]), checking
/// them as [`create`] checks options by name.
///
/// # Errors
/// As [`create`]; [`Error::Config`] for options by name, which do not say which tracker they
/// are for (use [`create`]).
pub fn build(config: &TrackerConfig) -> Result<Box<dyn Tracker>> {
    match &config.options {
        // The tracker reads and checks its typed options as it reads named ones.
        Options::Typed(options) => create(options.id(), config),
        Options::ByName(_) => Err(Error::Config(
            "options by name do not say which tracker they are for: use create(id, config)".into(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::default_camera;

    /// Every entry builds the tracker it names, once: ids are unique and each constructor is
    /// wired to its own id (a tracker reports its id in every estimate's consumers).
    #[test]
    fn every_entry_builds_the_tracker_it_names() {
        let camera = default_camera(320, 240).unwrap();
        let config = TrackerConfig::from_json_str(&format!(
            r#"{{"camera": {}, "particles": 50}}"#,
            serde_json::to_string(&camera.to_file()).unwrap()
        ))
        .unwrap();
        for (i, e) in REGISTRY.iter().enumerate() {
            assert!(
                REGISTRY[..i].iter().all(|other| other.id != e.id),
                "{} twice",
                e.id
            );
            assert_eq!(create(e.id, &config).unwrap().id(), e.id);
            assert!(e.particles > 0 && !e.ranges.is_empty(), "{}", e.id);
        }
        assert_eq!(TRACKER_IDS.len(), REGISTRY.len());
    }
}
