//! Plain arguments from JavaScript (ids, numbers, frames), checked on the `JsValue` before
//! anything is copied into wasm memory.
//!
//! The bound functions take `JsValue` rather than `&str`, `usize` or `&[u8]`: wasm-bindgen's
//! glue would coerce a string to a number, wrap 2^32 + 320 to 320, and allocate
//! `rgba.length` bytes for any object with a `length` (a negative or huge one traps). Nothing
//! here calls JavaScript that can throw without catching it: an exception passing through a
//! wasm frame would leave the object it was called on locked.

use super::error::Thrown;
use crate::num_text::Num;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

#[wasm_bindgen]
extern "C" {
    /// `ArrayBuffer.isView(value)`: true only for real typed arrays and `DataView`s (a Proxy or
    /// an object with a typed array's prototype is not one); never throws.
    #[wasm_bindgen(js_namespace = ArrayBuffer, js_name = isView)]
    fn is_view(value: &JsValue) -> bool;

    /// A `Uint8Array` seen through a `set` that returns a thrown exception instead.
    #[wasm_bindgen(extends = js_sys::Object, js_name = Uint8Array)]
    type ByteView;

    /// `TypedArray.prototype.set(source)`.
    #[wasm_bindgen(method, catch, js_name = set)]
    fn set(this: &ByteView, source: &JsValue) -> Result<(), JsValue>;
}

/// Longest id or name accepted, characters.
const MAX_NAME: u32 = 64;

/// A string argument such as a tracker id (`what`: `tracker id`), at most 64 characters.
///
/// # Errors
/// A [`super::error::Kind::Config`] error naming `what` for anything else.
pub fn name(value: &JsValue, what: &str) -> Result<String, Thrown> {
    let text = value.dyn_ref::<js_sys::JsString>().ok_or_else(|| {
        Thrown::config(format!("{what} must be a string, not {}", describe(value)))
    })?;
    if text.length() > MAX_NAME {
        return Err(Thrown::config(format!(
            "{what} is {} characters long: no {what} is longer than {MAX_NAME}",
            text.length()
        )));
    }
    Ok(String::from(text))
}

/// A finite number argument.
///
/// # Errors
/// A [`super::error::Kind::Input`] error naming `what` for a non-number (a numeric string
/// too), NaN or an infinity.
pub fn number(value: &JsValue, what: &str) -> Result<f64, Thrown> {
    match value.as_f64() {
        Some(x) if x.is_finite() => Ok(x),
        Some(x) => Err(Thrown::input(format!(
            "{what} is {}: it must be a finite number",
            show(x)
        ))),
        None => Err(Thrown::input(format!(
            "{what} must be a number, not {}",
            describe(value)
        ))),
    }
}

/// A whole-number argument from `min` to `max`.
///
/// # Errors
/// A [`super::error::Kind::Input`] error naming `what` and the range for anything else.
pub fn whole(value: &JsValue, what: &str, min: f64, max: f64) -> Result<f64, Thrown> {
    let x = number(value, what)?;
    if x.fract() != 0.0 || x < min || x > max {
        return Err(Thrown::input(format!(
            "{what} is {}: it must be a whole number from {} to {}",
            show(x),
            show(min),
            show(max)
        )));
    }
    Ok(x)
}

/// A frame side in pixels: a whole number from 1 to [`crate::image::MAX_SIDE`].
///
/// # Errors
/// As [`whole`].
pub fn side(value: &JsValue, what: &str) -> Result<usize, Thrown> {
    Ok(whole(value, what, 1.0, crate::image::MAX_SIDE as f64)? as usize)
}

/// A frame index: a whole number from 0 to 2^32 - 1.
///
/// # Errors
/// As [`whole`].
pub fn index(value: &JsValue, what: &str) -> Result<u32, Thrown> {
    Ok(whole(value, what, 0.0, f64::from(u32::MAX))? as u32)
}

/// Whether `value` is a real `Uint8Array` or `Uint8ClampedArray` (what a frame's bytes are).
pub fn is_frame_bytes(value: &JsValue) -> bool {
    is_view(value)
        && (value.is_instance_of::<js_sys::Uint8Array>()
            || value.is_instance_of::<js_sys::Uint8ClampedArray>())
}

