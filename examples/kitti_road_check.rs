//! Held-out check on KITTI road's labelled frame um_000000 (never used to develop or tune):
//! the camera from its calibration, every mono tracker's ego lane against the ego-lane mask,
//! and the calibrator's pose from the one still against the calibration's.
//!
//! `cargo run --release --example kitti_road_check -- [DATA_DIR]` (`../shared/data` by
//! default). The camera: intrinsics from `P2` (the left colour camera, rectified), the pose from
//! `Tr_cam_to_road` ([`lanepf::eval::kitti_road::camera_from_calib`]). Each tracker runs in
//! still mode (5 filter iterations on the frame from a fresh start) with tracker seeds 1-5,
//! with the papers' options and with `real-roads`; its ego lane (the image area between its ego-left and ego-right
//! boundaries) is scored against the mask pixel by pixel in the image
//! ([`lanepf::eval::kitti_road::score_ego_lane`]; KITTI's own benchmark scores a bird's-eye
//! view, so the figures are not comparable with its table). It prints the camera as a
//! `camera.json` too, for `lanepf track --camera` and `lanepf eval --format kitti-road`.

use lanepf::calib::{Calibrator, CalibratorConfig};
use lanepf::eval::kitti_road::{camera_from_calib, read_ego_lane_mask, score_ego_lane};
use lanepf::image::read_rgba;
use lanepf::trackers::{self, Preset, TrackerConfig, TrackerOptions};
use std::path::PathBuf;

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// Filter iterations on the still, as the real-data report's still mode.
const STILL_ITERATIONS: usize = 5;

/// Tracker seeds: one frame is one draw of each filter.
const SEEDS: std::ops::RangeInclusive<u64> = 1..=5;

/// The mono trackers.
const TRACKERS: [&str; 4] = ["adachi-mmpf", "danescu-mono", "lee-cpf", "liu-ppf"];

fn main() -> Res<()> {
    let data = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "../shared/data".into()),
    )
    .join("kitti-road/data_road/training");
    let image = read_rgba(&data.join("image_2/um_000000.png"))?;
    let calib = std::fs::read_to_string(data.join("calib/um_000000.txt"))?;
    let camera = camera_from_calib(&calib, image.width, image.height)?;
    let mask = read_ego_lane_mask(&data.join("gt_image_2/um_lane_000000.png"))?;
    println!(
        "KITTI road um_000000 ({}x{}): camera from its calibration: fx {:.1}, pitch {:.2} deg, yaw {:.2} deg, roll {:.2} deg, height {:.3} m",
        image.width,
        image.height,
        camera.fx,
        camera.pitch_deg,
        camera.yaw_deg,
        camera.roll_deg,
        camera.height_m
    );
    println!("as a camera.json: {}", camera.to_json_string());
    println!(
        "\ntracker seeds {}-{}: mean (min-max) over the seeds; a seed's figures count 0 when it is not valid",
        SEEDS.start(),
        SEEDS.end()
    );
    println!("\n| tracker | preset | valid | ego lane precision | recall | F1 |");
    println!("|---|---|---|---|---|---|");
    for id in TRACKERS {
        for (preset, name) in [(Preset::Paper, "paper"), (Preset::RealRoads, "real-roads")] {
            let (mut valid, mut figures) = (0, [Vec::new(), Vec::new(), Vec::new()]);
            for seed in SEEDS {
                let mut config =
                    TrackerConfig::new(camera.clone(), TrackerOptions::preset(id, preset)?);
                config.seed = seed;
                let mut tracker = trackers::build(&config)?;
                let mut estimate = tracker.step(&image.data, image.width, image.height)?;
                for _ in 1..STILL_ITERATIONS {
                    estimate = tracker.step(&image.data, image.width, image.height)?;
                }
                let score = score_ego_lane(&estimate, &mask)?;
                valid += usize::from(estimate.valid);
                for (list, value) in
                    figures
                        .iter_mut()
                        .zip([score.precision(), score.recall(), score.f1()])
                {
                    list.push(value.unwrap_or(0.0));
                }
            }
            let cell = |v: &[f64], scale: f64| {
                let mean = v.iter().sum::<f64>() / v.len() as f64;
                let (lo, hi) = v
                    .iter()
                    .fold((f64::MAX, f64::MIN), |(lo, hi), &x| (lo.min(x), hi.max(x)));
                format!("{:.3} ({:.3}-{:.3})", scale * mean, scale * lo, scale * hi)
            };
            println!(
                "| {id} | {name} | {valid} of {} | {} | {} | {} |",
                SEEDS.count(),
                cell(&figures[0], 1.0),
                cell(&figures[1], 1.0),
                cell(&figures[2], 1.0)
            );
        }
    }
    let mut calibrator = Calibrator::new(
        image.width,
        image.height,
        Some(&camera),
        CalibratorConfig {
            stable_frames: 1,
            ..CalibratorConfig::default()
        },
    )?;
    calibrator.feed_rgba(&image.data, image.width, image.height)?;
    match calibrator.estimate() {
        Some(e) => println!(
            "\ncalibrator on the one still (intrinsics given, stills mode): pitch {:.2} deg, yaw {:.2} deg, height {:.3} m (confidence {:.2}); calibration: {:.2} / {:.2} deg, {:.3} m",
            e.camera.pitch_deg,
            e.camera.yaw_deg,
            e.camera.height_m,
            e.confidence,
            camera.pitch_deg,
            camera.yaw_deg,
            camera.height_m
        ),
        None => println!("\ncalibrator on the one still: no estimate"),
    }
    Ok(())
}
