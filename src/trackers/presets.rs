//! Named option sets: `paper`, each paper's filter as written (every tracker's defaults), and
//! `real-roads`, the options beyond the papers (ours) that measured better on real footage
//! nobody tuned for (RESULTS.md, *Options beyond the papers*):
//!
//! | tracker | `real-roads` |
//! |---|---|
//! | adachi-mmpf | `relock_share` 0.05, `paired_edges`, `width_scaled_threshold`, `adjacent_lanes`, `side_search_share` 0.2, `reacquire_near_m` 4, `valid_support_frames` 2, `snap_to_paint`, `snap_follows_bends`, `valid_needs_paint`, `valid_from_paint` |
//! | danescu-mono | `relock_share` 0.1, `adjacent_lanes`, `start_iterations` 10, `valid_distance_m` 0.03, `valid_support_frames` 5, `width_range_m` [2.2, 4.5], `snap_to_paint`, `snap_follows_bends`, `valid_needs_paint`, `valid_from_paint` |
//! | danescu-stereo | `adjacent_lanes`, `start_iterations` 10, `valid_distance_m` 0.03 |
//! | lee-cpf | `relock_share` 0.05, `curvature_prior_sd` 0.004, `adjacent_lanes`, `valid_support_frames` 5, `side_search_share` 0.2, `kalman_process_sd` three times its defaults (ten times on the width), `reacquire_near_m` 4, `snap_to_paint`, `snap_follows_bends`, `valid_needs_paint`, `valid_from_paint` |
//! | liu-ppf | `top_view_resolved`, `reacquire_near_m` 4, `mode_candidates` 32, `valid_support_frames` 2, `snap_to_paint`, `snap_follows_bends`, `adjacent_lanes`, `valid_needs_paint`, `valid_from_paint` |
//! | liu-ppf-nokernel | none (the paper's baseline: its filter as written) |
//!
//! A preset is a starting point: options given beside it replace its values.

use super::adachi::config::AdachiConfig;
use super::danescu::config::DanescuConfig;
use super::lee::config::LeeConfig;
use super::liu::config::LiuConfig;
use super::TrackerOptions;
use crate::error::{Error, Result};
use std::str::FromStr;

/// A named set of tracker options.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Preset {
    /// Each paper's filter as written: the tracker's defaults.
    Paper,
    /// The options beyond the papers (ours) for real footage.
    RealRoads,
}

/// The names [`Preset::from_str`] accepts, in order.
pub const PRESET_NAMES: [&str; 2] = ["paper", "real-roads"];

impl FromStr for Preset {
    type Err = Error;
    fn from_str(name: &str) -> Result<Self> {
        match name {
            "paper" => Ok(Self::Paper),
            "real-roads" => Ok(Self::RealRoads),
            other => Err(Error::Config(format!(
                "unknown preset `{other}`: use one of {}",
                PRESET_NAMES.join(", ")
            ))),
        }
    }
}

/// The Danescu trackers' start rounds in `real-roads`: the first frame ends as one cluster,
/// so its estimate can be valid (with the paper's start it was not, on every video we ran:
/// the MBSAS cluster holds a quarter of a cloud drawn from the initial distribution).
const DANESCU_START_ITERATIONS: usize = 10;
/// The Danescu trackers' validity tolerance on the road in `real-roads`, metres: with the
/// 2-pixel floor it changes nothing through a 640-pixel camera of 309 px focal length
/// (Caltech) and widens the tolerance near the car on 1280x720 video.
const DANESCU_VALID_DISTANCE_M: f64 = 0.03;

/// danescu-mono's `valid_support_frames` (RESULTS.md, *Options beyond the papers*: over
/// `option_compare`'s synthetic seeds 201-213 boundaries 85.8 -> 87.1 %, Caltech tracker seeds
/// 1-5 ego lanes 83.7 -> 89.2 % at 1.5 -> 2.5 % false positives, challenge_video valid 80 ->
/// 90 %; not measured on the stereo tracker, which keeps one frame).
const DANESCU_VALID_SUPPORT_FRAMES: usize = 5;

