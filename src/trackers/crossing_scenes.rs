//! Scenes for the "no lane" tests (tests only): a synthetic scenario, optionally with every
//! marking removed over a stretch (an unmarked crossing), run frame by frame through a
//! tracker, and its validity counted on the unmarked and the marked road.

use crate::synth::{default_camera, scenario, Eye, Scene, Wear};

/// The frame size of these scenes (the tests' default camera, `default_camera(320, 240)`).
pub(crate) const SIZE: (usize, usize) = (320, 240);

/// Renders `frames` frames of scenario `name` (scene seed `seed`, [`SIZE`]), every marking
/// removed over `crossing` (s from, to; metres) if given, and hands each to `valid` (RGBA,
/// width, height), which tracks it and says whether the estimate was valid: each frame's
/// distance s along the road and that answer.
pub(crate) fn validity_along_road(
    name: &str,
    seed: u64,
    frames: u32,
    crossing: Option<[f64; 2]>,
    mut valid: impl FnMut(&[u8], usize, usize) -> bool,
) -> Vec<(f64, bool)> {
    let (w, h) = SIZE;
    let mut config = scenario(name).unwrap();
    config.frames = frames;
    if let Some([from_s, to_s]) = crossing {
        config.markings.wear.push(Wear {
            from_s,
            to_s,
            boundary: None,
            visibility: 0.0,
        });
    }
    let mut scene = Scene::new(config, default_camera(w, h).unwrap(), seed).unwrap();
    let mut rgba = vec![0; w * h * 4];
    (0..frames)
        .map(|f| {
            let s = scene.render(f, Eye::Left, &mut rgba, None).unwrap().s;
            (s, valid(&rgba, w, h))
        })
        .collect()
}

/// Over a run's frames (s, valid) with `crossing` unmarked: (frames whose next `ahead_m`
/// metres lie in the crossing, how many of them valid; frames whose next 30 m are marked after
/// the first second, how many of them valid).
pub(crate) fn crossing_counts(
    frames: &[(f64, bool)],
    crossing: [f64; 2],
    ahead_m: f64,
) -> ((usize, usize), (usize, usize)) {
    let (mut unmarked, mut marked) = ((0, 0), (0, 0));
    for (f, &(s, valid)) in frames.iter().enumerate() {
        if s >= crossing[0] && s + ahead_m <= crossing[1] {
            unmarked.0 += 1;
            unmarked.1 += usize::from(valid);
        } else if (s + 30.0 < crossing[0] || s > crossing[1]) && f >= 30 {
            marked.0 += 1;
            marked.1 += usize::from(valid);
        }
    }
    (unmarked, marked)
}
