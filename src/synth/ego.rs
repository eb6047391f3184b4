//! Ego motion: where the car is on the road at each frame.
//!
//! The car drives at constant speed v along the road, so at time t = frame / fps its arc
//! length is s(t) = s_0 + v t. Its lateral position (left of the reference line) is
//!
//! ```text
//! D(t) = c(t) + A sin(2 pi t / T)
//! ```
//!
//! where c(t) is the centre of the current lane; a lane change from lane i to lane j starting
//! at t_0 and lasting tau moves c smoothly, c = c_i + (c_j - c_i) (3u^2 - 2u^3), u = (t - t_0)/tau.
//! The car points along its path: its heading relative to the road is atan(dD/ds), with
//! dD/ds = (dD/dt) / v; its world heading is theta(s) + atan(dD/ds) and its yaw rate the time
//! derivative of that (both by central differences with h = 1 ms). The camera pitch and height
//! oscillate with the car body: pitch(t) = pitch_0 + A_p sin(2 pi t / T_p), height(t) = h_0 +
//! A_h sin(2 pi t / T_p + pi/2).

use super::road::Road;
use crate::error::{require_finite, require_positive, Error, Result};
use crate::math;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A lane change.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LaneChange {
    /// Start time, seconds.
    pub at_s: f64,
    /// Target lane (0 leftmost).
    pub to_lane: usize,
    /// Duration, seconds.
    pub duration_s: f64,
}

/// How the car moves.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct EgoConfig {
    /// Speed v, metres per second.
    pub speed_mps: f64,
    /// Frames per second.
    pub fps: f64,
    /// Arc length at frame 0, metres.
    pub start_s: f64,
    /// Lane at frame 0 (0 leftmost).
    pub lane: usize,
    /// Sway amplitude A inside the lane, metres.
    pub sway_amplitude_m: f64,
    /// Sway period T, seconds.
    pub sway_period_s: f64,
    /// Lane changes, in time order.
    pub lane_changes: Vec<LaneChange>,
    /// Pitch oscillation amplitude A_p, degrees.
    pub pitch_amplitude_deg: f64,
    /// Camera height oscillation amplitude A_h, metres.
    pub height_amplitude_m: f64,
    /// Period T_p of the body oscillation, seconds.
    pub body_period_s: f64,
}

impl Default for EgoConfig {
    fn default() -> Self {
        Self {
            speed_mps: 25.0,
            fps: 30.0,
            start_s: 20.0,
            lane: 0,
            sway_amplitude_m: 0.3,
            sway_period_s: 8.0,
            lane_changes: vec![],
            pitch_amplitude_deg: 0.0,
            height_amplitude_m: 0.0,
            body_period_s: 1.2,
        }
    }
}

/// The car at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Time, seconds.
    pub t: f64,
    /// Arc length along the road, metres.
    pub s: f64,
    /// Lateral position left of the reference line, metres.
    pub d: f64,
    /// World position of the point on the road under the camera.
    pub position: [f64; 2],
    /// World heading of the car, radians.
    pub heading: f64,
    /// Heading of the car relative to the road, radians (positive: the car points left).
    pub relative_heading: f64,
    /// Yaw rate, radians per second.
    pub yaw_rate: f64,
    /// Speed, metres per second.
    pub speed: f64,
    /// The lane containing the camera (0 leftmost).
    pub lane: usize,
    /// Camera pitch offset from its calibrated value, radians.
    pub pitch_offset: f64,
    /// Camera height offset from its calibrated value, metres.
    pub height_offset: f64,
}

impl EgoConfig {
    /// Checks the motion against a road with `lanes` lanes.
    ///
    /// # Errors
    /// [`Error::Parameter`] for a bad value, [`Error::Config`] for a lane that does not exist.
    pub fn validate(&self, lanes: usize) -> Result<()> {
        require_positive("speed_mps", self.speed_mps)?;
        require_positive("fps", self.fps)?;
        require_finite("start_s", self.start_s)?;
        require_finite("sway_amplitude_m", self.sway_amplitude_m)?;
        require_positive("sway_period_s", self.sway_period_s)?;
        require_finite("pitch_amplitude_deg", self.pitch_amplitude_deg)?;
        require_finite("height_amplitude_m", self.height_amplitude_m)?;
        require_positive("body_period_s", self.body_period_s)?;
        if self.pitch_amplitude_deg.abs() > 5.0 || self.height_amplitude_m.abs() > 0.3 {
            return Err(Error::Config(
                "body oscillation must stay within 5 degrees of pitch and 0.3 m of height".into(),
            ));
        }
        let lanes_used =
            std::iter::once(self.lane).chain(self.lane_changes.iter().map(|c| c.to_lane));
        for lane in lanes_used {
            if lane >= lanes {
                return Err(Error::Config(format!(
                    "the car cannot drive in lane {lane}: the road has {lanes} lanes"
                )));
            }
        }
        let mut last = f64::NEG_INFINITY;
        for c in &self.lane_changes {
            require_finite("lane_changes.at_s", c.at_s)?;
            require_positive("lane_changes.duration_s", c.duration_s)?;
            if c.at_s < last {
                return Err(Error::Config(
                    "lane changes must be in time order and not overlap".into(),
                ));
            }
            last = c.at_s + c.duration_s;
        }
        Ok(())
    }

