//! KITTI road's ego-lane frames: the camera from a frame's calibration file and the ego lane
//! scored against the lane mask, pixel by pixel in the image (a held-out check; KITTI's own
//! benchmark scores a bird's-eye view, so the figures are not comparable with its table).
//!
//! **Camera.** The calibration file holds `KEY: v1 v2 ...` lines. `P2` (3 x 4, row-major) is
//! the rectified left colour camera's projection: fx = `P2[0][0]`, fy = `P2[1][1]`,
//! cx = `P2[0][2]`, cy = `P2[1][2]`. `Tr_cam_to_road` (3 x 4) maps camera coordinates (x right,
//! y down, z ahead) to road coordinates with the same axes and the road plane at y = 0:
//! p_road = R p_cam + t.
//! The camera centre is then at t, so its height is -t_y. The optical axis in road coordinates
//! is R's third column d, the camera's x axis R's first column e; with the crate's
//! R = Rz(yaw) Ry(pitch) Rx(roll) ([`crate::camera`]), whose forward axis is (d_z, -d_x, -d_y)
//! and left axis (-e_z, e_x, e_y) in ISO 8855 road coordinates:
//!
//! ```text
//! pitch = asin(d_y)                   (positive looking down: y points down)
//! yaw   = atan2(-d_x, d_z)            (positive looking left: x points right)
//! roll  = asin(e_y / cos(pitch))      (positive when the right side dips)
//! ```
//!
//! `Tr_cam_to_road` is given for the rectified reference camera 0; camera 2 sits 6 cm beside
//! it on the same rig (P2's translation), which moves the road a few centimetres sideways and
//! is left out.
//!
//! **Mask.** `gt_image_2/um_lane_*.png` colours the ego lane magenta (255, 0, 255), the rest of
//! the image red, and pixels not evaluated black. A prediction's lane is, in each row where
//! both its ego-left and ego-right boundaries are, the pixels from the left one's column to the
//! right one's; an invalid estimate predicts nothing. Precision, recall and F1 count the
//! evaluated pixels.

use super::polyline::x_at_y;
use super::{percent, ratio};
use crate::camera::{Camera, CameraFile};
use crate::error::{Error, Result};
use crate::image::read_rgba;
use crate::lane::{LaneEstimate, Role};
use crate::math::{atan2, rad_to_deg};
use serde::Serialize;
use std::fmt;
use std::path::{Path, PathBuf};

/// The camera of a KITTI road frame `width` x `height` from its calibration file's text.
///
/// # Errors
/// [`Error::Config`] when `P2` or `Tr_cam_to_road` is missing, has other than 12 numbers or a
/// number that does not parse or is not finite, or when the camera they give is not valid
/// (a focal length or a height that is not positive, for example).
pub fn camera_from_calib(text: &str, width: usize, height: usize) -> Result<CameraFile> {
    let p2 = calib_matrix(text, "P2")?;
    let tr = calib_matrix(text, "Tr_cam_to_road")?;
    let at = |m: &[f64; 12], row: usize, col: usize| m[4 * row + col];
    let (d, e) = (
        [at(&tr, 0, 2), at(&tr, 1, 2), at(&tr, 2, 2)],
        [at(&tr, 0, 0), at(&tr, 1, 0), at(&tr, 2, 0)],
    );
    let camera = CameraFile {
        fx: at(&p2, 0, 0),
        fy: at(&p2, 1, 1),
        cx: at(&p2, 0, 2),
        cy: at(&p2, 1, 2),
        height_m: -at(&tr, 1, 3),
        pitch_deg: rad_to_deg(asin(d[1])),
        yaw_deg: rad_to_deg(atan2(-d[0], d[2])),
        roll_deg: rad_to_deg(asin(e[1] / (1.0 - d[1] * d[1]).sqrt().max(1e-9))),
        ..CameraFile::pinhole(width, height, 1.0)
    };
    Camera::from_file(&camera)
        .map_err(|e| Error::Config(format!("KITTI calibration gives no usable camera: {e}")))?;
    Ok(camera)
}

/// asin of `x` clamped to [-1, 1], through [`crate::math::atan2`] (bit-identical across
/// targets).
fn asin(x: f64) -> f64 {
    let x = x.clamp(-1.0, 1.0);
    atan2(x, (1.0 - x * x).sqrt())
}

