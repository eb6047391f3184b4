//! Scenario families: one seed, one road and one camera, within ranges each scenario names.
//!
//! [`draw_scenario`]`(name, seed)` draws a member of the family `name`: its geometry (the
//! curvature profile, lane count and width, marking types and widths, lane-change timing and
//! direction, blackout timing and length, vehicle placement, shadow layout, body motion) from
//! the seed's road stream and its camera ([`CameraMount::draw`]) from the camera stream. The
//! same seed also seeds the renderer's texture and noise ([`super::Scene::new`]), so `(name,
//! seed)` is one scene, bit for bit, natively and in wasm. [`RANDOM_SCENARIO`] first draws a
//! family name from the seed, then that family's member.
//!
//! Every member is what its name says, by construction (checked over seed ranges in the
//! tests): `lane-change` changes lane twice, `occlusion` has a blackout the car drives out of,
//! the curve families reach their curves within the run, and so on. All draws are uniform in
//! [lo, hi). Shared by the highway families unless the table says otherwise:
//!
//! | value | range |
//! |---|---|
//! | lanes | 2-4 (ego lane any) |
//! | lane width W | 2.8-4.2 m |
//! | speed | 20-30 m/s (30 fps) |
//! | sway inside the lane | amplitude 0-0.35 m, period 6-10 s |
//! | marking widths | outer 0.10-0.25 m, inner 0.10-0.20 m |
//! | inner markings | dashed: dash 2-4.5 m, gap 4-10 m |
//! | left road edge | solid white (65 %), solid yellow (20 %), double yellow, gap 0.1-0.2 m (15 %) |
//! | camera | [`super::MOUNT_RANGES`]: hfov 50-90 deg, height 1.1-2.4 m, pitch -2..8 deg, yaw +-2 deg, roll +-1 deg |
//!
//! Per family (curvature kappa in 1/m, positive left; "+-" draws the sign):
//!
//! | family | what the seed draws |
//! |---|---|
//! | `highway-straight` | straight 100 m then +-0-1e-4 (radius >= 10 km) |
//! | `highway-curve` | straight 30-90 m, clothoid 80-160 m into an arc of radius 300-1000 m, +-; runs until 4 s past the curve's start (>= 300 frames) |
//! | `s-curve` | straight 20-50 m, clothoid 50-90 m, arc 60-120 m of radius 250-500 m, clothoid 80-140 m to the opposite curvature (radius 250-500 m), arc 60-120 m, clothoid 50-90 m; first direction +-; runs to the middle of the second arc (300-660 frames) |
//! | `lane-change` | 2-4 lanes; first change at 1.5-4 s, 2-4 s long, to a neighbour that exists; after 1.5-3.5 s a second change 2-4 s long, back or onward (50 %, onward only if that lane exists); sway 0-0.1 m; runs 2 s past the second change |
//! | `occlusion` | straight 60-140 m, clothoid 80-150 m to +-0-0.0015; 2-5 cars in any lane 10-60 m ahead at speed +-3 m/s of ours (one in our lane that we would reach within 3 m goes as much faster instead), and a truck (12 x 2.5 x 3.6 m) with 50 %; one blackout starting at 3-7 s, 0.5-1.5 s long |
//! | `shadows` | straight 60-140 m, clothoid 100-200 m to +-0-0.002; tree shadows on the left and/or right (each side 75 %, at least one) from 20-80 m for 150-350 m, reach 3-7 m, light 0.35-0.6; a bridge (80 %) at 100-250 m, 8-25 m long, light 0.2-0.4 |
//! | `worn-markings` | straight 60-140 m, clothoid 80-150 m to +-0-0.0015; 2-4 worn stretches from 40-250 m, 40-100 m long, on all boundaries (30 %, visibility 0.2-0.5) or one (visibility 0-0.3); repair patches 0.1-0.35 |
//! | `night` | straight 60-140 m, clothoid 80-150 m to +-0-0.002; night; sensor noise 3-5 grey levels; 0-2 cars 30-80 m ahead |
//! | `width-change` | W_0 2.8-4.2 m; from 30-80 m over 50-100 m to W_1, then after 20-60 m over 40-80 m to W_2, each 2.8-4.2 m and >= 0.4 m from the one before; sway 0-0.15 m |
//! | `pitch-bumps` | straight; body pitch 0.6-1.6 deg and height 0.02-0.06 m at a period of 0.7-1.4 s; vertical curvature +-2e-4-6e-4 |
//! | `multi-lane` | 4 lanes, the car in lane 1 or 2; the lane on one side (drawn) is missing from 60-140 m for 80-140 m; the lane on the other side exists only from 40-100 m to 200-280 m; clothoid to +-0-0.001 after 100-180 m |
//! | `urban` | 2 lanes of 2.8-3.6 m, speed 8-14 m/s; straight 20-50 m, clothoid 20-40 m into a +-100-250 m radius turn 25-60 m long, clothoid back, running to the middle of the turn (>= 300 frames); kerbs on both edges, double yellow centre line; 3-8 cars parked on the right, half on the pavement (0.2 m into the lane), every 15-30 m from 30-60 m; an arrow and a bar of writing at 50-120 m; hood 0.08-0.15, glare, vignette |
//!
//! The fixed roads of the scenarios before families ([`super::scenario`]) stay reachable as
//! the **reference** members ([`reference_member`]: that road, [`CameraMount::REFERENCE`]),
//! so that the figures measured on them can still be reproduced; their seed changes only the
//! texture and noise, as it always did.

