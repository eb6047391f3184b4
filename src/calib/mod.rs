//! Camera auto-calibration: pitch, yaw and height of a camera over a flat road, estimated
//! online from the lane markings, so that any video can be tracked without a `camera.json`.
//!
//! Not from the four papers: this is the project's own, after the vanishing-point calibration
//! of openpilot's calibration daemon and the lane-width prior of "Online Extrinsic Camera
//! Calibration for Temporally Consistent IPM Using Lane Boundary Observations with a Lane Width
//! Prior" (arXiv 2008.03722). Per frame:
//!
//! 1. the marking intensity (white in luma, yellow where blue is low) and the saturation are
//!    box-averaged to at most 480 columns ([`marking_image`]), once a horizon is known only
//!    from 5 % of the height above it down (the sky is not needed);
//! 2. marking pixels are the centres of narrow bright ridges along rows ([`ridges`]), taken
//!    from just below the horizon (once it is known: the mode of the recent lines' crossings,
//!    else the estimate once three frames agree on it) to near the bottom, kept where grey road
//!    darker than the paint lies beside them ([`road_colour`]: not foliage, car paint or sky),
//!    and undistorted when the lens is known;
//! 3. straight lines through them come from a Hough transform with least-squares refinement,
//!    each with its bend ([`hough`]);
//! 4. the ego boundaries are the strong lines nearest the middle at the bottom, the left one
//!    leaning right and the right one leaning left; they meet at the frame's vanishing point.
//!
//! A frame measures the camera when both ego boundaries are straight (bend below
//! `max_bend_px`) and the vanishing points of the last `stable_frames` frames agree within
//! 1.5 % of the width: the stability of the vanishing point picks the straight stretches, as
//! openpilot does with the car's yaw rate. From such a frame ([`pose`]):
//!
//! ```text
//! pitch = atan((cy - v) / fy),   yaw = atan((u - cx) cos(pitch) / fx),   h = W / w_1
//! ```
//!
//! with (u, v) the vanishing point, W the lane-width prior (3.6 m by default) and w_1 the
//! distance between the ego boundaries seen from one metre above the road. The estimate is the
//! median of each over the frames used, with its spread (1.4826 MAD) and a confidence (see
//! [`Calibrator::estimate`]); but the yaw, from ten frames on, is that of a frame that does not
//! bend, from a line through the frames' yaws against their common bend: a gentle bend that
//! passes as straight moves the vanishing point towards its inside ([`bend_regression`]).
//! Once `tangent_yaw_after` frames (100 by default) that agree on the pose have a tangent
//! (and from then until a reset), or from the first frame with `tangent_yaw`, the yaw comes from the lane's tangent at the car instead of
//! the straight lines' crossing ([`tangent`]: both boundaries fitted with a curvature term
//! from [`calibrator::TANGENT_ROW_SHARE`] of the way below the vanishing point,
//! and on a bent frame the horizon row), and the estimate's yaw is the median over every
//! frame that agrees on the pose: the tangent does not follow the bend, so neither the
//! straighter half nor the yaw at zero bend applies to it. Why not from the first frame: on
//! short clips the crossing's yaw, pulled towards a bend's inside, suits a straight lane model
//! (adachi-mmpf) better than the true yaw; on the simulator's 20-s drives the trackers lost
//! at most 1.25 points to the default's cameras, and its yaw was within 0.5 degrees on every
//! seed where the crossing's was on 3 of 12 (RESULTS.md, *Auto-calibration*).
//!
//! What it cannot know: the focal length, which one vanishing point and parallel lines leave
//! undetermined (a wrong f stretches the road lengthwise, not across), comes from the field of
//! view when not given (`hfov_deg`, 60 degrees by default); roll, which one vanishing point does
//! not determine either, is taken as zero; the height is only as right as the lane-width prior.
//!
//! What it assumes (a dash-cam's mount): a pair of lines counts as the ego lane only when its
//! vanishing point implies a pitch of -10 to 20 degrees down and a yaw within 15 degrees
//! ([`calibrator::PITCH_RANGE_DEG`], [`calibrator::MAX_YAW_DEG`]) and, with the lane-width prior,
//! a height of 0.8 to 4 m ([`calibrator::HEIGHT_RANGE_M`]). Tree trunks, poles and the sides of
//! trucks meet where no mounted camera looks; a camera mounted outside these ranges gets no
//! estimate.

pub mod bend_regression;
pub mod box_counts;
pub mod calibrator;
pub mod ego_on_road;
pub mod hough;
pub mod marking_image;
pub mod marking_pixels;
pub mod pose;
pub mod ridges;
pub mod road_colour;
pub mod tangent;
pub mod vp_votes;

pub use calibrator::{CalibrationEstimate, Calibrator, CalibratorConfig, FrameObservation};
pub use hough::LineFit;

#[cfg(test)]
mod tests;
