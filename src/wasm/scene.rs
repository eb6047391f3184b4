//! `Scene` for JavaScript: the named synthetic scenarios with exact ground truth.

use super::camera::camera_from_js;
use super::error::to_js;
use crate::synth::{default_camera, scenario, Eye, Scene, SCENARIOS};
use wasm_bindgen::prelude::*;

/// A named synthetic scenario rendered through a camera.
#[wasm_bindgen(js_name = Scene)]
pub struct JsScene {
    scene: Scene,
    frame: Vec<u8>,
}

/// The scenario names and descriptions: `[{ name, description }, ...]`.
#[wasm_bindgen(unchecked_return_type = "ScenarioInfo[]")]
pub fn scenarios() -> Result<JsValue, JsError> {
    let list: Vec<serde_json::Value> = SCENARIOS
        .iter()
        .map(|(name, about)| serde_json::json!({ "name": name, "description": about }))
        .collect();
    super::to_js_value(&list)
}

fn get(options: &JsValue, key: &str) -> Result<Option<JsValue>, JsError> {
    if options.is_undefined() || options.is_null() {
        return Ok(None);
    }
    let v = js_sys::Reflect::get(options, &JsValue::from_str(key))
        .map_err(|_| JsError::new("scene options must be an object"))?;
    Ok((!v.is_undefined() && !v.is_null()).then_some(v))
}

fn whole_number(options: &JsValue, key: &str, default: f64, max: f64) -> Result<f64, JsError> {
    match get(options, key)? {
        None => Ok(default),
        Some(v) => {
            let n = v
                .as_f64()
                .ok_or_else(|| JsError::new(&format!("scene option `{key}` must be a number")))?;
            if !(n.is_finite() && n >= 0.0 && n <= max && n.fract() == 0.0) {
                return Err(JsError::new(&format!(
                    "scene option `{key}` = {n}: must be a whole number from 0 to {max}"
                )));
            }
            Ok(n)
        }
    }
}

#[wasm_bindgen(js_class = Scene)]
impl JsScene {
    /// `new Scene(name, { seed?, width?, height?, camera? })`: the scenario `name` (see
    /// `scenarios()`), rendered through `camera` (the `camera.json` format) or the default
    /// camera of `width` x `height` (640x480). Throws for an unknown name or bad options.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "ScenarioName")] name: &str,
        #[wasm_bindgen(unchecked_optional_param_type = "SceneOptions")] options: JsValue,
    ) -> Result<JsScene, JsError> {
        let config = scenario(name).map_err(to_js)?;
        let seed = whole_number(&options, "seed", 1.0, 9.007_199_254_740_991e15)? as u64;
        let camera = match get(&options, "camera")? {
            Some(c) => camera_from_js(&c)?,
            None => {
                let w = whole_number(&options, "width", 640.0, 16384.0)? as usize;
                let h = whole_number(&options, "height", 480.0, 16384.0)? as usize;
                default_camera(w, h).map_err(to_js)?
            }
        };
        let scene = Scene::new(config, camera, seed).map_err(to_js)?;
        let frame = vec![0; scene.width() * scene.height() * 4];
        Ok(JsScene { scene, frame })
    }

    /// Image width.
    #[wasm_bindgen(getter)]
    pub fn width(&self) -> usize {
        self.scene.width()
    }

    /// Image height.
    #[wasm_bindgen(getter)]
    pub fn height(&self) -> usize {
        self.scene.height()
    }

    /// The scenario's length in frames (any frame index renders; the road goes on).
    #[wasm_bindgen(getter)]
    pub fn frames(&self) -> u32 {
        self.scene.config().frames
    }

    /// The camera, as a plain `camera.json` object (with the stereo baseline).
    #[wasm_bindgen(unchecked_return_type = "CameraConfig")]
    pub fn camera(&self) -> Result<JsValue, JsError> {
        let mut file = self.scene.camera().to_file();
        file.baseline_m = Some(self.scene.baseline());
        super::to_js_value(&file)
    }

    /// Renders frame `index` of the left camera: a new `Uint8ClampedArray` (width*height*4).
    #[wasm_bindgen(unchecked_return_type = "Uint8ClampedArray<ArrayBuffer>")]
    pub fn render(&mut self, index: u32) -> Result<js_sys::Uint8ClampedArray, JsError> {
        self.scene
            .render(index, Eye::Left, &mut self.frame, None)
            .map_err(to_js)?;
        Ok(js_sys::Uint8ClampedArray::from(&self.frame[..]))
    }

    /// Renders frame `index` of the right camera of the stereo pair.
    #[wasm_bindgen(js_name = renderRight, unchecked_return_type = "Uint8ClampedArray<ArrayBuffer>")]
    pub fn render_right(&mut self, index: u32) -> Result<js_sys::Uint8ClampedArray, JsError> {
        self.scene
            .render(index, Eye::Right, &mut self.frame, None)
            .map_err(to_js)?;
        Ok(js_sys::Uint8ClampedArray::from(&self.frame[..]))
    }

    /// Exact ground truth of frame `index`: `{ frame, valid, boundaries: [{ role, points,
    /// road_points }], lateral_offset_m, heading_rad, curvature_per_m, lane_width_m, state }`.
    #[wasm_bindgen(unchecked_return_type = "Truth")]
    pub fn truth(&self, index: u32) -> Result<JsValue, JsError> {
        super::to_js_value(&self.scene.truth(index))
    }
}