use super::draw::Draw;
use super::ego::{EgoConfig, LaneChange};
use super::markings::{BoundaryStyle, MarkingConfig, MarkingStyle, Paint, Pattern, Wear};
use super::mount::CameraMount;
use super::road::{LaneGap, RoadConfig, Segment, WidthChange};
use super::scenarios::{arc, scenario, straight, street_markings, transition, SCENARIOS};
use super::scene::{Appearance, RoadPaint, SceneConfig, Shadow, Vehicle, VerticalProfile};
use super::simulator::Scene;
use crate::error::{Error, Result};

/// The scenario name that mixes all families.
pub const RANDOM_SCENARIO: &str = "random";

/// Salt of the road's draw stream.
const ROAD_SALT: u64 = 0x726f_6164_0000_0001;
/// Salt of the draw that picks a family for [`RANDOM_SCENARIO`].
const PICK_SALT: u64 = 0x7069_636b_0000_0001;
/// Frames per second of every family member.
const FPS: f64 = 30.0;
/// Where the car starts, metres along the road.
const START_S: f64 = 20.0;

/// One member of a scenario family.
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyMember {
    /// The family it belongs to (for [`RANDOM_SCENARIO`], the family the seed picked).
    pub scenario: &'static str,
    /// The scene.
    pub config: SceneConfig,
    /// The camera.
    pub mount: CameraMount,
    /// The seed, also of the renderer's texture and noise.
    pub seed: u64,
}

impl FamilyMember {
    /// The member as a scene rendered `width` x `height` through its camera.
    ///
    /// # Errors
    /// [`Error::Dimensions`] for an unusable size.
    pub fn scene(&self, width: usize, height: usize) -> Result<Scene> {
        Scene::new(
            self.config.clone(),
            self.mount.camera(width, height)?,
            self.seed,
        )
    }
}

/// Every name [`draw_scenario`] accepts: the families, then [`RANDOM_SCENARIO`].
pub fn family_names() -> Vec<&'static str> {
    SCENARIOS
        .iter()
        .map(|(n, _)| *n)
        .chain([RANDOM_SCENARIO])
        .collect()
}

/// The family name of `name`, or a [`Error::Config`] listing the names.
fn known(name: &str) -> Result<&'static str> {
    family_names()
        .into_iter()
        .find(|n| *n == name)
        .ok_or_else(|| {
            Error::Config(format!(
                "unknown scenario `{name}`; available: {}",
                family_names().join(", ")
            ))
        })
}

