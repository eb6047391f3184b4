//! Draws tracker output on its frames, to look at a run by eye: every boundary of each
//! prediction (the `lanepf track` JSON lines) as a polyline coloured by role (ego-left red,
//! ego-right blue, adjacent ones yellow), thicker when the frame is valid.
//! `cargo run --release --example overlay -- FRAMES_DIR PREDICTIONS.jsonl OUT_DIR [EVERY]`
//! writes OUT_DIR/<frame>.png for every EVERY-th prediction (default 1); with a fifth argument,
//! a Caltech `labels.json`, each frame's labelled lanes are drawn in green under the prediction
//! (thick for the two ego lanes of Aly's rule). Join the frames with
//! `ffmpeg -framerate 25 -pattern_type glob -i 'OUT_DIR/*.png' overlay.mp4`.

use lanepf::eval::caltech::{bezier_polyline, ego_lanes, read_labels};
use lanepf::eval::read_predictions;
use lanepf::image::{read_rgba, write_rgba_png};
use lanepf::lane::Role;
use std::path::PathBuf;

fn plot(rgba: &mut [u8], w: usize, h: usize, x: f64, y: f64, r: usize, c: [u8; 3]) {
    let (x, y) = (x.round() as i64, y.round() as i64);
    let r = r as i64;
    for dy in -r..=r {
        for dx in -r..=r {
            let (px, py) = (x + dx, y + dy);
            if px >= 0 && py >= 0 && (px as usize) < w && (py as usize) < h {
                let i = (py as usize * w + px as usize) * 4;
                rgba[i..i + 3].copy_from_slice(&c);
            }
        }
    }
}

/// Draws a polyline with `plot`'s square pen of radius `r`.
fn polyline(rgba: &mut [u8], w: usize, h: usize, points: &[[f64; 2]], r: usize, c: [u8; 3]) {
    for seg in points.windows(2) {
        let ([x0, y0], [x1, y1]) = (seg[0], seg[1]);
        let n = ((x1 - x0).abs().max((y1 - y0).abs()).ceil() as usize).max(1);
        for k in 0..=n {
            let t = k as f64 / n as f64;
            plot(rgba, w, h, x0 + t * (x1 - x0), y0 + t * (y1 - y0), r, c);
        }
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 4 {
        return Err(
            "usage: overlay FRAMES_DIR PREDICTIONS.jsonl OUT_DIR [EVERY] [CALTECH_LABELS.json]"
                .into(),
        );
    }
    let frames = PathBuf::from(&args[1]);
    let predictions = read_predictions(&PathBuf::from(&args[2]))?;
    let out = PathBuf::from(&args[3]);
    let every: usize = args.get(4).map_or(Ok(1), |s| s.parse())?;
    let labels = args
        .get(5)
        .map(|p| read_labels(&PathBuf::from(p)))
        .transpose()?;
    std::fs::create_dir_all(&out)?;
    for p in predictions.iter().step_by(every.max(1)) {
        let mut frame = read_rgba(&frames.join(&p.frame))?;
        let (w, h) = (frame.width, frame.height);
        let labelled = labels
            .as_ref()
            .and_then(|l| l.frames.iter().find(|f| f.frame == p.frame).map(|f| (l, f)));
        if let Some((l, f)) = labelled {
            let ego = ego_lanes(&f.lanes, l.image_size);
            for (i, lane) in f.lanes.iter().enumerate() {
                let r = if ego.contains(&Some(i)) { 2 } else { 0 };
                let points = bezier_polyline(&lane.bezier_xy, 30);
                polyline(&mut frame.data, w, h, &points, r, [40, 220, 60]);
            }
        }
        for b in &p.boundaries {
            let colour = match b.role {
                Role::EgoLeft => [230, 40, 40],
                Role::EgoRight => [40, 90, 240],
                _ => [240, 220, 40],
            };
            // Thinner over labels, so the green stays visible beside the boundary.
            let r = match (p.valid, labelled.is_some()) {
                (false, _) => 0,
                (true, true) => 1,
                (true, false) => 2,
            };
            polyline(&mut frame.data, w, h, &b.points, r, colour);
        }
        let name = std::path::Path::new(&p.frame).with_extension("png");
        write_rgba_png(&out.join(name), &frame.data, w, h)?;
    }
    Ok(())
}
