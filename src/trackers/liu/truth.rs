//! Liu's parameters of a ground truth (eqs. 15-16): `liu.<role>.rho`, `liu.<role>.theta`,
//! `liu.<role>.d` of each boundary on the default top view of `liu-ppf` (pixels, y_m at half
//! its height), by least squares on the boundary's road points inside the top view, as the
//! paper computes its ground truth from marked lane points. Boundaries with too few points in
//! the view are left out.

use super::config::LiuConfig;
use crate::lane::{LaneEstimate, LinearParabolic};

/// Liu's (rho, theta, d) of each boundary of `truth` (see the module docs).
pub fn truth_parameters(truth: &LaneEstimate) -> Vec<(String, f64)> {
    let config = LiuConfig::default();
    let v = config.top_view;
    let Ok((_, height)) = v.size() else {
        return Vec::new();
    };
    let y_m = config.split_row(height);
    let mut out = Vec::new();
    for b in &truth.boundaries {
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
        if let Some(m) = LinearParabolic::fit(&points, y_m) {
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
    use crate::lane::{Boundary, Role};

    /// A straight boundary 1.8 m left of the car runs straight up the top view: theta = 0,
    /// d = 0 and rho its column; a boundary without points in the view is left out.
    #[test]
    fn a_straight_boundary_is_a_vertical_line_of_the_top_view() {
        let v = LiuConfig::default().top_view;
        let boundary = |role, road_points| Boundary {
            role,
            points: Vec::new(),
            road_points,
        };
        let truth = LaneEstimate {
            boundaries: vec![
                boundary(
                    Role::EgoLeft,
                    (1..=60).map(|x| [f64::from(x), 1.8]).collect(),
                ),
                boundary(Role::EgoRight, vec![[200.0, -1.8], [201.0, -1.8]]),
            ],
            ..Default::default()
        };
        let p = truth_parameters(&truth);
        let names: Vec<&str> = p.iter().map(|(k, _)| k.as_str()).collect();
        assert_eq!(
            names,
            ["liu.ego-left.rho", "liu.ego-left.theta", "liu.ego-left.d"]
        );
        let column = (v.y_left_m - 1.8) / v.m_per_px - 0.5;
        assert!((p[0].1 - column).abs() < 1e-9, "{} vs {column}", p[0].1);
        assert!(p[1].1.abs() < 1e-12 && p[2].1.abs() < 1e-12, "{p:?}");
    }
}
