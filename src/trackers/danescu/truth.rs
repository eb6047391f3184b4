//! Danescu & Nedevschi's parameters of a ground truth (Sec. II: X to the right, Z ahead), from
//! the simulator's tracker-neutral truth (`crate::synth`'s truth docs), in the order of
//! [`crate::lane::Lane3d::NAMES`]:
//!
//! - `danescu.w0` = W - (W_L + W_R)/2, the width between the markings' inner edges
//!   (`lane_width_m` between marking centres, `marking_width_left_m`, `marking_width_right_m`);
//! - `danescu.ch` = -kappa (curving right positive; kappa = `curvature_per_m`, positive left);
//! - `danescu.wl` = dW/ds (`lane_width_rate_m_per_m`);
//! - `danescu.cv` = C_V (`vertical_curvature_per_m`);
//! - `danescu.y0` = the camera's height change (`camera_height_change_m`);
//! - `danescu.xcw` = o, the lane centre to the right of the camera (`lateral_offset_m`, the
//!   camera left of the centre);
//! - `danescu.alpha` = the pitch (`pitch_rad`), `danescu.gamma` = the roll (`roll_rad`);
//! - `danescu.psi` = -heading (`heading_rad` is positive left);
//! - `danescu.wl_mark` / `danescu.wr_mark` = W_L / W_R.
//!
//! A parameter whose scene key the truth lacks is left out.

use crate::lane::LaneEstimate;
use crate::synth::truth_keys as keys;

/// Danescu's parameters of `truth` (see the module docs).
pub fn truth_parameters(truth: &LaneEstimate) -> Vec<(String, f64)> {
    let key = |k: &str| truth.state.get(k).copied();
    let (wl_mark, wr_mark) = (
        key(keys::MARKING_WIDTH_LEFT),
        key(keys::MARKING_WIDTH_RIGHT),
    );
    let w0 = wl_mark
        .zip(wr_mark)
        .map(|(l, r)| truth.lane_width_m - (l + r) / 2.0);
    [
        ("danescu.w0", w0),
        ("danescu.ch", Some(-truth.curvature_per_m)),
        ("danescu.wl", key(keys::LANE_WIDTH_RATE)),
        ("danescu.cv", key(keys::VERTICAL_CURVATURE)),
        ("danescu.y0", key(keys::CAMERA_HEIGHT_CHANGE)),
        ("danescu.xcw", Some(truth.lateral_offset_m)),
        ("danescu.alpha", key(keys::PITCH)),
        ("danescu.gamma", key(keys::ROLL)),
        ("danescu.psi", Some(-truth.heading_rad)),
        ("danescu.wl_mark", wl_mark),
        ("danescu.wr_mark", wr_mark),
    ]
    .into_iter()
    .filter_map(|(k, v)| Some((k.to_string(), v?)))
    .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;
    use crate::lane::{Lane3d, LaneCamera};
    use crate::synth::{default_camera, scenario, Scene};
    use crate::trackers::scene_truth;

    /// The mapping on one frame against the scene's own figures: the width-change scenario's
    /// 0.15 m markings and 0.009 m/m widening, the camera's pitch and roll.
    #[test]
    fn the_parameters_follow_the_scene() {
        let camera = default_camera(320, 240).unwrap();
        let scene = Scene::new(scenario("width-change").unwrap(), camera, 1).unwrap();
        let frame = 120; // s = 120 m: inside the 60..160 m change
        let t = scene.truth(frame);
        let p: std::collections::BTreeMap<_, _> = truth_parameters(&t).into_iter().collect();
        assert_eq!(p.len(), Lane3d::NAMES.len());
        assert!((p["danescu.w0"] - (t.lane_width_m - 0.15)).abs() < 1e-12);
        assert!((p["danescu.wl"] - 0.009).abs() < 1e-12);
        assert_eq!(p["danescu.xcw"], t.lateral_offset_m);
        assert_eq!(p["danescu.psi"], -t.heading_rad);
        assert_eq!(p["danescu.ch"], -t.curvature_per_m);
        let cam = scene.frame_camera(&scene.pose(frame));
        assert_eq!(p["danescu.alpha"], cam.pitch());
        assert_eq!(p["danescu.y0"], scene.pose(frame).height_offset);
    }

    #[test]
    fn the_true_lane_projects_onto_the_true_boundaries_in_every_pose() {
        // The danescu.* truth, put through LaneCamera, lands on the truth polylines (marking centres) in scenes that bump the camera and bend the road.
        for name in ["pitch-bumps", "highway-curve", "width-change"] {
            let camera = default_camera(640, 480).unwrap();
            let scene = Scene::new(scenario(name).unwrap(), camera.clone(), 3).unwrap();
            let mut checked = 0;
            for frame in (0..200).step_by(9) {
                // Eq. 1 is linear: skip frames where the width's slope changes within 25 m.
                let s = scene.pose(frame).s;
                let road = scene.road();
                if road.lane_width_rate(s) != road.lane_width_rate(s + 25.0) {
                    continue;
                }
                checked += 1;
                let truth = scene_truth(&scene, frame);
                let mut a = [0.0; 11];
                for (k, n) in Lane3d::NAMES.iter().enumerate() {
                    a[k] = truth.state[&format!("danescu.{n}")];
                }
                let lane = Lane3d::from_array(a);
                let lc = LaneCamera::new(&camera, &lane);
                let mut worst: f64 = 0.0;
                for b in &truth.boundaries {
                    let right = match b.role {
                        crate::lane::Role::EgoLeft => false,
                        crate::lane::Role::EgoRight => true,
                        _ => continue,
                    };
                    for z in [6.0, 10.0, 15.0, 20.0] {
                        let Some(y) = b.y_at(z) else { continue };
                        let want = camera_of(&scene, frame).project([z, y, lane.cv * z * z / 2.0]);
                        let got = lc.project(lane.marking_centre_x(right, z), z).unwrap();
                        let want = want.unwrap();
                        worst = worst.max((got[0] - want[0]).abs().max((got[1] - want[1]).abs()));
                    }
                }
                // Within a pixel at 640x480: the second-order centre line against the
                // simulator's clothoid over 20 m.
                assert!(worst < 1.0, "{name} frame {frame}: {worst} px");
            }
            assert!(checked >= 15, "{name}: {checked} frames");
        }
    }

    fn camera_of(scene: &Scene, frame: u32) -> Camera {
        scene.frame_camera(&scene.pose(frame))
    }
}
