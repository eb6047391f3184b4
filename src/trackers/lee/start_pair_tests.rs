//! `start_pair_share` (ours: the paper does not say how the filter starts) against the
//! uniform start, on drawn members of the scenario families (320x240, tracker seed 1).

use crate::trackers::fresh_roads::member_scores;

/// lee-cpf's detection rate (share of valid frames) on each member of `scenario` with seeds
/// `seeds` over its first `frames` frames, starting with `share` of the particles around the
/// first frame's detected ego pair.
fn detection_rates(
    scenario: &str,
    seeds: std::ops::RangeInclusive<u64>,
    frames: u32,
    share: f64,
) -> Vec<f64> {
    let option = ("start_pair_share", serde_json::json!(share));
    member_scores("lee-cpf", scenario, seeds, frames, option)
        .iter()
        .map(|score| score.report.params.detection_rate.unwrap_or(0.0))
        .collect()
}

/// A uniform start leaves the cloud, on some roads, at the width limit with one boundary on
/// a marking and the other on bare road, and it stays there (never valid); drawing half of
/// the start around the detected pair finds most of those lanes. Not all, and not a
/// guarantee: where eq. 33 itself prefers such a lane (a solid line a lane beyond two dashed
/// ones) the uniform half can still find it, and which start does depends on the draws
/// (measured 2026-11-26: `worn-markings` seeds 6 and 13 found, seed 14 lost).
#[test]
fn the_start_from_the_detected_pair_finds_lanes_the_uniform_start_misses() {
    // Members of different families with one seed share the camera and the start of the
    // road: one family, many seeds.
    let uniform = detection_rates("worn-markings", 1..=16, 30, 0.0);
    let pairs = detection_rates("worn-markings", 1..=16, 30, 0.5);
    println!("uniform {uniform:.2?}\n  pairs {pairs:.2?}");
    let locked = |rates: &[f64]| rates.iter().filter(|&&r| r < 0.5).count();
    let mean = |rates: &[f64]| rates.iter().sum::<f64>() / rates.len() as f64;
    assert!(
        locked(&uniform) >= 2,
        "the uniform start's lock-in is gone: {uniform:.2?}"
    );
    assert!(
        locked(&pairs) < locked(&uniform) && mean(&pairs) > mean(&uniform),
        "{pairs:.2?} against {uniform:.2?}"
    );
}

/// `start_pair_share` 0 is the start as it was before the option: the same bits as the
/// cross-target golden had then (`tests::same_result_as_the_browser_build`'s run).
#[test]
fn share_zero_is_the_uniform_start_bit_for_bit() {
    let out = super::tests::run("highway-curve", 5, r#", "start_pair_share": 0"#);
    let offset = -out[4].1.state.y0;
    assert_eq!(offset.to_bits(), 0xbfac_3e05_c519_13f4, "{offset}");
}

/// The default start needs the line detector, which needs frames of at least 32x16: on a
/// smaller camera the tracker still builds and starts uniformly; asking for the detector by
/// an option (`relock_share`) is the error it always was.
#[test]
fn a_camera_too_small_for_the_detector_starts_uniformly() {
    use crate::camera::CameraFile;
    use crate::trackers::{create, TrackerConfig};
    let camera = CameraFile {
        pitch_deg: 4.0,
        ..CameraFile::pinhole(24, 16, 20.0)
    };
    let config = |extra: &str| {
        let cam = serde_json::to_string(&camera).unwrap();
        TrackerConfig::from_json_str(&format!(r#"{{"camera": {cam} {extra}}}"#)).unwrap()
    };
    let mut tracker = create("lee-cpf", &config("")).unwrap();
    tracker.step(&vec![90; 24 * 16 * 4], 24, 16).unwrap();
    let err = create("lee-cpf", &config(r#", "relock_share": 0.05"#))
        .err()
        .expect("the detector is refused")
        .to_string();
    assert!(err.contains("32x16"), "{err}");
}
