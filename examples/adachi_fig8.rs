//! Adachi et al. Fig. 8: the particle filter's lane position q is more stable than per-frame
//! maximum likelihood by grid search with the same likelihood. Runs `highway-straight` and
//! `worn-markings` over several seeds at 640x480 and prints, for both estimators, the RMSE of q
//! against the ground truth and the RMS of its frame-to-frame change minus the true change.
//! `cargo run --release --example adachi_fig8 -- [SEEDS] [FRAMES]`

use lanepf::synth::{default_camera, scenario, Eye, Scene};
use lanepf::trackers::adachi::AdachiTracker;
use lanepf::trackers::TrackerConfig;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let seeds: u64 = args.get(1).map_or(Ok(5), |s| s.parse())?;
    let frames: u32 = args.get(2).map_or(Ok(150), |s| s.parse())?;
    let camera = default_camera(640, 480)?;
    let cam = serde_json::to_string(&camera.to_file())?;
    println!("| scenario | seeds x frames | PF q RMSE (m) | ML q RMSE (m) | PF RMS of dq - dq_true (m) | ML RMS of dq - dq_true (m) |");
    println!("|---|---|---|---|---|---|");
    for name in ["highway-straight", "worn-markings"] {
        let (mut pf_se, mut ml_se, mut pf_d, mut ml_d, mut n, mut nd) =
            (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for seed in 1..=seeds {
            let mut scene = Scene::new(scenario(name)?, camera.clone(), seed)?;
            let config =
                TrackerConfig::from_json_str(&format!(r#"{{"camera": {cam}, "seed": {seed}}}"#))?;
            let mut tracker = AdachiTracker::new(&config)?;
            let mut rgba = vec![0u8; 640 * 480 * 4];
            let mut prev: Option<(f64, f64, f64)> = None; // (truth, pf, ml)
            for f in 0..frames {
                scene.render(f, Eye::Left, &mut rgba, None)?;
                let truth = scene.truth(f).state["adachi.q"];
                let e = tracker.track(&rgba, 640, 480)?;
                let (_, q_ml, w_ml, _) = tracker.grid_estimate();
                // Compare modulo the lane width (q and q +- w describe the same lanes).
                let err = |q: f64, w: f64| {
                    let d = q - truth;
                    d - (d / w).round() * w
                };
                pf_se += err(e.q, e.w).powi(2);
                ml_se += err(q_ml, w_ml).powi(2);
                n += 1.0;
                // Frame-to-frame change of the estimate minus that of the truth.
                if let Some((t0, a, b)) = prev {
                    let jump = |d: f64, w: f64| d - (d / w).round() * w;
                    pf_d += jump((e.q - a) - (truth - t0), e.w).powi(2);
                    ml_d += jump((q_ml - b) - (truth - t0), w_ml).powi(2);
                    nd += 1.0;
                }
                prev = Some((truth, e.q, q_ml));
            }
        }
        println!(
            "| {name} | {seeds} x {frames} | {:.3} | {:.3} | {:.3} | {:.3} |",
            (pf_se / n).sqrt(),
            (ml_se / n).sqrt(),
            (pf_d / nd).sqrt(),
            (ml_d / nd).sqrt()
        );
    }
    Ok(())
}
