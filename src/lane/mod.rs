//! Lane models and the shared output type.

mod estimate;
mod polyline;

pub use estimate::{Boundary, LaneEstimate, Role, MAX_POINT_SPACING_PX};
pub use polyline::sample_road_curve;