/// Member `seed` of the family `name` (see the module docs for the ranges).
///
/// # Errors
/// [`Error::Config`] listing the available names for an unknown one.
pub fn draw_scenario(name: &str, seed: u64) -> Result<FamilyMember> {
    let name = match known(name)? {
        RANDOM_SCENARIO => SCENARIOS[Draw::new(seed, PICK_SALT).int(0, SCENARIOS.len() - 1)].0,
        n => n,
    };
    let mut d = Draw::new(seed, ROAD_SALT);
    let config = match name {
        "highway-straight" => highway_straight(&mut d),
        "highway-curve" => highway_curve(&mut d),
        "s-curve" => s_curve(&mut d),
        "lane-change" => lane_change(&mut d),
        "occlusion" => occlusion(&mut d),
        "shadows" => shadows(&mut d),
        "worn-markings" => worn_markings(&mut d),
        "night" => night(&mut d),
        "width-change" => width_change(&mut d),
        "pitch-bumps" => pitch_bumps(&mut d),
        "multi-lane" => multi_lane(&mut d),
        _ => urban(&mut d),
    };
    Ok(FamilyMember {
        scenario: name,
        config,
        mount: CameraMount::draw(seed),
        seed,
    })
}

/// The reference member of the family `name`: the fixed road of [`scenario`] seen by
/// [`CameraMount::REFERENCE`], with `seed` for the texture and noise.
///
/// # Errors
/// [`Error::Config`] for an unknown name ([`RANDOM_SCENARIO`] has no reference).
pub fn reference_member(name: &str, seed: u64) -> Result<FamilyMember> {
    let name = known(name)?;
    if name == RANDOM_SCENARIO {
        return Err(Error::Config(format!(
            "`{RANDOM_SCENARIO}` has no reference road: it picks a family from the seed, so \
             draw it (`lanepf synth` without --reference; `drawn: true` in a Scene's options)"
        )));
    }
    Ok(FamilyMember {
        scenario: name,
        config: scenario(name)?,
        mount: CameraMount::REFERENCE,
        seed,
    })
}

/// A straight of `straight_m` (drawn) then a clothoid of `clothoid_m` (drawn) to a curvature
/// of magnitude up to `max_curvature` with a drawn sign, held to the end of the road.
fn gentle(
    d: &mut Draw,
    straight_m: [f64; 2],
    clothoid_m: [f64; 2],
    max_curvature: f64,
) -> Vec<Segment> {
    let a = d.range(straight_m[0], straight_m[1]);
    let t = d.range(clothoid_m[0], clothoid_m[1]);
    let k = d.signed(0.0, max_curvature);
    vec![straight(a), transition(t, 0.0, k), arc(2000.0, k)]
}

/// Highway lanes: 2-4 lanes of 2.8-4.2 m.
fn highway_road(d: &mut Draw, segments: Vec<Segment>) -> RoadConfig {
    RoadConfig {
        segments,
        lanes: d.int(2, 4),
        lane_width_m: d.range(2.8, 4.2),
        width_changes: vec![],
        lane_gaps: vec![],
    }
}

/// Highway markings: dashed inner lines, a solid right edge and a drawn left edge.
fn highway_markings(d: &mut Draw) -> MarkingConfig {
    let outer_width = d.range(0.10, 0.25);
    let inner_width = d.range(0.10, 0.20);
    let dash_m = d.range(2.0, 4.5);
    let period_m = dash_m + d.range(4.0, 10.0);
    let edge = d.range(0.0, 1.0);
    let gap_m = d.range(0.1, 0.2);
    let left_edge = if edge < 0.65 {
        None
    } else if edge < 0.85 {
        Some(MarkingStyle {
            pattern: Pattern::Solid,
            paint: Paint::Yellow,
            width_m: outer_width,
        })
    } else {
        Some(MarkingStyle {
            pattern: Pattern::Double { gap_m },
            paint: Paint::Yellow,
            width_m: outer_width.min(0.15),
        })
    };
    MarkingConfig {
        outer: MarkingStyle {
            pattern: Pattern::Solid,
            paint: Paint::White,
            width_m: outer_width,
        },
        inner: MarkingStyle {
            pattern: Pattern::Dashed { dash_m, period_m },
            paint: Paint::White,
            width_m: inner_width,
        },
        overrides: left_edge
            .map(|style| BoundaryStyle { boundary: 0, style })
            .into_iter()
            .collect(),
        ..MarkingConfig::default()
    }
}

