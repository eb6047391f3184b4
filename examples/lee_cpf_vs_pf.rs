//! Lee et al. Figs. 14-15 and Table 1: the cascade particle filter against single-stage
//! filters with the same cues and particle count. Runs scenarios over several seeds at
//! 640x480 and prints, per filter, the RMSE of the lateral offset, the heading (and the
//! standard deviation of the heading error), the lane width, the lateral error of the lane
//! centre 30 m ahead, the valid-frame rate and the mean ms/frame.
//! `cargo run --release --example lee_cpf_vs_pf -- [SEEDS] [FRAMES] [PARTICLES] [SCENARIO...]`

use lanepf::synth::{default_camera, scenario, Eye, Scene};
use lanepf::trackers::lee::clothoid::Curve;
use lanepf::trackers::lee::config::{LeeConfig, Variant};
use lanepf::trackers::lee::LeeTracker;
use lanepf::trackers::{TrackerConfig, TrackerOptions};

#[derive(Default)]
struct Sums {
    n: f64,
    offset: f64,
    heading: f64,
    heading_mean: f64,
    width: f64,
    far: f64,
    far_n: f64,
    valid: f64,
    ms: f64,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let seeds: u64 = args.get(1).map_or(Ok(3), |s| s.parse())?;
    let frames: u32 = args.get(2).map_or(Ok(150), |s| s.parse())?;
    let particles: usize = args.get(3).map_or(Ok(500), |s| s.parse())?;
    let names: Vec<String> = if args.len() > 4 {
        args[4..].to_vec()
    } else {
        [
            "highway-straight",
            "highway-curve",
            "s-curve",
            "lane-change",
        ]
        .map(String::from)
        .to_vec()
    };
    let camera = default_camera(640, 480)?;
    println!("{seeds} seeds x {frames} frames, {particles} particles per filter, 640x480, first 10 frames of each run skipped");
    println!();
    println!("| scenario | filter | offset RMSE (m) | heading RMSE (deg) | heading error sd (deg) | width RMSE (m) | centre error at 30 m (m) | valid | ms/frame |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for name in &names {
        for (variant, kalman, label) in [
            (Variant::Cascade, true, "CPF + Kalman"),
            (Variant::Cascade, false, "CPF"),
            (Variant::FirstOrder, false, "PF1 (first-order)"),
            (Variant::FullModel, false, "PF full model"),
        ] {
            let mut s = Sums::default();
            for seed in 1..=seeds {
                let mut scene = Scene::new(scenario(name)?, camera.clone(), seed)?;
                let lee = LeeConfig {
                    variant,
                    kalman,
                    ..LeeConfig::default()
                };
                let config = TrackerConfig::new(camera.to_file(), TrackerOptions::LeeCpf(lee))
                    .with_seed(seed)
                    .with_particles(particles);
                let mut tracker = LeeTracker::new(&config)?;
                let mut rgba = vec![0u8; 640 * 480 * 4];
                for f in 0..frames {
                    scene.render(f, Eye::Left, &mut rgba, None)?;
                    let t0 = std::time::Instant::now();
                    let e = tracker.track(&rgba, 640, 480)?;
                    let ms = t0.elapsed().as_secs_f64() * 1e3;
                    if f < 10 {
                        continue;
                    }
                    let truth = lanepf::trackers::scene_truth(&scene, f);
                    let st = e.state;
                    // Offsets compared modulo the lane width (a lane change re-centres).
                    let d = -st.y0 - truth.lateral_offset_m;
                    let d = d - (d / st.w).round() * st.w;
                    let h = (st.psi - truth.heading_rad).to_degrees();
                    s.n += 1.0;
                    s.offset += d * d;
                    s.heading += h * h;
                    s.heading_mean += h;
                    s.width += (st.w - truth.lane_width_m).powi(2);
                    s.valid += f64::from(u8::from(e.valid));
                    s.ms += ms;
                    let curve = Curve::new(st.c, st.delta, tracker.config().spiral_length_m);
                    if let Some(tc) = truth.ego_centre_at(30.0) {
                        let d = st.centre(30.0, Some(&curve)) - tc;
                        let d = d - (d / st.w).round() * st.w;
                        s.far += d * d;
                        s.far_n += 1.0;
                    }
                }
            }
            let n = s.n;
            let mean_h = s.heading_mean / n;
            println!(
                "| {name} | {label} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.1} % | {:.2} |",
                (s.offset / n).sqrt(),
                (s.heading / n).sqrt(),
                (s.heading / n - mean_h * mean_h).max(0.0).sqrt(),
                (s.width / n).sqrt(),
                (s.far / s.far_n.max(1.0)).sqrt(),
                100.0 * s.valid / n,
                s.ms / n
            );
        }
    }
    Ok(())
}
