//! Liu et al. Figs. 6 and 8: PPF-Kernel against PPF-NoKernel on the same frames. Runs
//! scenarios over several seeds at 640x480 and prints, per variant, the RMSE of the top-view
//! parameters (rho px, theta rad, d) of the ego-lane boundaries against the simulator's
//! least-squares truth, the lateral-offset and heading RMSE, the valid-frame rate and the mean
//! ms/frame (indicative: the runs share the machine).
//! `cargo run --release --example liu_kernel_vs_nokernel -- [SEEDS] [FRAMES] [PARTICLES] [SCENARIO...]`

use lanepf::synth::{default_camera, scenario, Eye, Scene};
use lanepf::trackers::{build, TrackerConfig, TrackerOptions};

#[derive(Default)]
struct Sums {
    n: f64,
    params: [f64; 3],
    params_n: f64,
    offset: f64,
    heading: f64,
    valid: f64,
    ms: f64,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let seeds: u64 = args.get(1).map_or(Ok(3), |s| s.parse())?;
    let frames: u32 = args.get(2).map_or(Ok(150), |s| s.parse())?;
    let particles: usize = args.get(3).map_or(Ok(200), |s| s.parse())?;
    let names: Vec<String> = if args.len() > 4 {
        args[4..].to_vec()
    } else {
        ["highway-straight", "highway-curve", "s-curve"]
            .map(String::from)
            .to_vec()
    };
    let camera = default_camera(640, 480)?;
    println!("{seeds} seeds x {frames} frames, N = {particles} (+ N' = 50), 640x480, first 10 frames of each run skipped");
    println!();
    println!("| scenario | variant | rho RMSE (px) | theta RMSE (rad) | d RMSE | offset RMSE (m) | heading RMSE (deg) | valid | ms/frame |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for name in &names {
        for id in ["liu-ppf", "liu-ppf-nokernel"] {
            let mut s = Sums::default();
            for seed in 1..=seeds {
                let mut scene = Scene::new(scenario(name)?, camera.clone(), seed)?;
                let config = TrackerConfig::new(camera.to_file(), TrackerOptions::defaults(id)?)
                    .with_seed(seed)
                    .with_particles(particles);
                let mut tracker = build(&config)?;
                let mut rgba = vec![0; 640 * 480 * 4];
                for f in 0..frames {
                    scene.render(f, Eye::Left, &mut rgba, None)?;
                    let t0 = std::time::Instant::now();
                    let e = tracker.step(&rgba, 640, 480)?;
                    let ms = t0.elapsed().as_secs_f64() * 1e3;
                    if f < 10 {
                        continue;
                    }
                    let t = lanepf::trackers::scene_truth(&scene, f);
                    s.n += 1.0;
                    s.ms += ms;
                    s.valid += f64::from(u8::from(e.valid));
                    s.offset += (e.lateral_offset_m - t.lateral_offset_m).powi(2);
                    s.heading += (e.heading_rad - t.heading_rad).powi(2);
                    for role in ["ego-left", "ego-right"] {
                        let key = |p: &str| format!("liu.{role}.{p}");
                        let errors: Option<Vec<f64>> = ["rho", "theta", "d"]
                            .iter()
                            .map(|p| Some(e.state.get(&key(p))? - t.state.get(&key(p))?))
                            .collect();
                        if let Some(errors) = errors {
                            s.params_n += 1.0;
                            for (acc, err) in s.params.iter_mut().zip(errors) {
                                *acc += err * err;
                            }
                        }
                    }
                }
            }
            let r = |v: f64, n: f64| (v / n.max(1.0)).sqrt();
            println!(
                "| {name} | {id} | {:.2} | {:.4} | {:.4} | {:.3} | {:.2} | {:.1} % | {:.1} |",
                r(s.params[0], s.params_n),
                r(s.params[1], s.params_n),
                r(s.params[2], s.params_n),
                r(s.offset, s.n),
                r(s.heading, s.n).to_degrees(),
                100.0 * s.valid / s.n.max(1.0),
                s.ms / s.n.max(1.0)
            );
        }
    }
    Ok(())
}
