//! The library of named, seeded, deterministic scenarios. Each is plain data (a
//! [`SceneConfig`]); any camera (so any resolution) can render it.

use super::ego::{EgoConfig, LaneChange};
use super::markings::{BoundaryStyle, MarkingConfig, MarkingStyle, Paint, Pattern, Wear};
use super::road::{LaneGap, RoadConfig, Segment, WidthChange};
use super::scene::{Appearance, RoadPaint, SceneConfig, Shadow, Vehicle, VerticalProfile};
use crate::error::{Error, Result};

/// Scenario names with a one-line description each.
pub const SCENARIOS: &[(&str, &str)] = &[
    (
        "highway-straight",
        "three-lane straight highway, light sway",
    ),
    (
        "highway-curve",
        "highway entering a 500 m radius left curve through a clothoid",
    ),
    (
        "s-curve",
        "left then right 300 m curves joined by clothoids",
    ),
    ("lane-change", "two lane changes to the right and back"),
    (
        "occlusion",
        "vehicles ahead hide the markings, and a 1 s total blackout",
    ),
    ("shadows", "tree shadows on both sides and a bridge"),
    ("worn-markings", "faded and missing stretches of paint"),
    ("night", "night, headlights only, more sensor noise"),
    (
        "width-change",
        "lane width grows to 4.5 m and narrows to 3.2 m (W_l)",
    ),
    (
        "pitch-bumps",
        "body pitch and height oscillation over a sag (C_V)",
    ),
    (
        "multi-lane",
        "four lanes, the outer ones appearing and disappearing",
    ),
    (
        "urban",
        "two-lane street: curbs, double yellow, parked cars, writing, hood, vignette",
    ),
];

/// A straight segment.
pub(super) fn straight(length_m: f64) -> Segment {
    Segment {
        length_m,
        curvature: 0.0,
        curvature_rate: 0.0,
    }
}

/// A clothoid from curvature `from` to `to` over `length_m`.
pub(super) fn transition(length_m: f64, from: f64, to: f64) -> Segment {
    Segment {
        length_m,
        curvature: from,
        curvature_rate: (to - from) / length_m,
    }
}

/// An arc of constant curvature.
pub(super) fn arc(length_m: f64, curvature: f64) -> Segment {
    Segment {
        length_m,
        curvature,
        curvature_rate: 0.0,
    }
}

fn highway(segments: Vec<Segment>) -> RoadConfig {
    RoadConfig {
        segments,
        lanes: 3,
        lane_width_m: 3.6,
        width_changes: vec![],
        lane_gaps: vec![],
    }
}

fn base(road: RoadConfig, frames: u32) -> SceneConfig {
    SceneConfig {
        road,
        markings: MarkingConfig::default(),
        ego: EgoConfig {
            lane: 1,
            ..Default::default()
        },
        vertical: VerticalProfile::default(),
        vehicles: vec![],
        shadows: vec![],
        road_paint: vec![],
        blackouts: vec![],
        appearance: Appearance::default(),
        frames,
    }
}

fn car(lane: usize, start_s: f64, speed_mps: f64, rgb: [u8; 3]) -> Vehicle {
    Vehicle {
        lane,
        start_s,
        speed_mps,
        size_m: [4.5, 1.8, 1.5],
        rgb,
        offset_m: 0.0,
    }
}

/// A two-lane street's boundaries: kerbs at both edges, `centre` between the lanes.
pub(super) fn street_markings(centre: MarkingStyle) -> Vec<BoundaryStyle> {
    let curb = MarkingStyle {
        pattern: Pattern::Curb,
        paint: Paint::White,
        width_m: 0.15,
    };
    vec![
        BoundaryStyle {
            boundary: 0,
            style: curb,
        },
        BoundaryStyle {
            boundary: 2,
            style: curb,
        },
        BoundaryStyle {
            boundary: 1,
            style: centre,
        },
    ]
}

