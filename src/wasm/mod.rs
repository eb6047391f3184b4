//! The JavaScript binding: the only module with wasm-bindgen types.
//!
//! Each class wraps a core type (`Camera`, `Scene`, `TestRoad`, `Tracker`, `Calibrator`); every
//! fallible call returns `Result<_, Thrown>`, so JavaScript gets a thrown `Error` with the
//! core's message and its kind in `error.name` (`error.rs`), and the object stays usable.
//! Arguments arrive as `JsValue` and are checked before anything is copied (`args.rs`);
//! option objects are read once, bounded and without re-entrancy (`object.rs`).
//!
//! The package is two wasm modules built from this one binding with different features: the
//! main one (`lanepf`, feature `wasm-track`: `Camera`, `Tracker`, `Calibrator` and their
//! functions) and the simulator's (`lanepf/sim`, feature `wasm-sim`: `Scene`, `TestRoad`,
//! `scenarios()`), so that a page that only tracks does not load the simulator. Both have
//! `version()`, `start()`, the errors and the TypeScript types; the default feature `wasm` has
//! both halves in one (what `cargo test` and `make test-wasm` build).

// A one-module build leaves some of the shared helpers unused.
#![cfg_attr(
    not(all(feature = "wasm-track", feature = "wasm-sim")),
    allow(dead_code, unused_imports)
)]

mod args;
#[cfg(feature = "wasm-track")]
mod calibrator;
mod camera;
#[cfg(feature = "wasm-track")]
mod deprecation;
mod error;
mod estimate;
#[cfg(feature = "wasm-track")]
mod layers;
mod object;
#[cfg(feature = "wasm-sim")]
mod scene;
#[cfg(feature = "wasm-track")]
mod step_input;
#[cfg(feature = "wasm-sim")]
mod test_road;
mod to_js;
#[cfg(feature = "wasm-track")]
mod tracker;
mod types;

#[cfg(feature = "wasm-track")]
pub use calibrator::JsCalibrator;
#[cfg(feature = "wasm-track")]
pub use camera::JsCamera;
pub use error::{Kind, Thrown};
#[cfg(feature = "wasm-sim")]
pub use scene::{scenarios, JsScene};
#[cfg(feature = "wasm-sim")]
pub use test_road::JsTestRoad;
#[cfg(feature = "wasm-track")]
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
