//! Lee et al.'s parameters of a ground truth (eqs. 18-19), from the simulator's
//! tracker-neutral truth (`crate::synth`'s truth docs):
//!
//! - `lee.psi` = the heading (`heading_rad`, positive left);
//! - `lee.y0` = -o, the lane centre seen from the camera (y left; o = `lateral_offset_m`);
//! - `lee.w` = W (`lane_width_m`), `lee.w1` = dW/ds (`lane_width_rate_m_per_m`);
//! - `lee.c` = the distance ahead to the next change of curvature (0 inside a curve or
//!   transition; `curvature_change_ahead_m`), `lee.delta` = the curvature the road reaches
//!   there (`curvature_ahead_per_m`).
//!
//! A parameter whose scene key the truth lacks is left out.

use crate::lane::LaneEstimate;
use crate::synth::truth_keys as keys;

/// Lee's parameters of `truth` (see the module docs).
pub fn truth_parameters(truth: &LaneEstimate) -> Vec<(String, f64)> {
    let key = |k: &str| truth.state.get(k).copied();
    [
        ("lee.psi", Some(truth.heading_rad)),
        ("lee.y0", Some(-truth.lateral_offset_m)),
        ("lee.w", Some(truth.lane_width_m)),
        ("lee.w1", key(keys::LANE_WIDTH_RATE)),
        ("lee.c", key(keys::CURVATURE_CHANGE_AHEAD)),
        ("lee.delta", key(keys::CURVATURE_AHEAD)),
    ]
    .into_iter()
    .filter_map(|(k, v)| Some((k.to_string(), v?)))
    .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{default_camera, scenario, Scene};
    use std::collections::BTreeMap;

    fn parameters(name: &str, frame: u32) -> (LaneEstimate, BTreeMap<String, f64>) {
        let camera = default_camera(320, 240).unwrap();
        let scene = Scene::new(scenario(name).unwrap(), camera, 1).unwrap();
        let t = scene.truth(frame);
        let p = truth_parameters(&t).into_iter().collect();
        (t, p)
    }

    /// The mapping against the scenes' own figures: the highway curve's clothoid starts 40 m
    /// ahead of the car and reaches 1/500 m; the width change widens 0.009 m per metre.
    #[test]
    fn the_parameters_follow_the_scene() {
        let (t, p) = parameters("highway-curve", 0); // s = 20: the clothoid starts at 60 m
        assert_eq!(p.len(), 6);
        assert!((p["lee.c"] - 40.0).abs() <= 0.5, "{}", p["lee.c"]);
        assert!((p["lee.delta"] - 0.002).abs() < 1e-9);
        assert_eq!(p["lee.y0"], -t.lateral_offset_m);
        assert_eq!(p["lee.psi"], t.heading_rad);
        let (t, p) = parameters("width-change", 120); // inside the 60..160 m change
        assert!((p["lee.w1"] - 0.009).abs() < 1e-12);
        assert!((p["lee.w"] - (3.6 + 0.9 * 0.6)).abs() < 1e-9);
        assert_eq!(p["lee.w"], t.lane_width_m);
    }

    /// Without the simulator's scene keys only what the fields give is there.
    #[test]
    fn a_truth_without_scene_keys_gives_the_field_parameters() {
        let names: Vec<String> = truth_parameters(&LaneEstimate::default())
            .into_iter()
            .map(|(k, _)| k)
            .collect();
        assert_eq!(names, ["lee.psi", "lee.y0", "lee.w"]);
    }
}
