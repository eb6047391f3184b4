//! `Calibrator` for JavaScript: camera auto-calibration (pitch, yaw, height) from the lane
//! markings of the frames it is fed (see `crate::calib`).

use super::args;
use super::error::{config, input, Kind, Thrown};
use super::object;
use crate::calib::{Calibrator, CalibratorConfig, FrameObservation};
use crate::camera::CameraFile;
use serde::{Deserialize, Serialize};
use wasm_bindgen::prelude::*;

/// The options of `new Calibrator(options)`: the frame size, the optional intrinsics and the
/// calibrator's own options (missing ones take `CalibratorConfig::default()`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Options {
    width: usize,
    height: usize,
    #[serde(default)]
    intrinsics: Option<CameraFile>,
    #[serde(default)]
    lane_width_m: Option<f64>,
    #[serde(default)]
    hfov_deg: Option<f64>,
    #[serde(default)]
    stable_frames: Option<usize>,
    #[serde(default)]
    max_bend_px: Option<f64>,
    #[serde(default)]
    tangent_yaw: Option<bool>,
    #[serde(default)]
    tangent_yaw_after: Option<usize>,
}

impl Options {
    fn config(&self) -> CalibratorConfig {
        let d = CalibratorConfig::default();
        CalibratorConfig {
            lane_width_m: self.lane_width_m.unwrap_or(d.lane_width_m),
            hfov_deg: self.hfov_deg.unwrap_or(d.hfov_deg),
            stable_frames: self.stable_frames.unwrap_or(d.stable_frames),
            max_bend_px: self.max_bend_px.unwrap_or(d.max_bend_px),
            tangent_yaw: self.tangent_yaw.unwrap_or(d.tangent_yaw),
            tangent_yaw_after: self.tangent_yaw_after.unwrap_or(d.tangent_yaw_after),
        }
    }
}

/// What `feed` returns: the frame's verdict, small enough to post every frame.
#[derive(Serialize)]
struct FeedStatus {
    /// The frame measured the camera.
    used: bool,
    /// Both ego boundaries were found.
    ego_found: bool,
    straight: bool,
    stable: bool,
    vanishing_point: Option<[f64; 2]>,
    frames_used: usize,
    frames_seen: usize,
}

/// Estimates a camera's pitch, yaw and height from lane markings, frame by frame.
#[wasm_bindgen(js_name = Calibrator)]
pub struct JsCalibrator {
    inner: Calibrator,
    /// The last frame's pixels, copied out of the JS array (reused).
    frame: Vec<u8>,
}

#[wasm_bindgen(js_class = Calibrator)]
impl JsCalibrator {
    /// `new Calibrator({ width, height, intrinsics?, lane_width_m?, hfov_deg?, stable_frames?,
    /// max_bend_px?, tangent_yaw?, tangent_yaw_after? })`: a calibrator for `width` x `height` frames.
    /// `intrinsics` (a camera object of the same size; its pose is ignored) gives the focal
    /// length, principal point and lens; without it the focal length comes from `hfov_deg` (60)
    /// and the principal point is the image centre. Throws an `Error` naming a bad or unknown
    /// option.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "CalibratorOptions")] options: JsValue,
    ) -> Result<JsCalibrator, Thrown> {
        let options: Options = object::read(&options, "calibrator options", Kind::Config)?;
        let inner = Calibrator::new(
            options.width,
            options.height,
            options.intrinsics.as_ref(),
            options.config(),
        )
        .map_err(config)?;
        Ok(JsCalibrator {
            inner,
            frame: Vec::new(),
        })
    }

    /// Frame width, pixels.
    #[wasm_bindgen(getter)]
    pub fn width(&self) -> usize {
        self.inner.size()[0]
    }

    /// Frame height, pixels.
    #[wasm_bindgen(getter)]
    pub fn height(&self) -> usize {
        self.inner.size()[1]
    }

    /// The options in effect: `{ lane_width_m, hfov_deg, stable_frames, max_bend_px,
    /// tangent_yaw, tangent_yaw_after }`.
    #[wasm_bindgen(
        unchecked_return_type = "Required<Omit<CalibratorOptions, 'width' | 'height' | 'intrinsics'>>"
    )]
    pub fn options(&self) -> Result<JsValue, Thrown> {
        super::to_js_value(self.inner.config())
    }

    /// Feeds one RGBA frame of the calibrator's size; returns `{ used, ego_found, straight,
    /// stable, vanishing_point, frames_used, frames_seen }`. Throws for a frame of another
    /// size or type; the calibrator is then unchanged.
    #[wasm_bindgen(unchecked_return_type = "CalibrationStatus")]
    pub fn feed(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "Rgba")] rgba: JsValue,
        #[wasm_bindgen(unchecked_param_type = "number")] width: JsValue,
        #[wasm_bindgen(unchecked_param_type = "number")] height: JsValue,
    ) -> Result<JsValue, Thrown> {
        let (w, h) = (args::side(&width, "width")?, args::side(&height, "height")?);
        let [cw, ch] = self.inner.size();
        if (w, h) != (cw, ch) {
            return Err(Thrown::input(format!(
                "{w}x{h}: this calibrator takes {cw}x{ch} frames"
            )));
        }
        args::rgba(&rgba, "rgba", [w, h], &mut self.frame)?;
        let obs = self.inner.feed_rgba(&self.frame, w, h).map_err(input)?;
        let (used, ego_found, straight, stable, vanishing_point) = (
            obs.used,
            obs.ego.is_some(),
            obs.straight,
            obs.stable,
            obs.vanishing_point,
        );
        super::to_js_value(&FeedStatus {
            used,
            ego_found,
            straight,
            stable,
            vanishing_point,
            frames_used: self.inner.frames_used(),
            frames_seen: self.inner.frames_seen(),
        })
    }

    /// The current estimate, or `null` before any frame measured the camera: `{ camera,
    /// confidence, frames_used, frames_seen, pitch_sd_deg, yaw_sd_deg, height_sd_m,
    /// vanishing_point, intrinsics_known, yaw_from_tangent }`; `camera` goes straight into `new Tracker(id, {
    /// camera })`.
    #[wasm_bindgen(unchecked_return_type = "CalibrationEstimate | null")]
    pub fn estimate(&self) -> Result<JsValue, Thrown> {
        match self.inner.estimate() {
            Some(e) => super::to_js_value(&e),
            None => Ok(JsValue::NULL),
        }
    }

    /// What the last frame showed, for drawing: `{ lines: [{ x_ref, y_ref, slope, support,
    /// y_top, y_bottom, bend }], ego: [left, right] | null, vanishing_point, straight, stable,
    /// used }`; line i runs x = x_ref + slope (y - y_ref) from y_top to y_bottom, in
    /// undistorted pixels; `ego` indexes `lines`.
    #[wasm_bindgen(unchecked_return_type = "CalibrationObservation")]
    pub fn observation(&self) -> Result<JsValue, Thrown> {
        let obs: &FrameObservation = self.inner.last_observation();
        super::to_js_value(obs)
    }

    /// The last frame's marking pixels as a `Float32Array` of x, y pairs (undistorted pixels).
    #[wasm_bindgen(js_name = markingPixels)]
    pub fn marking_pixels(&self) -> js_sys::Float32Array {
        let xy: Vec<f32> = self
            .inner
            .marking_pixels()
            .flat_map(|[x, y]| [x as f32, y as f32])
            .collect();
        js_sys::Float32Array::from(&xy[..])
    }

    /// Forgets every frame (a new video, or after the camera moved).
    pub fn reset(&mut self) {
        self.inner.reset();
    }
}
