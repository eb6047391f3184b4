//! The output every tracker (and the simulator's ground truth) produces for a frame.
//!
//! It is the JSON object of the command-line contract (one per line of `lanepf track` output):
//! boundaries as image polylines ordered from the bottom of the image upward, no more than
//! [`MAX_POINT_SPACING_PX`] apart in y, plus the lane parameters every paper shares and a map of
//! tracker-specific state.

use crate::num_text::Fixed;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Largest vertical gap between consecutive polyline points, in pixels.
pub const MAX_POINT_SPACING_PX: f64 = 10.0;

/// Which lane boundary a polyline is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Role {
    /// Left boundary of the ego lane.
    EgoLeft,
    /// Right boundary of the ego lane.
    EgoRight,
    /// Left boundary of the lane left of the ego lane.
    LeftAdjacent,
    /// Right boundary of the lane right of the ego lane.
    RightAdjacent,
}

impl Role {
    /// The role's name as written in JSON (`ego-left`, ...).
    pub fn as_str(self) -> &'static str {
        match self {
            Role::EgoLeft => "ego-left",
            Role::EgoRight => "ego-right",
            Role::LeftAdjacent => "left-adjacent",
            Role::RightAdjacent => "right-adjacent",
        }
    }
}

/// One lane boundary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Boundary {
    /// Which boundary this is.
    pub role: Role,
    /// Image points [x, y] in pixels, bottom of the image first.
    pub points: Vec<[f64; 2]>,
    /// The same boundary on the road plane, [x forward, y left] in metres (ISO 8855), near first.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub road_points: Vec<[f64; 2]>,
}

/// Which edge of a lane marking a [`Delimiter`] follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Side {
    /// The marking's edge towards the ego lane.
    Inner,
    /// The marking's edge away from the ego lane.
    Outer,
}

impl Side {
    /// The side's name as written in JSON (`inner`, `outer`).
    pub fn as_str(self) -> &'static str {
        match self {
            Side::Inner => "inner",
            Side::Outer => "outer",
        }
    }
}

/// One edge of a boundary's marking: for trackers whose lane model has marking widths
/// (Danescu & Nedevschi 2011, eqs. 2-3), the inner and outer delimiters of the marking whose
/// centre line is the boundary of the same role. Serialised as the boundary's fields plus
/// `"side": "inner" | "outer"`; the polyline rules are the boundaries'.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Delimiter {
    /// Which edge of the marking.
    pub side: Side,
    /// The edge's role (the boundary it belongs to) and polylines.
    #[serde(flatten)]
    pub boundary: Boundary,
}

/// A tracker's (or the ground truth's) description of the lane in one frame.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct LaneEstimate {
    /// Frame name (file name or index).
    #[serde(default)]
    pub frame: String,
    /// Whether the tracker is confident in this estimate.
    pub valid: bool,
    /// Processing time in milliseconds (0 for ground truth).
    #[serde(default)]
    pub ms: f64,
    /// The boundaries, in any order.
    pub boundaries: Vec<Boundary>,
    /// Lateral offset of the camera from the lane centre, metres, positive when the camera is
    /// left of the centre (ISO 8855 y).
    pub lateral_offset_m: f64,
    /// Heading of the lane relative to the camera's forward axis, radians, positive left.
    pub heading_rad: f64,
    /// Horizontal curvature of the lane at the camera, 1/m, positive turning left.
    pub curvature_per_m: f64,
    /// Lane width, metres.
    pub lane_width_m: f64,
    /// Tracker-specific parameters by name (e.g. Lee's psi, y0, w, w', c, delta).
    #[serde(default)]
    pub state: BTreeMap<String, f64>,
    /// The inner and outer edges of the boundaries' markings, from trackers that model
    /// marking widths (danescu-*); empty, and omitted from JSON, for the others. Evaluation
    /// and drawing of lanes use `boundaries` only.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub delimiters: Vec<Delimiter>,
}

impl Boundary {
    /// Lateral position y of the boundary `x` metres ahead, interpolated linearly between its
    /// road points (`None` outside them).
    pub fn y_at(&self, x: f64) -> Option<f64> {
        self.road_points.windows(2).find_map(|p| {
            let ([x0, y0], [x1, y1]) = (p[0], p[1]);
            (x0 <= x && x <= x1 && x1 > x0).then(|| y0 + (y1 - y0) * (x - x0) / (x1 - x0))
        })
    }

