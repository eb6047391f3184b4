//! `lanepf synth`: render a member of a scenario family into DIR/frames (and DIR/right,
//! DIR/disparity with --stereo), with DIR/camera.json, DIR/gt.jsonl and DIR/scene.json (the
//! drawn scene and camera mount, for reading what the seed chose).
//!
//! `--seed N` draws the road, the events and the camera of the family (see
//! `lanepf::synth::draw_scenario`); `--reference` renders the family's fixed reference road
//! through the default camera instead, where the seed changes only texture and noise (the
//! scenes of the figures measured before the families existed).

use lanepf::camera::Camera;
use lanepf::image::{write_disparity_png, write_rgba_png};
use lanepf::synth::{draw_scenario, reference_member, Eye, Scene, RANDOM_SCENARIO, SCENARIOS};
use lanepf::{Error, Result};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Options of `lanepf synth`.
#[derive(clap::Args)]
pub struct Args {
    /// Scenario family name, or `random` (`--list` shows them).
    #[arg(long, required_unless_present = "list")]
    scenario: Option<String>,
    /// Seed of the family member: road, events, camera, textures and noise.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Render the family's fixed reference road through the default camera (the seed then
    /// changes only textures and noise).
    #[arg(long)]
    reference: bool,
    /// Number of frames (default: the scenario's own length).
    #[arg(long)]
    frames: Option<u32>,
    /// Image width (with the drawn or default camera).
    #[arg(long, default_value_t = 640)]
    width: usize,
    /// Image height (with the drawn or default camera).
    #[arg(long, default_value_t = 480)]
    height: usize,
    /// Render through this camera.json instead of the drawn or default camera.
    #[arg(long, conflicts_with_all = ["width", "height"])]
    camera: Option<PathBuf>,
    /// Also render the right camera and the exact disparity of the left image.
    #[arg(long)]
    stereo: bool,
    /// Output folder.
    #[arg(long, required_unless_present = "list")]
    out: Option<PathBuf>,
    /// List the scenarios and exit.
    #[arg(long)]
    list: bool,
}

fn create_dir(path: &Path) -> Result<()> {
    std::fs::create_dir_all(path).map_err(|e| Error::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    })
}

fn io_error(path: &Path) -> impl Fn(std::io::Error) -> Error + '_ {
    move |e| Error::Io {
        path: path.display().to_string(),
        reason: e.to_string(),
    }
}

/// Runs the command.
pub fn run(args: Args) -> Result<()> {
    if args.list {
        let list: String = SCENARIOS
            .iter()
            .map(|(name, about)| format!("{name:18} {about}\n"))
            .chain([format!(
                "{RANDOM_SCENARIO:18} any of the above, drawn from the seed\n"
            )])
            .collect();
        return super::out(&list);
    }
    let (Some(name), Some(out)) = (args.scenario, args.out) else {
        return Err(Error::Config("--scenario and --out are required".into()));
    };
    let mut member = if args.reference {
        reference_member(&name, args.seed)?
    } else {
        draw_scenario(&name, args.seed)?
    };
    if let Some(n) = args.frames {
        member.config.frames = n;
    }
    let camera = match &args.camera {
        Some(path) => Camera::load(path)?,
        None => member.mount.camera(args.width, args.height)?,
    };
    let frames = member.config.frames;
    let mut scene = Scene::new(member.config.clone(), camera, args.seed)?;
    let (w, h) = (scene.width(), scene.height());
    create_dir(&out.join("frames"))?;
    if args.stereo {
        create_dir(&out.join("right"))?;
        create_dir(&out.join("disparity"))?;
    }
    let mut file = scene.camera().to_file();
    file.baseline_m = Some(scene.baseline());
    file.write(&out.join("camera.json"))?;
    write_scene_file(&out.join("scene.json"), &name, &member)?;
    let gt_path = out.join("gt.jsonl");
    let gt_file = std::fs::File::create(&gt_path).map_err(io_error(&gt_path))?;
    let mut gt = std::io::BufWriter::new(gt_file);
    let mut rgba = vec![0u8; w * h * 4];
    let mut depth = vec![0f32; w * h];
    let mut disparity = vec![0f32; w * h];
    let fb = scene.camera().focal()[0] * scene.baseline();
    for frame in 0..frames {
        let name = format!("{frame:06}.png");
        scene.render(frame, Eye::Left, &mut rgba, Some(&mut depth))?;
        write_rgba_png(&out.join("frames").join(&name), &rgba, w, h)?;
        if args.stereo {
            scene.render(frame, Eye::Right, &mut rgba, None)?;
            write_rgba_png(&out.join("right").join(&name), &rgba, w, h)?;
            for (d, &z) in disparity.iter_mut().zip(&depth) {
                *d = if z > 0.0 { (fb / z as f64) as f32 } else { 0.0 };
            }
            write_disparity_png(&out.join("disparity").join(&name), &disparity, w, h)?;
        }
        let truth = lanepf::trackers::scene_truth(&scene, frame);
        let line = serde_json::to_string(&truth).map_err(|e| Error::Config(e.to_string()))?;
        writeln!(gt, "{line}").map_err(io_error(&gt_path))?;
    }
    gt.flush().map_err(io_error(&gt_path))?;
    eprintln!(
        "lanepf synth: {frames} frames of `{name}`{} seed {} ({w}x{h}{}) in {}",
        if args.reference {
            " (reference)".to_string()
        } else if member.scenario != name {
            format!(" ({})", member.scenario)
        } else {
            String::new()
        },
        args.seed,
        if args.stereo { ", stereo" } else { "" },
        out.display()
    );
    Ok(())
}

/// Writes what the seed drew: the family, the seed, the camera mount and the scene.
fn write_scene_file(path: &Path, name: &str, member: &lanepf::synth::FamilyMember) -> Result<()> {
    let value = serde_json::json!({
        "scenario": name,
        "family": member.scenario,
        "seed": member.seed,
        "mount": member.mount,
        "scene": member.config,
    });
    let text = serde_json::to_string_pretty(&value).map_err(|e| Error::Config(e.to_string()))?;
    std::fs::write(path, text + "\n").map_err(io_error(path))
}
