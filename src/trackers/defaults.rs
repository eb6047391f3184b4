//! Every option of a tracker with its default value: what a settings panel starts from, and
//! the documentation of the options in one machine-readable object.

use super::{Error, Preset, Result};
use serde_json::{Map, Value};

fn object(particles: usize, config: Value) -> Result<Value> {
    let mut map = Map::new();
    map.insert("particles".into(), Value::from(particles));
    match config {
        Value::Object(options) => map.extend(options),
        // Not shown: Value's Display (serde_json's JSON writer) costs the main wasm 6.1 kB
        // raw, 2.4 kB gzip -9 (2026-11-30).
        _ => {
            return Err(Error::Config(
                "tracker defaults are not an object".to_string(),
            ))
        }
    }
    Ok(Value::Object(map))
}

/// The options of tracker `id` with their defaults, `particles` included (the camera and the
/// seed are not tracker options). Passing them back unchanged builds the default tracker.
///
/// # Errors
/// [`Error::UnknownTracker`] for an id not in [`super::TRACKER_IDS`].
pub fn default_options(id: &str) -> Result<Value> {
    preset_options(id, Preset::Paper)
}

/// Every option of tracker `id` with its value in `preset`, `particles` included, as
/// [`default_options`] gives the defaults (the `paper` preset).
///
/// # Errors
/// [`Error::UnknownTracker`] for an id not in [`super::TRACKER_IDS`].
pub fn preset_options(id: &str, preset: Preset) -> Result<Value> {
    let entry = super::registry::entry(id)?;
    let config = serde_json::to_value(super::TrackerOptions::preset(id, preset)?)
        .map_err(|e| Error::Config(format!("{id} options: {e}")))?;
    object(entry.particles, config)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{default_camera, scenario, Eye, Scene};
    use crate::trackers::{create, TrackerConfig, TRACKER_IDS};

    #[test]
    fn the_defaults_build_the_default_tracker() {
        let camera = default_camera(320, 240).unwrap();
        let camera_json = serde_json::to_value(camera.to_file()).unwrap();
        let mut scene = Scene::new(scenario("highway-curve").unwrap(), camera, 1).unwrap();
        let (mut rgba, mut right) = (vec![0; 320 * 240 * 4], vec![0; 320 * 240 * 4]);
        scene.render(0, Eye::Left, &mut rgba, None).unwrap();
        scene.render(0, Eye::Right, &mut right, None).unwrap();
        for id in TRACKER_IDS {
            let defaults = default_options(id).unwrap();
            assert!(defaults["particles"].as_u64().unwrap() > 0, "{id}");
            let mut with = defaults.as_object().unwrap().clone();
            with.insert("camera".into(), camera_json.clone());
            let plain = serde_json::json!({ "camera": camera_json });
            let build = |v: &Value| {
                let c = TrackerConfig::from_json_str(&v.to_string()).unwrap();
                create(id, &c).unwrap_or_else(|e| panic!("{id}: {e}"))
            };
            let (mut a, mut b) = (build(&Value::Object(with)), build(&plain));
            if a.is_stereo() {
                a.set_right(&right, 320, 240).unwrap();
                b.set_right(&right, 320, 240).unwrap();
            }
            assert_eq!(
                a.step(&rgba, 320, 240).unwrap(),
                b.step(&rgba, 320, 240).unwrap(),
                "{id}"
            );
            assert_eq!(a.particles(), b.particles(), "{id}");
        }
        assert!(matches!(
            default_options("nope"),
            Err(Error::UnknownTracker { .. })
        ));
    }
}
