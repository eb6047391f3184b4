//! `Camera` for JavaScript: built from a plain object in the `camera.json` format.

use super::args;
use super::error::{config, input, Kind, Thrown};
use super::object;
use crate::camera::{Camera, CameraFile};
use crate::num_text::Num;
use wasm_bindgen::prelude::*;

/// A validated camera (intrinsics, distortion, height and angles). In the main module only:
/// the simulator's takes cameras as plain objects (`camera_from_js`).
#[cfg(feature = "wasm-track")]
#[wasm_bindgen(js_name = Camera)]
pub struct JsCamera {
    inner: Camera,
}

/// Reads a JS camera object into a validated core camera.
pub fn camera_from_js(value: &JsValue) -> Result<Camera, Thrown> {
    let file: CameraFile = object::read(value, "camera", Kind::Config)?;
    Camera::from_file(&file).map_err(config)
}

#[cfg(feature = "wasm-track")]
#[wasm_bindgen(js_class = Camera)]
impl JsCamera {
    /// `new Camera({ width, height, fx, fy, cx, cy, height_m, pitch_deg, yaw_deg?, roll_deg?,
    /// k1?, k2?, p1?, p2?, k3?, baseline_m? })`; throws an `Error` naming any bad field.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "CameraConfig")] config: JsValue,
    ) -> Result<JsCamera, Thrown> {
        Ok(JsCamera {
            inner: camera_from_js(&config)?,
        })
    }

    /// Image width in pixels.
    #[wasm_bindgen(getter)]
    pub fn width(&self) -> usize {
        self.inner.width()
    }

    /// Image height in pixels.
    #[wasm_bindgen(getter)]
    pub fn height(&self) -> usize {
        self.inner.height()
    }

    /// Pixel `[u, v]` of the road point (x forward, y left, metres); throws when the point is
    /// behind the camera.
    #[wasm_bindgen(js_name = projectRoad)]
    pub fn project_road(
        &self,
        #[wasm_bindgen(unchecked_param_type = "number")] x: JsValue,
        #[wasm_bindgen(unchecked_param_type = "number")] y: JsValue,
    ) -> Result<Vec<f64>, Thrown> {
        let (x, y) = (args::number(&x, "x")?, args::number(&y, "y")?);
        self.inner
            .road_to_pixel(x, y)
            .map(|p| p.to_vec())
            .ok_or_else(|| {
                Thrown::input(format!(
                    "road point ({}, {}) is behind the camera",
                    Num(x),
                    Num(y)
                ))
            })
    }

    /// The pixels of many road points in one call: `xy` holds x0, y0, x1, y1, ... (metres),
    /// the answer u0, v0, u1, v1, ..., NaN for a point behind the camera (what `projectRoad`
    /// throws for). One call instead of one per point: the demo's top-view table projects
    /// 64 000 road cells. Throws when `xy` has an odd length.
    #[wasm_bindgen(js_name = projectRoadPoints)]
    pub fn project_road_points(&self, xy: &[f64]) -> Result<Vec<f64>, Thrown> {
        if xy.len() % 2 != 0 {
            return Err(Thrown::input(format!(
                "projectRoadPoints: xy holds x, y pairs, got {} numbers",
                xy.len()
            )));
        }
        Ok(xy
            .chunks_exact(2)
            .flat_map(|p| {
                self.inner
                    .road_to_pixel(p[0], p[1])
                    .unwrap_or([f64::NAN, f64::NAN])
            })
            .collect())
    }

    /// Road point `[x, y]` (metres) seen at pixel (u, v); throws above the horizon.
    #[wasm_bindgen(js_name = roadPoint)]
    pub fn road_point(
        &self,
        #[wasm_bindgen(unchecked_param_type = "number")] u: JsValue,
        #[wasm_bindgen(unchecked_param_type = "number")] v: JsValue,
    ) -> Result<Vec<f64>, Thrown> {
        let (u, v) = (args::number(&u, "u")?, args::number(&v, "v")?);
        self.inner
            .pixel_to_road(u, v)
            .map(|p| p.to_vec())
            .map_err(input)
    }

    /// The camera as a plain object in the `camera.json` format.
    #[wasm_bindgen(js_name = toJSON, unchecked_return_type = "CameraConfig")]
    pub fn to_json(&self) -> Result<JsValue, Thrown> {
        super::to_js_value(&self.inner.to_file())
    }
}

#[cfg(feature = "wasm-track")]
impl JsCamera {
    /// The core camera.
    pub fn inner(&self) -> &Camera {
        &self.inner
    }
}
