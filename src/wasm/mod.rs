//! The JavaScript binding: the only module with wasm-bindgen types.
//!
//! Each class wraps a core type (`Camera`, `Scene`, `TestRoad`, `Tracker`, `Calibrator`); every
//! fallible call returns `Result<_, Thrown>`, so JavaScript gets a thrown `Error` with the
//! core's message and its kind in `error.name` (`error.rs`), and the object stays usable.
//! Arguments arrive as `JsValue` and are checked before anything is copied (`args.rs`);
//! option objects are read once, bounded and without re-entrancy (`object.rs`).

mod args;
mod calibrator;
mod camera;
mod deprecation;
mod error;
mod estimate;
mod layers;
mod object;
mod scene;
mod step_input;
mod test_road;
mod to_js;
mod tracker;
mod types;

pub use calibrator::JsCalibrator;
pub use camera::JsCamera;
pub use error::{Kind, Thrown};
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

/// Serialises a core value into a plain JS object: the object of its JSON (so field names are
/// the contract's snake_case names), built without the text (`to_js.rs`).
fn to_js_value<T: serde::Serialize>(value: &T) -> Result<JsValue, Thrown> {
    to_js::to_js(value).map_err(|e| Thrown::input(format!("cannot serialise the result: {e}")))
}