/// The 12 numbers of the calibration line `key: ...`.
fn calib_matrix(text: &str, key: &str) -> Result<[f64; 12]> {
    let line = text
        .lines()
        .find_map(|l| l.trim().strip_prefix(key)?.strip_prefix(':'))
        .ok_or_else(|| Error::Config(format!("KITTI calibration: no `{key}:` line")))?;
    let values: Vec<f64> = line
        .split_whitespace()
        .map(|v| v.parse::<f64>().ok().filter(|v| v.is_finite()))
        .collect::<Option<_>>()
        .ok_or_else(|| Error::Config(format!("KITTI calibration: `{key}` has a bad number")))?;
    values.try_into().map_err(|v: Vec<f64>| {
        Error::Config(format!(
            "KITTI calibration: `{key}` has {} numbers, not 12",
            v.len()
        ))
    })
}

/// One pixel of a KITTI lane mask.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MaskPixel {
    /// The ego lane (magenta).
    Lane,
    /// Evaluated, not the ego lane (any colour but magenta and black).
    Other,
    /// Not evaluated (black).
    Ignored,
}

/// A KITTI ego-lane mask.
#[derive(Debug, Clone, PartialEq)]
pub struct EgoLaneMask {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Row-major pixels.
    pub pixels: Vec<MaskPixel>,
}

impl EgoLaneMask {
    /// The mask of an RGBA image `width` x `height`.
    ///
    /// # Errors
    /// [`Error::BufferSize`] when `rgba` does not hold `width` x `height` pixels.
    pub fn from_rgba(rgba: &[u8], width: usize, height: usize) -> Result<Self> {
        crate::image::check_rgba(rgba, width, height)?;
        let pixels = rgba
            .chunks_exact(4)
            .map(|p| match (p[0], p[1], p[2]) {
                (255, 0, 255) => MaskPixel::Lane,
                (0, 0, 0) => MaskPixel::Ignored,
                _ => MaskPixel::Other,
            })
            .collect();
        Ok(Self {
            width,
            height,
            pixels,
        })
    }
}

/// Reads a KITTI lane mask PNG.
///
/// # Errors
/// [`Error::Io`] or [`Error::Decode`] when the file cannot be read or decoded.
pub fn read_ego_lane_mask(path: &Path) -> Result<EgoLaneMask> {
    let image = read_rgba(path)?;
    EgoLaneMask::from_rgba(&image.data, image.width, image.height)
}

/// Pixel counts of a predicted ego lane against a mask.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct MaskScore {
    /// Lane pixels predicted as lane.
    pub true_positives: usize,
    /// Other pixels predicted as lane.
    pub false_positives: usize,
    /// Lane pixels not predicted.
    pub false_negatives: usize,
}

impl MaskScore {
    /// TP / (TP + FP); `None` when nothing was predicted.
    pub fn precision(&self) -> Option<f64> {
        ratio(
            self.true_positives,
            self.true_positives + self.false_positives,
        )
    }

    /// TP / (TP + FN); `None` when the mask has no lane.
    pub fn recall(&self) -> Option<f64> {
        ratio(
            self.true_positives,
            self.true_positives + self.false_negatives,
        )
    }

    /// 2 TP / (2 TP + FP + FN); `None` when there is neither a lane nor a prediction.
    pub fn f1(&self) -> Option<f64> {
        ratio(
            2 * self.true_positives,
            2 * self.true_positives + self.false_positives + self.false_negatives,
        )
    }
}