/// lee-cpf's `valid_support_frames` (RESULTS.md, *Options beyond the papers*: over
/// `option_compare`'s synthetic seeds 201-213 boundaries 88.8 -> 89.3 %, detected 92.7 ->
/// 94.2; Caltech tracker seeds 1-5 ego lanes 89.3 -> 94.0 % at 2.7 -> 3.7 % false positives;
/// challenge_video valid 276 -> 282 of 300, every frame gained on the markings by eye).
/// adachi-mmpf keeps two frames (below): with five its held frames were off the markings.
const LEE_VALID_SUPPORT_FRAMES: usize = 5;

/// adachi-mmpf's `valid_support_frames` (RESULTS.md, *Options beyond the papers*, 2026-11-29:
/// option_compare's synthetic seeds 201-213 boundaries 88.1 -> 88.3 %, detected 89.9 -> 90.3,
/// no scene worse; Caltech tracker seeds 1-5 ego lanes 92.1 / 0.9 -> 96.2 / 1.9 %, all lanes
/// 71.9 -> 74.7, the broken right line's gaps (210) and the turn pocket held, the crossings
/// still not valid; TuSimple unchanged; `no_lane_eval` on `shadows` and `highway-straight`
/// unchanged; project_video and challenge_video one more valid frame each of 300 (project 48:
/// its left boundary off the yellow line). With 5 (2026-11-26, before `paired_edges`): Caltech
/// false positives 2.3 -> 5.5 %, project_video frames 48-51 a lane off.)
const ADACHI_VALID_SUPPORT_FRAMES: usize = 2;

/// lee-cpf's Kalman smoother in `real-roads`: its process standard deviations (our design: the
/// paper gives none) three times the defaults', so that the smoother lags the particle filter
/// less (RESULTS.md, *Options beyond the papers*: option_compare's synthetic seeds 201-213
/// boundaries 89.3 -> 89.8 % and 214-239 94.4 -> 94.6; Caltech tracker seeds 1-5 ego lanes
/// 94.0 -> 95.2 % at 3.7 -> 2.4 % false positives; TuSimple 88.6 -> 88.5; the estimate's
/// frame-to-frame change on the Udacity videos 1.4 times the default's, the smoother off 1.6
/// times).
/// Since 2026-11-28 its width term is ten times the default's (0.1 m a frame), so that the
/// smoother follows the width the side search finds (below): with the side search, Caltech
/// tracker seeds 1-5 ego lanes 96.6 / 3.7 % at 0.03 -> 97.7 / 2.6 at 0.1 (its left boundary
/// had lagged the found width in the turn pocket); alone the change left Caltech, TuSimple and
/// option_compare's synthetic figures as they were.
const LEE_KALMAN_PROCESS_SD: [f64; 6] = [0.009, 0.09, 0.1, 0.0015, 6.0, 0.0006];

/// lee-cpf's `side_search_share` (RESULTS.md, *Options beyond the papers*: option_compare's
/// synthetic seeds 201-213 boundaries 89.8 -> 90.8 %, detected 94.2 -> 95.9, 214-239 94.7 ->
/// 95.7 and 96.5 -> 97.9, the gains all on `pitch-bumps` (+11 to +15 points on three
/// members), no scene worse; Caltech tracker seeds 1-5 ego lanes 95.2 / 2.4 -> 97.7 / 2.6 %
/// with the smoother's width term above, the turn pocket 212-215 found; TuSimple unchanged).
const LEE_SIDE_SEARCH_SHARE: f64 = 0.2;

