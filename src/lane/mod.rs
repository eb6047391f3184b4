//! Lane models and the shared output type.

mod estimate;
mod linear_parabolic;
mod polyline;

pub use estimate::{Boundary, LaneEstimate, Role, MAX_POINT_SPACING_PX};
pub use linear_parabolic::LinearParabolic;
pub use polyline::sample_road_curve;