/// Scores `estimate`'s ego lane against `mask` (see the module docs). The boundaries are in
/// the mask's pixels: track the frame at its own size (KITTI's masks are the images' size).
///
/// # Errors
/// [`Error::Parameter`] when a boundary point is not finite; [`Error::BufferSize`] when the
/// mask's pixels are not `width` x `height`.
pub fn score_ego_lane(estimate: &LaneEstimate, mask: &EgoLaneMask) -> Result<MaskScore> {
    let expected = mask.width.saturating_mul(mask.height);
    if mask.pixels.len() != expected {
        return Err(Error::BufferSize {
            what: format!("a {}x{} lane mask", mask.width, mask.height),
            expected,
            actual: mask.pixels.len(),
        });
    }
    let boundary = |role: Role| {
        estimate
            .boundaries
            .iter()
            .find(|b| b.role == role)
            .map(|b| b.points.as_slice())
    };
    for b in &estimate.boundaries {
        if let Some(p) = b
            .points
            .iter()
            .find(|p| !p[0].is_finite() || !p[1].is_finite())
        {
            return Err(Error::parameter(
                "boundary point",
                format!("[{}, {}]", p[0], p[1]),
                "must be finite",
            ));
        }
    }
    let pair = match (
        estimate.valid,
        boundary(Role::EgoLeft),
        boundary(Role::EgoRight),
    ) {
        (true, Some(l), Some(r)) => Some((l, r)),
        _ => None,
    };
    let mut score = MaskScore::default();
    for y in 0..mask.height {
        let span = pair.and_then(|(l, r)| {
            let (xl, xr) = (x_at_y(l, y as f64)?, x_at_y(r, y as f64)?);
            Some((xl.min(xr), xl.max(xr)))
        });
        let row = &mask.pixels[y * mask.width..(y + 1) * mask.width];
        for (x, &pixel) in row.iter().enumerate() {
            let predicted = span.is_some_and(|(lo, hi)| (lo..=hi).contains(&(x as f64)));
            match (pixel, predicted) {
                (MaskPixel::Lane, true) => score.true_positives += 1,
                (MaskPixel::Lane, false) => score.false_negatives += 1,
                (MaskPixel::Other, true) => score.false_positives += 1,
                _ => {}
            }
        }
    }
    Ok(score)
}

/// One KITTI road ground-truth frame: the image's file name and its lane mask's path.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct KittiRoadFrame {
    /// The image's file name (`um_000000.png` for the mask `um_lane_000000.png`).
    pub frame: String,
    /// The mask file.
    pub mask: PathBuf,
}

/// The frames of a KITTI road lane mask `path`, or of every `*_lane_*.png` in the folder
/// `path` (KITTI's `gt_image_2`), sorted by name. The masks are read when scored.
///
/// # Errors
/// [`Error::Io`] when the folder cannot be listed; [`Error::Config`] when it holds no lane
/// masks or a file's name is not `<category>_lane_<number>.png`.
pub fn read_labels(path: &Path) -> Result<Vec<KittiRoadFrame>> {
    let frame = |mask: &Path| -> Result<KittiRoadFrame> {
        let name = mask
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        match name.split_once("_lane_") {
            Some((category, rest)) if !category.is_empty() && rest.ends_with(".png") => {
                Ok(KittiRoadFrame {
                    frame: format!("{category}_{rest}"),
                    mask: mask.to_path_buf(),
                })
            }
            _ => Err(Error::Config(format!(
                "{}: a KITTI road lane mask is named <category>_lane_<number>.png \
                 (gt_image_2/um_lane_000000.png)",
                mask.display()
            ))),
        }
    };
    super::each_file(
        path,
        |name| name.contains("_lane_"),
        "KITTI road lane masks (*_lane_*.png)",
        frame,
    )
}

/// One frame's pixel counts.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KittiRoadFrameScore {
    /// The image's file name.
    pub frame: String,
    /// Its pixel counts.
    pub score: MaskScore,
}

/// The ego-lane pixel counts over every frame, and each frame's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KittiRoadReport {
    /// Pixels summed over the frames.
    pub total: MaskScore,
    /// Precision of the summed pixels (`None` when nothing was predicted).
    pub precision: Option<f64>,
    /// Recall of the summed pixels.
    pub recall: Option<f64>,
    /// F1 of the summed pixels.
    pub f1: Option<f64>,
    /// Each frame, in the ground truth's order.
    pub frames: Vec<KittiRoadFrameScore>,
}

impl KittiRoadReport {
    /// One line a frame: its pixel counts and F1 (`lanepf eval --per-frame`).
    pub fn frames_table(&self) -> String {
        let mut out = String::from("  frame                     TP       FP       FN     F1\n");
        for f in &self.frames {
            let s = f.score;
            out.push_str(&format!(
                "  {:<20} {:>8} {:>8} {:>8}  {}\n",
                f.frame,
                s.true_positives,
                s.false_positives,
                s.false_negatives,
                s.f1().map_or("n/a".into(), |v| format!("{v:.3}"))
            ));
        }
        out
    }
}

