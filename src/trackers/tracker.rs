//! The [`Tracker`] trait every paper's tracker implements, and the frame checks its
//! implementations share.

use super::{EgoMotion, Hypothesis, Layer, StageTimes};
use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::filter::{ResampleDecision, Scheduled};
use crate::lane::LaneEstimate;

/// A lane tracker: one frame in, one estimate out.
pub trait Tracker {
    /// The tracker's id.
    fn id(&self) -> &'static str;
    /// Processes one RGBA frame of the configured camera size.
    ///
    /// # Errors
    /// [`Error::BufferSize`] / [`Error::Dimensions`] for a frame that does not match the camera.
    fn step(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<LaneEstimate>;
    /// Forgets the past: the next frame starts from the initial distribution.
    fn reset(&mut self);
    /// The car's motion for the next frame (Danescu's drift input). Trackers whose motion
    /// model has no ego-motion input ignore it.
    ///
    /// # Errors
    /// [`Error::Parameter`] for a NaN or out-of-range value (see [`EgoMotion::check`]).
    fn set_ego_motion(&mut self, motion: EgoMotion) -> Result<()> {
        motion.check()
    }
    /// Whether the tracker needs a right image with every frame ([`Tracker::set_right`]).
    fn is_stereo(&self) -> bool {
        false
    }
    /// The right image of the next frame, for stereo trackers (`danescu-stereo`): call it
    /// before every [`Tracker::step`] / [`Tracker::begin_frame`].
    ///
    /// # Errors
    /// [`Error::State`] for a one-camera tracker; [`Error::BufferSize`] /
    /// [`Error::Dimensions`] as for a frame.
    fn set_right(&mut self, _rgba: &[u8], _width: usize, _height: usize) -> Result<()> {
        Err(Error::State(format!(
            "{} takes one camera; a right image is for danescu-stereo",
            self.id()
        )))
    }
    /// The particle cloud after the last step, flattened for drawing: `particle_stride()`
    /// numbers per particle, the layout documented by each tracker; empty by default.
    fn particles(&self) -> Vec<f32> {
        Vec::new()
    }
    /// Numbers per particle in [`Tracker::particles`].
    fn particle_stride(&self) -> usize {
        0
    }
    /// At most `max` particles of the cloud, spread over it ([`super::spread_indices`]), each drawn as
    /// the boundaries it stands for (the same roles and ranges as the estimate); empty by
    /// default.
    fn hypotheses(&self, _max: usize) -> Vec<Hypothesis> {
        Vec::new()
    }
    /// Milliseconds spent in each stage of the last [`Tracker::step`] (for `lanepf bench`).
    fn stage_times(&self) -> StageTimes {
        StageTimes::default()
    }
    /// Pictures of the tracker's cues after the last frame (empty by default).
    fn layers(&self) -> Vec<Layer> {
        Vec::new()
    }
    /// The steps one frame is cut into in per-step (teaching) mode, in order; empty when the
    /// tracker has no per-step mode.
    fn step_names(&self) -> &'static [&'static str] {
        &[]
    }
    /// Starts a frame in per-step mode: checks it and computes its image cues; the filter's
    /// steps then run one [`Tracker::advance`] at a time. `begin_frame` followed by all the
    /// steps gives exactly what [`Tracker::step`] gives.
    ///
    /// # Errors
    /// As [`Tracker::step`] for a bad frame; [`Error::State`] for a tracker without a
    /// per-step mode.
    fn begin_frame(&mut self, _rgba: &[u8], _width: usize, _height: usize) -> Result<()> {
        Err(Error::State(format!(
            "{} has no per-step mode yet; use step()",
            self.id()
        )))
    }
    /// Runs the next step of the frame started by [`Tracker::begin_frame`]; returns the
    /// estimate after the last step, `None` before it.
    ///
    /// # Errors
    /// [`Error::State`] when no frame is in progress.
    fn advance(&mut self) -> Result<Option<LaneEstimate>> {
        Err(Error::State(format!(
            "{} has no per-step mode yet; use step()",
            self.id()
        )))
    }
    /// Index into [`Tracker::step_names`] of the next step, or `None` when no frame is in
    /// progress.
    fn next_step(&self) -> Option<usize> {
        None
    }
    /// The resampling decisions of the last [`Tracker::step`] (the whole frame's) or
    /// [`Tracker::advance`] (that step's), as its filters made them, in order; empty after
    /// [`Tracker::begin_frame`] and [`Tracker::reset`] (the schedule's record,
    /// [`crate::filter::Stepper::resamplings`]).
    fn resamplings(&self) -> &[ResampleDecision] {
        &[]
    }
}

/// Checks that an RGBA frame has the camera's size.
///
/// # Errors
/// [`Error::Dimensions`] for another size, [`Error::BufferSize`] for a buffer that is not
/// width * height * 4 bytes.
pub(crate) fn check_frame(camera: &Camera, rgba: &[u8], width: usize, height: usize) -> Result<()> {
    if (width, height) != (camera.width(), camera.height()) {
        return Err(Error::Dimensions(format!(
            "the tracker was built for {}x{} frames but got {width}x{height}",
            camera.width(),
            camera.height()
        )));
    }
    crate::image::check_rgba(rgba, width, height)
}

/// [`Tracker::advance`] of a tracker on the filter core's stepper: the next step of its
/// schedule, and after the last the estimate as `output` makes it the shared type.
///
/// # Errors
/// [`Error::State`] when no frame is in progress.
pub(crate) fn advance_scheduled<T: Scheduled>(
    tracker: &mut T,
    output: impl FnOnce(&T, &T::Estimate) -> LaneEstimate,
) -> Result<Option<LaneEstimate>> {
    if !tracker.stepper().in_progress() {
        return Err(no_frame_in_progress());
    }
    Ok(tracker.advance_step().map(|e| output(tracker, &e)))
}

/// The error of [`Tracker::advance`] without a frame in progress.
fn no_frame_in_progress() -> Error {
    Error::State("no frame in progress: call beginFrame (begin_frame in Rust) first".into())
}
