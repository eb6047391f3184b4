//! `valid_support_frames` (ours) against the single-frame validity, on drawn members of
//! `highway-straight` (dashed lines; 320x240, 60 frames, tracker seed 3): the option changes
//! only the validity flag, never the lanes, and it calls more frames valid, not fewer.

use super::*;
use crate::synth::Eye;
use crate::trackers::fresh_roads::{config_for, member_scene};

/// Every frame's estimate of danescu-mono on member `seed` with the options `extra`.
fn run(seed: u64, extra: &str) -> Vec<DanescuEstimate> {
    let (_, mut scene) = member_scene("highway-straight", seed, 320, 240, 60);
    let config = config_for(&scene, &format!(r#", "seed": 3 {extra}"#));
    let mut tracker = DanescuTracker::new(&config, ID_MONO).unwrap();
    let mut rgba = vec![0; 320 * 240 * 4];
    (0..60)
        .map(|i| {
            scene.render(i, Eye::Left, &mut rgba, None).unwrap();
            tracker.track(&rgba, 320, 240).unwrap()
        })
        .collect()
}

#[test]
fn remembered_support_changes_only_validity_and_never_loses_a_frame() {
    let mut gained = 0;
    for seed in 1..=4 {
        let one = run(seed, r#", "start_iterations": 10"#);
        let five = run(
            seed,
            r#", "start_iterations": 10, "valid_support_frames": 5"#,
        );
        for (i, (a, b)) in one.iter().zip(&five).enumerate() {
            assert_eq!(a.lane, b.lane, "seed {seed} frame {i}: the lanes differ");
            assert_eq!(a.support, b.support, "seed {seed} frame {i}");
            assert!(
                b.valid || !a.valid,
                "seed {seed} frame {i}: valid with one frame, not with five"
            );
            gained += usize::from(b.valid && !a.valid);
        }
        let count = |v: &[DanescuEstimate]| v.iter().filter(|e| e.valid).count();
        println!(
            "seed {seed}: valid {} of {} with one frame, {} with five",
            count(&one),
            one.len(),
            count(&five)
        );
    }
    // Shows the option does something on dashed lines at all.
    assert!(gained > 0, "no frame gained");
}
