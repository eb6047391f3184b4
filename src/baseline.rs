//! A classical lane detector, the yardstick the particle filters are measured against on real
//! footage (issue 18: "a 50-line classical OpenCV pipeline: colour mask, Canny, Hough,
//! Kalman"). Not a particle filter and not from the four papers; it is not one of the
//! trackers the package offers, only a row of the real-data report.
//!
//! Per frame it runs the auto-calibration's line detector with the camera's vanishing point
//! known ([`crate::trackers::relock::RelockDetector`]): the white-and-yellow marking image
//! (the colour mask), the centres of narrow bright ridges along rows (in place of Canny's
//! edges), straight lines through them by a Hough transform, and the ego pair, the strong lines
//! nearest the middle leaning towards each other. Each boundary of the pair, taken to the road
//! as y = a + b x, is smoothed by a Kalman filter on (a, b) with a random-walk model and the two
//! components independent:
//!
//! ```text
//! predict:  P <- P + q²
//! update:   K = P / (P + r²),   s <- s + K (z - s),   P <- (1 - K) P
//! ```
//!
//! A detected boundary more than [`RESTART_JUMP_M`] from its filter's offset (another line
//! taken as the ego boundary, a lane change) starts that filter afresh instead of being
//! blended in over several frames. A frame without a detected pair only predicts; the lane
//! stays valid for [`HOLD_FRAMES`] such frames and is then forgotten (the next pair starts the
//! filters afresh). Its lanes are straight and it outputs the ego pair alone.

use crate::camera::Camera;
use crate::error::Result;
use crate::lane::{sample_road_curve, Boundary, LaneEstimate, Role};
use crate::trackers::relock::RelockDetector;
use crate::trackers::Tracker;

/// Frames without a detection the lane stays valid through.
pub const HOLD_FRAMES: usize = 5;
/// A measured offset this far from the filter's, metres, restarts the filter.
pub const RESTART_JUMP_M: f64 = 1.0;
/// Random-walk spread per frame of a boundary's offset (m) and slope.
const PROCESS_SD: [f64; 2] = [0.1, 0.01];
/// Measurement spread of a detected boundary's offset (m) and slope.
const MEASUREMENT_SD: [f64; 2] = [0.15, 0.02];
/// The boundaries are drawn from this distance ahead (or where they enter the image) ...
const NEAR_M: f64 = 3.0;
/// ... to this one, metres.
const FAR_M: f64 = 35.0;

/// One boundary's line y = a + b x on the road and its two variances.
#[derive(Debug, Clone, Copy)]
struct LineFilter {
    state: [f64; 2],
    variance: [f64; 2],
}

impl LineFilter {
    fn start(z: [f64; 2]) -> Self {
        Self {
            state: z,
            variance: MEASUREMENT_SD.map(|s| s * s),
        }
    }

    fn predict(&mut self) {
        for (p, q) in self.variance.iter_mut().zip(PROCESS_SD) {
            *p += q * q;
        }
    }

    fn update(&mut self, z: [f64; 2]) {
        if (z[0] - self.state[0]).abs() > RESTART_JUMP_M {
            *self = Self::start(z);
            return;
        }
        for i in 0..2 {
            let r2 = MEASUREMENT_SD[i] * MEASUREMENT_SD[i];
            let gain = self.variance[i] / (self.variance[i] + r2);
            self.state[i] += gain * (z[i] - self.state[i]);
            self.variance[i] *= 1.0 - gain;
        }
    }
}

/// The classical detector: Hough lines of the marking ridges, Kalman-smoothed.
#[derive(Debug, Clone)]
pub struct ClassicalBaseline {
    camera: Camera,
    detector: RelockDetector,
    /// Left and right boundary, once a pair was seen.
    lines: Option<[LineFilter; 2]>,
    /// Frames since the last detected pair.
    misses: usize,
}

impl ClassicalBaseline {
    /// A detector for frames of `camera`.
    ///
    /// # Errors
    /// As [`RelockDetector::new`].
    pub fn new(camera: &Camera) -> Result<Self> {
        Ok(Self {
            detector: RelockDetector::new(camera)?,
            camera: camera.clone(),
            lines: None,
            misses: 0,
        })
    }

    fn boundary(&self, role: Role, line: [f64; 2]) -> Boundary {
        let (points, road_points) = sample_road_curve(
            |x| line[0] + line[1] * x,
            |x, y| self.camera.road_to_pixel(x, y),
            NEAR_M,
            FAR_M,
            self.camera.width(),
            self.camera.height(),
        );
        Boundary {
            role,
            points,
            road_points,
        }
    }
}

