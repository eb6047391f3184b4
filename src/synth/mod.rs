//! Synthetic road scenes with exact ground truth.

mod test_road;

pub use test_road::{TestRoad, TestRoadConfig};
