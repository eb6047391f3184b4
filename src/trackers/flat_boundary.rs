//! A boundary polyline taken to the flat road of a camera: the shared geometry of the
//! searches that move an estimate's boundaries sideways onto paint
//! ([`super::adjacent_lanes`], [`super::paint_snap`]).
//!
//! The boundary's image points are taken to the road plane z = 0 of the tracker's camera, so
//! that the searches sit in one frame whatever the tracker's own road model (Danescu's
//! vertical profile included): the boundary is y_b(x), interpolated between them, held
//! constant beyond its ends. A moved boundary y_b(x) + dy(x) is drawn back through the camera
//! over the same distances.

use crate::camera::Camera;
use crate::lane::{sample_road_curve, Boundary, Role};

/// A boundary on the flat road of the camera: (x, y) points, x increasing.
pub struct FlatBoundary {
    points: Vec<[f64; 2]>,
}

impl FlatBoundary {
    /// The boundary's image points on the flat road; `None` with fewer than two.
    pub fn new(camera: &Camera, boundary: &Boundary) -> Option<Self> {
        let mut points: Vec<[f64; 2]> = Vec::with_capacity(boundary.points.len());
        for p in &boundary.points {
            let Ok(q) = camera.pixel_to_road(p[0], p[1]) else {
                break;
            };
            // The polyline runs up the image: distances grow; a point that does not is past
            // a fold (a lens at its rim) and ends it.
            if points.last().is_some_and(|l| q[0] <= l[0]) {
                break;
            }
            points.push(q);
        }
        (points.len() >= 2).then_some(Self { points })
    }

    /// Nearest and farthest distance, metres.
    pub fn range(&self) -> (f64, f64) {
        (self.points[0][0], self.points[self.points.len() - 1][0])
    }

    /// Lateral position at distance `x`, held constant beyond the ends.
    pub fn y_at(&self, x: f64) -> f64 {
        let p = &self.points;
        let i = p.partition_point(|q| q[0] < x);
        if i == 0 {
            return p[0][1];
        }
        if i == p.len() {
            return p[p.len() - 1][1];
        }
        let ([x0, y0], [x1, y1]) = (p[i - 1], p[i]);
        y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    }

    /// The boundary moved sideways by `dy(x)` metres at distance x, as image and road
    /// polylines with `role`; `None` when fewer than two of its points are in view.
    pub fn offset(&self, camera: &Camera, dy: &dyn Fn(f64) -> f64, role: Role) -> Option<Boundary> {
        let (near, far) = self.range();
        let (points, road_points) = sample_road_curve(
            |x| self.y_at(x) + dy(x),
            |x, y| camera.road_to_pixel(x, y),
            near,
            far,
            camera.width(),
            camera.height(),
        );
        (points.len() >= 2).then_some(Boundary {
            role,
            points,
            road_points,
        })
    }
}
