//! The lane trackers of the four papers behind one [`Tracker`] trait, and the registry that
//! builds them by id from a configuration.
//!
//! Layout: `tracker.rs` the trait, `registry.rs` the one table of ids (built by [`create`]),
//! `config.rs` the [`TrackerConfig`], `options.rs` the typed [`TrackerOptions`], `defaults.rs`
//! / `ranges.rs` every option's default and range, `presets.rs` the named option sets (`paper`,
//! `real-roads`), `ego_motion.rs`, `layer.rs` the types the trait speaks (and the filter core's
//! [`StageTimes`]), `truth.rs` the papers' ground truth (each paper's `truth_parameters` of the
//! simulator's neutral truth: [`papers_truth`]), `lane_change.rs` the lane-change rule trackers
//! share, `relock.rs` the detector proposal, `adjacent_lanes.rs` the neighbouring lanes found
//! beside an ego lane, `paint_snap.rs` the boundaries moved onto the paint, `paint_output.rs`
//! the output options that read the paint in their one order, and one folder per paper. Each
//! paper's tracker is its image cues, its models and its frame schedule: a
//! [`crate::filter::Schedule`] whose operations it implements ([`crate::filter::Scheduled`])
//! and the filter core's stepper runs, whole (`step`) or one step at a time (`begin_frame`,
//! `advance`).
//!
//! Ids (see ../shared/DESIGN.md): `liu-ppf`, `liu-ppf-nokernel`, `lee-cpf`, `adachi-mmpf`,
//! `danescu-stereo`, `danescu-mono`. An id is listed in [`TRACKER_IDS`] only once its tracker
//! is implemented; asking for any other id is an [`Error::UnknownTracker`] that lists the
//! available ones.

pub mod adachi;
#[cfg(test)]
#[path = "adachi/fresh_road_tests.rs"]
mod adachi_fresh_road_tests;
pub mod adjacent_lanes;
mod config;
#[cfg(test)]
pub(crate) mod crossing_scenes;
pub mod danescu;
mod defaults;
mod ego_motion;
pub(crate) mod flat_boundary;
#[cfg(test)]
pub(crate) mod fresh_roads;
mod hypothesis;
pub mod lane_change;
mod layer;
pub mod lee;
pub mod liu;
#[cfg(test)]
mod option_fuzz;
mod options;
pub mod paint_output;
#[cfg(test)]
mod paint_output_tests;
pub mod paint_snap;
#[cfg(test)]
mod paint_snap_tests;
mod presets;
mod ranges;
pub mod reacquire;
#[cfg(test)]
mod reacquire_tests;
mod registry;
pub mod relock;
pub mod side_search;
pub mod support_memory;
#[cfg(test)]
mod support_memory_tests;
#[cfg(test)]
mod tests;
mod tracker;
mod truth;

pub(crate) use crate::filter::now;
pub use crate::filter::StageTimes;
pub(crate) use config::parse_options;
pub use config::{TrackerConfig, DEFAULT_SEED, MAX_PARTICLES};
pub use defaults::{default_options, preset_options};
pub use ego_motion::EgoMotion;
pub use hypothesis::{spread_indices, Hypothesis};
pub use layer::{Layer, PlaneAxes};
pub use options::{Options, TrackerOptions};
pub use presets::{Preset, PRESET_NAMES};
pub use ranges::{option_ranges, OptionRange};
pub use registry::{build, create, TRACKER_IDS};
pub use tracker::Tracker;
pub(crate) use tracker::{advance_scheduled, check_frame};
pub use truth::{papers_truth, scene_truth, truth_parameters};

use crate::error::{Error, Result};