/// `reacquire_near_m` of lee-cpf and adachi-mmpf (RESULTS.md, *Options beyond the papers*:
/// Caltech tracker seeds 1-5 ego lanes, lee-cpf 97.7 / 2.6 -> 97.7 / 1.5 %, the crossing 139
/// not valid on four seeds; adachi-mmpf 91.9 / 2.5 -> 91.9 / 1.0, on all five; option_compare's
/// synthetic seeds 201-213 boundaries lee-cpf 90.8 -> 90.6 %, 214-239 95.7 -> 95.6, the loss
/// all on `pitch-bumps` (-0.6 to -1.7 points on three members); adachi-mmpf 88.2 -> 88.1,
/// 89.6 -> 89.6 (-0.7 to -1.3 on three members); TuSimple, the Udacity videos' validity
/// unchanged; liu-ppf 90.1 / 7.0 -> 90.1 / 6.2, 139 not valid on three seeds, synthetic
/// detection -0.1). 4 m lies between the reach of Caltech's valid frames (at most 3 m for
/// lee-cpf, 0.7 m for adachi-mmpf) and the crossing's (6 and 7.3 m; liu-ppf 5.5 from its 6 m).
const REACQUIRE_NEAR_M: f64 = 4.0;

/// liu-ppf's `mode_candidates` (RESULTS.md, *Options beyond the papers*: 8 and 32 measured
/// alike, Caltech 93.6 / 4.1 and 93.8 / 3.5 %; 32 of the 250 particles cost about 0.05 ms a
/// frame natively).
const LIU_MODE_CANDIDATES: usize = 32;

/// liu-ppf's `valid_support_frames` (RESULTS.md, *Options beyond the papers*, 2026-11-29:
/// option_compare's synthetic seeds 201-213 boundaries 72.9 -> 72.9 %, detected 97.3 -> 97.4;
/// Caltech tracker seeds 1-5 ego lanes 94.9 / 2.4 -> 97.5 / 2.4 %, all lanes 68.3 -> 70.2, the
/// frames after the sequence's gaps (123, 148) held; TuSimple unchanged; project_video valid
/// 290 -> 291 of 300 (the new frame on the lines), challenge_video 246 -> 250 (two on the lines,
/// two with the right boundary on the seam between asphalt and concrete). 2 as adachi-mmpf's:
/// 3 measured the same on Caltech, 5 97.7 / 2.6.)
const LIU_VALID_SUPPORT_FRAMES: usize = 2;

/// adachi-mmpf's `side_search_share` (RESULTS.md, *Options beyond the papers*: option_compare's
/// synthetic seeds 201-213 boundaries 87.6 -> 88.2 %, detected 88.7 -> 90.1, 214-239 89.6 ->
/// 89.6 and 90.6 -> 90.8, no scene worse (`pitch-bumps` seed 210 67.3 -> 73.5 %); Caltech tracker
/// seeds 1-5 ego lanes 88.4 / 2.3 -> 91.9 / 2.5 %, the turn pocket's first frames found;
/// TuSimple unchanged).
const ADACHI_SIDE_SEARCH_SHARE: f64 = 0.2;

/// The mono trackers' `snap_to_paint` (RESULTS.md, *Options beyond the papers*, 2026-11-30
/// session 33, on `real-roads`, adachi-mmpf / danescu-mono / lee-cpf / liu-ppf): CULane F1
/// (auto camera, stills, tracker seed 1) 0.38 -> 0.42, 0.19 -> 0.24, 0.21 -> 0.24, 0.41 ->
/// 0.56 (adachi-mmpf with `edge_response: "gradient"` 0.45 -> 0.53): the estimates lay a
/// median 7-14 pixels off the labels near the car, up to half of the scored line's 30;
/// `option_compare`:
/// TuSimple 91.3 -> 92.1, 90.7 -> 90.0, 88.6 -> 93.0, 72.9 -> 82.4; Caltech tracker seeds 1-5
/// ego lanes 96.2 / 1.9 -> 95.5 / 2.6, 89.7 / 1.9 -> 89.7 / 1.9, 98.5 / 0.7 -> 97.9 / 1.2,
/// 97.5 / 2.4 -> 97.9 / 2.0 % (adachi-mmpf and lee-cpf lose a boundary of frame 123 on every
/// seed: its labels lie 0.3-0.4 m beside the paint the boundary moves onto); synthetic seeds
/// 201-213 boundaries 88.3 -> 88.5, 87.1 -> 86.8, 90.6 -> 90.9, 72.9 -> 72.5 %.
/// danescu-stereo's is not measured (no labelled stereo footage) and stays off.
const SNAP_TO_PAINT: bool = true;

