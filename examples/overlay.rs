//! Draws tracker output on its frames, to look at a run by eye: every boundary of each
//! prediction (the `lanepf track` JSON lines) as a polyline coloured by role (ego-left red,
//! ego-right blue, adjacent ones yellow), thicker when the frame is valid.
//! `cargo run --release --example overlay -- FRAMES_DIR PREDICTIONS.jsonl OUT_DIR [EVERY]`
//! writes OUT_DIR/<frame>.png for every EVERY-th prediction (default 1); with a fifth argument,
//! a Caltech `labels.json` or a CULane folder of `.lines.txt` files, each frame's labelled
//! lanes are drawn in green under the prediction (Caltech: thick for the two ego lanes of Aly's
//! rule, thin for the others; CULane: all thick). Join the frames with
//! `ffmpeg -framerate 25 -pattern_type glob -i 'OUT_DIR/*.png' overlay.mp4`.

use lanepf::eval::caltech::{bezier_polyline, ego_lanes};
use lanepf::eval::{caltech, culane, read_predictions};
use lanepf::image::{read_rgba, write_rgba_png};
use lanepf::lane::Role;
use std::collections::HashMap;
use std::path::Path;
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

/// Each frame's labelled lanes: the points, and whether the lane is drawn thick.
type Labels = HashMap<String, Vec<(Vec<[f64; 2]>, bool)>>;

/// Reads a CULane folder (or `.lines.txt` file), else a Caltech `labels.json`.
fn read_labels(path: &Path) -> lanepf::Result<Labels> {
    if path.is_dir() || path.to_string_lossy().ends_with(".lines.txt") {
        let frames = culane::read_labels(path)?;
        return Ok(frames
            .into_iter()
            .map(|f| (f.frame, f.lanes.into_iter().map(|l| (l, true)).collect()))
            .collect());
    }
    let labels = caltech::read_labels(path)?;
    Ok(labels
        .frames
        .iter()
        .map(|f| {
            let ego = ego_lanes(&f.lanes, labels.image_size);
            let lanes =
                f.lanes.iter().enumerate().map(|(i, lane)| {
                    (bezier_polyline(&lane.bezier_xy, 30), ego.contains(&Some(i)))
                });
            (f.frame.clone(), lanes.collect())
        })
        .collect())
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
            "usage: overlay FRAMES_DIR PREDICTIONS.jsonl OUT_DIR [EVERY] [CALTECH_LABELS.json | \
             CULANE_DIR]"
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
        let labelled = labels.as_ref().and_then(|l| l.get(&p.frame));
        for (points, thick) in labelled.into_iter().flatten() {
            let r = if *thick { 2 } else { 0 };
            polyline(&mut frame.data, w, h, points, r, [40, 220, 60]);
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