/// Highway driving: 20-30 m/s in any lane, swaying 0-0.35 m with a 6-10 s period.
fn highway_ego(d: &mut Draw, lanes: usize) -> EgoConfig {
    EgoConfig {
        speed_mps: d.range(20.0, 30.0),
        fps: FPS,
        start_s: START_S,
        lane: d.int(0, lanes - 1),
        sway_amplitude_m: d.range(0.0, 0.35),
        sway_period_s: d.range(6.0, 10.0),
        ..EgoConfig::default()
    }
}

/// A highway scene on `segments` running `frames` frames (road, markings, ego drawn).
fn highway(d: &mut Draw, segments: Vec<Segment>, frames: u32) -> SceneConfig {
    let road = highway_road(d, segments);
    let markings = highway_markings(d);
    let ego = highway_ego(d, road.lanes);
    SceneConfig {
        road,
        markings,
        ego,
        vertical: VerticalProfile::default(),
        vehicles: vec![],
        shadows: vec![],
        road_paint: vec![],
        blackouts: vec![],
        appearance: Appearance::default(),
        frames,
    }
}

/// Frames until the car, starting at [`START_S`], is `seconds_past` seconds past arc length
/// `s`, at least `min_frames`.
fn frames_to_reach(s: f64, speed_mps: f64, seconds_past: f64, min_frames: u32) -> u32 {
    let t = (s - START_S).max(0.0) / speed_mps + seconds_past;
    ((t * FPS).ceil() as u32).max(min_frames)
}

fn highway_straight(d: &mut Draw) -> SceneConfig {
    let k = d.signed(0.0, 1e-4);
    highway(d, vec![straight(100.0), arc(2000.0, k)], 300)
}

fn highway_curve(d: &mut Draw) -> SceneConfig {
    let a = d.range(30.0, 90.0);
    let t = d.range(80.0, 160.0);
    let k = d.sign() / d.range(300.0, 1000.0);
    let mut c = highway(
        d,
        vec![straight(a), transition(t, 0.0, k), arc(2000.0, k)],
        300,
    );
    c.frames = frames_to_reach(a + t, c.ego.speed_mps, 4.0, 300);
    c
}

fn s_curve(d: &mut Draw) -> SceneConfig {
    let a = d.range(20.0, 50.0);
    let t1 = d.range(50.0, 90.0);
    let k1 = d.sign() / d.range(250.0, 500.0);
    let l1 = d.range(60.0, 120.0);
    let t2 = d.range(80.0, 140.0);
    let k2 = -k1.signum() / d.range(250.0, 500.0);
    let l2 = d.range(60.0, 120.0);
    let t3 = d.range(50.0, 90.0);
    let segments = vec![
        straight(a),
        transition(t1, 0.0, k1),
        arc(l1, k1),
        transition(t2, k1, k2),
        arc(l2, k2),
        transition(t3, k2, 0.0),
    ];
    let mut c = highway(d, segments, 300);
    let middle_of_second_arc = a + t1 + l1 + t2 + l2 / 2.0;
    c.frames = frames_to_reach(middle_of_second_arc, c.ego.speed_mps, 0.0, 300).min(660);
    c
}