    /// Lateral position D(t) on `road`.
    fn lateral(&self, road: &Road, t: f64) -> f64 {
        let s = self.start_s + self.speed_mps * t;
        let mut centre = road.lane_centre(self.lane, s);
        for c in &self.lane_changes {
            if t <= c.at_s {
                break;
            }
            let target = road.lane_centre(c.to_lane, s);
            let u = ((t - c.at_s) / c.duration_s).min(1.0);
            centre += (target - centre) * u * u * (3.0 - 2.0 * u);
        }
        centre + self.sway_amplitude_m * math::sin(2.0 * PI * t / self.sway_period_s)
    }

    /// World heading of the car at time t.
    fn world_heading(&self, road: &Road, t: f64) -> f64 {
        const H: f64 = 1e-3;
        let s = self.start_s + self.speed_mps * t;
        let dd_dt = (self.lateral(road, t + H) - self.lateral(road, t - H)) / (2.0 * H);
        road.at(s).heading + math::atan(dd_dt / self.speed_mps)
    }

    /// The pose at frame `frame`.
    pub fn pose(&self, road: &Road, frame: u32) -> Pose {
        const H: f64 = 1e-3;
        let t = frame as f64 / self.fps;
        let s = self.start_s + self.speed_mps * t;
        let d = self.lateral(road, t);
        let heading = self.world_heading(road, t);
        let yaw_rate =
            (self.world_heading(road, t + H) - self.world_heading(road, t - H)) / (2.0 * H);
        let lane = (0..road.lanes())
            .find(|&i| d <= road.boundary_offset(i, s) && d > road.boundary_offset(i + 1, s))
            .unwrap_or(if d > 0.0 { 0 } else { road.lanes() - 1 });
        let phase = 2.0 * PI * t / self.body_period_s;
        Pose {
            t,
            s,
            d,
            position: road.point(s, d),
            heading,
            relative_heading: heading - road.at(s).heading,
            yaw_rate,
            speed: self.speed_mps,
            lane,
            pitch_offset: math::deg_to_rad(self.pitch_amplitude_deg) * math::sin(phase),
            height_offset: self.height_amplitude_m * math::cos(phase),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::road::{RoadConfig, Segment};

    fn road() -> Road {
        let config = RoadConfig {
            segments: vec![Segment {
                length_m: 2000.0,
                curvature: 0.002,
                curvature_rate: 0.0,
            }],
            lanes: 3,
            lane_width_m: 3.6,
            width_changes: vec![],
            lane_gaps: vec![],
        };
        Road::new(config, 1000.0).unwrap()
    }

    #[test]
    fn the_car_follows_its_lane_and_turns_with_the_road() {
        let road = road();
        let ego = EgoConfig {
            lane: 1,
            sway_amplitude_m: 0.0,
            ..Default::default()
        };
        ego.validate(3).unwrap();
        let p = ego.pose(&road, 60);
        assert!((p.t - 2.0).abs() < 1e-12 && (p.s - 70.0).abs() < 1e-12);
        assert_eq!((p.d, p.lane), (0.0, 1));
        assert!(p.relative_heading.abs() < 1e-9);
        // Yaw rate = v kappa on a circle.
        assert!((p.yaw_rate - 25.0 * 0.002).abs() < 1e-6, "{}", p.yaw_rate);
    }

    #[test]
    fn a_lane_change_moves_the_car_one_lane_width_with_a_heading() {
        let road = road();
        let ego = EgoConfig {
            lane: 1,
            sway_amplitude_m: 0.0,
            lane_changes: vec![LaneChange {
                at_s: 1.0,
                to_lane: 2,
                duration_s: 3.0,
            }],
            ..Default::default()
        };
        ego.validate(3).unwrap();
        let mid = ego.pose(&road, 75); // t = 2.5 s: half-way
        assert!((mid.d + 1.8).abs() < 1e-9, "{}", mid.d);
        // Moving right (negative d) at the steepest point: dD/dt = -3.6 * 1.5 / 3.
        let want = math::atan(-3.6 * 1.5 / 3.0 / 25.0);
        assert!((mid.relative_heading - want).abs() < 1e-6);
        let end = ego.pose(&road, 150);
        assert!((end.d + 3.6).abs() < 1e-9 && end.lane == 2);
        let bad = EgoConfig {
            lane: 3,
            ..Default::default()
        };
        assert!(bad.validate(3).unwrap_err().to_string().contains("lane 3"));
    }
}
