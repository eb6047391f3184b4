//! `Camera` for JavaScript: built from a plain object in the `camera.json` format.

use super::error::{from_js_object, to_js};
use crate::camera::{Camera, CameraFile};
use wasm_bindgen::prelude::*;

/// A validated camera (intrinsics, distortion, height and angles).
#[wasm_bindgen(js_name = Camera)]
pub struct JsCamera {
    inner: Camera,
}

/// Reads a JS camera object into a validated core camera.
pub fn camera_from_js(value: &JsValue) -> Result<Camera, JsError> {
    let file: CameraFile = from_js_object(value, "camera")?;
    Camera::from_file(&file).map_err(to_js)
}

fn finite(name: &str, v: f64) -> Result<f64, JsError> {
    crate::error::require_finite(name, v).map_err(to_js)
}

#[wasm_bindgen(js_class = Camera)]
impl JsCamera {
    /// `new Camera({ width, height, fx, fy, cx, cy, height_m, pitch_deg, yaw_deg?, roll_deg?,
    /// k1?, k2?, p1?, p2?, k3?, baseline_m? })`; throws an `Error` naming any bad field.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "CameraConfig")] config: JsValue,
    ) -> Result<JsCamera, JsError> {
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
    pub fn project_road(&self, x: f64, y: f64) -> Result<Vec<f64>, JsError> {
        let (x, y) = (finite("x", x)?, finite("y", y)?);
        self.inner
            .road_to_pixel(x, y)
            .map(|p| p.to_vec())
            .ok_or_else(|| JsError::new(&format!("road point ({x}, {y}) is behind the camera")))
    }

    /// Road point `[x, y]` (metres) seen at pixel (u, v); throws above the horizon.
    #[wasm_bindgen(js_name = roadPoint)]
    pub fn road_point(&self, u: f64, v: f64) -> Result<Vec<f64>, JsError> {
        let (u, v) = (finite("u", u)?, finite("v", v)?);
        self.inner
            .pixel_to_road(u, v)
            .map(|p| p.to_vec())
            .map_err(to_js)
    }

    /// The camera as a plain object in the `camera.json` format.
    #[wasm_bindgen(js_name = toJSON, unchecked_return_type = "CameraConfig")]
    pub fn to_json(&self) -> Result<JsValue, JsError> {
        let text = serde_json::to_string(&self.inner.to_file())
            .map_err(|e| JsError::new(&format!("cannot serialise the camera: {e}")))?;
        js_sys::JSON::parse(&text).map_err(|_| JsError::new("cannot parse the camera JSON"))
    }
}

impl JsCamera {
    /// The core camera.
    pub fn inner(&self) -> &Camera {
        &self.inner
    }
}
