//! Lee et al. calibrate the process noise Q of eq. 20 "through the lane parameter estimation
//! using ground-truth lane-marking points". This does the same on the simulator: for each
//! scenario, the RMS and the largest frame-to-frame change of the true [psi, y0, w, w'] (y0
//! modulo a lane width, so lane changes count as the sideways motion, not the jump). The
//! default `process_sd` of `lee-cpf` is set from the largest changes, so that a random walk can
//! follow the fastest motion in the library (the lane change).
//! `cargo run --release --example lee_calibrate_q -- [FRAMES]`

use lanepf::synth::{default_camera, scenario, Scene, SCENARIOS};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let frames: u32 = std::env::args().nth(1).map_or(Ok(300), |s| s.parse())?;
    println!("| scenario | RMS change psi, y0, w, w' per frame | largest change |");
    println!("|---|---|---|");
    for (name, _) in SCENARIOS {
        let config = scenario(name)?;
        let n = config.frames.min(frames);
        let scene = Scene::new(config, default_camera(320, 240)?, 1)?;
        let mut prev: Option<[f64; 4]> = None;
        let (mut sum, mut max) = ([0.0f64; 4], [0.0f64; 4]);
        for f in 0..n {
            let t = lanepf::trackers::scene_truth(&scene, f);
            let s = ["lee.psi", "lee.y0", "lee.w", "lee.w1"].map(|k| t.state[k]);
            if let Some(p) = prev {
                for i in 0..4 {
                    let mut d = s[i] - p[i];
                    if i == 1 {
                        d -= (d / s[2]).round() * s[2];
                    }
                    sum[i] += d * d;
                    max[i] = max[i].max(d.abs());
                }
            }
            prev = Some(s);
        }
        let rms = sum.map(|v| (v / (n - 1) as f64).sqrt());
        println!(
            "| {name} | {:.4}, {:.4}, {:.4}, {:.4} | {:.4}, {:.4}, {:.4}, {:.4} |",
            rms[0], rms[1], rms[2], rms[3], max[0], max[1], max[2], max[3]
        );
    }
    Ok(())
}
