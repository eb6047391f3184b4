//! Adachi et al.'s parameters of a ground truth (eqs. 3, 5), from the simulator's
//! tracker-neutral truth (`crate::synth`'s truth docs). On their rho axis (across the road,
//! positive to the right, so that rho_3 = q - 3w/2 is the left neighbour's boundary):
//!
//! - `adachi.q` = o, the ego-lane centre relative to the car (`lateral_offset_m`, the camera
//!   left of the centre);
//! - `adachi.w` = W (`lane_width_m`);
//! - `adachi.r` = the paper's model number: 1 ego lane only, 2 with a left neighbour, 3 with a
//!   right neighbour, 4 with both; a neighbour exists when the truth lists its outer boundary
//!   (`left-adjacent`, `right-adjacent`), as the simulator does whenever the lane exists.

use crate::lane::{LaneEstimate, Role};

/// Adachi's parameters of `truth` (see the module docs).
pub fn truth_parameters(truth: &LaneEstimate) -> Vec<(String, f64)> {
    let has = |role: Role| truth.boundaries.iter().any(|b| b.role == role);
    let (left, right) = (has(Role::LeftAdjacent), has(Role::RightAdjacent));
    vec![
        ("adachi.q".to_string(), truth.lateral_offset_m),
        ("adachi.w".to_string(), truth.lane_width_m),
        (
            "adachi.r".to_string(),
            f64::from(1 + u8::from(left) + 2 * u8::from(right)),
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lane::Boundary;
    use crate::synth::{default_camera, scenario, Scene};

    fn model(roles: &[Role]) -> f64 {
        let truth = LaneEstimate {
            boundaries: roles
                .iter()
                .map(|&role| Boundary {
                    role,
                    points: Vec::new(),
                    road_points: Vec::new(),
                })
                .collect(),
            ..Default::default()
        };
        truth_parameters(&truth)[2].1
    }

    #[test]
    fn the_model_number_counts_the_neighbours_as_the_paper_does() {
        let ego = [Role::EgoLeft, Role::EgoRight];
        assert_eq!(model(&ego), 1.0);
        assert_eq!(model(&[&ego[..], &[Role::LeftAdjacent]].concat()), 2.0);
        assert_eq!(model(&[&ego[..], &[Role::RightAdjacent]].concat()), 3.0);
        let both = [Role::RightAdjacent, Role::LeftAdjacent];
        assert_eq!(model(&[&ego[..], &both].concat()), 4.0);
    }

    /// The lane-change scene starts in the middle of three lanes: model 4; q is the offset.
    #[test]
    fn the_parameters_follow_the_scene() {
        let camera = default_camera(320, 240).unwrap();
        let scene = Scene::new(scenario("lane-change").unwrap(), camera, 1).unwrap();
        let t = scene.truth(0);
        let p = truth_parameters(&t);
        assert_eq!(p[0], ("adachi.q".to_string(), t.lateral_offset_m));
        assert_eq!(p[1], ("adachi.w".to_string(), t.lane_width_m));
        assert_eq!(p[2], ("adachi.r".to_string(), 4.0));
    }
}
