//! The lane trackers of the four papers behind one [`Tracker`] trait, and the registry that
//! builds them by id from a configuration.
//!
//! Layout: `tracker.rs` the trait, `registry.rs` the one table of ids (built by [`create`]),
//! `config.rs` the [`TrackerConfig`], `options.rs` the typed [`TrackerOptions`], `defaults.rs` / `ranges.rs` every option's default and
//! range, `ego_motion.rs`, `layer.rs`, `stage_times.rs` the types the trait speaks,
//! `lane_change.rs` the lane-change rule trackers share, `relock.rs` the detector proposal, and
//! one folder per paper.
//!
//! Ids (see ../shared/DESIGN.md): `liu-ppf`, `liu-ppf-nokernel`, `lee-cpf`, `adachi-mmpf`,
//! `danescu-stereo`, `danescu-mono`. An id is listed in [`TRACKER_IDS`] only once its tracker
//! is implemented; asking for any other id is an [`Error::UnknownTracker`] that lists the
//! available ones.

pub mod adachi;
mod config;
pub mod danescu;
mod defaults;
mod ego_motion;
mod hypothesis;
pub mod lane_change;
mod layer;
pub mod lee;
pub mod liu;
#[cfg(test)]
mod option_fuzz;
mod options;
mod ranges;
mod registry;
pub mod relock;
mod stage_times;
#[cfg(test)]
mod tests;
mod tracker;

pub(crate) use config::parse_options;
pub use config::{TrackerConfig, MAX_PARTICLES};
pub use defaults::default_options;
pub use ego_motion::EgoMotion;
pub use hypothesis::{spread_indices, Hypothesis};
pub use layer::{Layer, PlaneAxes};
pub use options::{Options, TrackerOptions};
pub use ranges::{option_ranges, OptionRange};
pub use registry::{build, create, TRACKER_IDS};
pub(crate) use stage_times::now;
pub use stage_times::StageTimes;
pub use tracker::Tracker;
pub(crate) use tracker::{check_frame, no_frame_in_progress};

use crate::error::{Error, Result};
