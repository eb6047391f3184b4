//! The `Tracker` factory for JavaScript: `new Tracker(id, config)`.

use super::error::{from_js_object, to_js};
use crate::trackers::{self, TrackerConfig};
use wasm_bindgen::prelude::*;

/// A lane tracker built by id (see `trackerIds()`).
#[wasm_bindgen(js_name = Tracker)]
pub struct JsTracker {
    inner: Box<dyn trackers::Tracker>,
}

/// The ids `new Tracker(id, ...)` accepts.
#[wasm_bindgen(js_name = trackerIds)]
pub fn tracker_ids() -> Vec<String> {
    trackers::TRACKER_IDS
        .iter()
        .map(|s| s.to_string())
        .collect()
}

#[wasm_bindgen(js_class = Tracker)]
impl JsTracker {
    /// `new Tracker(id, { camera, particles?, seed?, ...options })`; throws an `Error` for an
    /// unknown id (listing the available ones) or a bad configuration.
    #[wasm_bindgen(constructor)]
    pub fn new(id: &str, config: JsValue) -> Result<JsTracker, JsError> {
        let config: TrackerConfig = from_js_object(&config, "tracker config")?;
        let inner = trackers::create(id, &config).map_err(to_js)?;
        Ok(JsTracker { inner })
    }

    /// The tracker's id.
    #[wasm_bindgen(getter)]
    pub fn id(&self) -> String {
        self.inner.id().to_string()
    }

    /// Processes one RGBA frame (`ImageData.data`) and returns the estimate.
    pub fn step(&mut self, rgba: &[u8], width: usize, height: usize) -> Result<JsValue, JsError> {
        let estimate = self.inner.step(rgba, width, height).map_err(to_js)?;
        super::to_js_value(&estimate)
    }

    /// The particle cloud after the last step as a `Float32Array` of `particleStride` numbers
    /// per particle (adachi-mmpf: model r 1..4, q in metres, w in metres, weight).
    pub fn particles(&self) -> js_sys::Float32Array {
        js_sys::Float32Array::from(&self.inner.particles()[..])
    }

    /// Numbers per particle in `particles()`.
    #[wasm_bindgen(getter, js_name = particleStride)]
    pub fn particle_stride(&self) -> usize {
        self.inner.particle_stride()
    }

    /// Forgets the past.
    pub fn reset(&mut self) {
        self.inner.reset();
    }
}
