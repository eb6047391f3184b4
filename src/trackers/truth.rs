//! The papers' ground truth: the simulator's tracker-neutral truth (`crate::synth`) mapped to
//! every paper's parameters by the paper's own `truth_parameters` (`adachi/truth.rs`,
//! `danescu/truth.rs`, `lee/truth.rs`, `liu/truth.rs`: each with its equations, signs and
//! units), so that the simulator knows no tracker and dependencies point down. The command
//! line's `gt.jsonl`, the evaluation suite and the wasm `Scene.truth` use [`papers_truth`].

use super::{adachi, danescu, lee, liu};
use crate::lane::LaneEstimate;
use crate::synth::{Scene, SCENE_KEYS};

/// A paper's mapping of a truth to its parameters, by name.
type Mapping = fn(&LaneEstimate) -> Vec<(String, f64)>;

/// Each paper's mapping (`danescu-mono` and `danescu-stereo`, `liu-ppf` and
/// `liu-ppf-nokernel` share theirs).
const MAPPINGS: [Mapping; 4] = [
    adachi::truth::truth_parameters,
    danescu::truth::truth_parameters,
    lee::truth::truth_parameters,
    liu::truth::truth_parameters,
];

/// Every paper's parameters of `truth`, by name (`adachi.q`, `danescu.w0`, `lee.c`,
/// `liu.ego-left.rho`, ...).
pub fn truth_parameters(truth: &LaneEstimate) -> Vec<(String, f64)> {
    MAPPINGS.iter().flat_map(|map| map(truth)).collect()
}

/// `truth` with every paper's parameters in its `state` and the scene keys they come from
/// ([`SCENE_KEYS`]) taken out: the fields and boundaries, the motion keys (`t`, `speed_mps`,
/// `yaw_rate`, `ego_lane`, `lane_change`, `blackout`) and the papers' parameters, the keys
/// `gt.jsonl` has always had.
pub fn papers_truth(mut truth: LaneEstimate) -> LaneEstimate {
    for (k, v) in truth_parameters(&truth) {
        truth.state.insert(k, v);
    }
    for k in SCENE_KEYS {
        truth.state.remove(k);
    }
    truth
}

/// The papers' ground truth of `scene`'s `frame` ([`papers_truth`] of [`Scene::truth`]).
pub fn scene_truth(scene: &Scene, frame: u32) -> LaneEstimate {
    papers_truth(scene.truth(frame))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{default_camera, scenario};

    /// The papers' truth has the keys `gt.jsonl` has always had: the motion keys and every
    /// paper's parameters (Liu's per boundary), none of the scene keys.
    #[test]
    fn the_papers_truth_has_the_motion_keys_and_every_papers_parameters() {
        let camera = default_camera(320, 240).unwrap();
        let scene = Scene::new(scenario("lane-change").unwrap(), camera, 1).unwrap();
        let t = scene_truth(&scene, 0);
        let mut want: Vec<String> = ["t", "speed_mps", "yaw_rate", "ego_lane"]
            .into_iter()
            .chain(["lane_change", "blackout", "lee.psi", "lee.y0", "lee.w"])
            .chain([
                "lee.w1",
                "lee.c",
                "lee.delta",
                "adachi.q",
                "adachi.w",
                "adachi.r",
            ])
            .map(String::from)
            .chain(
                crate::lane::Lane3d::NAMES
                    .iter()
                    .map(|n| format!("danescu.{n}")),
            )
            .collect();
        for role in ["ego-left", "ego-right", "left-adjacent", "right-adjacent"] {
            want.extend(["rho", "theta", "d"].map(|p| format!("liu.{role}.{p}")));
        }
        want.sort();
        let got: Vec<String> = t.state.keys().cloned().collect();
        assert_eq!(got, want);
        assert_eq!(t.state["danescu.xcw"], t.lateral_offset_m);
    }
}
