//! The calibrator's ego boundaries of one frame, taken to the road plane through a known
//! camera: a bottom-up lane detection (ridges, Hough lines, the pair nearest the middle) that
//! a tracker can use as a proposal for its particles (see `relock_share` of `lee-cpf`).
//!
//! An image line through undistorted pixels (u, v) meets the road at
//!
//! ```text
//! r = R^T ((u - cx) / fx, (v - cy) / fy, 1),   (x, y) = h (r_x, r_y) / -r_z
//! ```
//!
//! (R the camera's rotation, h its height). Two rows of each boundary, a quarter of the way
//! down from the vanishing point and near the bottom of the image, give two road points and
//! so a straight boundary y = offset + slope x; a bend is not measured.

use super::FrameObservation;
use crate::camera::Camera;

/// One boundary on the road: y = `offset` + `slope` x (metres; y positive left).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoadLine {
    /// Lateral position at the car (x = 0), metres.
    pub offset: f64,
    /// dy / dx.
    pub slope: f64,
}

/// The ego boundaries of a frame on the road.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EgoOnRoad {
    /// Left boundary.
    pub left: RoadLine,
    /// Right boundary.
    pub right: RoadLine,
}

impl EgoOnRoad {
    /// Lateral position of the lane centre at the car, metres.
    pub fn centre(&self) -> f64 {
        0.5 * (self.left.offset + self.right.offset)
    }

    /// Lane width at the car, metres.
    pub fn width(&self) -> f64 {
        self.left.offset - self.right.offset
    }

    /// Heading of the lane relative to the car, radians, positive left: the mean direction of
    /// the two boundaries.
    pub fn heading(&self) -> f64 {
        crate::math::atan(0.5 * (self.left.slope + self.right.slope))
    }
}

/// The ego boundaries `observation` found, on the road seen by `camera` (whose intrinsics
/// the calibrator was given, so that its undistorted pixels are this camera's); `None` when
/// the frame has no ego pair or a row of it does not meet the road ahead.
pub fn ego_on_road(camera: &Camera, observation: &FrameObservation) -> Option<EgoOnRoad> {
    let [l, r] = observation.ego?;
    let vp = observation.vanishing_point?;
    let bottom = 0.95 * camera.height() as f64;
    let below_vanishing_point = bottom > vp[1];
    if !below_vanishing_point {
        return None;
    }
    let rows = [vp[1] + 0.25 * (bottom - vp[1]), bottom];
    let on_road = |line: usize| -> Option<RoadLine> {
        let fit = observation.lines.get(line)?;
        let [x1, y1] = camera
            .undistorted_pixel_to_road(fit.x_at(rows[0]), rows[0])
            .ok()?;
        let [x2, y2] = camera
            .undistorted_pixel_to_road(fit.x_at(rows[1]), rows[1])
            .ok()?;
        let spans_distance = (x1 - x2).abs() > 1e-6;
        if !spans_distance {
            return None;
        }
        let slope = (y1 - y2) / (x1 - x2);
        Some(RoadLine {
            offset: y2 - slope * x2,
            slope,
        })
    };
    let pair = EgoOnRoad {
        left: on_road(l)?,
        right: on_road(r)?,
    };
    (pair.width() > 0.0 && pair.centre().is_finite() && pair.heading().is_finite()).then_some(pair)
}
