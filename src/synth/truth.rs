//! Exact ground truth of a simulator frame, in tracker-neutral terms.
//!
//! Boundaries are sampled on the road model itself (not on the rendered pixels): for a
//! distance x ahead in the vehicle frame, the point of boundary k with that x is found by
//! Newton steps on the arc length, lifted onto the road surface z = C_V x^2 / 2 and projected
//! through the frame's camera (calibrated pose plus the body oscillation), exactly as the
//! renderer casts rays. The ego lane's two boundaries are always listed; a neighbour lane's
//! outer boundary (`left-adjacent`, `right-adjacent`) is listed whenever that lane exists at
//! the car, even with no point in view. The scalar parameters are evaluated at the car:
//!
//! - `lateral_offset_m` o: camera left of the ego-lane centre; `heading_rad`: the lane's
//!   direction relative to the car (positive left); `curvature_per_m`: of the ego-lane centre,
//!   kappa / (1 - kappa d_c); `lane_width_m`: W between marking centres.
//! - Motion (the trackers' ego-motion input): `t`, `speed_mps`, `yaw_rate`, `ego_lane`, and
//!   `lane_change` = 1 while the camera's lane differs from the previous frame's, `blackout` = 1
//!   on frames of a total blackout (the disturbances `lanepf eval` measures recovery from).
//! - The scene ([`keys`], [`SCENE_KEYS`]): what a paper's parameters need that the fields and
//!   boundaries above do not say. `lane_width_rate_m_per_m` dW/ds; `marking_width_left_m` /
//!   `marking_width_right_m` W_L / W_R, the painted widths of the ego lane's boundaries (0 for
//!   none or a kerb); `vertical_curvature_per_m` C_V; `camera_height_change_m` the camera's
//!   height above its calibrated height; `pitch_rad` the camera's pitch (calibrated plus the
//!   body oscillation, positive looking down); `roll_rad` its roll (positive when its right
//!   side dips, as camera.json's `roll_deg`); `curvature_change_ahead_m` the distance ahead to
//!   the next change of curvature within [`TRUTH_RANGE_M`] (0 inside a curve or transition,
//!   [`TRUTH_RANGE_M`] when none) and `curvature_ahead_per_m` the curvature the road reaches
//!   there.
//!
//! The simulator knows no paper: each tracker maps this truth to its own parameters
//! (`truth_parameters` in the tracker's folder, `src/trackers/<paper>/truth.rs`), and the
//! trackers' `papers_truth` gives the truth the command line writes (`gt.jsonl`), the
//! evaluators and the wasm `Scene.truth` use: these fields and boundaries, the motion keys and
//! every paper's parameters.

use super::ego::Pose;
use super::markings::Pattern;
use super::render::MAX_RANGE_M;
use super::simulator::Scene;
use crate::camera::Camera;
use crate::lane::{sample_road_curve, Boundary, LaneEstimate, Role};
use crate::math;

/// Nearest distance sampled, metres.
const X_MIN_M: f64 = 1.0;
/// Farthest distance reported, metres.
pub const TRUTH_RANGE_M: f64 = 120.0;

/// The names of the scene's keys in a truth's `state` (see the module docs).
pub mod keys {
    /// dW/ds, the change of the lane width per metre along the road.
    pub const LANE_WIDTH_RATE: &str = "lane_width_rate_m_per_m";
    /// W_L, the painted width of the ego lane's left boundary, metres (0: none or a kerb).
    pub const MARKING_WIDTH_LEFT: &str = "marking_width_left_m";
    /// W_R, the painted width of the ego lane's right boundary, metres (0: none or a kerb).
    pub const MARKING_WIDTH_RIGHT: &str = "marking_width_right_m";
    /// C_V, the vertical curvature of the road (surface z = C_V x^2 / 2), 1/m.
    pub const VERTICAL_CURVATURE: &str = "vertical_curvature_per_m";
    /// The camera's height above its calibrated height, metres.
    pub const CAMERA_HEIGHT_CHANGE: &str = "camera_height_change_m";
    /// The camera's pitch, calibrated plus the body oscillation, radians (positive looking
    /// down).
    pub const PITCH: &str = "pitch_rad";
    /// The camera's roll, radians (positive when its right side dips).
    pub const ROLL: &str = "roll_rad";
    /// Distance ahead to the next change of curvature, metres (0 inside a curve or
    /// transition; the truth range when there is none).
    pub const CURVATURE_CHANGE_AHEAD: &str = "curvature_change_ahead_m";
    /// The curvature the road reaches at the end of that change, 1/m.
    pub const CURVATURE_AHEAD: &str = "curvature_ahead_per_m";
}

