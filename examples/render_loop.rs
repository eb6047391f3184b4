//! Renders frames of a scenario in a loop (for profiling the renderer with `perf`).
//! `cargo run --release --example render_loop -- SCENARIO FRAMES [W H]`.

use lanepf::synth::{default_camera, scenario, Eye, Scene};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let name = args.get(1).map_or("highway-curve", |s| s.as_str());
    let frames: u32 = args.get(2).map_or(Ok(100), |s| s.parse())?;
    let (w, h): (usize, usize) = match (args.get(3), args.get(4)) {
        (Some(a), Some(b)) => (a.parse()?, b.parse()?),
        _ => (640, 480),
    };
    let mut scene = Scene::new(scenario(name)?, default_camera(w, h)?, 1)?;
    let mut rgba = vec![0u8; w * h * 4];
    let start = std::time::Instant::now();
    for f in 0..frames {
        scene.render(f, Eye::Left, &mut rgba, None)?;
    }
    let ms = start.elapsed().as_secs_f64() * 1e3 / frames as f64;
    println!("{name} {w}x{h}: {ms:.2} ms/frame over {frames} frames");
    Ok(())
}
