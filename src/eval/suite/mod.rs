//! The evaluation suite: trackers x scenario families x seeds, rendered, tracked and scored.
//!
//! For every scenario family and seed, [`run_member`] renders the member once and steps every
//! tracker on each frame (the right frame too for stereo trackers, the true ego motion for
//! those that take it); [`score_run`] scores each tracker's output with the metrics of this
//! module's parents ([`super::synthetic::evaluate`], [`super::lane_changes`],
//! [`super::lane_configuration`]); [`SuiteCell`] pools the scores of the seeds of one tracker
//! and scenario (see its docs for how), and [`markdown_table`] writes the table.

mod cell;
mod run;
mod table;

pub use cell::{CellRow, SeedScore, SuiteCell};
pub use run::{run_member, score_run, MemberRun};
pub use table::markdown_table;

#[cfg(test)]
mod tests;
