//! Draws what the calibrator sees on frames, for checking by eye: every line found (grey), the
//! ego boundaries (green when the frame was used, red otherwise) and the vanishing point.
//! `cargo run --release --example calibration_overlay -- FRAMES_DIR OUT_DIR [EVERY] [intrinsics.json]`
//! writes OUT_DIR/NNNNN.png for every EVERY-th frame (default 25) and prints one line a frame.

use lanepf::calib::{Calibrator, CalibratorConfig};
use lanepf::camera::CameraFile;
use lanepf::image::{read_rgba, write_rgba_png};
use std::path::Path;

fn config() -> CalibratorConfig {
    let mut c = CalibratorConfig::default();
    if let Some(b) = std::env::var("BEND").ok().and_then(|s| s.parse().ok()) {
        c.max_bend_px = b;
    }
    if let Some(k) = std::env::var("STABLE").ok().and_then(|s| s.parse().ok()) {
        c.stable_frames = k;
    }
    c
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (Some(dir), Some(out)) = (args.get(1), args.get(2)) else {
        return Err(
            "usage: calibration_overlay FRAMES_DIR OUT_DIR [EVERY] [intrinsics.json]".into(),
        );
    };
    let every: usize = args.get(3).map_or(Ok(25), |s| s.parse())?;
    let intrinsics = args
        .get(4)
        .map(|p| CameraFile::read(Path::new(p)))
        .transpose()?;
    std::fs::create_dir_all(out)?;
    let mut files: Vec<_> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "png" || x == "jpg"))
        .collect();
    files.sort();
    let mut cal: Option<Calibrator> = None;
    let mut feed_ms = Vec::new();
    for (i, path) in files.iter().enumerate() {
        let mut f = read_rgba(path)?;
        let c = match &mut cal {
            Some(c) => c,
            None => cal.insert(Calibrator::new(
                f.width,
                f.height,
                intrinsics.as_ref(),
                config(),
            )?),
        };
        let t = std::time::Instant::now();
        let obs = c.feed_rgba(&f.data, f.width, f.height)?.clone();
        feed_ms.push(t.elapsed().as_secs_f64() * 1e3);
        let est = c.estimate();
        println!(
            "{i:5} lines {} ego {:?} vp {:?} straight {} stable {} used {} bends {:?} | est {:?}",
            obs.lines.len(),
            obs.ego,
            obs.vanishing_point.map(|p| [p[0].round(), p[1].round()]),
            obs.straight,
            obs.stable,
            obs.used,
            obs.ego.map(|[l, r]| [
                (obs.lines[l].bend * 10.0).round() / 10.0,
                (obs.lines[r].bend * 10.0).round() / 10.0
            ]),
            est.as_ref().map(|e| (
                (e.camera.pitch_deg * 100.0).round() / 100.0,
                (e.camera.yaw_deg * 100.0).round() / 100.0,
                (e.camera.height_m * 100.0).round() / 100.0,
                (e.confidence * 100.0).round() / 100.0,
                e.frames_used
            ))
        );
        if i % every != 0 {
            continue;
        }
        if std::env::var("LINES").is_ok() {
            for l in &obs.lines {
                println!("  line x_ref {:.1} y_ref {:.1} slope {:.3} support {} rows {:.0}-{:.0} bend {:.2}", l.x_ref, l.y_ref, l.slope, l.support, l.y_top, l.y_bottom, l.bend);
            }
        }
        let (w, h) = (f.width, f.height);
        let mut put = |x: f64, y: f64, rgb: [u8; 3]| {
            if x >= 0.0 && y >= 0.0 && (x as usize) < w && (y as usize) < h {
                let o = (y as usize * w + x as usize) * 4;
                f.data[o..o + 3].copy_from_slice(&rgb);
            }
        };
        let marks: Vec<[f64; 2]> = c.marking_pixels().collect();
        for [x, y] in marks {
            put(x, y, [255, 0, 255]);
        }
        for (k, l) in obs.lines.iter().enumerate() {
            let ego = obs.ego.is_some_and(|e| e.contains(&k));
            let rgb = match (ego, obs.used) {
                (false, _) => [160, 160, 255],
                (true, true) => [0, 255, 0],
                (true, false) => [255, 0, 0],
            };
            let mut y = l.y_top;
            while y <= l.y_bottom {
                put(l.x_at(y), y, rgb);
                put(l.x_at(y) + 1.0, y, rgb);
                y += 0.5;
            }
        }
        if let Some([u, v]) = obs.vanishing_point {
            for d in -6..=6 {
                put(u + d as f64, v, [255, 255, 0]);
                put(u, v + d as f64, [255, 255, 0]);
            }
        }
        write_rgba_png(&Path::new(out).join(format!("{i:05}.png")), &f.data, w, h)?;
    }
    feed_ms.sort_by(f64::total_cmp);
    if let Some(median) = feed_ms.get(feed_ms.len() / 2) {
        eprintln!(
            "calibrator: median {median:.2} ms a frame over {} frames",
            feed_ms.len()
        );
    }
    Ok(())
}