/// Every scene key of a truth's `state` ([`keys`]): the quantities only the papers' mappings
/// read (the trackers' `papers_truth` leaves them out of the truth it gives).
pub const SCENE_KEYS: [&str; 9] = [
    keys::LANE_WIDTH_RATE,
    keys::MARKING_WIDTH_LEFT,
    keys::MARKING_WIDTH_RIGHT,
    keys::VERTICAL_CURVATURE,
    keys::CAMERA_HEIGHT_CHANGE,
    keys::PITCH,
    keys::ROLL,
    keys::CURVATURE_CHANGE_AHEAD,
    keys::CURVATURE_AHEAD,
];

impl Scene {
    /// The camera of `pose` (calibrated pitch and height plus the body oscillation).
    pub fn frame_camera(&self, pose: &Pose) -> Camera {
        let mut file = self.camera().to_file();
        file.pitch_deg += math::rad_to_deg(pose.pitch_offset);
        file.height_m += pose.height_offset;
        // The offsets are validated to keep the camera valid (|pitch| < 5 deg, |h| < 0.3 m
        // on a camera that was valid); fall back to the calibrated camera otherwise.
        Camera::from_file(&file).unwrap_or_else(|_| self.camera().clone())
    }

    /// Vehicle-frame lateral position y of boundary `k` at distance `x` ahead, or `None`
    /// beyond the built road.
    pub fn boundary_y(&self, pose: &Pose, k: usize, x: f64) -> Option<f64> {
        let road = self.road();
        let (ch, sh) = (math::cos(pose.heading), math::sin(pose.heading));
        let local = |s: f64| {
            let [px, py] = road.point(s, road.boundary_offset(k, s));
            let (dx, dy) = (px - pose.position[0], py - pose.position[1]);
            (dx * ch + dy * sh, -dx * sh + dy * ch)
        };
        let mut s = pose.s + x;
        for _ in 0..20 {
            let (lx, _) = local(s);
            let rel = road.at(s).heading - pose.heading;
            let step = (x - lx) / math::cos(rel).max(0.2);
            s += step;
            if step.abs() < 1e-9 {
                break;
            }
        }
        (s <= road.length()).then(|| local(s).1)
    }