/// `valid_needs_paint` of the four mono trackers: a frame is reported valid only with a run of
/// paint along one of its ego boundaries (beginning within 12 m of the nearest probe since
/// 2026-12-01, session 37: RESULTS.md, *No lane*). Measured 2026-11-30, `real-roads` without and with,
/// tracker seed 1 unless stated (adachi-mmpf, danescu-mono, lee-cpf, liu-ppf): CULane F1, auto
/// camera, 41.6 -> 43.0, 23.8 -> 24.5, 23.8 -> 24.0, 55.8 -> 57.1 % (adachi-mmpf
/// `gradient` 52.6 -> 53.7); TuSimple unchanged; Caltech tracker seeds 1-5 ego correct / FP
/// 95.5 / 2.6 unchanged, 89.7 / 1.9 -> 89.7 / 1.6, 97.9 / 1.2 unchanged, 97.9 / 2.0 -> 97.9 /
/// 1.2 % (an unmarked crossing's frames 138 and 249 and liu-ppf's wrong 212-213 now not
/// valid; no correct frame lost); synthetic seeds 201-213 unchanged (`option_compare`);
/// Udacity in RESULTS.md. danescu-stereo's is not measured
/// (no labelled stereo footage) and stays off.
const VALID_NEEDS_PAINT: bool = true;

/// `snap_follows_bends` of the four mono trackers: the snap's search follows the paint round a
/// bend and its correction gets a quadratic term. Measured 2026-11-30, `real-roads` without
/// and with (adachi-mmpf, danescu-mono, lee-cpf, liu-ppf): CULane F1, auto camera, tracker
/// seed 1, 43.0 -> 43.5, 24.5 -> 27.7, 24.0 -> 31.9, 57.1 -> 57.9 % (adachi-mmpf `gradient`
/// 53.7 -> 53.7); `option_compare`: TuSimple 92.1 -> 92.4, 90.0 -> 91.8, 93.0 -> 93.2, 87.9
/// -> 90.6; Caltech tracker seeds 1-5 ego correct / FP 95.5 / 2.6 -> 96.0 / 2.1, 89.7 / 1.6
/// unchanged, 97.9 / 1.2 -> 98.4 / 0.8, 97.9 / 1.2 -> 97.8 / 1.4 %, all lanes 74.7 -> 76.2,
/// 70.6 -> 70.9, 75.7 -> 76.6, 77.8 -> 78.0 %; synthetic seeds 201-213 boundaries 88.5 ->
/// 89.2, 86.8 -> 86.9, 90.9 -> 91.2, 93.4 -> 93.5 %; Udacity valid unchanged. On straight
/// paint it costs 0.6-2.7 mm of mean ego error (`highway-straight`). Off for danescu-stereo
/// with its snap.
const SNAP_FOLLOWS_BENDS: bool = true;

/// `valid_from_paint` of the four mono trackers: a frame the filter finds not valid is
/// reported valid when paint runs along both drawn ego boundaries, along one from the car and
/// along the other within a dashed line's gap. Measured 2026-11-30, `real-roads` without and
/// with, `option_compare` (adachi-mmpf, danescu-mono, lee-cpf, liu-ppf): synthetic seeds
/// 201-213 boundaries 89.2 -> 92.6, 86.9 -> 87.8, 91.2 -> 92.3, 93.5 -> 93.6 %, detected 90.3
/// -> 98.7, 92.1 -> 93.6, 95.7 -> 98.3, 97.4 -> 97.6 %; Caltech tracker seeds 1-5 ego correct
/// / FP 96.0 / 2.1 unchanged, 89.7 / 1.6 -> 94.2 / 3.1 (the turn pocket 200-216 held; frame
/// 123, whose labels lie beside the paint, and seed 2's 139, paint 12 m ahead across the
/// junction, now drawn), 98.4 / 0.8 -> 98.6 / 0.8, 97.8 / 1.4 -> 97.9 / 1.5 %; TuSimple and
/// CULane (tracker seed 1) unchanged; `no_lane_eval` seeds 301-312 on `highway-straight` and
/// `shadows`: no unmarked frame more called valid, marked frames called not valid on `shadows`
/// 41 -> 32, 31 -> 30, 4 -> 4, 12 -> 10 of 2220. danescu-stereo's is not measured and stays
/// off.
const VALID_FROM_PAINT: bool = true;

