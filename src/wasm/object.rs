//! Option and config objects from JavaScript, read safely: once, by `JSON.stringify` with a
//! replacer (every JS exception caught: cyclic objects, throwing getters and Proxy traps, a
//! BigInt), bounded in size (1 MiB of JSON) and depth (serde_json's 128 levels), then checked
//! for NaN, infinities, functions and `null` anywhere, and deserialised with the key path of
//! any unknown key or wrong type in the message.
//!
//! One policy for every object: a key left out (or `undefined`) takes its default; `null`, an
//! unknown key or a wrong type is an error naming the key path, e.g. `dld.gama` or
//! `process_sd[5]`.

use super::args::{describe, exception_message};
use super::error::{Kind, Thrown};
use serde::de::DeserializeOwned;
use serde_json::Value;
use wasm_bindgen::prelude::*;

/// Largest object accepted, in characters of its JSON.
const MAX_JSON: u32 = 1 << 20;

/// Marks a value `JSON.stringify` would drop or turn into `null` (NaN, an infinity, a function,
/// a symbol, a BigInt) so that the check after parsing can name it; `#` then marks a number.
const MARK: char = '\u{1}';

/// Reads the object `value` (an argument called `what`, e.g. `tracker config`) into `T`.
///
/// # Errors
/// An error of `kind` naming `what` (and the key path) for a missing or non-object value, one
/// that cannot be read, and any value `T` does not accept.
pub fn read<T: DeserializeOwned>(value: &JsValue, what: &str, kind: Kind) -> Result<T, Thrown> {
    deserialize(read_value(value, what, kind)?, what, "", kind)
}

/// As [`read`], with `undefined` or `null` (the argument left out) giving `None`.
///
/// # Errors
/// As [`read`].
pub fn read_optional<T: DeserializeOwned>(
    value: &JsValue,
    what: &str,
    kind: Kind,
) -> Result<Option<T>, Thrown> {
    if value.is_undefined() || value.is_null() {
        return Ok(None);
    }
    read(value, what, kind).map(Some)
}

/// Reads the object `value` into a checked JSON value (an object, with no `null`, NaN,
/// infinity, function, symbol or BigInt anywhere in it).
///
/// # Errors
/// As [`read`].
pub fn read_value(value: &JsValue, what: &str, kind: Kind) -> Result<Value, Thrown> {
    let fail = |message: String| Thrown::new(kind, message);
    if value.is_undefined() || value.is_null() {
        return Err(fail(format!("{what} is missing: pass an object")));
    }
    if !value.is_object() || value.is_function() {
        return Err(fail(format!(
            "{what} must be an object, not {}",
            describe(value)
        )));
    }
    let replacer = Closure::<dyn Fn(JsValue, JsValue) -> JsValue>::new(mark_unrepresentable);
    let text = js_sys::JSON::stringify_with_replacer(value, replacer.as_ref())
        .map_err(|e| fail(format!("{what} cannot be read: {}", exception_message(&e))))?;
    drop(replacer);
    // Not always a string: a `toJSON` that returns undefined makes `JSON.stringify` return
    // undefined, and reading its length would throw through this frame.
    let text = JsValue::from(text)
        .dyn_into::<js_sys::JsString>()
        .map_err(|_| fail(format!("{what} gives no JSON: its toJSON returns nothing")))?;
    if text.length() > MAX_JSON {
        return Err(fail(format!(
            "{what} is too large: {} characters of JSON, at most {MAX_JSON}",
            text.length()
        )));
    }
    // The text back as a tree of plain values (no getters, proxies or cycles left to meet),
    // read into a `Value` here rather than by serde_json's text parser: the same values, and
    // the parser's code (about 21 kB of the wasm) is not in the package (issue 21 part 5).
    let tree = parse(&text)
        .map_err(|e| fail(format!("{what} cannot be read: {}", exception_message(&e))))?;
    let parsed = tree_value(&tree, 0).map_err(|m| fail(format!("{what} cannot be read: {m}")))?;
    if !parsed.is_object() {
        return Err(fail(format!(
            "{what} must be an object, but its JSON is {}",
            first_chars(&String::from(text), 40)
        )));
    }
    check(&parsed, "").map_err(|m| fail(format!("invalid {what}: {m}")))?;
    Ok(parsed)
}

/// Deserialises a checked JSON value (at key path `path` inside `what`; empty for the whole).
///
/// # Errors
/// An error of `kind` naming `what` and the key path of the first value `T` refuses.
pub fn deserialize<T: DeserializeOwned>(
    value: Value,
    what: &str,
    path: &str,
    kind: Kind,
) -> Result<T, Thrown> {
    crate::keypath::deserialize(&value).map_err(|(inner, e)| {
        let at = match (path, inner.as_str()) {
            ("", ".") => String::new(),
            (p, ".") => format!("{p}: "),
            ("", i) => format!("{i}: "),
            (p, i) => format!("{p}.{i}: "),
        };
        Thrown::new(kind, format!("invalid {what}: {at}{e}"))
    })
}

