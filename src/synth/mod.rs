//! Synthetic road scenes with exact ground truth.
//!
//! A [`SceneConfig`] (road of clothoid segments, lanes, markings, ego motion, vehicles,
//! shadows, appearance) is built for a [`crate::camera::Camera`] into a [`Scene`] that renders
//! frames by ray casting through the same camera model the trackers use, mono or stereo, with
//! the exact depth of every pixel.

mod appearance;
mod draw;
mod ego;
mod family;
mod kerbs;
mod markings;
mod mount;
mod render;
mod road;
mod scenarios;
mod scene;
mod simulator;
mod test_road;
mod truth;

pub use appearance::hash_unit;
pub use ego::{EgoConfig, LaneChange, Pose};
pub use family::{draw_scenario, family_names, reference_member, FamilyMember, RANDOM_SCENARIO};
pub use markings::{BoundaryStyle, Coverage, MarkingConfig, MarkingStyle, Paint, Pattern, Wear};
pub use mount::{CameraMount, MOUNT_RANGES};
pub use render::MAX_RANGE_M;
pub use road::{LaneGap, Road, RoadConfig, Sample, Segment, WidthChange};
pub use scenarios::{scenario, SCENARIOS};
pub use scene::{Appearance, RoadPaint, SceneConfig, Shadow, Vehicle, VerticalProfile};
pub use simulator::{
    default_camera, drawn_camera, frame_fingerprint, Eye, Scene, DEFAULT_BASELINE_M,
};
pub use test_road::{TestRoad, TestRoadConfig};
pub use truth::{keys as truth_keys, SCENE_KEYS, TRUTH_RANGE_M};