/// Copies a `width` x `height` RGBA frame (`Uint8Array` or `Uint8ClampedArray`) into `out`,
/// reusing its allocation; anything else, or an array of another length, is refused before
/// anything is allocated or copied.
///
/// # Errors
/// A [`super::error::Kind::Input`] error naming `what` and what it was.
pub fn rgba(
    value: &JsValue,
    what: &str,
    [width, height]: [usize; 2],
    out: &mut Vec<u8>,
) -> Result<(), Thrown> {
    if !is_frame_bytes(value) {
        return Err(Thrown::input(format!(
            "{what} must be a Uint8Array or Uint8ClampedArray of RGBA pixels (ImageData.data), \
             not {}",
            describe(value)
        )));
    }
    let length = js_sys::Reflect::get(value, &"length".into())
        .ok()
        .and_then(|n| n.as_f64())
        .ok_or_else(|| Thrown::input(format!("{what}: its length cannot be read")))?;
    let expected = width * height * 4;
    if length != expected as f64 {
        return Err(Thrown::input(format!(
            "{what} has {} bytes but a {width}x{height} RGBA frame needs {expected} \
             (width*height*4)",
            show(length)
        )));
    }
    out.clear();
    out.resize(expected, 0);
    // SAFETY: the view covers `out`, which lives and is not moved or resized until the copy
    // returns; a growth of wasm memory during the copy only detaches the view (JS checks it).
    let view = unsafe { js_sys::Uint8Array::view_mut_raw(out.as_mut_ptr(), out.len()) };
    view.unchecked_ref::<ByteView>().set(value).map_err(|e| {
        Thrown::input(format!(
            "{what} cannot be copied: {}",
            exception_message(&e)
        ))
    })
}

/// A number as JavaScript writes it, roughly: `Infinity` rather than Rust's `inf`, whole numbers
/// in full up to 1e19 (`4294967936`), other numbers to 6 significant digits as [`Num`] writes
/// them (`640.5`, `1e300`).
pub fn show(x: f64) -> String {
    if x.is_infinite() {
        return if x > 0.0 { "Infinity" } else { "-Infinity" }.into();
    }
    if x == x.trunc() && x.abs() < 1e19 {
        let whole = x.abs() as u64;
        return if x < 0.0 {
            format!("-{whole}")
        } else {
            whole.to_string()
        };
    }
    Num(x).to_string()
}

/// The message of a caught exception, read without running anything that can throw.
pub fn exception_message(e: &JsValue) -> String {
    if let Some(text) = e.as_string() {
        return text;
    }
    js_sys::Reflect::get(e, &"message".into())
        .ok()
        .and_then(|m| m.as_string())
        .unwrap_or_else(|| describe(e))
}

/// What a JS value is, for a message: its type (`null`, `undefined`, `string`, `number`,
/// `object`, ...), or `an array`, `a Float32Array`, ... for common objects.
pub fn describe(value: &JsValue) -> String {
    if value.is_null() {
        return "null".into();
    }
    if value.is_function() {
        return "a function".into();
    }
    if value.is_object() {
        for (name, yes) in [
            ("an array", value.is_instance_of::<js_sys::Array>()),
            (
                "an ArrayBuffer",
                value.is_instance_of::<js_sys::ArrayBuffer>(),
            ),
            (
                "a Float32Array",
                value.is_instance_of::<js_sys::Float32Array>(),
            ),
            (
                "a Float64Array",
                value.is_instance_of::<js_sys::Float64Array>(),
            ),
            (
                "a Uint16Array",
                value.is_instance_of::<js_sys::Uint16Array>(),
            ),
            ("an Int8Array", value.is_instance_of::<js_sys::Int8Array>()),
        ] {
            if yes {
                return name.into();
            }
        }
        return "an object".into();
    }
    if let Some(x) = value.as_f64() {
        return format!("the number {}", show(x));
    }
    if let Some(s) = value.dyn_ref::<js_sys::JsString>() {
        return if s.length() <= MAX_NAME {
            format!("the string {}", crate::keypath::quoted(&String::from(s)))
        } else {
            format!("a string of {} characters", s.length())
        };
    }
    value
        .js_typeof()
        .as_string()
        .unwrap_or_else(|| "unknown".into())
}
