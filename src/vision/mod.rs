//! Image preprocessing, one operation per file. Each operation is an executor struct that owns
//! its output and scratch buffers, so that a tracker builds it once and calls it every frame
//! without allocating.
//!
//! - [`Ipm`]: inverse perspective mapping to a metric top view (lookup table, bilinear);
//! - [`Gradients`]: Sobel gx, gy, magnitude and orientation;
//! - [`GaussianBlur`]: separable Gaussian smoothing;
//! - [`Canny`]: Canny edges with hysteresis;
//! - [`Dld`]: the dark-light-dark marking detector of Lee et al. (eqs. 21-24);
//! - [`DistanceTransform`]: the exact Euclidean distance transform;
//! - [`HGradient`]: Danescu's horizontal gradient with a variable-width kernel;
//! - [`Density`]: Danescu's 3-D point density image in the lateral plane and DT^D;
//! - [`StereoMatcher`]: dense stereo disparity of the road rows by census block matching.

mod blur;
mod canny;
mod density;
mod disparity;
mod distance_transform;
mod dld;
mod gradient;
mod hgradient;
mod ipm;

pub use blur::{GaussianBlur, MAX_SIGMA};
pub use canny::{Canny, CannyConfig, EDGE};
pub use density::{Density, DensityConfig};
pub use disparity::{DisparityConfig, StereoMatcher, MAX_DISPARITY, MAX_RADIUS};
pub use distance_transform::DistanceTransform;
pub use dld::{Dld, DldConfig, FALLING, RISING};
pub use gradient::Gradients;
pub use hgradient::{HGradient, HGradientConfig};
pub use ipm::{Ipm, TopViewConfig};