/// danescu-mono's `width_range_m`: the lane widths (between the markings' inner edges) its
/// validation accepts, metres. The paper zeroes the weight of a particle whose lane is "too narrow,
/// too wide" (Sec. VII-D) and gives no limits; the default's 5.0 let the cloud jump to a wrong pair
/// (the kerb, a farther line) after a gap in Caltech's sequence, and 4.5 m is the widest lane in
/// common use (a 15 ft US kerb lane with its markings; lee-cpf's limit too). Measured 2026-12-01
/// (session 38), `real-roads` with [2.2, 5.0] and with [2.2, 4.5]: Caltech tracker seeds 1-5 ego
/// lanes 95.3 / 3.3 -> 96.6 / 2.6 %, all lanes 74.4 -> 75.8 (after the sequence's gaps, 123 and
/// 128, the filter had jumped to lanes 4.8-5.5 m wide: both now held on every seed, 128 but on seed
/// 5); `option_compare`'s synthetic seeds 201-213 boundaries 88.0 -> 87.9 %, 214-239 89.9 -> 89.8;
/// TuSimple unchanged; CULane F1 (auto camera, tracker seeds 1-3) 0.305 / 0.315 / 0.330 -> 0.303 /
/// 0.320 / 0.333; `no_lane_eval` unchanged within a frame or two. 4.2 measured alike on Caltech
/// (96.6 / 2.4) but would reject `width-change`'s 4.5 m lane (4.35 m between the inner edges).
const DANESCU_WIDTH_RANGE_M: [f64; 2] = [2.2, 4.5];

/// liu-ppf's `adjacent_lanes` (its partitions give the ego pair and one neighbour; the option
/// adds the other side's). Measured 2026-11-30, `real-roads` with and without, tracker seed 1
/// unless stated: TuSimple 82.4 -> 87.9 (FN 0.38 -> 0.17); CULane F1 55.9 -> 55.8 (TP / FP
/// 105 / 51 -> 108 / 59); Caltech tracker seeds 1-5 all lanes 70.5 / 7.7 -> 77.8 / 14.5 %
/// correct / FP (the added false positives are kerbs, which Caltech does not label), ego lanes
/// unchanged; `option_compare` with `real-roads`: synthetic seeds 201-213 boundaries 72.5 ->
/// 93.4 %, 0.07 ms a frame more.
const LIU_ADJACENT_LANES: bool = true;

