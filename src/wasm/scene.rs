//! `Scene` for JavaScript: the named synthetic scenarios with exact ground truth.

use super::args;
use super::error::{self, input, Kind, Thrown};
use super::estimate::{self, Keep};
use super::object;
use crate::camera::{Camera, CameraFile};
use crate::synth::{draw_scenario, reference_member, Eye, Scene, SCENARIOS};
use crate::Error;
use serde::Deserialize;
use wasm_bindgen::prelude::*;

/// A named synthetic scenario rendered through a camera.
#[wasm_bindgen(js_name = Scene)]
pub struct JsScene {
    scene: Scene,
    frame: Vec<u8>,
}

/// The scenario names and descriptions: `[{ name, description }, ...]`.
#[wasm_bindgen(unchecked_return_type = "ScenarioInfo[]")]
pub fn scenarios() -> Result<JsValue, Thrown> {
    let list: Vec<serde_json::Value> = SCENARIOS
        .iter()
        .map(|(name, about)| serde_json::json!({ "name": name, "description": about }))
        .collect();
    super::to_js_value(&list)
}

/// The options of `new Scene(name, options)`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Options {
    #[serde(default = "default_seed")]
    seed: u64,
    #[serde(default = "default_width")]
    width: usize,
    #[serde(default = "default_height")]
    height: usize,
    #[serde(default)]
    camera: Option<CameraFile>,
    #[serde(default)]
    drawn: bool,
}

fn default_seed() -> u64 {
    1
}

fn default_width() -> usize {
    640
}

fn default_height() -> usize {
    480
}

/// Largest seed: the largest whole number a JS number holds exactly (2^53 - 1).
const MAX_SEED: u64 = (1 << 53) - 1;

#[wasm_bindgen(js_class = Scene)]
impl JsScene {
    /// `new Scene(name, { seed?, width?, height?, camera?, drawn? })`: the scenario `name` (see
    /// `scenarios()`), rendered through `camera` (the `camera.json` format) or else a camera of
    /// `width` x `height` (640x480). By default the family's fixed reference road through the
    /// default camera (the roads the demo shows); with `drawn: true` the member the seed draws
    /// from the family, its road, events and camera (as `lanepf synth --seed`, bit for bit;
    /// `random` picks the family too). Throws for an unknown name or bad options.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "ScenarioName")] name: JsValue,
        #[wasm_bindgen(unchecked_optional_param_type = "SceneOptions")] options: JsValue,
    ) -> Result<JsScene, Thrown> {
        let name = args::name(&name, "scenario name")?;
        let options: Options = object::read_optional(&options, "scene options", Kind::Config)?
            .unwrap_or(Options {
                seed: default_seed(),
                width: default_width(),
                height: default_height(),
                camera: None,
                drawn: false,
            });
        if options.seed > MAX_SEED {
            return Err(error::config(Error::parameter(
                "seed",
                options.seed,
                "must be at most 2^53 - 1",
            )));
        }
        let member = if options.drawn {
            draw_scenario(&name, options.seed)
        } else {
            reference_member(&name, options.seed)
        }
        .map_err(error::config)?;
        // Without a camera, the member's own: the reference mount is the default camera.
        let scene = match &options.camera {
            Some(file) => {
                let camera = Camera::from_file(file).map_err(error::config)?;
                Scene::new(member.config, camera, options.seed)
            }
            None => member.scene(options.width, options.height),
        }
        .map_err(error::config)?;
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
    pub fn camera(&self) -> Result<JsValue, Thrown> {
        let mut file = self.scene.camera().to_file();
        file.baseline_m = Some(self.scene.baseline());
        super::to_js_value(&file)
    }

    /// Renders frame `index` of the left camera: a new `Uint8ClampedArray` (width*height*4).
    #[wasm_bindgen(unchecked_return_type = "Uint8ClampedArray<ArrayBuffer>")]
    pub fn render(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "number")] index: JsValue,
    ) -> Result<js_sys::Uint8ClampedArray, Thrown> {
        let index = args::index(&index, "index")?;
        self.scene
            .render(index, Eye::Left, &mut self.frame, None)
            .map_err(input)?;
        Ok(js_sys::Uint8ClampedArray::from(&self.frame[..]))
    }

    /// Renders frame `index` of the right camera of the stereo pair.
    #[wasm_bindgen(js_name = renderRight, unchecked_return_type = "Uint8ClampedArray<ArrayBuffer>")]
    pub fn render_right(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "number")] index: JsValue,
    ) -> Result<js_sys::Uint8ClampedArray, Thrown> {
        let index = args::index(&index, "index")?;
        self.scene
            .render(index, Eye::Right, &mut self.frame, None)
            .map_err(input)?;
        Ok(js_sys::Uint8ClampedArray::from(&self.frame[..]))
    }

    /// Exact ground truth of frame `index`: `{ frame, valid, boundaries: [{ role, points,
    /// road_points }], lateral_offset_m, heading_rad, curvature_per_m, lane_width_m, state }`,
    /// `state` the motion keys and every paper's parameters (`trackers::papers_truth`).
    #[wasm_bindgen(unchecked_return_type = "Truth")]
    pub fn truth(
        &self,
        #[wasm_bindgen(unchecked_param_type = "number")] index: JsValue,
    ) -> Result<JsValue, Thrown> {
        let index = args::index(&index, "index")?;
        estimate::to_js(
            &crate::trackers::scene_truth(&self.scene, index),
            Keep::Frame,
        )
    }
}
