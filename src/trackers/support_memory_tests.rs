//! `valid_support_frames` (ours) against the single-frame validity, for every tracker that has
//! it, on drawn members of `highway-straight` (dashed lines; 320x240, 60 frames, tracker seed
//! 3): the option changes only the validity flag, never the ego lane or its support, and it
//! calls more frames valid, not fewer.

use super::fresh_roads::{config_for, member_scene};
use super::registry::create;
use crate::lane::{LaneEstimate, Role};
use crate::synth::Eye;

/// The trackers with `valid_support_frames` and the options each runs with: adachi-mmpf's
/// threshold raised from 0.08 and liu-ppf's from 0.15 (where every frame of these members is
/// valid on one frame's support) to where a dashed line's phase matters; danescu-mono's start
/// rounds (the paper's start leaves the first frames' cloud in clusters, not valid).
const TRACKERS: [(&str, &str); 4] = [
    ("adachi-mmpf", r#", "valid_support": 0.3"#),
    ("danescu-mono", r#", "start_iterations": 10"#),
    ("lee-cpf", ""),
    ("liu-ppf", r#", "valid_fraction": 0.3"#),
];

/// Every frame's estimate of tracker `id` on member `seed` with the options `extra`.
fn run(id: &str, seed: u64, extra: &str) -> Vec<LaneEstimate> {
    let (_, mut scene) = member_scene("highway-straight", seed, 320, 240, 60);
    let config = config_for(&scene, &format!(r#", "seed": 3 {extra}"#));
    let mut tracker = create(id, &config).unwrap();
    let mut rgba = vec![0; 320 * 240 * 4];
    (0..60)
        .map(|i| {
            scene.render(i, Eye::Left, &mut rgba, None).unwrap();
            tracker.step(&rgba, 320, 240).unwrap()
        })
        .collect()
}

/// The ego boundaries' points (the adjacent lanes are drawn only when valid).
fn ego(e: &LaneEstimate) -> Vec<&Vec<[f64; 2]>> {
    e.boundaries
        .iter()
        .filter(|b| matches!(b.role, Role::EgoLeft | Role::EgoRight))
        .map(|b| &b.points)
        .collect()
}

#[test]
fn remembered_support_changes_only_validity_and_never_loses_a_frame() {
    for (id, start) in TRACKERS {
        let mut gained = 0;
        for seed in 1..=4 {
            let one = run(id, seed, start);
            let five = run(id, seed, &format!(r#"{start}, "valid_support_frames": 5"#));
            for (i, (a, b)) in one.iter().zip(&five).enumerate() {
                let at = format!("{id} seed {seed} frame {i}");
                assert_eq!(ego(a), ego(b), "{at}: the lanes differ");
                assert_eq!(a.state, b.state, "{at}: the state (support) differs");
                assert!(b.valid || !a.valid, "{at}: valid with one frame, not five");
                gained += usize::from(b.valid && !a.valid);
            }
            let count = |v: &[LaneEstimate]| v.iter().filter(|e| e.valid).count();
            println!(
                "{id} seed {seed}: valid {} of {} with one frame, {} with five",
                count(&one),
                one.len(),
                count(&five)
            );
        }
        // Shows the option does something on dashed lines at all.
        assert!(gained > 0, "{id}: no frame gained");
    }
}

/// `last` is the support pushed last, through the ring's wrap, and zero when empty.
#[test]
fn last_is_the_latest_push_and_zero_after_a_clear() {
    use super::support_memory::SupportMemory;
    let mut m = SupportMemory::new(2);
    assert_eq!(m.last(), [0.0; 2]);
    for s in [[0.1, 0.2], [0.3, 0.4], [0.5, 0.6]] {
        m.push(s);
        assert_eq!(m.last(), s);
    }
    m.clear();
    assert_eq!(m.last(), [0.0; 2]);
}
