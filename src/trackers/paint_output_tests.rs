//! Tests of [`super::paint_output`]'s `valid_needs_paint` on every mono tracker: a highway
//! whose markings stop for 80 m, as across a junction, with tree shadows along it.

use crate::camera::Camera;
use crate::lane::LaneEstimate;
use crate::synth::{default_camera, scenario, Eye, Scene, Wear};
use crate::trackers::{create, preset_options, Preset, Tracker, TrackerConfig};
use serde_json::Value;

/// Where the markings stop and start again, metres along the road.
const UNMARKED_M: [f64; 2] = [100.0, 180.0];
/// Frames rendered.
const FRAMES: u32 = 220;

/// Tracker `id` with its `real-roads` options and `option` set to `on`, for `camera`, tracker
/// seed 1.
pub(super) fn real_roads_tracker(
    id: &str,
    camera: &Camera,
    option: &str,
    on: bool,
) -> Box<dyn Tracker> {
    real_roads_tracker_with(id, camera, &[(option, on.into())])
}

/// Tracker `id` with its `real-roads` options and each of `set` (option, value; `seed` among
/// them replaces tracker seed 1), for `camera`.
pub(super) fn real_roads_tracker_with(
    id: &str,
    camera: &Camera,
    set: &[(&str, Value)],
) -> Box<dyn Tracker> {
    let serde_json::Value::Object(mut options) = preset_options(id, Preset::RealRoads).unwrap()
    else {
        panic!("{id}: the preset is not an object");
    };
    options.insert("seed".into(), 1.into());
    for (option, value) in set {
        options.insert((*option).into(), value.clone());
    }
    options.insert(
        "camera".into(),
        serde_json::to_value(camera.to_file()).unwrap(),
    );
    let config =
        TrackerConfig::from_json_str(&serde_json::Value::Object(options).to_string()).unwrap();
    create(id, &config).unwrap()
}

/// Tracker `id`'s `real-roads` with each of `set` (option, value) on `shadows` without markings
/// over [`UNMARKED_M`] (320x240, [`FRAMES`] frames, scene and tracker seed 1): per frame, the
/// distance s of the car along the road and the estimate.
fn unmarked_run(id: &str, set: &[(&str, Value)]) -> Vec<(f64, LaneEstimate)> {
    shadows_run(id, set, [320, 240], UNMARKED_M, FRAMES)
}

/// [`unmarked_run`] at `size`, without markings over `unmarked`, for `frames` frames.
fn shadows_run(
    id: &str,
    set: &[(&str, Value)],
    [width, height]: [usize; 2],
    unmarked: [f64; 2],
    frames: u32,
) -> Vec<(f64, LaneEstimate)> {
    let camera = default_camera(width, height).unwrap();
    let mut config = scenario("shadows").unwrap();
    config.frames = frames;
    config.markings.wear = vec![Wear {
        from_s: unmarked[0],
        to_s: unmarked[1],
        boundary: None,
        visibility: 0.0,
    }];
    let ego = config.ego.clone();
    let mut scene = Scene::new(config, camera.clone(), 1).unwrap();
    let mut tracker = real_roads_tracker_with(id, &camera, set);
    let mut rgba = vec![0; width * height * 4];
    (0..frames)
        .map(|f| {
            scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            let e = tracker.step(&rgba, width, height).unwrap();
            (ego.start_s + ego.speed_mps * f as f64 / ego.fps, e)
        })
        .collect()
}

/// Share of the frames of `run` with s in `range` that were valid.
fn valid_share(run: &[(f64, LaneEstimate)], range: [f64; 2]) -> f64 {
    let frames: Vec<bool> = run
        .iter()
        .filter(|(s, _)| *s >= range[0] && *s <= range[1])
        .map(|(_, e)| e.valid)
        .collect();
    frames.iter().filter(|&&v| v).count() as f64 / frames.len() as f64
}

