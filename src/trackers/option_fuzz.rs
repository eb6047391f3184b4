//! Property test of the option ranges: any value of any option either is refused with an
//! error naming an option, or builds a tracker whose first steps return.
//!
//! Each draw starts from a tracker's defaults and replaces one to three options (an entry of
//! an array, a field of a nested object, the particle count) by a value from a wide
//! distribution: the range's edges and just beyond, zero, subnormals, 1e308, huge integers,
//! negatives, fractions for counts, `null` (what NaN and infinities become in JSON) and
//! log-uniform values inside the range. Work is bounded by the draw count, a small frame and
//! three steps; a hang would stop the test, a panic fails it with the configuration.

use super::{create, default_options, option_ranges, TrackerConfig, TRACKER_IDS};
use crate::filter::Rng;
use crate::synth::{default_camera, scenario, Eye, Scene};
use serde_json::{json, Value};

const DRAWS_PER_TRACKER: usize = 300;
const W: usize = 96;
const H: usize = 72;

fn wild(rng: &mut Rng, min: f64, max: f64) -> Value {
    let log_uniform = |rng: &mut Rng| {
        let (lo, hi) = (min.abs().max(1e-9), max.abs().max(1e-9));
        let v = crate::math::exp(
            crate::math::ln(lo) + rng.uniform() * (crate::math::ln(hi) - crate::math::ln(lo)),
        );
        v.clamp(min, max)
    };
    let v = match rng.below(16) {
        0 => min,
        1 => max,
        2 => min - (max - min).abs() * 0.01 - 1e-9,
        3 => max * 1.01 + 1e-9,
        4 => 0.0,
        5 => 5e-324,
        6 => 1e308,
        7 => -1e308,
        8 => -1.0,
        9 => return json!(u64::MAX),
        10 => return json!(1u64 << 31),
        11 => return Value::Null,
        12 => min + 0.5,
        _ => log_uniform(rng),
    };
    serde_json::Number::from_f64(v).map_or(Value::Null, Value::Number)
}

/// Replaces the value at `path` (`a.b`, `a[2]`; a whole array: one random entry) by `value`.
fn set(root: &mut Value, path: &str, value: Value, rng: &mut Rng) {
    let mut node = root;
    for part in path.split('.') {
        let (key, index) = match part.split_once('[') {
            Some((key, rest)) => (key, rest.trim_end_matches(']').parse::<usize>().ok()),
            None => (part, None),
        };
        let Some(next) = node.get_mut(key) else {
            return;
        };
        node = next;
        if let Some(k) = index {
            let Some(next) = node.get_mut(k) else { return };
            node = next;
        }
    }
    // A whole array (or an array of arrays): one entry of it.
    while let Value::Array(items) = node {
        if items.is_empty() {
            return;
        }
        let k = rng.below(items.len());
        node = &mut items[k];
    }
    *node = value;
}

#[test]
fn every_option_drawn_wild_is_refused_or_steps() {
    let camera = default_camera(W, H).unwrap();
    let camera_json = serde_json::to_value(camera.to_file()).unwrap();
    let mut scene = Scene::new(scenario("highway-curve").unwrap(), camera, 3).unwrap();
    let (mut left, mut right) = (vec![0; W * H * 4], vec![0; W * H * 4]);
    scene.render(0, Eye::Left, &mut left, None).unwrap();
    scene.render(0, Eye::Right, &mut right, None).unwrap();
    let mut rng = Rng::new(19);
    for id in TRACKER_IDS {
        let ranges = option_ranges(id).unwrap();
        let (mut built, mut refused) = (0, 0);
        for draw in 0..DRAWS_PER_TRACKER {
            let mut options = default_options(id).unwrap();
            options["particles"] = json!(64);
            for _ in 0..1 + rng.below(3) {
                if rng.below(8) == 0 {
                    options["particles"] = wild(&mut rng, 1.0, 200_000.0);
                } else {
                    let r = ranges[rng.below(ranges.len())];
                    let v = wild(&mut rng, r.min, r.max);
                    set(&mut options, r.option, v, &mut rng);
                }
            }
            if options["particles"].as_u64().is_some_and(|n| n > 2000) {
                // Valid but slow in a test build: the budget is the other options'.
                options["particles"] = json!(2000);
            }
            options["camera"] = camera_json.clone();
            let text = options.to_string();
            let outcome = std::panic::catch_unwind(|| {
                let config = match TrackerConfig::from_json_str(&text) {
                    Ok(c) => c,
                    Err(e) => return Err(e.to_string()),
                };
                let mut t = create(id, &config).map_err(|e| e.to_string())?;
                for _ in 0..3 {
                    if t.is_stereo() {
                        t.set_right(&right, W, H).unwrap();
                    }
                    let e = t.step(&left, W, H).unwrap();
                    for b in &e.boundaries {
                        assert!(
                            b.points.iter().flatten().all(|v| v.is_finite()),
                            "non-finite boundary point"
                        );
                    }
                }
                Ok(())
            });
            match outcome {
                Ok(Ok(())) => built += 1,
                Ok(Err(e)) => {
                    // A clean error names what was wrong.
                    assert!(
                        e.contains('`') || e.contains("options:") || e.contains("invalid"),
                        "{id} draw {draw}: unclear error {e}"
                    );
                    refused += 1;
                }
                Err(_) => panic!("{id} draw {draw} panicked with options {text}"),
            }
        }
        // Both outcomes happen: the distribution reaches inside and outside the ranges.
        assert!(
            built >= 10 && refused >= 10,
            "{id}: {built} built, {refused} refused"
        );
    }
}
