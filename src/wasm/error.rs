//! Conversion of lanepf errors into thrown JavaScript `Error`s.

use wasm_bindgen::JsError;

/// Turns a core error into a `JsError` with the same, human-readable message.
pub fn to_js(e: crate::Error) -> JsError {
    JsError::new(&e.to_string())
}

/// Reads a JS value (a plain object) into a serde type by way of `JSON.stringify`, with errors
/// that name what was being read.
pub fn from_js_object<T: serde::de::DeserializeOwned>(
    value: &wasm_bindgen::JsValue,
    what: &str,
) -> Result<T, JsError> {
    if value.is_undefined() || value.is_null() {
        return Err(JsError::new(&format!("{what} is missing: pass an object")));
    }
    reject_non_finite(value, what)?;
    let text = js_sys::JSON::stringify(value)
        .map_err(|_| JsError::new(&format!("{what} cannot be converted to JSON")))?;
    let text: String = text.into();
    serde_json::from_str(&text)
        .map_err(|e| JsError::new(&format!("invalid {what}: {e} (given {text})")))
}

/// `JSON.stringify` silently turns NaN and Infinity into `null`; find them first and name them.
fn reject_non_finite(value: &wasm_bindgen::JsValue, path: &str) -> Result<(), JsError> {
    if let Some(x) = value.as_f64() {
        if !x.is_finite() {
            return Err(JsError::new(&format!(
                "{path} is {x}: it must be a finite number"
            )));
        }
        return Ok(());
    }
    if value.is_object() && !value.is_function() {
        let entries = js_sys::Object::entries(&js_sys::Object::from(value.clone()));
        for entry in entries.iter() {
            let pair = js_sys::Array::from(&entry);
            let key = pair.get(0).as_string().unwrap_or_default();
            reject_non_finite(&pair.get(1), &format!("{path}.{key}"))?;
        }
    }
    Ok(())
}
