//! Renders one frame of every named scenario side by side into a contact sheet PNG, for
//! checking by eye. `cargo run --release --example contact_sheet -- OUT.png [FRAME] [W H]`.

use lanepf::camera::{Camera, CameraFile};
use lanepf::synth::{scenario, Eye, Scene, SCENARIOS};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let out = args.get(1).map_or("contact-sheet.png", |s| s.as_str());
    let frame: u32 = args.get(2).map_or(Ok(90), |s| s.parse())?;
    let (w, h): (usize, usize) = match (args.get(3), args.get(4)) {
        (Some(a), Some(b)) => (a.parse()?, b.parse()?),
        _ => (640, 480),
    };
    let scale = w as f64 / 640.0;
    let camera = Camera::from_file(&CameraFile {
        cx: w as f64 / 2.0,
        cy: h as f64 / 2.0,
        pitch_deg: 4.0,
        ..CameraFile::pinhole(w, h, 520.0 * scale)
    })?;
    let cols = 4;
    let rows = SCENARIOS.len().div_ceil(cols);
    let mut sheet = vec![0u8; cols * w * rows * h * 4];
    let mut rgba = vec![0u8; w * h * 4];
    for (k, (name, _)) in SCENARIOS.iter().enumerate() {
        let mut scene = Scene::new(scenario(name)?, camera.clone(), 1)?;
        let t = std::time::Instant::now();
        scene.render(frame, Eye::Left, &mut rgba, None)?;
        eprintln!("{name}: {:.1} ms", t.elapsed().as_secs_f64() * 1e3);
        let (cx, cy) = (k % cols, k / cols);
        for y in 0..h {
            let dst = ((cy * h + y) * cols * w + cx * w) * 4;
            sheet[dst..dst + w * 4].copy_from_slice(&rgba[y * w * 4..(y + 1) * w * 4]);
        }
    }
    lanepf::image::write_rgba_png(std::path::Path::new(out), &sheet, cols * w, rows * h)?;
    Ok(())
}
