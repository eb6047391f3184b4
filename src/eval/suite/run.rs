//! One family member through every tracker: [`run_member`] and [`score_run`].

use super::cell::SeedScore;
use crate::error::Result;
use crate::eval::lane_changes::lane_change_counts;
use crate::eval::lane_configuration::lane_configuration_counts;
use crate::eval::synthetic::evaluate;
use crate::lane::LaneEstimate;
use crate::synth::{Eye, FamilyMember};
use crate::trackers::{self, EgoMotion, TrackerConfig};
use std::collections::BTreeMap;
use std::time::Instant;

/// The truth of a member's frames and every tracker's output on them.
#[derive(Debug, Clone)]
pub struct MemberRun {
    /// Ground truth, one per frame.
    pub truth: Vec<LaneEstimate>,
    /// (tracker id, its estimates, one per frame, with `ms` the time of its step).
    pub outputs: Vec<(String, Vec<LaneEstimate>)>,
}

/// Renders `member` at `width` x `height` for its own number of frames (at most `max_frames`
/// when given) and runs each tracker of `ids` on every frame, built on the member's camera
/// with `tracker_seed` and `options` (the tracker options; empty: each tracker's defaults).
///
/// # Errors
/// An unknown tracker id, an unusable size, or a tracker's error on a frame.
pub fn run_member(
    member: &FamilyMember,
    ids: &[String],
    width: usize,
    height: usize,
    max_frames: Option<u32>,
    tracker_seed: u64,
    options: &BTreeMap<String, serde_json::Value>,
) -> Result<MemberRun> {
    let mut scene = member.scene(width, height)?;
    let camera = scene.camera().to_file();
    let config = TrackerConfig {
        camera,
        particles: None,
        seed: tracker_seed,
        options: trackers::Options::ByName(options.clone()),
    };
    let mut trackers = ids
        .iter()
        .map(|id| trackers::create(id, &config))
        .collect::<Result<Vec<_>>>()?;
    let stereo = trackers.iter().any(|t| t.is_stereo());
    let frames = max_frames.map_or(member.config.frames, |m| m.min(member.config.frames));
    let mut left = vec![0u8; width * height * 4];
    let mut right = vec![0u8; width * height * 4];
    let mut truth = Vec::with_capacity(frames as usize);
    let mut outputs: Vec<Vec<LaneEstimate>> = vec![Vec::with_capacity(frames as usize); ids.len()];
    for frame in 0..frames {
        scene.render(frame, Eye::Left, &mut left, None)?;
        if stereo {
            scene.render(frame, Eye::Right, &mut right, None)?;
        }
        let t = crate::trackers::scene_truth(&scene, frame);
        let motion = EgoMotion {
            t_s: t.state.get("t").copied().unwrap_or(0.0),
            speed_mps: t.state.get("speed_mps").copied().unwrap_or(0.0),
            yaw_rate: t.state.get("yaw_rate").copied().unwrap_or(0.0),
        };
        for (tracker, out) in trackers.iter_mut().zip(&mut outputs) {
            tracker.set_ego_motion(motion)?;
            let start = Instant::now();
            if tracker.is_stereo() {
                tracker.set_right(&right, width, height)?;
            }
            let mut e = tracker.step(&left, width, height)?;
            e.ms = start.elapsed().as_secs_f64() * 1e3;
            e.frame = t.frame.clone();
            out.push(e);
        }
        truth.push(t);
    }
    Ok(MemberRun {
        truth,
        outputs: ids.iter().cloned().zip(outputs).collect(),
    })
}

/// The scores of one tracker's `output` on `truth` (frame i with frame i).
///
/// # Errors
/// [`crate::Error::Config`] without frames.
pub fn score_run(truth: &[LaneEstimate], output: &[LaneEstimate]) -> Result<SeedScore> {
    let preds: Vec<Option<&LaneEstimate>> = (0..truth.len()).map(|i| output.get(i)).collect();
    let report = evaluate(truth, &preds)?;
    let ms: Vec<f64> = output.iter().map(|e| e.ms).collect();
    Ok(SeedScore {
        report,
        lane_changes: lane_change_counts(truth, &preds),
        configuration: lane_configuration_counts(truth, &preds),
        ms_sum: ms.iter().sum(),
        ms_frames: ms.len(),
    })
}
