//! The camera pose Caltech's own labels imply, beside the dataset's `camera.json` and the
//! auto-calibration: is the "true camera" of the calibration goal (issue 18) true?
//!
//! `cargo run --release --example caltech_label_pose -- [DATA_DIR]` (`../shared/data` by
//! default). For every labelled frame whose ego pair ([`lanepf::eval::caltech::ego_lanes`]) is
//! straight (each Bezier, sampled at 21 points, within `STRAIGHT_PX` of its least-squares
//! line), the two lines meet at the road's vanishing point; with the dataset's intrinsics that
//! gives pitch and yaw (`pose_from_vanishing_point`, no roll), and with the dataset's height the
//! lane width at the lowest labelled row. Prints each frame and the medians, then the dataset's
//! pose and what `Calibrator` estimates from the frames (intrinsics given), so the three are
//! compared in one run. Last, over the frames the calibrator used (not all of them straight),
//! the yaw of the labels' tangent at the car: each ego lane's line over its lowest
//! `TANGENT_ROWS_PX` rows, where the two meet, which is what `tangent_yaw` measures in the
//! pixels. `-- [DATA_DIR] --tangent-yaw` calibrates with `tangent_yaw`. Then, on the same
//! frames, where the calibrator's marking pixels lie against the labels: per ego side and
//! band of `RESIDUAL_BAND_PX` rows, the mean column of the pixel nearest each labelled row
//! (within `RESIDUAL_MAX_PX`) minus the label's.

use lanepf::calib::pose::{lateral_at_unit_height, pose_from_vanishing_point, Pinhole};
use lanepf::calib::{Calibrator, CalibratorConfig};
use lanepf::camera::CameraFile;
use lanepf::eval::caltech::{bezier_polyline, ego_lanes, read_labels};
use lanepf::image::read_rgba;
use std::path::PathBuf;

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// Largest distance, pixels, of a labelled lane's samples from its fitted line for the lane
/// to count as straight.
const STRAIGHT_PX: f64 = 2.0;

/// Rows above a labelled lane's lowest point over which its tangent at the car is fitted.
const TANGENT_ROWS_PX: f64 = 40.0;

/// Rows per band of the pixels-against-labels table.
const RESIDUAL_BAND_PX: f64 = 40.0;

/// A marking pixel further than this from a label's column in its row is not that label's.
const RESIDUAL_MAX_PX: f64 = 8.0;

/// Column of the polyline `p` at row `y`, where it crosses that row.
fn column_at(p: &[[f64; 2]], y: f64) -> Option<f64> {
    p.windows(2).find_map(|w| {
        let (lo, hi) = if w[0][1] < w[1][1] {
            (w[0], w[1])
        } else {
            (w[1], w[0])
        };
        (lo[1] <= y && y <= hi[1] && hi[1] > lo[1])
            .then(|| lo[0] + (hi[0] - lo[0]) * (y - lo[1]) / (hi[1] - lo[1]))
    })
}

/// x = a + b y fitted to `pts`, and the largest residual.
fn fit_line(pts: &[[f64; 2]]) -> Option<(f64, f64, f64)> {
    let n = pts.len() as f64;
    let my = pts.iter().map(|p| p[1]).sum::<f64>() / n;
    let mx = pts.iter().map(|p| p[0]).sum::<f64>() / n;
    let syy: f64 = pts.iter().map(|p| (p[1] - my).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p[1] - my) * (p[0] - mx)).sum();
    if pts.len() < 2 || syy < 1e-9 {
        return None;
    }
    let b = sxy / syy;
    let a = mx - b * my;
    let worst = pts
        .iter()
        .map(|p| (p[0] - a - b * p[1]).abs())
        .fold(0.0, f64::max);
    Some((a, b, worst))
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

/// Where the lines x = a + b y of two fits meet, unless they are parallel.
fn crossing(l: &(f64, f64, f64), r: &(f64, f64, f64)) -> Option<[f64; 2]> {
    if (l.1 - r.1).abs() < 1e-6 {
        return None;
    }
    let y = (r.0 - l.0) / (l.1 - r.1);
    Some([l.0 + l.1 * y, y])
}