    /// Checks the polyline rules of the contract: points ordered bottom-up (y non-increasing)
    /// and no gap larger than [`MAX_POINT_SPACING_PX`] in y. Returns a description of the first
    /// violation.
    pub fn check_polyline(&self) -> Result<(), String> {
        for (i, pair) in self.points.windows(2).enumerate() {
            let dy = pair[0][1] - pair[1][1];
            if dy < 0.0 {
                return Err(format!(
                    "{}: point {} goes down the image",
                    self.role.as_str(),
                    i + 1
                ));
            }
            if dy > MAX_POINT_SPACING_PX + 1e-9 {
                return Err(format!(
                    "{}: points {i} and {} are {} px apart in y",
                    self.role.as_str(),
                    i + 1,
                    Fixed(dy, 1)
                ));
            }
        }
        Ok(())
    }
}

/// The `state` keys of each tracker's effective sample size after a frame's weighing, in the
/// order [`LaneEstimate::ess`] reads them (lee-cpf's stage 1 before its stage 2).
const ESS_KEYS: [&str; 5] = [
    "lee.ess1",
    "danescu.ess",
    "adachi.ess",
    "liu.ess",
    "lee.ess2",
];

impl LaneEstimate {
    /// The effective sample size of the tracker's particles after the frame's weighing
    /// (lee-cpf: stage 1's), in particles; `None` for the ground truth. Read from `state`
    /// (`lee.ess1`, `adachi.ess`, `liu.ess`, `danescu.ess`), so the command line's JSON is
    /// unchanged; JavaScript results carry it as `ess`.
    pub fn ess(&self) -> Option<f64> {
        ESS_KEYS.iter().find_map(|k| self.state.get(*k).copied())
    }

    /// adachi-mmpf's model probabilities P(r) of the four lane configurations r = 1..4 (they sum
    /// to 1); `None` for the other trackers. Read from `state` (`adachi.p1` .. `adachi.p4`);
    /// JavaScript results carry them as `model_probabilities`.
    pub fn model_probabilities(&self) -> Option<[f64; 4]> {
        let p = |k: &str| self.state.get(k).copied();
        Some([
            p("adachi.p1")?,
            p("adachi.p2")?,
            p("adachi.p3")?,
            p("adachi.p4")?,
        ])
    }

    /// Lateral position of the ego-lane centre `x` metres ahead (the mean of the ego
    /// boundaries), if both reach that far.
    pub fn ego_centre_at(&self, x: f64) -> Option<f64> {
        let at = |role: Role| self.boundaries.iter().find(|b| b.role == role)?.y_at(x);
        Some((at(Role::EgoLeft)? + at(Role::EgoRight)?) / 2.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn serialises_in_the_contract_format() {
        let e = LaneEstimate {
            frame: "f00000.png".into(),
            valid: true,
            ms: 1.5,
            boundaries: vec![Boundary {
                role: Role::EgoLeft,
                points: vec![[10.0, 470.0], [12.0, 460.0]],
                road_points: vec![],
            }],
            lateral_offset_m: 0.12,
            heading_rad: -0.004,
            curvature_per_m: 0.0008,
            lane_width_m: 3.62,
            state: BTreeMap::from([("w".to_string(), 3.62)]),
            delimiters: vec![],
        };
        let json = serde_json::to_string(&e).unwrap();
        assert!(json.contains(r#""role":"ego-left""#), "{json}");
        assert!(
            json.contains(r#""points":[[10.0,470.0],[12.0,460.0]]"#),
            "{json}"
        );
        assert!(
            !json.contains("road_points"),
            "empty road polylines are omitted"
        );
        assert!(!json.contains("delimiters"), "no delimiters, no field");
        let back: LaneEstimate = serde_json::from_str(&json).unwrap();
        assert_eq!(back, e);
        // A marking's edges: the boundary's fields and the side, read back the same.
        let e = LaneEstimate {
            delimiters: vec![Delimiter {
                side: Side::Outer,
                boundary: Boundary {
                    role: Role::EgoRight,
                    points: vec![[600.0, 470.0]],
                    road_points: vec![[5.0, -1.95]],
                },
            }],
            ..e
        };
        let json = serde_json::to_string(&e).unwrap();
        assert!(
            json.contains(
                r#""delimiters":[{"side":"outer","role":"ego-right","points":[[600.0,470.0]],"road_points":[[5.0,-1.95]]}]"#
            ),
            "{json}"
        );
        let back: LaneEstimate = serde_json::from_str(&json).unwrap();
        assert_eq!(back, e);
    }

    #[test]
    fn polyline_rules_are_checked() {
        let mut b = Boundary {
            role: Role::EgoRight,
            points: vec![[0.0, 400.0], [0.0, 390.0], [0.0, 385.0]],
            road_points: vec![],
        };
        assert_eq!(b.check_polyline(), Ok(()));
        b.points.push([0.0, 370.0]);
        assert!(b.check_polyline().unwrap_err().contains("15.0 px apart"));
        b.points = vec![[0.0, 300.0], [0.0, 301.0]];
        assert!(b.check_polyline().unwrap_err().contains("goes down"));
    }
}
