//! Adachi et al. Fig. 8: the particle filter's lane position q is more stable than per-frame
//! maximum likelihood by grid search with the same likelihood. Runs `highway-straight` and
//! `worn-markings` over several seeds at 640x480 and prints, for the filter and for the grid
//! search with two q steps (the 5 cm bin, and a finer step, 5 mm by default, so that the
//! grid's quantisation of q is not mistaken for instability), the RMSE of q against the ground
//! truth and the RMS of its frame-to-frame change minus the true change. Each grid searches w
//! in 2 cm steps.
//! `cargo run --release --example adachi_fig8 -- [SEEDS] [FRAMES] [FINE_Q_STEP_M] [SCENARIOS]`
//! (SCENARIOS comma-separated, `highway-straight,worn-markings` by default).

use lanepf::synth::{default_camera, scenario, Eye, Scene};
use lanepf::trackers::adachi::config::AdachiConfig;
use lanepf::trackers::adachi::AdachiTracker;
use lanepf::trackers::{TrackerConfig, TrackerOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let seeds: u64 = args.get(1).map_or(Ok(5), |s| s.parse())?;
    let frames: u32 = args.get(2).map_or(Ok(150), |s| s.parse())?;
    let fine: f64 = args.get(3).map_or(Ok(0.005), |s| s.parse())?;
    let names: Vec<&str> = args
        .get(4)
        .map_or("highway-straight,worn-markings", |s| s.as_str())
        .split(',')
        .collect();
    let camera = default_camera(640, 480)?;
    println!("| scenario | seeds x frames | estimator | q RMSE (m) | RMS of dq - dq_true (m) |");
    println!("|---|---|---|---|---|");
    for name in names {
        // Per estimator (PF, ML on the bin grid, ML on the fine grid): squared errors, squared
        // jumps, and the previous frame's estimate.
        let mut se = [0.0; 3];
        let mut jumps = [0.0; 3];
        let (mut n, mut nd) = (0.0, 0.0);
        for seed in 1..=seeds {
            let mut scene = Scene::new(scenario(name)?, camera.clone(), seed)?;
            let config = TrackerConfig::new(
                camera.to_file(),
                TrackerOptions::AdachiMmpf(AdachiConfig::default()),
            )
            .with_seed(seed);
            let mut tracker = AdachiTracker::new(&config)?;
            let mut rgba = vec![0u8; 640 * 480 * 4];
            let mut prev: Option<(f64, [f64; 3])> = None; // (truth, estimates)
            for f in 0..frames {
                scene.render(f, Eye::Left, &mut rgba, None)?;
                let truth = lanepf::trackers::scene_truth(&scene, f).state["adachi.q"];
                let e = tracker.track(&rgba, 640, 480)?;
                let (_, q_bin, w_bin, _) = tracker.grid_estimate();
                let (_, q_fine, w_fine, _) = tracker.grid_estimate_with(fine, 0.02);
                let q = [e.q, q_bin, q_fine];
                let w = [e.w, w_bin, w_fine];
                // Compare modulo the lane width (q and q +- w describe the same lanes).
                let modulo = |d: f64, w: f64| d - (d / w).round() * w;
                for k in 0..3 {
                    se[k] += modulo(q[k] - truth, w[k]).powi(2);
                }
                n += 1.0;
                // Frame-to-frame change of the estimate minus that of the truth.
                if let Some((t0, q0)) = prev {
                    for k in 0..3 {
                        jumps[k] += modulo((q[k] - q0[k]) - (truth - t0), w[k]).powi(2);
                    }
                    nd += 1.0;
                }
                prev = Some((truth, q));
            }
        }
        let labels = [
            "particle filter".to_string(),
            format!(
                "ML grid, q step {} m (the bin)",
                AdachiConfig::default().bin_m
            ),
            format!("ML grid, q step {fine} m"),
        ];
        for k in 0..3 {
            println!(
                "| {name} | {seeds} x {frames} | {} | {:.3} | {:.4} |",
                labels[k],
                (se[k] / n).sqrt(),
                (jumps[k] / nd).sqrt()
            );
        }
    }
    Ok(())
}