/// `shadows` (tree shadows along both sides, whose edges run beside the lane) with its
/// markings gone over [`UNMARKED_M`]. Measured (2026-11-30, valid share without -> with the
/// option, frames whose view from 4 to 40 m ahead is all unmarked; before and after the
/// stretch 1.00 -> 1.00 for every tracker): adachi-mmpf 0.00 -> 0.00, danescu-mono 0.77 ->
/// 0.00 (its filter holds the lane on the shadows' edges), lee-cpf 0.00 -> 0.00, liu-ppf 0.15
/// -> 0.00. Thresholds: with the option at most 5 % valid in the stretch and, before and after
/// it, as valid as without the option and at least 95 %; without the option danescu-mono valid
/// in at least half the stretch (the scene tests what it should).
#[test]
fn every_mono_tracker_reports_no_lane_where_the_paint_stops() {
    // The view from 4 to 40 m ahead: all unmarked, and all marked before and after.
    let unmarked = [UNMARKED_M[0] - 4.0, UNMARKED_M[1] - 40.0];
    let (before, after) = ([30.0, UNMARKED_M[0] - 40.0], [UNMARKED_M[1] + 10.0, 1e9]);
    for id in ["adachi-mmpf", "danescu-mono", "lee-cpf", "liu-ppf"] {
        // Without `valid_from_paint`, which could only add valid frames.
        let run = |on: bool| {
            unmarked_run(
                id,
                &[
                    ("valid_needs_paint", on.into()),
                    ("valid_from_paint", false.into()),
                ],
            )
        };
        let (without, with) = (run(false), run(true));
        let shares = |run: &[(f64, LaneEstimate)]| {
            [before, unmarked, after].map(|range| valid_share(run, range))
        };
        let ([b0, u0, a0], [b1, u1, a1]) = (shares(&without), shares(&with));
        let message = format!("{id}: before / unmarked / after {b0:.2} / {u0:.2} / {a0:.2} -> {b1:.2} / {u1:.2} / {a1:.2}");
        assert!(u1 <= 0.05, "{message}");
        assert!(
            b1 >= b0 && a1 >= a0 && b1 >= 0.95 && a1 >= 0.95,
            "{message}"
        );
        if id == "danescu-mono" {
            assert!(u0 >= 0.5, "{message}");
        }
    }
}

/// `valid_needs_paint` on the near side of a 30 m crossing at 640x480, where the paint beyond
/// it comes into view, with danescu-mono, whose filter holds a lane on the tree shadows'
/// edges: of the frames whose next paint lies 18 m or more ahead (12 m beyond the nearest
/// probe at 4 m, and 2 m to spare) at most 5 % are valid; before the crossing, and from
/// 10 m after it, at least 95 % are. Measured (2026-12-01, valid shares before /
/// near side / after, the option off -> on): 1.00 / 0.53 / 0.96 -> 1.00 / 0.00 / 0.96; with
/// `NEEDS_PAINT_WITHIN_M` 40 m, the rule before session 37, the near side 0.11 (the test
/// fails). liu-ppf's filter, the other that holds on shadows, lets this crossing go by
/// itself. The run keeps the paper's `width_range_m` [2.2, 5.0], as when it was measured: with
/// `real-roads`' [2.2, 4.5] (session 38), which moves the filter's random stream but not this
/// lane's width (3.6 m), one frame after the crossing is not valid with the option and
/// without alike (0.96 -> 0.93 both; `no_lane_eval` `shadows` over 12 seeds: 27 -> 28 of
/// 2220 marked frames not valid).
#[test]
fn paint_beyond_a_crossing_does_not_keep_its_near_side_valid() {
    const CROSSING_M: [f64; 2] = [100.0, 130.0];
    let near_side = [CROSSING_M[0] - 4.0, CROSSING_M[1] - 18.0];
    let (before, after) = ([30.0, CROSSING_M[0] - 40.0], [CROSSING_M[1] + 10.0, 1e9]);
    let run = |on: bool| {
        shadows_run(
            "danescu-mono",
            &[
                ("valid_needs_paint", on.into()),
                ("valid_from_paint", false.into()),
                ("width_range_m", serde_json::json!([2.2, 5.0])),
            ],
            [640, 480],
            CROSSING_M,
            190,
        )
    };
    let (without, with) = (run(false), run(true));
    let shares = |run: &[(f64, LaneEstimate)]| {
        [before, near_side, after].map(|range| valid_share(run, range))
    };
    let ([b0, u0, a0], [b1, u1, a1]) = (shares(&without), shares(&with));
    let message = format!(
        "before / near side / after {b0:.2} / {u0:.2} / {a0:.2} -> {b1:.2} / {u1:.2} / {a1:.2}"
    );
    // Without the option the filter holds its lane there: the scene tests the rule.
    assert!(u0 >= 0.3, "{message}");
    assert!(u1 <= 0.05, "{message}");
    assert!(b1 >= 0.95 && a1 >= 0.95, "{message}");
}

