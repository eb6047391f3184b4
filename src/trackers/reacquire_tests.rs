//! The scene every tracker with `reacquire_near_m` is tested on: a highway whose markings
//! vanish, come back from some metres ahead only, then near the car again.

use crate::synth::{default_camera, scenario, Eye, Scene};

/// Frame size of the scene.
pub(crate) const W: usize = 320;
/// Frame size of the scene.
pub(crate) const H: usize = 240;

/// What the scene needs of a tracker.
pub(crate) trait Reacquiring {
    /// Tracks one frame; whether its estimate is valid.
    fn valid_on(&mut self, rgba: &[u8]) -> bool;
    /// The road distance up to which markings are too near to be "only ahead": the nearest
    /// distance the tracker measures plus the reach it accepts after a loss.
    fn accepted_m(&self) -> f64;
}

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

/// The validity of each frame on `highway-straight` through the default camera: frames 0-39 as
/// rendered, 40-44 with no marking at all, 45-54 with markings only from `ahead_m` metres on,
/// 55-79 as rendered; and `ahead_m`. Without `ahead_m` it is 3 m beyond what the tracker
/// accepts at frame 45.
pub(crate) fn validity(tracker: &mut impl Reacquiring, ahead_m: Option<f64>) -> (Vec<bool>, f64) {
    let mut scene = Scene::new(
        scenario("highway-straight").unwrap(),
        default_camera(W, H).unwrap(),
        1,
    )
    .unwrap();
    let mut ahead = ahead_m.unwrap_or(f64::INFINITY);
    let mut rgba = vec![0; W * H * 4];
    let valid = (0..80)
        .map(|f| {
            scene.render(f, Eye::Left, &mut rgba, None).unwrap();
            if f == 45 && ahead_m.is_none() {
                ahead = tracker.accepted_m() + 3.0;
            }
            match f {
                40..=44 => unmarked_up_to(&mut rgba, 1000.0),
                45..=54 => unmarked_up_to(&mut rgba, ahead),
                _ => {}
            }
            tracker.valid_on(&rgba)
        })
        .collect();
    (valid, ahead)
}

/// The rule against the paper's validity on the scene: both valid on the road and not without
/// markings; the paper's takes the markings ahead as the lane, the rule does not; the rule is
/// valid again once the markings are near.
pub(crate) fn check(rule: &mut impl Reacquiring, paper: &mut impl Reacquiring, max_ahead_m: f64) {
    let (rule, ahead) = validity(rule, None);
    let (paper, _) = validity(paper, Some(ahead));
    assert!(
        ahead <= max_ahead_m,
        "markings from {ahead} m leave too little of the measured range"
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
