//! Exact ground truth of a simulator frame.
//!
//! Boundaries are sampled on the road model itself (not on the rendered pixels): for a
//! distance x ahead in the vehicle frame, the point of boundary k with that x is found by
//! Newton steps on the arc length, lifted onto the road surface z = C_V x^2 / 2 and projected
//! through the frame's camera (calibrated pose plus the body oscillation), exactly as the
//! renderer casts rays. The scalar parameters are evaluated at the car:
//!
//! - `lateral_offset_m` o: camera left of the ego-lane centre; `heading_rad`: the lane's
//!   direction relative to the car (positive left); `curvature_per_m`: of the ego-lane centre,
//!   kappa / (1 - kappa d_c); `lane_width_m`: W between marking centres.
//! - Lee et al. (eq. 18-19): `lee.psi` = heading, `lee.y0` = -o (lane centre, y left),
//!   `lee.w` = W, `lee.w1` = dW/ds, `lee.c` = distance ahead to the next change of curvature
//!   (0 inside a curve or transition), `lee.delta` = the curvature the road reaches there.
//! - Danescu & Nedevschi (Sec. II, X right): `danescu.w0` = W - (W_L + W_R)/2 (between inner
//!   edges), `danescu.ch` = -kappa (curving right positive), `danescu.wl` = dW/ds, `danescu.cv` = C_V, `danescu.y0` = the
//!   camera's height change, `danescu.xcw` = o (lane centre to the right of the camera),
//!   `danescu.alpha` = pitch, `danescu.gamma` = roll, `danescu.psi` = -heading,
//!   `danescu.wl_mark` / `danescu.wr_mark` = W_L / W_R.
//! - Adachi et al. (eq. 3, 5): on their rho axis (across the road, positive to the right, so
//!   that rho_3 = q - 3w/2 is the left neighbour's boundary), `adachi.q` = o (the ego-lane
//!   centre relative to the car), `adachi.w` = W, `adachi.r` = the paper's model number: 1 ego
//!   lane only, 2 with a left neighbour, 3 with a right neighbour, 4 with both.
//! - Motion (Danescu's drift input): `t`, `speed_mps`, `yaw_rate`, `ego_lane`, and
//!   `lane_change` = 1 while the camera's lane differs from the previous frame's, `blackout` = 1
//!   on frames of a total blackout (the disturbances `lanepf eval` measures recovery from).
//!
//! - Liu et al. (eqs. 15-16): `liu.<role>.rho`, `liu.<role>.theta`, `liu.<role>.d` of each
//!   boundary on the default top view of `liu-ppf` (pixels, y_m at half its height), by least
//!   squares on the boundary's points inside the top view, as the paper computes its ground
//!   truth from marked lane points.

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
        let (lee_c, lee_delta) = self.next_curvature_change(s);
        let previous_lane = if frame > 0 {
            self.pose(frame - 1).lane
        } else {
            lane
        };
        let liu = liu_truth(&boundaries);
        let pairs = [
            ("t", pose.t),
            ("speed_mps", pose.speed),
            ("yaw_rate", pose.yaw_rate),
            ("ego_lane", lane as f64),
            ("lane_change", f64::from(u8::from(previous_lane != lane))),
            ("blackout", f64::from(u8::from(self.blacked_out(frame)))),
            ("lee.psi", heading),
            ("lee.y0", -o),
            ("lee.w", width),
            ("lee.w1", road.lane_width_rate(s)),
            ("lee.c", lee_c),
            ("lee.delta", lee_delta),
            ("danescu.w0", width - (wl_mark + wr_mark) / 2.0),
            ("danescu.ch", -kappa),
            ("danescu.wl", road.lane_width_rate(s)),
            ("danescu.cv", c_v),
            ("danescu.y0", pose.height_offset),
            ("danescu.xcw", o),
            ("danescu.alpha", cam.pitch()),
            ("danescu.gamma", math::deg_to_rad(cam.to_file().roll_deg)),
            ("danescu.psi", -heading),
            ("danescu.wl_mark", wl_mark),
            ("danescu.wr_mark", wr_mark),
            ("adachi.q", o),
            ("adachi.w", width),
            (
                "adachi.r",
                f64::from(1 + u8::from(left_neighbour) + 2 * u8::from(right_neighbour)),
            ),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .chain(liu);
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

    /// Lee's (c, delta): distance ahead of `s` to the next change of curvature within the
    /// truth range and the curvature reached at the end of that change; (0, kappa) when the
    /// curvature is changing or non-zero here.
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

/// Liu's (rho, theta, d) of each boundary on `liu-ppf`'s default top view (see the module
/// docs); boundaries with too few points in the view are left out.
fn liu_truth(boundaries: &[Boundary]) -> Vec<(String, f64)> {
    let config = crate::trackers::liu::config::LiuConfig::default();
    let v = config.top_view;
    let Ok((_, height)) = v.size() else {
        return Vec::new();
    };
    let y_m = config.split_row(height);
    let mut out = Vec::new();
    for b in boundaries {
        let points: Vec<[f64; 2]> = b
            .road_points
            .iter()
            .map(|&[x, y]| {
                [
                    (v.y_left_m - y) / v.m_per_px - 0.5,
                    (v.x_max_m - x) / v.m_per_px - 0.5,
                ]
            })
            .filter(|&[_, r]| r >= 0.0 && r < height as f64)
            .collect();
        if let Some(m) = crate::lane::LinearParabolic::fit(&points, y_m) {
            let role = b.role.as_str();
            out.push((format!("liu.{role}.rho"), m.rho));
            out.push((format!("liu.{role}.theta"), m.theta));
            out.push((format!("liu.{role}.d"), m.d));
        }
    }
    out
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
        // Width change: W and W_l from the road; Lee and Danescu agree.
        let scene = Scene::new(scenario("width-change").unwrap(), cam.clone(), 1).unwrap();
        let t = scene.truth(120); // s = 20 + 25 * 4 = 120 m: inside the 60..160 m change
        assert!(
            (t.lane_width_m - (3.6 + 0.9 * 0.6)).abs() < 1e-9,
            "{}",
            t.lane_width_m
        );
        assert!((t.state["lee.w1"] - 0.009).abs() < 1e-12);
        assert_eq!(t.state["danescu.wl"], t.state["lee.w1"]);
        assert!((t.state["danescu.w0"] - (t.lane_width_m - 0.15)).abs() < 1e-12);
        // Curve: curvature of the lane centre, and Lee's transition point ahead.
        let scene = Scene::new(scenario("highway-curve").unwrap(), cam.clone(), 1).unwrap();
        let t0 = scene.truth(0); // s = 20: the clothoid starts at 60 m
        assert!(
            (t0.state["lee.c"] - 40.0).abs() <= 0.5,
            "{}",
            t0.state["lee.c"]
        );
        assert!((t0.state["lee.delta"] - 0.002).abs() < 1e-9);
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
        assert_eq!(
            t.state["adachi.r"], 4.0,
            "lanes on both sides: Adachi's model 4"
        );
        assert_eq!(t.state["adachi.q"], t.lateral_offset_m);
        assert_eq!(t.boundaries.len(), 4);
        for b in &t.boundaries {
            b.check_polyline().unwrap();
        }
    }
}
