//! `reacquire_near_m` (ours, beyond the paper): after the lane was lost, markings that begin
//! only further ahead do not make it valid again; markings near the car do.

use super::tests::config;
use super::LeeTracker;
use crate::synth::{default_camera, scenario, Eye, Scene};

const W: usize = 320;
const H: usize = 240;

/// Every row nearer than `from_m` metres ahead painted with the grey of its own middle pixel
/// (the ego lane's asphalt): an unmarked stretch up to `from_m`.
fn unmarked_up_to(rgba: &mut [u8], from_m: f64) {
    let camera = default_camera(W, H).unwrap();
    let first = camera
        .road_to_pixel(from_m, 0.0)
        .map_or(0, |[_, y]| y.ceil().max(0.0) as usize);
    for row in rgba.chunks_exact_mut(W * 4).skip(first) {
        let middle: [u8; 4] = row[W / 2 * 4..W / 2 * 4 + 4].try_into().unwrap();
        for px in row.chunks_exact_mut(4) {
            px.copy_from_slice(&middle);
        }
    }
}

/// The validity of each frame, for the tracker with `extra` options, on `highway-straight`:
/// frames 0-39 as rendered, 40-44 with no marking at all, 45-54 with markings only from
/// `ahead_m` metres on, 55-79 as rendered; and `ahead_m`. Without `ahead_m` it is 3 m beyond
/// the reach the tracker accepts after the loss (its limit at frame 45: the dashed lines' gaps
/// it was tracked through).
fn validity(extra: &str, ahead_m: Option<f64>) -> (Vec<bool>, f64) {
    let mut scene = Scene::new(
        scenario("highway-straight").unwrap(),
        default_camera(W, H).unwrap(),
        1,
    )
    .unwrap();
    let mut tracker = LeeTracker::new(&config(extra)).unwrap();
    let near = tracker.measurement.near_positions()[0];
    let mut ahead = ahead_m.unwrap_or(f64::INFINITY);
    let mut rgba = vec![0; W * H * 4];
    let valid = (0..80)
        .map(|f| {
            scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            if f == 45 && ahead_m.is_none() {
                ahead = near + tracker.reacquire.limit() + 3.0;
            }
            match f {
                40..=44 => unmarked_up_to(&mut rgba, 1000.0),
                45..=54 => unmarked_up_to(&mut rgba, ahead),
                _ => {}
            }
            tracker.track(&rgba, W, H).unwrap().valid
        })
        .collect();
    (valid, ahead)
}

#[test]
fn markings_only_ahead_do_not_revalidate_a_lost_lane_and_near_ones_do() {
    let (rule, ahead) = validity(r#", "reacquire_near_m": 4.0"#, None);
    let (paper, _) = validity("", Some(ahead));
    assert!(
        ahead <= 17.0,
        "markings from {ahead} m leave too little of the 5-20 m near range"
    );
    for (name, v) in [("paper", &paper), ("rule", &rule)] {
        assert!(
            v[30..40].iter().all(|&x| x),
            "{name}: valid on the road {v:?}"
        );
        assert!(!v[44], "{name}: not valid with no marking {v:?}");
    }
    assert!(
        paper[45..55].iter().any(|&x| x),
        "the paper's rule takes the markings from {ahead} m as the lane: {paper:?}"
    );
    assert!(
        rule[45..55].iter().all(|&x| !x),
        "not valid on the markings from {ahead} m only: {rule:?}"
    );
    assert!(
        rule[60..80].iter().all(|&x| x),
        "valid again with the markings near: {rule:?}"
    );
}
