//! The JavaScript binding: the only module with wasm-bindgen types.
//!
//! Each class wraps a core type (`Camera`, `Scene`, `TestRoad`, `Tracker`, `Calibrator`); every fallible call returns
//! `Result<_, JsError>`, so JavaScript gets a thrown `Error` with the core's message and the
//! object stays usable.

mod calibrator;
mod camera;
mod error;
mod scene;
mod test_road;
mod tracker;
mod types;

pub use calibrator::JsCalibrator;
pub use camera::JsCamera;
pub use error::to_js;
pub use scene::{scenarios, JsScene};
pub use test_road::JsTestRoad;
pub use tracker::{tracker_ids, JsTracker};

use wasm_bindgen::prelude::*;

/// Installs the panic hook so that a bug shows a readable message in the console.
#[wasm_bindgen(start)]
pub fn start() {
    console_error_panic_hook::set_once();
}

/// The library version.
#[wasm_bindgen]
pub fn version() -> String {
    crate::VERSION.to_string()
}

/// Serialises a core value into a plain JS object (by way of JSON, so field names are the
/// contract's snake_case names).
fn to_js_value<T: serde::Serialize>(value: &T) -> Result<JsValue, JsError> {
    let text = serde_json::to_string(value)
        .map_err(|e| JsError::new(&format!("cannot serialise the result: {e}")))?;
    js_sys::JSON::parse(&text).map_err(|_| JsError::new("cannot parse the result JSON"))
}
