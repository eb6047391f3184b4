//! Lane estimates as JavaScript gets them: the core's `LaneEstimate` without the fields only
//! the command line fills in. `ms` (the step's time, written by `lanepf track`) would always be
//! 0 here, and `frame` (the file name) always `''` from a tracker, so both are left out; a
//! scene's ground truth keeps `frame`, the file name `lanepf synth` writes for that frame.
//! Two typed fields are added from `state`: `ess` and adachi-mmpf's `model_probabilities`.

use super::error::Thrown;
use crate::lane::LaneEstimate;
use wasm_bindgen::{JsCast, JsValue};

/// Which of the command line's fields an estimate keeps in JavaScript.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Keep {
    /// Neither `frame` nor `ms`: a tracker's estimate, a test road's truth.
    Neither,
    /// `frame` (a scene's ground truth, named like the file `lanepf synth` writes), not `ms`.
    Frame,
}

/// `estimate` as a plain JS object without `ms`, and without `frame` unless `keep` says so
/// (the other keys in the core type's order, as before).
///
/// # Errors
/// As [`super::to_js_value`].
pub fn to_js(estimate: &LaneEstimate, keep: Keep) -> Result<JsValue, Thrown> {
    let value = super::to_js_value(estimate)?;
    let object: &js_sys::Object = value.unchecked_ref();
    // A plain object of our own (`to_js.rs`): deleting its own data properties cannot throw.
    let _ = js_sys::Reflect::delete_property(object, &"ms".into());
    if keep == Keep::Neither {
        let _ = js_sys::Reflect::delete_property(object, &"frame".into());
    }
    // The typed fields read from `state` (`LaneEstimate::ess`, `model_probabilities`): set on
    // a plain object of our own, which cannot throw.
    if let Some(ess) = estimate.ess() {
        let _ = js_sys::Reflect::set(object, &"ess".into(), &ess.into());
    }
    if let Some(p) = estimate.model_probabilities() {
        let [a, b, c, d] = p.map(JsValue::from);
        let array = js_sys::Array::of4(&a, &b, &c, &d);
        let _ = js_sys::Reflect::set(object, &"model_probabilities".into(), &array);
    }
    Ok(value)
}