fn main() -> Res<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let tangent_yaw = args.iter().any(|a| a == "--tangent-yaw");
    let data = PathBuf::from(
        args.iter()
            .find(|a| !a.starts_with("--"))
            .map_or("../shared/data", |a| a.as_str()),
    )
    .join("caltech-cordova1");
    let camera = CameraFile::read(&data.join("camera.json"))?;
    let labels = read_labels(&data.join("labels.json"))?;
    let k = Pinhole {
        fx: camera.fx,
        fy: camera.fy,
        cx: camera.cx,
        cy: camera.cy,
    };
    let size = [camera.width, camera.height];
    let (mut pitches, mut yaws, mut widths) = (Vec::new(), Vec::new(), Vec::new());
    println!("frame        pitch   yaw     lane width at the dataset's height");
    for frame in &labels.frames {
        let [Some(li), Some(ri)] = ego_lanes(&frame.lanes, size) else {
            continue;
        };
        let sample = |i: usize| bezier_polyline(&frame.lanes[i].bezier_xy, 20);
        let (lp, rp) = (sample(li), sample(ri));
        let (Some(l), Some(r)) = (fit_line(&lp), fit_line(&rp)) else {
            continue;
        };
        if l.2 > STRAIGHT_PX || r.2 > STRAIGHT_PX {
            continue;
        }
        let Some(vp) = crossing(&l, &r) else {
            continue;
        };
        let [pitch, yaw] = pose_from_vanishing_point(&k, vp);
        // The lowest row both lanes reach.
        let low = |p: &[[f64; 2]]| p.iter().map(|q| q[1]).fold(f64::MIN, f64::max);
        let row = low(&lp).min(low(&rp));
        let at = |f: &(f64, f64, f64)| [f.0 + f.1 * row, row];
        let (Some(yl), Some(yr)) = (
            lateral_at_unit_height(&k, pitch, yaw, at(&l)),
            lateral_at_unit_height(&k, pitch, yaw, at(&r)),
        ) else {
            continue;
        };
        let width = camera.height_m * (yl - yr);
        println!(
            "{:12} {:6.2}  {:6.2}  {:.2} m",
            frame.frame,
            pitch.to_degrees(),
            yaw.to_degrees(),
            width
        );
        pitches.push(pitch.to_degrees());
        yaws.push(yaw.to_degrees());
        widths.push(width);
    }
    println!(
        "\nlabels ({} straight frames), medians: pitch {:.2} deg, yaw {:.2} deg, lane width {:.2} m at {:.2} m",
        pitches.len(),
        median(&mut pitches),
        median(&mut yaws),
        median(&mut widths),
        camera.height_m
    );
    println!(
        "camera.json:  pitch {:.2} deg, yaw {:.2} deg, height {:.2} m",
        camera.pitch_deg, camera.yaw_deg, camera.height_m
    );
    let mut calibrator = Calibrator::new(
        camera.width,
        camera.height,
        Some(&camera),
        CalibratorConfig {
            tangent_yaw,
            ..CalibratorConfig::default()
        },
    )?;
    let mut tangent_yaws = Vec::new();
    // (side, band) -> sum and count of pixel column minus label column.
    let mut residuals = std::collections::BTreeMap::<(usize, i64), (f64, usize)>::new();
    for frame in &labels.frames {
        let image = read_rgba(&data.join("frames").join(&frame.frame))?;
        calibrator.feed_rgba(&image.data, image.width, image.height)?;
        if calibrator.last_observation().used {
            let [Some(li), Some(ri)] = ego_lanes(&frame.lanes, size) else {
                continue;
            };
            let near = |i: usize| {
                let p = bezier_polyline(&frame.lanes[i].bezier_xy, 200);
                let lowest = p.iter().map(|q| q[1]).fold(f64::MIN, f64::max);
                let rows: Vec<[f64; 2]> = p
                    .into_iter()
                    .filter(|q| q[1] >= lowest - TANGENT_ROWS_PX)
                    .collect();
                fit_line(&rows)
            };
            for (side, i) in [(0, li), (1, ri)] {
                let label = bezier_polyline(&frame.lanes[i].bezier_xy, 400);
                // Per pixel row, the marking pixel nearest the label.
                let mut nearest = std::collections::BTreeMap::<i64, f64>::new();
                for q in calibrator.marking_pixels() {
                    let Some(x) = column_at(&label, q[1]) else {
                        continue;
                    };
                    let d = q[0] - x;
                    let e = nearest.entry(q[1].round() as i64).or_insert(d);
                    if d.abs() < e.abs() {
                        *e = d;
                    }
                }
                for (row, d) in nearest {
                    if d.abs() <= RESIDUAL_MAX_PX {
                        let band = (row as f64 / RESIDUAL_BAND_PX).floor() as i64;
                        let cell = residuals.entry((side, band)).or_insert((0.0, 0));
                        cell.0 += d;
                        cell.1 += 1;
                    }
                }
            }
            if let Some(vp) = near(li).zip(near(ri)).and_then(|(l, r)| crossing(&l, &r)) {
                tangent_yaws.push(pose_from_vanishing_point(&k, vp)[1].to_degrees());
            }
        }
    }
    match calibrator.estimate() {
        Some(e) => println!(
            "calibrator:   pitch {:.2} deg, yaw {:.2} deg, height {:.2} m ({} frames, confidence {:.2})",
            e.camera.pitch_deg, e.camera.yaw_deg, e.camera.height_m, e.frames_used, e.confidence
        ),
        None => println!("calibrator:   no estimate"),
    }
    if !tangent_yaws.is_empty() {
        println!(
            "labels' tangent at the car over the {} labelled frames the calibrator used: median yaw {:.2} deg",
            tangent_yaws.len(),
            median(&mut tangent_yaws)
        );
    }
    println!(
        "the calibrator's marking pixels nearest the labels, minus the labels, on those frames (mean, pixels; rows):"
    );
    for (side, name) in [(0, "ego-left "), (1, "ego-right")] {
        let cells: Vec<String> = residuals
            .iter()
            .filter(|((s, _), _)| *s == side)
            .map(|((_, band), (sum, n))| {
                let top = *band as f64 * RESIDUAL_BAND_PX;
                format!(
                    "{top:.0}-{:.0}: {:+.2} ({n})",
                    top + RESIDUAL_BAND_PX - 1.0,
                    sum / *n as f64
                )
            })
            .collect();
        println!("  {name}  {}", cells.join(", "));
    }
    Ok(())
}