/// `valid_needs_paint`'s rule on the snap's `painted_from_m`: a run of paint beginning within
/// [`super::paint_output::NEEDS_PAINT_WITHIN_M`] of the nearest probe along either ego
/// boundary keeps a frame valid; paint farther off on both, or none, does not.
#[test]
fn paint_within_a_dashed_gap_of_the_car_keeps_a_lane() {
    use super::paint_output::{paint_keeps_valid, NEEDS_PAINT_WITHIN_M};
    use super::paint_snap::Snapped;
    let keeps = |painted_from_m: [f64; 2]| {
        paint_keeps_valid(&Snapped {
            painted_from_m,
            ..Snapped::default()
        })
    };
    let (within, beyond) = (NEEDS_PAINT_WITHIN_M, NEEDS_PAINT_WITHIN_M + 0.5);
    assert!(keeps([0.0, 0.0]) && keeps([0.0, f64::INFINITY]) && keeps([f64::INFINITY, 0.0]));
    assert!(keeps([within, beyond]) && keeps([beyond, within]));
    assert!(!keeps([beyond, beyond]) && !keeps([beyond, f64::INFINITY]));
    assert!(!keeps(Snapped::default().painted_from_m));
}

/// `valid_from_paint` on every mono tracker, on the `shadows` road whose markings stop for
/// 80 m: the filter is the same with and without it (each frame's state), a frame valid
/// without it is the same frame with it, a frame it leaves not valid keeps its boundaries
/// where the filter put them, and where the next markings begin more than 8 m ahead (paint
/// beyond 2 m of the nearest probe at 4 m on both sides, a crossing's far side) no frame is
/// made valid. Measured (2026-11-30, frames made valid of 220): adachi-mmpf 0, danescu-mono
/// 0, lee-cpf 1, liu-ppf 1 (the scene asks the option for at least one).
#[test]
fn paint_makes_a_frame_valid_only_where_the_filter_found_none_and_paint_begins_near() {
    let mut made_valid = 0;
    for id in ["adachi-mmpf", "danescu-mono", "lee-cpf", "liu-ppf"] {
        let off = unmarked_run(id, &[("valid_from_paint", false.into())]);
        let on = unmarked_run(id, &[("valid_from_paint", true.into())]);
        for ((s, a), (_, b)) in off.iter().zip(&on) {
            assert_eq!(a.state, b.state, "{id} at {s:.1} m: the filter changed");
            if a.valid {
                assert_eq!(a, b, "{id} at {s:.1} m");
            } else if !b.valid {
                assert_eq!(a.boundaries, b.boundaries, "{id} at {s:.1} m: moved");
            } else {
                made_valid += 1;
                let paint_ahead = UNMARKED_M[1] - s;
                assert!(
                    !(*s > UNMARKED_M[0] - 4.0 && paint_ahead > 8.0),
                    "{id} at {s:.1} m: made valid with the next paint {paint_ahead:.1} m ahead"
                );
            }
        }
    }
    assert!(
        made_valid >= 1,
        "no frame made valid: the scene does not test the option"
    );
}

/// `valid_from_paint`'s rule on the snap's `painted_from_m`: paint from the car along one
/// boundary and within a dashed line's gap along the other makes a frame valid; paint that
/// begins ahead on both (a crossing's far side), farther than the gap on one, or missing on
/// one does not.
#[test]
fn paint_from_the_car_on_one_side_and_within_a_gap_on_the_other_makes_a_lane() {
    use super::paint_output::{paint_makes_valid, FROM_PAINT_FAR_M, FROM_PAINT_NEAR_M};
    use super::paint_snap::Snapped;
    let with = |painted_from_m: [f64; 2]| {
        paint_makes_valid(&Snapped {
            painted_from_m,
            ..Snapped::default()
        })
    };
    let (near, far) = (FROM_PAINT_NEAR_M, FROM_PAINT_FAR_M);
    assert!(with([0.0, 0.0]));
    assert!(with([0.0, 6.5]) && with([6.5, 0.0]));
    assert!(with([near, far]) && with([far, near]));
    assert!(!with([0.0, far + 0.5]) && !with([far + 0.5, 0.0]));
    // Caltech 139 (tracker seed 2): the double yellow from 8 m beyond the nearest probe, the
    // dashes from 9.5 m, across the junction.
    assert!(!with([8.0, 9.5]));
    assert!(!with([near + 0.5, near + 0.5]));
    assert!(!with([0.0, f64::INFINITY]) && !with([f64::INFINITY, 0.0]));
    assert!(!Snapped::default()
        .painted_from_m
        .iter()
        .any(|x| x.is_finite()));
    assert!(!with(Snapped::default().painted_from_m));
}
