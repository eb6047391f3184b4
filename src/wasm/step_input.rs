//! The arguments of `step` and `beginFrame`, in either form:
//!
//! - `step(frame, options?)`: `frame` is an `ImageData` or any `{ data, width, height }` with
//!   RGBA bytes, and `options` a `{ right?, motion? }` object (`right` a frame of the same kind,
//!   the right camera's for `danescu-stereo`; `motion` an `EgoMotion`), so one call carries
//!   what `setRight` and `setEgoMotion` would otherwise have to precede it with;
//! - `step(rgba, width, height)`: the bytes and the size, as before.
//!
//! Everything is read and checked here before the tracker is touched, so a call that throws
//! leaves the tracker as it was: no motion applied, no right frame pending.

use super::args::{self, describe, exception_message};
use super::error::{Kind, Thrown};
use super::object;
use crate::trackers::EgoMotion;
use wasm_bindgen::prelude::*;

#[wasm_bindgen]
extern "C" {
    /// `Object.keys(value)`, with a throwing Proxy trap returned as an error rather than
    /// thrown through this frame.
    #[wasm_bindgen(catch, js_namespace = Object, js_name = keys)]
    fn object_keys(value: &JsValue) -> Result<js_sys::Array, JsValue>;
}

/// The keys a `step` options object may have.
const OPTION_KEYS: [&str; 2] = ["right", "motion"];

/// A frame read from JavaScript: its size, with the bytes copied into the caller's buffer.
pub type Size = [usize; 2];

/// What a `step` / `beginFrame` call carries besides the left frame, checked.
#[derive(Debug, Default)]
pub struct Extras {
    /// The right frame was copied into the caller's right buffer, with this size.
    pub right: Option<Size>,
    /// The car's motion for this frame, already checked ([`EgoMotion::check`]).
    pub motion: Option<EgoMotion>,
}

/// Reads `step(first, second, third)` in either form: the left frame into `left`, a right
/// frame (if given) into `right`, and the motion.
///
/// # Errors
/// A [`Kind::Input`] error naming the argument for a frame that is not RGBA bytes of its
/// size, an options object that is not one or has an unknown key or a `null`, a bad motion,
/// or a right frame of another size than the left.
pub fn read(
    first: &JsValue,
    second: Option<&JsValue>,
    third: Option<&JsValue>,
    left: &mut Vec<u8>,
    right: &mut Vec<u8>,
) -> Result<(Size, Extras), Thrown> {
    if second.is_some_and(|s| s.as_f64().is_some()) || third.is_some() {
        // step(rgba, width, height)
        let width = second.cloned().unwrap_or(JsValue::UNDEFINED);
        let height = third.cloned().unwrap_or(JsValue::UNDEFINED);
        let size = [args::side(&width, "width")?, args::side(&height, "height")?];
        args::rgba(first, "rgba", size, left)?;
        return Ok((size, Extras::default()));
    }
    let mut extras = Extras::default();
    let mut right_value = None;
    if let Some(options) = second {
        let (r, m) = options_of(options)?;
        right_value = r;
        if let Some(m) = m {
            let motion: EgoMotion = object::read(&m, "step options: motion", Kind::Input)?;
            motion
                .check()
                .map_err(|e| Thrown::input(format!("step options: motion: {e}")))?;
            extras.motion = Some(motion);
        }
    }
    let size = frame(first, "frame", left)?;
    if let Some(r) = right_value {
        let right_size = frame(&r, "step options: right", right)?;
        if right_size != size {
            return Err(Thrown::input(format!(
                "step options: right is {}x{} but the frame is {}x{}: both cameras' frames \
                 have one size",
                right_size[0], right_size[1], size[0], size[1]
            )));
        }
        extras.right = Some(right_size);
    }
    Ok((size, extras))
}

/// The `right` and `motion` of a `step` options object (`undefined` for either: not given).
fn options_of(options: &JsValue) -> Result<(Option<JsValue>, Option<JsValue>), Thrown> {
    const WHAT: &str = "step options";
    if !options.is_object() || options.is_function() || args::is_frame_bytes(options) {
        return Err(Thrown::input(format!(
            "{WHAT} must be an object {{ right?, motion? }} (or pass the frame's width and \
             height after its bytes), not {}",
            describe(options)
        )));
    }
    let keys = object_keys(options)
        .map_err(|e| Thrown::input(format!("{WHAT} cannot be read: {}", exception_message(&e))))?;
    for key in keys.iter() {
        let key = key.as_string().unwrap_or_default();
        if !OPTION_KEYS.contains(&key.as_str()) {
            return Err(Thrown::input(format!(
                "{WHAT}: unknown key `{key}`, expected `right` or `motion`"
            )));
        }
    }
    let mut out = [None, None];
    for (slot, key) in out.iter_mut().zip(OPTION_KEYS) {
        let value = get(options, key, WHAT)?;
        if value.is_null() {
            return Err(Thrown::input(format!(
                "{WHAT}: {key} is null: leave it out instead"
            )));
        }
        if !value.is_undefined() {
            *slot = Some(value);
        }
    }
    let [right, motion] = out;
    Ok((right, motion))
}

/// Copies a frame object (`ImageData`, `{ data, width, height }`) into `out`; returns its
/// size.
fn frame(value: &JsValue, what: &str, out: &mut Vec<u8>) -> Result<Size, Thrown> {
    if args::is_frame_bytes(value) {
        return Err(Thrown::input(format!(
            "{what} is bare RGBA bytes: pass an ImageData or {{ data, width, height }}, or the \
             width and height after the bytes (step(rgba, width, height))"
        )));
    }
    if !value.is_object() || value.is_function() {
        return Err(Thrown::input(format!(
            "{what} must be an ImageData or {{ data, width, height }} of RGBA bytes, not {}",
            describe(value)
        )));
    }
    let width = get(value, "width", what)?;
    let height = get(value, "height", what)?;
    let data = get(value, "data", what)?;
    let size = [
        args::side(&width, &format!("{what}.width"))?,
        args::side(&height, &format!("{what}.height"))?,
    ];
    args::rgba(&data, &format!("{what}.data"), size, out)?;
    Ok(size)
}

/// `value[key]`, with a throwing getter or Proxy trap returned as an error.
fn get(value: &JsValue, key: &str, what: &str) -> Result<JsValue, Thrown> {
    js_sys::Reflect::get(value, &key.into()).map_err(|e| {
        Thrown::input(format!(
            "{what}: {key} cannot be read: {}",
            exception_message(&e)
        ))
    })
}
