//! Draws tracker output on its frames, to look at a run by eye: every boundary of each
//! prediction (the `lanepf track` JSON lines) as a polyline coloured by role (ego-left red,
//! ego-right blue, adjacent ones yellow), thicker when the frame is valid.
//! `cargo run --release --example overlay -- FRAMES_DIR PREDICTIONS.jsonl OUT_DIR [EVERY]`
//! writes OUT_DIR/<frame>.png for every EVERY-th prediction (default 1); join them with
//! `ffmpeg -framerate 25 -pattern_type glob -i 'OUT_DIR/*.png' overlay.mp4`.

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

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 4 {
        return Err("usage: overlay FRAMES_DIR PREDICTIONS.jsonl OUT_DIR [EVERY]".into());
    }
    let frames = PathBuf::from(&args[1]);
    let predictions = read_predictions(&PathBuf::from(&args[2]))?;
    let out = PathBuf::from(&args[3]);
    let every: usize = args.get(4).map_or(Ok(1), |s| s.parse())?;
    std::fs::create_dir_all(&out)?;
    for p in predictions.iter().step_by(every.max(1)) {
        let mut frame = read_rgba(&frames.join(&p.frame))?;
        let (w, h) = (frame.width, frame.height);
        for b in &p.boundaries {
            let colour = match b.role {
                Role::EgoLeft => [230, 40, 40],
                Role::EgoRight => [40, 90, 240],
                _ => [240, 220, 40],
            };
            let r = if p.valid { 2 } else { 0 };
            for seg in b.points.windows(2) {
                let ([x0, y0], [x1, y1]) = (seg[0], seg[1]);
                let n = ((x1 - x0).abs().max((y1 - y0).abs()).ceil() as usize).max(1);
                for k in 0..=n {
                    let t = k as f64 / n as f64;
                    plot(
                        &mut frame.data,
                        w,
                        h,
                        x0 + t * (x1 - x0),
                        y0 + t * (y1 - y0),
                        r,
                        colour,
                    );
                }
            }
        }
        let name = std::path::Path::new(&p.frame).with_extension("png");
        write_rgba_png(&out.join(name), &frame.data, w, h)?;
    }
    Ok(())
}