    /// The exact ground truth of `frame`.
    pub fn truth(&self, frame: u32) -> LaneEstimate {
        let pose = self.pose(frame);
        let road = self.road();
        let config = self.config();
        let cam = self.frame_camera(&pose);
        let c_v = config.vertical.curvature;
        let (s, lane) = (pose.s, pose.lane);
        let centre = road.lane_centre(lane, s);
        let o = pose.d - centre;
        let width = road.lane_width(s);
        let mut boundaries = Vec::new();
        let mut roles = vec![(Role::EgoLeft, lane), (Role::EgoRight, lane + 1)];
        let left_neighbour = lane > 0 && road.lane_exists(lane - 1, s);
        let right_neighbour = road.lane_exists(lane + 1, s);
        if left_neighbour {
            roles.push((Role::LeftAdjacent, lane - 1));
        }
        if right_neighbour {
            roles.push((Role::RightAdjacent, lane + 2));
        }
        for (role, k) in roles {
            let (points, road_points) = sample_road_curve(
                |x| self.boundary_y(&pose, k, x).unwrap_or(f64::NAN),
                |x, y| {
                    if !y.is_finite() {
                        return None;
                    }
                    cam.project([x, y, c_v * x * x / 2.0])
                },
                X_MIN_M,
                TRUTH_RANGE_M.min(MAX_RANGE_M),
                self.width(),
                self.height(),
            );
            boundaries.push(Boundary {
                role,
                points,
                road_points,
            });
        }
        let sample = road.at(s);
        let kappa = sample.curvature / (1.0 - sample.curvature * centre);
        let heading = -pose.relative_heading;
        let marking_width = |k: usize| {
            config
                .markings
                .style(road, k, s)
                .filter(|st| !matches!(st.pattern, Pattern::None | Pattern::Curb))
                .map_or(0.0, |st| st.width_m)
        };
        let (wl_mark, wr_mark) = (marking_width(lane), marking_width(lane + 1));
        let previous_lane = if frame > 0 {
            self.pose(frame - 1).lane
        } else {
            lane
        };
        let (ahead_m, ahead_per_m) = self.next_curvature_change(s);
        let pairs = [
            ("t", pose.t),
            ("speed_mps", pose.speed),
            ("yaw_rate", pose.yaw_rate),
            ("ego_lane", lane as f64),
            ("lane_change", f64::from(u8::from(previous_lane != lane))),
            ("blackout", f64::from(u8::from(self.blacked_out(frame)))),
            (keys::LANE_WIDTH_RATE, road.lane_width_rate(s)),
            (keys::MARKING_WIDTH_LEFT, wl_mark),
            (keys::MARKING_WIDTH_RIGHT, wr_mark),
            (keys::VERTICAL_CURVATURE, c_v),
            (keys::CAMERA_HEIGHT_CHANGE, pose.height_offset),
            (keys::PITCH, cam.pitch()),
            (keys::ROLL, math::deg_to_rad(cam.to_file().roll_deg)),
            (keys::CURVATURE_CHANGE_AHEAD, ahead_m),
            (keys::CURVATURE_AHEAD, ahead_per_m),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v));
        // Inserted, not collected: `collect` into a map sorts its pairs first, one more
        // instance of the stable sort in the wasm (issue 21 part 5); the last of a repeated key
        // wins either way.
        let mut state = std::collections::BTreeMap::new();
        for (k, v) in pairs {
            state.insert(k, v);
        }
        LaneEstimate {
            frame: format!("{frame:06}.png"),
            valid: true,
            ms: 0.0,
            boundaries,
            lateral_offset_m: o,
            heading_rad: heading,
            curvature_per_m: kappa,
            lane_width_m: width,
            delimiters: Vec::new(),
            state,
        }
    }

    /// Distance ahead of `s` to the next change of curvature within the truth range and the
    /// curvature reached at the end of that change; (0, kappa) when the curvature is changing
    /// or non-zero here.
    fn next_curvature_change(&self, s: f64) -> (f64, f64) {
        let road = self.road();
        let here = road.at(s);
        if here.curvature_rate.abs() > 1e-12 || here.curvature.abs() > 1e-9 {
            // Inside a transition or a curve: report the curvature it settles at.
            let mut x = 0.0;
            while x < TRUTH_RANGE_M && road.at(s + x).curvature_rate.abs() > 1e-12 {
                x += 0.5;
            }
            return (0.0, road.at(s + x).curvature);
        }
        let mut x = 0.0;
        while x < TRUTH_RANGE_M {
            let a = road.at(s + x);
            if a.curvature_rate.abs() > 1e-12 || a.curvature.abs() > 1e-9 {
                let mut end = x;
                while end < x + 500.0 && road.at(s + end).curvature_rate.abs() > 1e-12 {
                    end += 0.5;
                }
                return (x, road.at(s + end).curvature);
            }
            x += 0.5;
        }
        (TRUTH_RANGE_M, 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{scenario, Eye, SCENARIOS};

    fn camera(w: usize, h: usize) -> Camera {
        let f = 0.8 * w as f64;
        Camera::from_json_str(&format!(
            r#"{{"width": {w}, "height": {h}, "fx": {f}, "fy": {f}, "cx": {cx}, "cy": {cy},
                "height_m": 1.5, "pitch_deg": 4.0, "baseline_m": 0.4}}"#,
            cx = w as f64 / 2.0,
            cy = h as f64 / 2.0
        ))
        .unwrap()
    }

    fn luma(rgba: &[u8], w: usize, p: [f64; 2]) -> f64 {
        let i = (p[1].round() as usize * w + p[0].round() as usize) * 4;
        0.299 * rgba[i] as f64 + 0.587 * rgba[i + 1] as f64 + 0.114 * rgba[i + 2] as f64
    }

    /// For every scenario: the ground-truth boundary points that carry visible, unoccluded
    /// paint filling a pixel land on pixels that the paint clearly brightens: the same scene
    /// rendered without any paint (same seed, so same texture, shadows and noise) is much
    /// darker there.
    fn truth_lands_on_markings(w: usize, h: usize, frames: &[u32]) {
        let cam = camera(w, h);
        for (name, _) in SCENARIOS {
            truth_lands_on_markings_of(name, scenario(name).unwrap(), &cam, 3, frames);
        }
    }

    /// [`truth_lands_on_markings`] for one scene.
    fn truth_lands_on_markings_of(
        name: &str,
        config: crate::synth::SceneConfig,
        cam: &Camera,
        seed: u64,
        frames: &[u32],
    ) {
        let (w, h) = (cam.width(), cam.height());
        {
            let mut scene = Scene::new(config.clone(), cam.clone(), seed).unwrap();
            let mut unpainted = config;
            unpainted.markings.wear = vec![crate::synth::Wear {
                from_s: -1e9,
                to_s: 1e9,
                boundary: None,
                visibility: 0.0,
            }];
            let mut bare_scene = Scene::new(unpainted, cam.clone(), seed).unwrap();
            let mut bare = vec![0; w * h * 4];
            let mut rgba = vec![0; w * h * 4];
            let mut depth = vec![0.0; w * h];
            let (mut checked, mut bright) = (0, 0);
            for &frame in frames {
                if scene.blacked_out(frame) {
                    continue;
                }
                let pose = scene
                    .render(frame, Eye::Left, &mut rgba, Some(&mut depth))
                    .unwrap();
                bare_scene
                    .render(frame, Eye::Left, &mut bare, None)
                    .unwrap();
                let truth = scene.truth(frame);
                let fcam = scene.frame_camera(&pose);
                let road = scene.road();
                for b in &truth.boundaries {
                    for q in &b.road_points {
                        // Where is this point on the road, and which paint lines does its
                        // boundary carry there (one, or two for a double line)?
                        let (ch, sh) = (math::cos(pose.heading), math::sin(pose.heading));
                        let world = [
                            pose.position[0] + q[0] * ch - q[1] * sh,
                            pose.position[1] + q[0] * sh + q[1] * ch,
                        ];
                        let (s, d) = road.project(world, pose.s + q[0]);
                        let n = road.lanes() as f64;
                        let k = (n / 2.0 - d / road.lane_width(s)).round() as usize;
                        let Some(style) = scene.config().markings.style(road, k, s) else {
                            continue;
                        };
                        let offsets = match style.pattern {
                            Pattern::Double { gap_m } => {
                                let off = (gap_m + style.width_m) / 2.0;
                                vec![-off, off]
                            }
                            _ => vec![0.0],
                        };
                        for off in offsets {
                            let (y, d) = (q[1] + off, d + off);
                            // Only where paint fills the pixel's whole footprint (as the
                            // renderer computes it, widened by the half-pixel rounding).
                            let cov = scene.config().markings.coverage(road, s, d, 1e-3, 1e-3);
                            let fs = q[0] * q[0] / (fcam.focal()[1] * fcam.height_m());
                            let fd = q[0] / fcam.focal()[0] + (y / q[0]).abs() * fs;
                            let wide =
                                scene
                                    .config()
                                    .markings
                                    .coverage(road, s, d, fd * 2.0, fs * 2.0);
                            if cov.alpha < 0.9 || wide.alpha < 0.9 {
                                continue;
                            }
                            let zs = scene.config().vertical.curvature * q[0] * q[0] / 2.0;
                            let Some(p) = fcam.project([q[0], y, zs]) else {
                                continue;
                            };
                            let hood = h as f64 * (1.0 - scene.config().appearance.hood);
                            if p[0] < 0.0
                                || p[0] > (w - 1) as f64
                                || p[1] < 0.0
                                || p[1] > hood - 2.0
                            {
                                continue;
                            }
                            let z = fcam.road_to_camera([q[0], y, zs])[2];
                            let i = p[1].round() as usize * w + p[0].round() as usize;
                            if (depth[i] as f64 - z).abs() > 0.05 * z {
                                continue; // occluded by a vehicle
                            }
                            let (on, off) = (luma(&rgba, w, p), luma(&bare, w, p));
                            if !(20.0..200.0).contains(&off) {
                                continue; // too dark (night) or saturated (glare) to compare
                            }
                            checked += 1;
                            if on > off * 1.25 + 10.0 {
                                bright += 1;
                            } else if std::env::var("LANEPF_DEBUG").is_ok() {
                                eprintln!(
                                    "{name} {frame} {:?} x={:.1} p={p:?} on={on:.0} off={off:.0}",
                                    b.role, q[0]
                                );
                            }
                        }
                    }
                }
            }
            assert!(checked >= 10, "{name}: only {checked} points to check");
            let rate = bright as f64 / checked as f64;
            assert!(
                rate > 0.95,
                "{name}: {bright}/{checked} truth points on paint"
            );
        }
    }

    #[test]
    fn truth_lands_on_rendered_markings_in_every_scenario() {
        truth_lands_on_markings(320, 240, &[0, 45, 120, 200]);
    }

    /// The same on drawn family members: drawn roads, markings and cameras (yaw, roll, field
    /// of view) render where the truth says.
    #[test]
    fn truth_lands_on_rendered_markings_of_family_members() {
        for (name, _) in SCENARIOS {
            for seed in 1..=2 {
                let m = crate::synth::draw_scenario(name, seed).unwrap();
                let cam = m.mount.camera(320, 240).unwrap();
                truth_lands_on_markings_of(name, m.config, &cam, seed, &[30, 150]);
            }
        }
    }

    #[test]
    fn truth_lands_on_rendered_markings_at_640x480_and_1280x720() {
        truth_lands_on_markings(640, 480, &[10, 150]);
        truth_lands_on_markings(1280, 720, &[10]);
    }

    #[test]
    fn stereo_pixels_agree_with_the_true_disparity() {
        // Every scenario (`urban` has raised kerbs and pavements: their faces and tops must
        // agree too).
        for (name, _) in SCENARIOS {
            stereo_pair_agrees_with_the_true_disparity(name);
        }
    }

    fn stereo_pair_agrees_with_the_true_disparity(name: &str) {
        let mut config = scenario(name).unwrap();
        config.appearance.noise = 0.0;
        // Glare and vignette sit at the same image place in both eyes: not a scene property.
        config.appearance.glare = None;
        config.appearance.vignette = 0.0;
        let (w, h) = (320, 240);
        let mut scene = Scene::new(config, camera(w, h), 1).unwrap();
        let (mut left, mut right) = (vec![0; w * h * 4], vec![0; w * h * 4]);
        let mut depth = vec![0.0; w * h];
        scene
            .render(30, Eye::Left, &mut left, Some(&mut depth))
            .unwrap();
        scene.render(30, Eye::Right, &mut right, None).unwrap();
        let fb = scene.camera().focal()[0] * scene.baseline();
        let (mut err_true, mut err_off, mut n) = (0.0, 0.0, 0);
        // The hood too is painted at the same place in both eyes.
        let bottom = (h as f64 * (1.0 - scene.config().appearance.hood)) as usize - 2;
        for v in (h / 2 + 10..bottom).step_by(3) {
            for u in (40..w - 40).step_by(2) {
                let z = depth[v * w + u] as f64;
                if z <= 0.0 {
                    continue;
                }
                let ur = u as f64 - fb / z;
                let sample = |x: f64| {
                    let (x0, a) = (x.floor() as usize, x - x.floor());
                    let p = |x: usize| right[(v * w + x) * 4 + 1] as f64;
                    p(x0) * (1.0 - a) + p(x0 + 1) * a
                };
                let l = left[(v * w + u) * 4 + 1] as f64;
                err_true += (l - sample(ur)).abs();
                err_off += (l - sample(ur + 4.0)).abs();
                n += 1;
            }
        }
        let (err_true, err_off) = (err_true / n as f64, err_off / n as f64);
        assert!(
            err_true < 1.5,
            "{name}: mean error at the true disparity {err_true}"
        );
        assert!(err_off > 2.0 * err_true, "{name}: {err_off} vs {err_true}");
    }

    #[test]
    fn truth_parameters_follow_the_scene() {
        let cam = camera(320, 240);
        // Width change: W and dW/ds from the road, the markings' widths.
        let scene = Scene::new(scenario("width-change").unwrap(), cam.clone(), 1).unwrap();
        let t = scene.truth(120); // s = 20 + 25 * 4 = 120 m: inside the 60..160 m change
        assert!(
            (t.lane_width_m - (3.6 + 0.9 * 0.6)).abs() < 1e-9,
            "{}",
            t.lane_width_m
        );
        assert!((t.state[keys::LANE_WIDTH_RATE] - 0.009).abs() < 1e-12);
        let marks = t.state[keys::MARKING_WIDTH_LEFT] + t.state[keys::MARKING_WIDTH_RIGHT];
        assert!((marks / 2.0 - 0.15).abs() < 1e-12, "{marks}");
        // Curve: curvature of the lane centre, and the transition ahead.
        let scene = Scene::new(scenario("highway-curve").unwrap(), cam.clone(), 1).unwrap();
        let t0 = scene.truth(0); // s = 20: the clothoid starts at 60 m
        assert!(
            (t0.state[keys::CURVATURE_CHANGE_AHEAD] - 40.0).abs() <= 0.5,
            "{}",
            t0.state[keys::CURVATURE_CHANGE_AHEAD]
        );
        assert!((t0.state[keys::CURVATURE_AHEAD] - 0.002).abs() < 1e-9);
        let t = scene.truth(240); // s = 220: on the 500 m arc
        assert!(
            (t.curvature_per_m - 0.002).abs() < 5e-5,
            "{}",
            t.curvature_per_m
        );
        // Lane change: events and adjacent lanes.
        let scene = Scene::new(scenario("lane-change").unwrap(), cam, 1).unwrap();
        let events: Vec<u32> = (0..360)
            .filter(|&f| scene.truth(f).state["lane_change"] == 1.0)
            .collect();
        assert_eq!(events.len(), 2, "{events:?}");
        let t = scene.truth(0);
        // Lanes on both sides: both adjacent boundaries are listed.
        assert_eq!(t.boundaries.len(), 4);
        assert!(t.boundaries.iter().any(|b| b.role == Role::LeftAdjacent));
        assert!(t.boundaries.iter().any(|b| b.role == Role::RightAdjacent));
        // Only the motion and scene keys: the papers' parameters are the trackers' business.
        assert_eq!(t.state.len(), 6 + SCENE_KEYS.len());
        for b in &t.boundaries {
            b.check_polyline().unwrap();
        }
    }
}