fn lane_change(d: &mut Draw) -> SceneConfig {
    let mut c = highway(d, vec![straight(100.0)], 360);
    let lanes = c.road.lanes;
    let start = c.ego.lane;
    c.ego.sway_amplitude_m = d.range(0.0, 0.1);
    // A neighbour that exists: to the right (+1) from the leftmost lane, to the left from the
    // rightmost, either otherwise.
    let step = |lane: usize, preferred: f64| -> usize {
        match (lane == 0, lane + 1 == lanes) {
            (true, _) => lane + 1,
            (_, true) => lane - 1,
            _ if preferred > 0.0 => lane + 1,
            _ => lane - 1,
        }
    };
    let first = step(start, d.sign());
    let at1 = d.range(1.5, 4.0);
    let dur1 = d.range(2.0, 4.0);
    let gap = d.range(1.5, 3.5);
    let dur2 = d.range(2.0, 4.0);
    let onward = 2 * first as i64 - start as i64;
    let second = if d.chance(0.5) && (0..lanes as i64).contains(&onward) {
        onward as usize
    } else {
        start
    };
    let at2 = at1 + dur1 + gap;
    c.ego.lane_changes = vec![
        LaneChange {
            at_s: at1,
            to_lane: first,
            duration_s: dur1,
        },
        LaneChange {
            at_s: at2,
            to_lane: second,
            duration_s: dur2,
        },
    ];
    c.frames = (((at2 + dur2 + 2.0) * FPS).ceil() as u32).max(300);
    c
}

/// A car in `lane`, `ahead_m` metres ahead of the start, at `speed_mps`.
fn car(lane: usize, ahead_m: f64, speed_mps: f64, rgb: [u8; 3]) -> Vehicle {
    Vehicle {
        lane,
        start_s: START_S + ahead_m,
        speed_mps,
        size_m: [4.5, 1.8, 1.5],
        rgb,
        offset_m: 0.0,
    }
}

/// Body colours the cars are drawn from.
const COLOURS: [[u8; 3]; 5] = [
    [170, 30, 30],
    [40, 60, 150],
    [200, 200, 205],
    [90, 90, 95],
    [30, 110, 60],
];

/// Closest a vehicle ahead in the car's lane comes to the camera, metres (the car's front is
/// 1 m ahead of it).
const CLEAR_AHEAD_M: f64 = 3.0;

fn occlusion(d: &mut Draw) -> SceneConfig {
    let segments = gentle(d, [60.0, 140.0], [80.0, 150.0], 0.0015);
    let mut c = highway(d, segments, 300);
    let (lanes, v, own) = (c.road.lanes, c.ego.speed_mps, c.ego.lane);
    let seconds = c.frames as f64 / c.ego.fps;
    // Up to 3 m/s slower or faster than the car; but a slower one in the car's own lane that
    // the car (which does not brake) would reach before the end goes as much faster instead.
    let speed = |d: &mut Draw, lane: usize, ahead: f64| {
        let dv = d.range(-3.0, 3.0);
        let reached = lane == own && ahead + dv * seconds < CLEAR_AHEAD_M;
        v + if reached { dv.abs() } else { dv }
    };
    let n = d.int(2, 5);
    c.vehicles = (0..n)
        .map(|k| {
            let lane = d.int(0, lanes - 1);
            let ahead = d.range(10.0, 60.0);
            let speed = speed(d, lane, ahead);
            car(lane, ahead, speed, COLOURS[k % COLOURS.len()])
        })
        .collect();
    if d.chance(0.5) {
        let lane = d.int(0, lanes - 1);
        let ahead = d.range(10.0, 60.0);
        let speed = speed(d, lane, ahead);
        c.vehicles.push(Vehicle {
            size_m: [12.0, 2.5, 3.6],
            ..car(lane, ahead, speed, [230, 230, 225])
        });
    }
    let start = d.range(3.0, 7.0);
    let length = d.range(0.5, 1.5);
    c.blackouts = vec![[start, start + length]];
    c
}

fn shadows(d: &mut Draw) -> SceneConfig {
    let segments = gentle(d, [60.0, 140.0], [100.0, 200.0], 0.002);
    let mut c = highway(d, segments, 300);
    let left = d.chance(0.75);
    let right = !left || d.chance(0.75);
    for (side, present) in [(true, left), (false, right)] {
        let from_s = d.range(20.0, 80.0);
        let length = d.range(150.0, 350.0);
        let reach_m = d.range(3.0, 7.0);
        let light = d.range(0.35, 0.6);
        if present {
            c.shadows.push(Shadow::Trees {
                from_s,
                to_s: from_s + length,
                left: side,
                reach_m,
                light,
            });
        }
    }
    let bridge_s = d.range(100.0, 250.0);
    let bridge_m = d.range(8.0, 25.0);
    let light = d.range(0.2, 0.4);
    if d.chance(0.8) {
        c.shadows.push(Shadow::Band {
            from_s: bridge_s,
            to_s: bridge_s + bridge_m,
            light,
        });
    }
    c
}