impl Tracker for ClassicalBaseline {
    fn id(&self) -> &'static str {
        "classical-baseline"
    }

    fn step(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<LaneEstimate> {
        crate::trackers::check_frame(&self.camera, rgba, width, height)?;
        self.detector.feed(&self.camera, rgba, width, height)?;
        if let Some(lines) = self.lines.as_mut() {
            lines.iter_mut().for_each(LineFilter::predict);
        }
        match self.detector.detection() {
            Some(d) => {
                let z = [
                    [d.left.offset, d.left.slope],
                    [d.right.offset, d.right.slope],
                ];
                match self.lines.as_mut() {
                    Some(lines) => lines.iter_mut().zip(z).for_each(|(l, z)| l.update(z)),
                    None => self.lines = Some(z.map(LineFilter::start)),
                }
                self.misses = 0;
            }
            None => {
                self.misses += 1;
                if self.misses > HOLD_FRAMES {
                    self.lines = None;
                }
            }
        }
        let Some([left, right]) = self.lines else {
            return Ok(LaneEstimate::default());
        };
        let (l, r) = (left.state, right.state);
        Ok(LaneEstimate {
            valid: true,
            boundaries: vec![
                self.boundary(Role::EgoLeft, l),
                self.boundary(Role::EgoRight, r),
            ],
            lateral_offset_m: -0.5 * (l[0] + r[0]),
            heading_rad: crate::math::atan(0.5 * (l[1] + r[1])),
            curvature_per_m: 0.0,
            lane_width_m: l[0] - r[0],
            ..LaneEstimate::default()
        })
    }

    fn reset(&mut self) {
        self.detector.reset();
        self.lines = None;
        self.misses = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{default_camera, scenario, Eye, Scene};

    /// On rendered roads the baseline follows the ego lane of the truth: after the first
    /// second, valid on at least 90 % of the frames, and where valid the lateral offset within
    /// 0.25 m, the width within 0.3 m (marking centres) and the heading within 0.02 rad (the
    /// relock detector's test's tolerances) on 90 % of them; a frame of another size is an
    /// error and the detector goes on afterwards. Measured (2026-11-30): lane-change, through
    /// its first change, 107 of 116 valid frames right (the filters lag the turn and the jump
    /// of the ego pair; with the heading's sign flipped 41).
    #[test]
    fn the_baseline_follows_the_ego_lane_of_rendered_roads() {
        let camera = default_camera(320, 240).unwrap();
        let mut rgba = vec![0u8; 320 * 240 * 4];
        // lane-change: the car turns about 0.05 rad into the next lane from frame 60 on.
        for (name, frames) in [
            ("highway-straight", 60),
            ("worn-markings", 60),
            ("highway-curve", 60),
            ("lane-change", 150),
        ] {
            let mut config = scenario(name).unwrap();
            config.frames = frames;
            let mut scene = Scene::new(config, camera.clone(), 1).unwrap();
            let mut baseline = ClassicalBaseline::new(&camera).unwrap();
            let (mut scored, mut valid, mut right) = (0, 0, 0);
            for f in 0..frames {
                scene.render(f, Eye::Left, &mut rgba, None).unwrap();
                if f == 30 {
                    assert!(baseline.step(&rgba[..100], 10, 10).is_err());
                }
                let e = baseline.step(&rgba, 320, 240).unwrap();
                if f < 25 {
                    continue;
                }
                scored += 1;
                if !e.valid {
                    continue;
                }
                valid += 1;
                let t = crate::trackers::scene_truth(&scene, f);
                right += usize::from(
                    (e.lateral_offset_m - t.lateral_offset_m).abs() < 0.25
                        && (e.lane_width_m - t.lane_width_m).abs() < 0.3
                        && (e.heading_rad - t.heading_rad).abs() < 0.02
                        && e.boundaries.iter().all(|b| b.check_polyline().is_ok()),
                );
            }
            assert!(
                valid as f64 >= 0.9 * scored as f64 && right as f64 >= 0.9 * valid as f64,
                "{name}: valid {valid} / {scored}, right {right}"
            );
        }
    }

    /// Once the markings are gone (a blank grey road) the lane is held for [`HOLD_FRAMES`]
    /// frames and is "no lane" from the next one on.
    #[test]
    fn without_markings_the_lane_is_held_then_dropped() {
        let camera = default_camera(320, 240).unwrap();
        let mut rgba = vec![0u8; 320 * 240 * 4];
        let mut scene =
            Scene::new(scenario("highway-straight").unwrap(), camera.clone(), 2).unwrap();
        let mut baseline = ClassicalBaseline::new(&camera).unwrap();
        for f in 0..20 {
            scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            baseline.step(&rgba, 320, 240).unwrap();
        }
        let grey = [90u8, 90, 90, 255].repeat(320 * 240);
        let valid: Vec<bool> = (0..HOLD_FRAMES + 3)
            .map(|_| baseline.step(&grey, 320, 240).unwrap().valid)
            .collect();
        let mut expected = vec![true; HOLD_FRAMES];
        expected.extend([false; 3]);
        assert_eq!(valid, expected);
    }
}