/// The `JSON.stringify` replacer: NaN, infinities, functions, symbols and BigInts become marked
/// strings (instead of `null`, nothing, or a thrown TypeError); everything else passes.
fn mark_unrepresentable(_key: JsValue, value: JsValue) -> JsValue {
    let what = match value.as_f64() {
        Some(x) if x.is_finite() => return value,
        Some(x) if x.is_nan() => "#NaN",
        Some(x) if x > 0.0 => "#Infinity",
        Some(_) => "#-Infinity",
        None if value.is_function() => "a function",
        None if value.is_symbol() => "a symbol",
        None if value.is_bigint() => "a BigInt",
        None => return value,
    };
    JsValue::from_str(&format!("{MARK}{what}"))
}

#[wasm_bindgen]
extern "C" {
    /// `JSON.parse` of a JS string as it is (js_sys's takes a `&str`: the text would be
    /// copied out of JavaScript and back).
    #[wasm_bindgen(catch, js_namespace = JSON, js_name = parse)]
    fn parse(text: &js_sys::JsString) -> Result<JsValue, JsValue>;
}

/// serde_json's nesting limit, which its parser applied here before: a value inside 128 arrays
/// or objects is refused.
const MAX_DEPTH: usize = 128;

/// The `Value` serde_json's `from_str` gave for the JSON text of `value`, a tree `JSON.parse`
/// made (so only null, booleans, finite numbers, strings, arrays and plain objects), inside
/// `open` arrays and objects.
fn tree_value(value: &JsValue, open: usize) -> Result<Value, String> {
    if value.is_null() {
        return Ok(Value::Null);
    }
    if let Some(b) = value.as_bool() {
        return Ok(Value::Bool(b));
    }
    if let Some(x) = value.as_f64() {
        return Ok(number(x));
    }
    if let Some(s) = value.as_string() {
        return Ok(Value::String(s));
    }
    if open + 1 >= MAX_DEPTH {
        return Err(format!("deeper than {} levels", MAX_DEPTH - 1));
    }
    if js_sys::Array::is_array(value) {
        let items = js_sys::Array::from(value);
        let mut out = Vec::with_capacity(items.length() as usize);
        for item in items.iter() {
            out.push(tree_value(&item, open + 1)?);
        }
        return Ok(Value::Array(out));
    }
    let mut map = serde_json::Map::new();
    for entry in js_sys::Object::entries(value.unchecked_ref()).iter() {
        let entry = js_sys::Array::from(&entry);
        let key = entry.get(0).as_string().unwrap_or_default();
        map.insert(key, tree_value(&entry.get(1), open + 1)?);
    }
    Ok(Value::Object(map))
}

/// A finite number as serde_json read `JSON.stringify`'s text of it: a whole number written
/// without an exponent (below 1e21) is an integer when its digits fit a `u64` (an `i64` when
/// negative), anything else an `f64`. Above 2^53 the digits are JavaScript's shortest ones
/// (2^60 is written 1152921504606847000), so those are read from the same text.
fn number(x: f64) -> Value {
    const EXACT: f64 = 9_007_199_254_740_992.0; // 2^53
    if x.fract() == 0.0 && x.abs() < 1e21 {
        if x.abs() < EXACT {
            // (-0 is written "0".)
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            return if x >= 0.0 {
                Value::from(x as u64)
            } else {
                Value::from(x as i64)
            };
        }
        let text = String::from(
            js_sys::Number::from(x)
                .to_string_with_radix(10)
                .unwrap_or_default(),
        );
        if let Ok(u) = text.parse::<u64>() {
            return Value::from(u);
        }
        if let Ok(i) = text.parse::<i64>() {
            return Value::from(i);
        }
    }
    serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number)
}

/// At most `n` characters of `text`, with `...` when cut.
fn first_chars(text: &str, n: usize) -> String {
    match text.char_indices().nth(n) {
        Some((i, _)) => format!("{}...", &text[..i]),
        None => text.to_string(),
    }
}

/// Finds the first marked or `null` value and names its key path.
fn check(value: &Value, path: &str) -> Result<(), String> {
    match value {
        Value::Null => Err(format!(
            "{path} is null: leave the key out for its default, or give a value"
        )),
        Value::String(s) => match s.strip_prefix(MARK) {
            Some(what) => match what.strip_prefix('#') {
                Some(number) => Err(format!("{path} is {number}: it must be a finite number")),
                None => Err(format!("{path} is {what}: it must be a JSON value")),
            },
            None => Ok(()),
        },
        Value::Array(items) => items
            .iter()
            .enumerate()
            .try_for_each(|(i, v)| check(v, &format!("{path}[{i}]"))),
        Value::Object(map) => map.iter().try_for_each(|(k, v)| {
            if path.is_empty() {
                check(v, k)
            } else {
                check(v, &format!("{path}.{k}"))
            }
        }),
        Value::Bool(_) | Value::Number(_) => Ok(()),
    }
}