impl fmt::Display for KittiRoadReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let t = &self.total;
        writeln!(f, "  KITTI road ego lane (image pixels)   value")?;
        writeln!(
            f,
            "  TP / FP / FN pixels                  {} / {} / {}",
            t.true_positives, t.false_positives, t.false_negatives
        )?;
        writeln!(
            f,
            "  precision                            {}",
            percent(self.precision)
        )?;
        writeln!(
            f,
            "  recall                               {}",
            percent(self.recall)
        )?;
        write!(
            f,
            "  F1                                   {}",
            percent(self.f1)
        )
    }
}

/// Scores predictions (`preds[i]` belongs to `labels[i]`; `None`: no prediction, nothing
/// predicted), reading each frame's mask.
///
/// # Errors
/// [`Error::Config`] when there are no frames; [`Error::Io`] / [`Error::Decode`] when a mask
/// cannot be read; [`Error::Parameter`] for a boundary point that is not finite.
pub fn evaluate(
    labels: &[KittiRoadFrame],
    preds: &[Option<&LaneEstimate>],
) -> Result<KittiRoadReport> {
    if labels.is_empty() {
        return Err(Error::Config("no KITTI road frames to evaluate".into()));
    }
    let nothing = LaneEstimate::default();
    let mut total = MaskScore::default();
    let mut frames = Vec::with_capacity(labels.len());
    for (label, pred) in labels.iter().zip(preds) {
        let mask = read_ego_lane_mask(&label.mask)?;
        let score = score_ego_lane(pred.unwrap_or(&nothing), &mask)?;
        total.true_positives += score.true_positives;
        total.false_positives += score.false_positives;
        total.false_negatives += score.false_negatives;
        frames.push(KittiRoadFrameScore {
            frame: label.frame.clone(),
            score,
        });
    }
    Ok(KittiRoadReport {
        total,
        precision: total.precision(),
        recall: total.recall(),
        f1: total.f1(),
        frames,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lane::Boundary;

    /// A calibration with P2 (fx 700, fy 710, cx 600, cy 170) and a camera 1.6 m above the
    /// road pitched down by `pitch` degrees, yawed left by `yaw` and rolled by `roll`, its
    /// rotation built by the crate's own camera model.
    fn calib(pitch: f64, yaw: f64, roll: f64) -> String {
        // Rows: the camera's X, Y, Z axes in ISO road coordinates (x ahead, y left, z up);
        // KITTI's road axes are x right, y down, z ahead: (-v_y, -v_z, v_x). Its columns are
        // the camera's axes there.
        let iso = crate::camera::road_to_camera_rotation(
            pitch.to_radians(),
            yaw.to_radians(),
            roll.to_radians(),
        );
        let m = nalgebra::Matrix3::from_fn(|i, j| {
            let v = iso.row(j);
            [-v[1], -v[2], v[0]][i]
        });
        let t = [0.01, -1.6, 0.28];
        let tr: Vec<String> = (0..3)
            .flat_map(|i| (0..4).map(move |j| if j < 3 { m[(i, j)] } else { t[i] }))
            .map(|v| format!("{v:e}"))
            .collect();
        format!(
            "P0: 1 0 0 0 0 1 0 0 0 0 1 0\nP2: 7.0e+02 0 6.0e+02 4.4e+01 0 7.1e+02 1.7e+02 0.2 0 0 1 0.003\nTr_cam_to_road: {}\n",
            tr.join(" ")
        )
    }

    #[test]
    fn the_camera_follows_the_calibration() {
        let cam = camera_from_calib(&calib(2.0, 1.0, 0.5), 1242, 375).unwrap();
        assert_eq!(
            (cam.fx, cam.fy, cam.cx, cam.cy),
            (700.0, 710.0, 600.0, 170.0)
        );
        assert!((cam.height_m - 1.6).abs() < 1e-9, "{}", cam.height_m);
        assert!(
            (cam.pitch_deg - 2.0).abs() < 1e-6,
            "pitch {}",
            cam.pitch_deg
        );
        assert!((cam.yaw_deg - 1.0).abs() < 1e-6, "yaw {}", cam.yaw_deg);
        assert!((cam.roll_deg - 0.5).abs() < 1e-6, "roll {}", cam.roll_deg);
        let up = camera_from_calib(&calib(-0.6, -0.4, 0.0), 1242, 375).unwrap();
        assert!((up.pitch_deg + 0.6).abs() < 1e-6 && (up.yaw_deg + 0.4).abs() < 1e-6);
    }

    #[test]
    fn a_broken_calibration_is_an_error() {
        let good = calib(0.0, 0.0, 0.0);
        let no_road: String = good
            .lines()
            .filter(|l| !l.starts_with("Tr_cam_to_road"))
            .collect::<Vec<_>>()
            .join("\n");
        for (text, what) in [
            (no_road, "no `Tr_cam_to_road:`"),
            (good.replace("P2: 7.0e+02", "P2: x"), "bad number"),
            (good.replace("P2: 7.0e+02", "P2: NaN"), "bad number"),
            (good.replace(" 0.003\n", "\n"), "11 numbers"),
            (good.replace("-1.6e0", "1.6e0"), "no usable camera"),
        ] {
            let err = camera_from_calib(&text, 1242, 375).unwrap_err().to_string();
            assert!(err.contains(what), "{what}: {err}");
        }
    }

    /// A 10 x 4 mask: rows 0-1 ignored, rows 2-3 lane in columns 3-6, other elsewhere.
    fn mask() -> EgoLaneMask {
        let mut rgba = Vec::new();
        for y in 0..4 {
            for x in 0..10 {
                let c = match (y, x) {
                    (0..=1, _) => [0, 0, 0],
                    (_, 3..=6) => [255, 0, 255],
                    _ => [255, 0, 0],
                };
                rgba.extend_from_slice(&[c[0], c[1], c[2], 255]);
            }
        }
        EgoLaneMask::from_rgba(&rgba, 10, 4).unwrap()
    }

    fn estimate(valid: bool, left: f64, right: f64) -> LaneEstimate {
        let line = |x: f64| vec![[x, 3.0], [x, 0.0]];
        LaneEstimate {
            valid,
            boundaries: vec![
                Boundary {
                    role: Role::EgoLeft,
                    points: line(left),
                    road_points: Vec::new(),
                },
                Boundary {
                    role: Role::EgoRight,
                    points: line(right),
                    road_points: Vec::new(),
                },
            ],
            ..LaneEstimate::default()
        }
    }

    #[test]
    fn a_folder_gives_its_lane_masks_as_frames() {
        let dir = std::env::temp_dir().join(format!("lanepf-kitti-labels-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let err = read_labels(&dir).unwrap_err().to_string();
        assert!(err.contains("no KITTI road lane masks"), "{err}");
        for name in [
            "umm_lane_000003.png",
            "um_road_000000.png",
            "um_lane_000000.png",
        ] {
            std::fs::write(dir.join(name), b"").unwrap();
        }
        let frames = read_labels(&dir).unwrap();
        let names: Vec<&str> = frames.iter().map(|f| f.frame.as_str()).collect();
        assert_eq!(
            names,
            ["um_000000.png", "umm_000003.png"],
            "road masks are not lanes"
        );
        assert_eq!(frames[0].mask, dir.join("um_lane_000000.png"));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_ego_lane_is_scored_pixel_by_pixel() {
        let m = mask();
        let exact = score_ego_lane(&estimate(true, 3.0, 6.0), &m).unwrap();
        assert_eq!(
            (
                exact.true_positives,
                exact.false_positives,
                exact.false_negatives
            ),
            (8, 0, 0)
        );
        assert_eq!(exact.f1(), Some(1.0));
        // Shifted right by two columns: columns 5-8, of which 5-6 are the lane.
        let shifted = score_ego_lane(&estimate(true, 5.0, 8.0), &m).unwrap();
        assert_eq!(
            (
                shifted.true_positives,
                shifted.false_positives,
                shifted.false_negatives
            ),
            (4, 4, 4)
        );
        assert_eq!(shifted.precision(), Some(0.5));
        // Not valid: nothing predicted.
        let invalid = score_ego_lane(&estimate(false, 3.0, 6.0), &m).unwrap();
        assert_eq!(invalid.false_negatives, 8);
        assert_eq!((invalid.precision(), invalid.recall()), (None, Some(0.0)));
        let mut nan = estimate(true, 3.0, 6.0);
        nan.boundaries[0].points[0][0] = f64::NAN;
        assert!(score_ego_lane(&nan, &m).is_err());
        let short = EgoLaneMask {
            height: 5,
            ..m.clone()
        };
        let err = score_ego_lane(&estimate(true, 3.0, 6.0), &short).unwrap_err();
        assert!(err.to_string().contains("10x5 lane mask"), "{err}");
    }
}
