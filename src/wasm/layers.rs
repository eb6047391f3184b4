//! A tracker's cue layers as JavaScript objects: every field as `Layer`'s JSON names it, but
//! `values` a `Float32Array` (one copy of the core's `f32`s) rather than an array of JSON
//! numbers. danescu-stereo's layers hold about 230 000 values a frame: by way of JSON they were
//! formatted, parsed and kept as boxed numbers; as typed arrays they are one memcpy each, and
//! the worker can transfer them.

use super::error::Thrown;
use crate::trackers::{Layer, PlaneAxes};
use js_sys::{Array, Float32Array, Object, Reflect};
use wasm_bindgen::JsValue;

/// `layers` as an array of plain objects (`kind`, the layer's fields, `values: Float32Array`).
///
/// # Errors
/// Only if setting a property on a new plain object threw, which it does not.
pub fn to_js(layers: &[Layer]) -> Result<JsValue, Thrown> {
    let out = Array::new();
    for layer in layers {
        let o = Object::new();
        let set = |key: &str, value: JsValue| {
            Reflect::set(&o, &key.into(), &value)
                .map(drop)
                .map_err(|_| Thrown::input(format!("cannot set a layer's `{key}`")))
        };
        let values = match layer {
            Layer::Histogram {
                name,
                axis,
                start,
                step,
                values,
            } => {
                set("kind", "histogram".into())?;
                set("name", name.into())?;
                set("axis", axis.into())?;
                set("start", (*start).into())?;
                set("step", (*step).into())?;
                values
            }
            Layer::Grid {
                name,
                width,
                height,
                x0,
                y0,
                cell,
                values,
            } => {
                set("kind", "grid".into())?;
                set("name", name.into())?;
                set("width", (*width as f64).into())?;
                set("height", (*height as f64).into())?;
                set("x0", (*x0).into())?;
                set("y0", (*y0).into())?;
                set("cell", (*cell).into())?;
                values
            }
            Layer::Plane {
                name,
                width,
                height,
                axes:
                    PlaneAxes {
                        x_axis,
                        x0,
                        dx,
                        y_axis,
                        y0,
                        dy,
                    },
                values,
            } => {
                set("kind", "plane".into())?;
                set("name", name.into())?;
                set("width", (*width as f64).into())?;
                set("height", (*height as f64).into())?;
                set("x_axis", x_axis.into())?;
                set("x0", (*x0).into())?;
                set("dx", (*dx).into())?;
                set("y_axis", y_axis.into())?;
                set("y0", (*y0).into())?;
                set("dy", (*dy).into())?;
                values
            }
        };
        set("values", Float32Array::from(&values[..]).into())?;
        out.push(&o);
    }
    Ok(out.into())
}