fn worn_markings(d: &mut Draw) -> SceneConfig {
    let segments = gentle(d, [60.0, 140.0], [80.0, 150.0], 0.0015);
    let mut c = highway(d, segments, 300);
    let boundaries = c.road.lanes + 1;
    let n = d.int(2, 4);
    c.markings.wear = (0..n)
        .map(|_| {
            let from_s = d.range(40.0, 250.0);
            let length = d.range(40.0, 100.0);
            let all = d.chance(0.3);
            let boundary = d.int(0, boundaries - 1);
            let visibility = if all {
                d.range(0.2, 0.5)
            } else {
                d.range(0.0, 0.3)
            };
            Wear {
                from_s,
                to_s: from_s + length,
                boundary: (!all).then_some(boundary),
                visibility,
            }
        })
        .collect();
    c.appearance.patches = d.range(0.1, 0.35);
    c
}

fn night(d: &mut Draw) -> SceneConfig {
    let segments = gentle(d, [60.0, 140.0], [80.0, 150.0], 0.002);
    let mut c = highway(d, segments, 300);
    c.appearance.night = true;
    c.appearance.noise = d.range(3.0, 5.0);
    let (lanes, v) = (c.road.lanes, c.ego.speed_mps);
    let n = d.int(0, 2);
    c.vehicles = (0..n)
        .map(|k| {
            let lane = d.int(0, lanes - 1);
            let ahead = d.range(30.0, 80.0);
            let speed = v + d.range(0.0, 3.0);
            car(lane, ahead, speed, COLOURS[(k + 2) % COLOURS.len()])
        })
        .collect();
    c
}

/// A width in 2.8-4.2 m at least `min_step` from `from` (drawn on the side with room, or
/// either side when both have).
fn new_width(d: &mut Draw, from: f64, min_step: f64) -> f64 {
    let (lo, hi) = (2.8, 4.2);
    let up = hi - (from + min_step);
    let down = (from - min_step) - lo;
    let go_up = match (up > 0.0, down > 0.0) {
        (true, true) => d.chance(up / (up + down)),
        (up_ok, _) => up_ok,
    };
    if go_up {
        d.range(from + min_step, hi)
    } else {
        d.range(lo, from - min_step)
    }
}

fn width_change(d: &mut Draw) -> SceneConfig {
    let mut c = highway(d, vec![straight(100.0)], 300);
    c.ego.sway_amplitude_m = d.range(0.0, 0.15);
    let w0 = c.road.lane_width_m;
    let from1 = d.range(30.0, 80.0);
    let to1 = from1 + d.range(50.0, 100.0);
    let w1 = new_width(d, w0, 0.4);
    let from2 = to1 + d.range(20.0, 60.0);
    let to2 = from2 + d.range(40.0, 80.0);
    let w2 = new_width(d, w1, 0.4);
    c.road.width_changes = vec![
        WidthChange {
            from_s: from1,
            to_s: to1,
            width_m: w1,
        },
        WidthChange {
            from_s: from2,
            to_s: to2,
            width_m: w2,
        },
    ];
    c
}

fn pitch_bumps(d: &mut Draw) -> SceneConfig {
    let mut c = highway(d, vec![straight(100.0)], 300);
    c.ego.pitch_amplitude_deg = d.range(0.6, 1.6);
    c.ego.height_amplitude_m = d.range(0.02, 0.06);
    c.ego.body_period_s = d.range(0.7, 1.4);
    c.vertical.curvature = d.signed(2e-4, 6e-4);
    c
}