/// `real-roads` for tracker `id`'s options (`paper` are its defaults).
pub(crate) fn real_roads(defaults: TrackerOptions) -> TrackerOptions {
    match defaults {
        TrackerOptions::AdachiMmpf(c) => TrackerOptions::AdachiMmpf(AdachiConfig {
            relock_share: 0.05,
            paired_edges: true,
            width_scaled_threshold: true,
            adjacent_lanes: true,
            side_search_share: ADACHI_SIDE_SEARCH_SHARE,
            reacquire_near_m: REACQUIRE_NEAR_M,
            valid_support_frames: ADACHI_VALID_SUPPORT_FRAMES,
            snap_to_paint: SNAP_TO_PAINT,
            snap_follows_bends: SNAP_FOLLOWS_BENDS,
            valid_needs_paint: VALID_NEEDS_PAINT,
            valid_from_paint: VALID_FROM_PAINT,
            ..c
        }),
        TrackerOptions::DanescuMono(c) => TrackerOptions::DanescuMono(DanescuConfig {
            relock_share: 0.1,
            adjacent_lanes: true,
            start_iterations: DANESCU_START_ITERATIONS,
            valid_distance_m: DANESCU_VALID_DISTANCE_M,
            valid_support_frames: DANESCU_VALID_SUPPORT_FRAMES,
            width_range_m: DANESCU_WIDTH_RANGE_M,
            snap_to_paint: SNAP_TO_PAINT,
            snap_follows_bends: SNAP_FOLLOWS_BENDS,
            valid_needs_paint: VALID_NEEDS_PAINT,
            valid_from_paint: VALID_FROM_PAINT,
            ..c
        }),
        TrackerOptions::DanescuStereo(c) => TrackerOptions::DanescuStereo(DanescuConfig {
            adjacent_lanes: true,
            start_iterations: DANESCU_START_ITERATIONS,
            valid_distance_m: DANESCU_VALID_DISTANCE_M,
            ..c
        }),
        TrackerOptions::LeeCpf(c) => TrackerOptions::LeeCpf(LeeConfig {
            relock_share: 0.05,
            curvature_prior_sd: 0.004,
            adjacent_lanes: true,
            valid_support_frames: LEE_VALID_SUPPORT_FRAMES,
            side_search_share: LEE_SIDE_SEARCH_SHARE,
            kalman_process_sd: LEE_KALMAN_PROCESS_SD,
            reacquire_near_m: REACQUIRE_NEAR_M,
            snap_to_paint: SNAP_TO_PAINT,
            snap_follows_bends: SNAP_FOLLOWS_BENDS,
            valid_needs_paint: VALID_NEEDS_PAINT,
            valid_from_paint: VALID_FROM_PAINT,
            ..c
        }),
        // liu-ppf: a top view that ends where the camera resolves it (RESULTS.md, *Options
        // beyond the papers*: Caltech tracker seeds 1-5 64.7 / 20.6 -> 90.1 / 7.0 % ego correct
        // / FP, option_compare's synthetic seeds 201-213 72.3 -> 72.1 %, 214-239 74.9 -> 75.9;
        // video from f_x 540 up unchanged); `reacquire_near_m` 4 as for lee-cpf and
        // adachi-mmpf (Caltech 90.1 / 7.0 -> 90.1 / 6.2 %, synthetic -0.1 detected); the
        // estimate's mode the heaviest of the 32 heaviest particles' (Caltech 90.1 / 6.2 -> 93.8
        // / 3.5 %, synthetic 201-213 72.1 / 96.4 -> 72.9 / 97.3, 214-239 75.9 / 99.0 -> 76.2 /
        // 99.3, TuSimple 73.5 -> 72.9).
        TrackerOptions::LiuPpf(c) => TrackerOptions::LiuPpf(LiuConfig {
            top_view_resolved: true,
            reacquire_near_m: REACQUIRE_NEAR_M,
            mode_candidates: LIU_MODE_CANDIDATES,
            valid_support_frames: LIU_VALID_SUPPORT_FRAMES,
            snap_to_paint: SNAP_TO_PAINT,
            snap_follows_bends: SNAP_FOLLOWS_BENDS,
            valid_needs_paint: VALID_NEEDS_PAINT,
            valid_from_paint: VALID_FROM_PAINT,
            adjacent_lanes: LIU_ADJACENT_LANES,
            ..c
        }),
        // liu-ppf-nokernel, the paper's baseline without the kernels, keeps the paper's filter
        // (the same top view: Caltech 25.2 / 41.0 -> 35.9 / 54.4 %, more false positives).
        nokernel @ TrackerOptions::LiuPpfNokernel(_) => nokernel,
    }
}

