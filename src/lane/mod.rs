//! Lane models and the shared output type.

mod estimate;
mod lane_3d;
mod linear_parabolic;
mod polyline;

pub use estimate::{Boundary, Delimiter, LaneEstimate, Role, Side, MAX_POINT_SPACING_PX};
pub use lane_3d::{Edge, Lane3d, LaneCamera};
pub use linear_parabolic::LinearParabolic;
pub use polyline::sample_road_curve;
