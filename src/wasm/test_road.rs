//! `TestRoad` for JavaScript: the straight synthetic road with ground truth.

use super::args;
use super::camera::camera_from_js;
use super::error::{self, input, Kind, Thrown};
use super::estimate::{self, Keep};
use super::object;
use crate::synth::{TestRoad, TestRoadConfig};
use wasm_bindgen::prelude::*;

/// A synthetic straight road rendered through a camera, with exact ground truth.
#[wasm_bindgen(js_name = TestRoad)]
pub struct JsTestRoad {
    road: TestRoad,
    frame: Vec<u8>,
}

#[wasm_bindgen(js_class = TestRoad)]
impl JsTestRoad {
    /// `new TestRoad(camera, { lane_width_m?, marking_width_m?, dash_length_m?, dash_period_m?,
    /// speed_mps?, fps?, sway_amplitude_m?, sway_period_s?, max_distance_m? })`.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_param_type = "CameraConfig")] camera: JsValue,
        #[wasm_bindgen(unchecked_optional_param_type = "TestRoadOptions")] options: JsValue,
    ) -> Result<JsTestRoad, Thrown> {
        let camera = camera_from_js(&camera)?;
        let config: TestRoadConfig =
            object::read_optional(&options, "test road options", Kind::Config)?.unwrap_or_default();
        let road = TestRoad::new(camera, config).map_err(error::config)?;
        let frame = vec![0; road.width() * road.height() * 4];
        Ok(JsTestRoad { road, frame })
    }

    /// Image width.
    #[wasm_bindgen(getter)]
    pub fn width(&self) -> usize {
        self.road.width()
    }

    /// Image height.
    #[wasm_bindgen(getter)]
    pub fn height(&self) -> usize {
        self.road.height()
    }

    /// Renders frame `index` and returns a new `Uint8ClampedArray` (width*height*4, RGBA) that
    /// can go straight into `new ImageData(...)`.
    #[wasm_bindgen(unchecked_return_type = "Uint8ClampedArray<ArrayBuffer>")]
    pub fn render(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "number")] index: JsValue,
    ) -> Result<js_sys::Uint8ClampedArray, Thrown> {
        let index = args::index(&index, "index")?;
        self.road.render(index, &mut self.frame).map_err(input)?;
        Ok(js_sys::Uint8ClampedArray::from(&self.frame[..]))
    }

    /// Ground truth of frame `index`: `{ valid, boundaries: [{ role, points, road_points }],
    /// lateral_offset_m, heading_rad, curvature_per_m, lane_width_m, ... }`.
    #[wasm_bindgen(unchecked_return_type = "LaneEstimate")]
    pub fn truth(
        &self,
        #[wasm_bindgen(unchecked_param_type = "number")] index: JsValue,
    ) -> Result<JsValue, Thrown> {
        let index = args::index(&index, "index")?;
        estimate::to_js(&self.road.truth(index), Keep::Neither)
    }
}