/// The scenario `name`.
///
/// # Errors
/// [`Error::Config`] listing the available names for an unknown one.
pub fn scenario(name: &str) -> Result<SceneConfig> {
    let s = match name {
        "highway-straight" => base(highway(vec![straight(100.0)]), 300),
        "highway-curve" => base(
            highway(vec![
                straight(60.0),
                transition(120.0, 0.0, 0.002),
                arc(2000.0, 0.002),
            ]),
            300,
        ),
        "s-curve" => base(
            highway(vec![
                straight(40.0),
                transition(80.0, 0.0, 1.0 / 300.0),
                arc(120.0, 1.0 / 300.0),
                transition(160.0, 1.0 / 300.0, -1.0 / 300.0),
                arc(120.0, -1.0 / 300.0),
                transition(80.0, -1.0 / 300.0, 0.0),
            ]),
            450,
        ),
        "lane-change" => {
            let mut c = base(highway(vec![straight(100.0)]), 360);
            c.ego.sway_amplitude_m = 0.0;
            c.ego.lane_changes = vec![
                LaneChange {
                    at_s: 2.0,
                    to_lane: 2,
                    duration_s: 3.0,
                },
                LaneChange {
                    at_s: 8.0,
                    to_lane: 1,
                    duration_s: 3.0,
                },
            ];
            c
        }
        "occlusion" => {
            let mut c = base(
                highway(vec![
                    straight(100.0),
                    transition(100.0, 0.0, 0.001),
                    arc(2000.0, 0.001),
                ]),
                300,
            );
            c.vehicles = vec![
                // In the car's lane, a little faster than it (25 m/s): it draws away instead
                // of being driven through.
                car(1, 38.0, 26.0, [170, 30, 30]),
                car(0, 60.0, 27.0, [40, 60, 150]),
                car(2, 25.0, 24.0, [200, 200, 205]),
                Vehicle {
                    size_m: [12.0, 2.5, 3.6],
                    ..car(2, 70.0, 23.0, [230, 230, 225])
                },
            ];
            c.blackouts = vec![[5.0, 6.0]];
            c
        }
        "shadows" => {
            let mut c = base(
                highway(vec![
                    straight(100.0),
                    transition(150.0, 0.0, -0.0015),
                    arc(2000.0, -0.0015),
                ]),
                300,
            );
            c.shadows = vec![
                Shadow::Trees {
                    from_s: 30.0,
                    to_s: 400.0,
                    left: true,
                    reach_m: 6.0,
                    light: 0.45,
                },
                Shadow::Trees {
                    from_s: 80.0,
                    to_s: 300.0,
                    left: false,
                    reach_m: 4.0,
                    light: 0.5,
                },
                Shadow::Band {
                    from_s: 180.0,
                    to_s: 196.0,
                    light: 0.3,
                },
            ];
            c
        }
        "worn-markings" => {
            let mut c = base(
                highway(vec![
                    straight(100.0),
                    transition(100.0, 0.0, 0.0012),
                    arc(2000.0, 0.0012),
                ]),
                300,
            );
            c.markings.wear = vec![
                Wear {
                    from_s: 60.0,
                    to_s: 140.0,
                    boundary: None,
                    visibility: 0.35,
                },
                Wear {
                    from_s: 160.0,
                    to_s: 220.0,
                    boundary: Some(1),
                    visibility: 0.0,
                },
                Wear {
                    from_s: 240.0,
                    to_s: 290.0,
                    boundary: Some(2),
                    visibility: 0.0,
                },
            ];
            c.appearance.patches = 0.25;
            c
        }
        "night" => {
            let mut c = base(
                highway(vec![
                    straight(80.0),
                    transition(100.0, 0.0, 0.0015),
                    arc(2000.0, 0.0015),
                ]),
                300,
            );
            c.appearance.night = true;
            c.appearance.noise = 4.0;
            c.vehicles = vec![car(0, 70.0, 27.0, [120, 120, 130])];
            c
        }
        "width-change" => {
            let mut r = highway(vec![straight(100.0)]);
            r.width_changes = vec![
                WidthChange {
                    from_s: 60.0,
                    to_s: 160.0,
                    width_m: 4.5,
                },
                WidthChange {
                    from_s: 220.0,
                    to_s: 300.0,
                    width_m: 3.2,
                },
            ];
            let mut c = base(r, 300);
            c.ego.sway_amplitude_m = 0.1;
            c
        }
        "pitch-bumps" => {
            let mut c = base(highway(vec![straight(100.0)]), 300);
            c.ego.pitch_amplitude_deg = 1.2;
            c.ego.height_amplitude_m = 0.04;
            c.ego.body_period_s = 0.9;
            c.vertical.curvature = 0.0004;
            c
        }
        "multi-lane" => {
            let mut r = highway(vec![
                straight(150.0),
                transition(100.0, 0.0, 0.001),
                arc(2000.0, 0.001),
            ]);
            r.lanes = 4;
            r.lane_gaps = vec![
                LaneGap {
                    lane: 0,
                    from_s: 90.0,
                    to_s: 200.0,
                },
                LaneGap {
                    lane: 3,
                    from_s: 0.0,
                    to_s: 70.0,
                },
                LaneGap {
                    lane: 3,
                    from_s: 230.0,
                    to_s: 1e6,
                },
            ];
            let mut c = base(r, 300);
            c.ego.lane = 1;
            c
        }
        "urban" => {
            let mut r = RoadConfig {
                segments: vec![
                    straight(60.0),
                    transition(40.0, 0.0, 0.006),
                    arc(40.0, 0.006),
                    transition(40.0, 0.006, 0.0),
                    straight(2000.0),
                ],
                lanes: 2,
                lane_width_m: 3.3,
                width_changes: vec![],
                lane_gaps: vec![],
            };
            r.lane_width_m = 3.3;
            let mut c = base(r, 300);
            c.ego = EgoConfig {
                speed_mps: 11.0,
                lane: 1,
                sway_amplitude_m: 0.2,
                ..Default::default()
            };
            c.markings.overrides = street_markings(MarkingStyle {
                pattern: Pattern::Double { gap_m: 0.1 },
                paint: Paint::Yellow,
                width_m: 0.1,
            });
            c.vehicles = (0..6)
                // Parked half on the pavement beyond the right kerb (1.65 m right of the
                // lane's centre), 0.2 m into the lane: clear of the car.
                .map(|k| Vehicle {
                    offset_m: -2.35,
                    ..car(
                        1,
                        45.0 + 22.0 * k as f64,
                        0.0,
                        [[90, 90, 95], [150, 20, 20], [30, 50, 110]][k % 3],
                    )
                })
                .collect();
            c.road_paint = (0..4)
                .map(|k| RoadPaint {
                    s: 70.0 + k as f64 * 0.9,
                    d: -1.65,
                    size_m: [0.5, 1.6],
                })
                .chain([RoadPaint {
                    s: 110.0,
                    d: -1.65,
                    size_m: [4.0, 0.3],
                }])
                .collect();
            c.appearance = Appearance {
                patches: 0.3,
                seam_period_m: 6.0,
                hood: 0.12,
                vignette: 0.6,
                glare: Some([0.8, 0.25, 0.08]),
                exposure: 0.1,
                blur: 1,
                ..Appearance::default()
            };
            c
        }
        _ => {
            let names: Vec<&str> = SCENARIOS.iter().map(|(n, _)| *n).collect();
            return Err(Error::Config(format!(
                "unknown scenario `{name}`; available: {}",
                names.join(", ")
            )));
        }
    };
    Ok(s)
}
