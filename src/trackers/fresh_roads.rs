//! Test helpers for the trackers' accuracy tests on fresh roads (issue 20): members of the
//! simulator's scenario families ([`crate::synth::draw_scenario`]), each rendered through its
//! own drawn camera, which is the camera the tracker is given. A threshold tested over a range
//! of seeds is a property of the tracker, not of one road.
//!
//! The tests use scene seeds below 40; the figures in RESULTS.md's `eval-suite` tables come
//! from seeds 1000 and up, which no test uses.

use super::TrackerConfig;
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