impl TrackerOptions {
    /// Tracker `id`'s options of `preset`.
    ///
    /// # Errors
    /// [`Error::UnknownTracker`] for an id not in [`super::TRACKER_IDS`].
    pub fn preset(id: &str, preset: Preset) -> Result<Self> {
        let defaults = Self::defaults(id)?;
        Ok(match preset {
            Preset::Paper => defaults,
            Preset::RealRoads => real_roads(defaults),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::default_camera;
    use crate::trackers::{create, Options, TrackerConfig, TRACKER_IDS};
    use serde_json::Value;

    /// The options `real-roads` changes, by name, with their values.
    fn changed(id: &str) -> Vec<(String, Value)> {
        let of = |p| match serde_json::to_value(TrackerOptions::preset(id, p).unwrap()) {
            Ok(Value::Object(m)) => m,
            other => panic!("{other:?}"),
        };
        let (paper, roads) = (of(Preset::Paper), of(Preset::RealRoads));
        roads
            .into_iter()
            .filter(|(k, v)| paper.get(k) != Some(v))
            .collect()
    }

    #[test]
    fn real_roads_changes_only_our_options_and_builds_every_tracker() {
        let ours = [
            "relock_share",
            "curvature_prior_sd",
            "adjacent_lanes",
            "start_iterations",
            "valid_distance_m",
            "valid_support_frames",
            "paired_edges",
            "width_scaled_threshold",
            // lee-cpf's and adachi-mmpf's search for a lost boundary at new widths: ours.
            "side_search_share",
            // lee-cpf's smoother: the paper has one but gives no design; its noises are ours.
            "kalman_process_sd",
            // lee-cpf's, adachi-mmpf's and liu-ppf's validity after a loss: ours.
            "reacquire_near_m",
            // danescu-mono's validation: the paper rejects a lane "too wide" but names no
            // limit; ours.
            "width_range_m",
            // liu-ppf's top view: the paper names no range; ours.
            "top_view_resolved",
            // liu-ppf's estimate: the paper does not say how it reads it off; ours.
            "mode_candidates",
            // The boundaries moved onto the paint's centre after the estimate: ours.
            "snap_to_paint",
            // The snap following the paint round bends: ours.
            "snap_follows_bends",
            // A valid frame reported only with paint along an ego boundary: ours.
            "valid_needs_paint",
            // A frame the filter finds not valid reported valid with paint along its lane: ours.
            "valid_from_paint",
        ];
        let camera = default_camera(320, 240).unwrap().to_file();
        for id in TRACKER_IDS {
            let changed = changed(id);
            let paper_only = *id == "liu-ppf-nokernel";
            assert_eq!(changed.is_empty(), paper_only, "{id}: {changed:?}");
            for (key, _) in &changed {
                assert!(ours.contains(&key.as_str()), "{id}: {key} is the paper's");
            }
            for preset in [Preset::Paper, Preset::RealRoads] {
                let options = TrackerOptions::preset(id, preset).unwrap();
                let config = TrackerConfig {
                    camera: camera.clone(),
                    particles: None,
                    seed: 1,
                    options: Options::Typed(Box::new(options)),
                };
                create(id, &config).unwrap();
            }
        }
        // lee-cpf's smoother in real-roads: three times the defaults' process noise, ten
        // times on the width (index 2).
        let lee = |p| match TrackerOptions::preset("lee-cpf", p).unwrap() {
            TrackerOptions::LeeCpf(c) => c.kalman_process_sd,
            other => panic!("{other:?}"),
        };
        let pairs = lee(Preset::Paper).into_iter().zip(lee(Preset::RealRoads));
        for (i, (paper, roads)) in pairs.enumerate() {
            let times = if i == 2 { 10.0 } else { 3.0 };
            assert!(
                (roads - times * paper).abs() <= 1e-12 * roads,
                "{i}: {paper} {roads}"
            );
        }
        let json = |o: TrackerOptions| serde_json::to_value(o).unwrap();
        assert_eq!(
            json(TrackerOptions::preset("lee-cpf", Preset::Paper).unwrap()),
            json(TrackerOptions::defaults("lee-cpf").unwrap())
        );
    }

    #[test]
    fn names_round_trip_and_an_unknown_one_lists_them() {
        for name in PRESET_NAMES {
            name.parse::<Preset>().unwrap();
        }
        let e = "real".parse::<Preset>().unwrap_err().to_string();
        assert!(e.contains("paper, real-roads"), "{e}");
    }
}
