//! Test helpers for the trackers' accuracy tests on fresh roads (issue 20): members of the
//! simulator's scenario families ([`crate::synth::draw_scenario`]), each rendered through its
//! own drawn camera, which is the camera the tracker is given. A threshold tested over a range
//! of seeds is a property of the tracker, not of one road.
//!
//! The tests use scene seeds below 40; the figures in RESULTS.md's `eval-suite` tables come
//! from seeds 1000 and up, which no test uses.

use super::TrackerConfig;
use crate::lane::LaneEstimate;
use crate::synth::{draw_scenario, FamilyMember, Scene};

/// Member `seed` of the family `name` rendered `width` x `height` through its own camera, with
/// at most `max_frames` frames (the member's own number when it has fewer).
pub(crate) fn member_scene(
    name: &str,
    seed: u64,
    width: usize,
    height: usize,
    max_frames: u32,
) -> (FamilyMember, Scene) {
    let mut member = draw_scenario(name, seed).unwrap();
    member.config.frames = member.config.frames.min(max_frames);
    let scene = member.scene(width, height).unwrap();
    (member, scene)
}

/// A tracker configuration on the camera of `scene`, with `extra` appended to the JSON object
/// (`, "particles": 300, "seed": 2`).
pub(crate) fn config_for(scene: &Scene, extra: &str) -> TrackerConfig {
    let cam = serde_json::to_string(&scene.camera().to_file()).unwrap();
    TrackerConfig::from_json_str(&format!(r#"{{"camera": {cam} {extra}}}"#)).unwrap()
}

/// A one-line summary of a member's road and camera, for the per-seed lines tests print.
pub(crate) fn describe(member: &FamilyMember) -> String {
    let m = &member.mount;
    format!(
        "{} seed {}: {} lanes of {:.2} m, lane {}, hfov {:.0} deg, height {:.2} m, pitch {:.1} \
         deg, yaw {:.1} deg",
        member.scenario,
        member.seed,
        member.config.road.lanes,
        member.config.road.lane_width_m,
        member.config.ego.lane,
        m.hfov_deg,
        m.height_m,
        m.pitch_deg,
        m.yaw_deg,
    )
}

/// How far inside the true ego-left boundary the line nearest the lane lies, metres: half the
/// span of a double line when the car drives in the leftmost lane of member `seed` of `name`
/// and its left edge is one (the truth puts the boundary between the two lines; a tracker
/// finds the inner one), else 0.
pub(crate) fn inner_line_m(name: &str, seed: u64) -> f64 {
    use crate::synth::Pattern;
    let m = draw_scenario(name, seed).unwrap().config;
    m.markings
        .overrides
        .iter()
        .filter(|o| o.boundary == 0 && m.ego.lane == 0)
        .map(|o| match o.style.pattern {
            Pattern::Double { gap_m } => (gap_m + o.style.width_m) / 2.0,
            _ => 0.0,
        })
        .sum()
}

/// Lane changes as (frame, direction), +1 to the left as the trackers' `change` flags count.
pub(crate) type Changes = Vec<(usize, i8)>;

/// The lane changes of a run: the truth's (the evaluator's events, +1 right, turned round) and the flags'
/// (one per frame, 0: none).
pub(crate) fn lane_change_events(
    truth: &[LaneEstimate],
    flags: impl Iterator<Item = i8>,
) -> (Changes, Changes) {
    let truth = crate::eval::lane_changes::truth_lane_changes(truth)
        .iter()
        .map(|c| (c.frame, -c.direction))
        .collect();
    let events = flags
        .enumerate()
        .filter(|&(_, change)| change != 0)
        .collect();
    (truth, events)
}

/// Whether `events` are `truth`'s changes one for one, each in the same direction and within
/// `frames` frames of it.
pub(crate) fn changes_match(events: &[(usize, i8)], truth: &[(usize, i8)], frames: usize) -> bool {
    events.len() == truth.len()
        && events
            .iter()
            .zip(truth)
            .all(|(e, t)| e.1 == t.1 && e.0.abs_diff(t.0) <= frames)
}

/// Boundary accuracy and valid share of tracker `id` (300 particles, tracker `seed`, `options`
/// appended to the config's JSON) on the reference `occlusion` road (scene `scene_seed`,
/// 320x240, the default camera), from 10 to 50 frames after its blackout.
pub(crate) fn after_blackout(id: &str, options: &str, scene_seed: u64, seed: u64) -> (f64, f64) {
    use crate::synth::{default_camera, scenario, Eye};
    let camera = default_camera(320, 240).unwrap();
    let config = scenario("occlusion").unwrap();
    let end = (config.blackouts[0][1] * config.ego.fps).ceil() as u32;
    let mut scene = Scene::new(config, camera.clone(), scene_seed).unwrap();
    let extra = format!(r#", "particles": 300, "seed": {seed} {options}"#);
    let mut tracker = super::create(id, &config_for(&scene, &extra)).unwrap();
    let mut rgba = vec![0; 320 * 240 * 4];
    let (mut gt, mut out) = (Vec::new(), Vec::new());
    for f in 0..end + 50 {
        scene.render(f, Eye::Left, &mut rgba, None).unwrap();
        let e = tracker.step(&rgba, 320, 240).unwrap();
        if f >= end + 10 {
            gt.push(crate::trackers::scene_truth(&scene, f));
            out.push(e);
        }
    }
    let preds: Vec<Option<&LaneEstimate>> = out.iter().map(Some).collect();
    let accuracy = crate::eval::synthetic::evaluate(&gt, &preds)
        .unwrap()
        .boundaries
        .accuracy
        .unwrap_or(0.0);
    let valid = out.iter().filter(|e| e.valid).count() as f64 / out.len() as f64;
    (accuracy, valid)
}

/// `eval-suite`'s score of tracker `id` (tracker seed 1, 320x240, `option` set to `value`,
/// every other option its default) on each member of the family `scenario` with seeds
/// `seeds`, over at most `frames` frames of each.
pub(crate) fn member_scores(
    id: &str,
    scenario: &str,
    seeds: std::ops::RangeInclusive<u64>,
    frames: u32,
    (option, value): (&str, serde_json::Value),
) -> Vec<crate::eval::suite::SeedScore> {
    use crate::eval::suite::{run_member, score_run};
    let options = std::collections::BTreeMap::from([(option.to_string(), value)]);
    seeds
        .map(|seed| {
            let member = draw_scenario(scenario, seed).unwrap();
            let ids = [id.to_string()];
            let run = run_member(&member, &ids, 320, 240, Some(frames), 1, &options).unwrap();
            score_run(&run.truth, &run.outputs[0].1).unwrap()
        })
        .collect()
}