fn multi_lane(d: &mut Draw) -> SceneConfig {
    let a = d.range(100.0, 180.0);
    let t = d.range(80.0, 150.0);
    let k = d.signed(0.0, 0.001);
    let mut c = highway(
        d,
        vec![straight(a), transition(t, 0.0, k), arc(2000.0, k)],
        300,
    );
    c.road.lanes = 4;
    c.ego.lane = d.int(1, 2);
    let missing_left = d.chance(0.5);
    let (gap_lane, short_lane) = if missing_left { (0, 3) } else { (3, 0) };
    let gap_from = d.range(60.0, 140.0);
    let gap_to = gap_from + d.range(80.0, 140.0);
    let appears = d.range(40.0, 100.0);
    let ends = d.range(200.0, 280.0);
    c.road.lane_gaps = vec![
        LaneGap {
            lane: gap_lane,
            from_s: gap_from,
            to_s: gap_to,
        },
        LaneGap {
            lane: short_lane,
            from_s: 0.0,
            to_s: appears,
        },
        LaneGap {
            lane: short_lane,
            from_s: ends,
            to_s: 1e6,
        },
    ];
    c
}

fn urban(d: &mut Draw) -> SceneConfig {
    let a = d.range(20.0, 50.0);
    let t = d.range(20.0, 40.0);
    let k = d.sign() / d.range(100.0, 250.0);
    let l = d.range(25.0, 60.0);
    let w = d.range(2.8, 3.6);
    let road = RoadConfig {
        segments: vec![
            straight(a),
            transition(t, 0.0, k),
            arc(l, k),
            transition(t, k, 0.0),
            straight(2000.0),
        ],
        lanes: 2,
        lane_width_m: w,
        width_changes: vec![],
        lane_gaps: vec![],
    };
    let speed_mps = d.range(8.0, 14.0);
    let ego = EgoConfig {
        speed_mps,
        fps: FPS,
        start_s: START_S,
        lane: 1,
        sway_amplitude_m: d.range(0.0, 0.25),
        sway_period_s: d.range(6.0, 10.0),
        ..EgoConfig::default()
    };
    let centre = MarkingStyle {
        pattern: Pattern::Double {
            gap_m: d.range(0.1, 0.2),
        },
        paint: Paint::Yellow,
        width_m: d.range(0.10, 0.15),
    };
    let markings = MarkingConfig {
        overrides: street_markings(centre),
        ..MarkingConfig::default()
    };
    let parked = d.int(3, 8);
    let mut s = d.range(30.0, 60.0);
    let mut vehicles = Vec::with_capacity(parked);
    // Parked half on the pavement, 0.2 m into the lane: clear of the car, which keeps to the
    // lane's centre within its sway of at most 0.25 m (half-width 0.9 m).
    for k in 0..parked {
        vehicles.push(Vehicle {
            offset_m: -(w / 2.0 + 0.7),
            ..car(1, s, 0.0, COLOURS[(k * 2) % COLOURS.len()])
        });
        s += d.range(15.0, 30.0);
    }
    let paint_s = d.range(50.0, 120.0);
    let road_paint = (0..4)
        .map(|k| RoadPaint {
            s: paint_s + k as f64 * 0.9,
            d: -w / 2.0,
            size_m: [0.5, 1.6],
        })
        .chain([RoadPaint {
            s: paint_s + 40.0,
            d: -w / 2.0,
            size_m: [4.0, 0.3],
        }])
        .collect();
    let appearance = Appearance {
        patches: d.range(0.15, 0.35),
        seam_period_m: d.range(5.0, 8.0),
        hood: d.range(0.08, 0.15),
        vignette: d.range(0.3, 0.7),
        glare: Some([d.range(0.6, 0.9), d.range(0.15, 0.3), d.range(0.05, 0.1)]),
        exposure: d.range(0.0, 0.15),
        blur: 1,
        ..Appearance::default()
    };
    SceneConfig {
        road,
        markings,
        ego,
        vertical: VerticalProfile::default(),
        vehicles,
        shadows: vec![],
        road_paint,
        blackouts: vec![],
        appearance,
        frames: frames_to_reach(a + t + l / 2.0, speed_mps, 0.0, 300),
    }
}

#[cfg(test)]
#[path = "family_tests.rs"]
mod tests;
