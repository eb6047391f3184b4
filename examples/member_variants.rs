//! Renders one drawn family member with some of its settings changed and runs a tracker on
//! it, to tell which property of a member a tracker's error comes from (RESULTS, liu-ppf on
//! curves, at night; the variants' figures: CHANGELOG, 2026-11-28). Prints the offset RMSE and
//! width MAE over the valid frames.
//! `cargo run --release --example member_variants -- FAMILY SEED FRAMES CHANGES [TRACKER_SEED]
//! [OPTIONS] [TRACKER]` at 320x240 with the member's own camera; CHANGES joins with `+` any of
//! `as-is`, `day`, `night`, `noise:<grey levels>`, `width:<lane m>`, `hfov:<deg>`,
//! `pitch:<deg>`, `height:<m>`, `straight` (every segment's curvature 0); OPTIONS is JSON
//! text added to the tracker config (e.g. `, "intensity_variance": 0.05`); TRACKER defaults
//! to `liu-ppf`. The true ego motion is not given (trackers that use it run without).

use lanepf::synth::{draw_scenario, Eye, Scene};
use lanepf::trackers::{create, TrackerConfig};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let a: Vec<String> = std::env::args().collect();
    if a.len() < 5 {
        return Err(
            "usage: member_variants FAMILY SEED FRAMES CHANGES [TRACKER_SEED] [OPTIONS] [TRACKER]"
                .into(),
        );
    }
    let (family, seed, frames, changes) = (&a[1], a[2].parse()?, a[3].parse()?, &a[4]);
    let tracker_seed: u64 = a.get(5).map_or(Ok(1), |s| s.parse())?;
    let options = a.get(6).cloned().unwrap_or_default();
    let tracker = a.get(7).map_or("liu-ppf", String::as_str);
    let mut m = draw_scenario(family, seed)?;
    m.config.frames = frames;
    for change in changes.split('+') {
        let (key, value) = change.split_once(':').unwrap_or((change, ""));
        match key {
            "as-is" => {}
            "day" => m.config.appearance.night = false,
            "night" => m.config.appearance.night = true,
            "noise" => m.config.appearance.noise = value.parse()?,
            "width" => m.config.road.lane_width_m = value.parse()?,
            "hfov" => m.mount.hfov_deg = value.parse()?,
            "pitch" => m.mount.pitch_deg = value.parse()?,
            "height" => m.mount.height_m = value.parse()?,
            "straight" => {
                for s in &mut m.config.road.segments {
                    s.curvature = 0.0;
                    s.curvature_rate = 0.0;
                }
            }
            _ => return Err(format!("unknown change `{change}`").into()),
        }
    }
    let camera = m.mount.camera(320, 240)?;
    let mut scene = Scene::new(m.config.clone(), camera.clone(), seed)?;
    let cam = serde_json::to_string(&camera.to_file())?;
    let config = TrackerConfig::from_json_str(&format!(
        r#"{{"camera": {cam}, "seed": {tracker_seed} {options}}}"#
    ))?;
    let mut t = create(tracker, &config)?;
    let mut rgba = vec![0u8; 320 * 240 * 4];
    let (mut offset2, mut width, mut valid) = (0.0, 0.0, 0u32);
    for f in 0..frames {
        scene.render(f, Eye::Left, &mut rgba, None)?;
        let e = t.step(&rgba, 320, 240)?;
        let truth = lanepf::trackers::scene_truth(&scene, f);
        if e.valid {
            valid += 1;
            offset2 += (e.lateral_offset_m - truth.lateral_offset_m).powi(2);
            width += (e.lane_width_m - truth.lane_width_m).abs();
        }
    }
    let n = f64::from(valid.max(1));
    println!(
        "{family} {seed} {changes} {tracker} seed {tracker_seed}: valid {valid}/{frames}, offset RMSE \
         {:.1} cm, width MAE {:.1} cm",
        (offset2 / n).sqrt() * 100.0,
        width / n * 100.0
    );
    Ok(())
}
