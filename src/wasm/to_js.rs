//! Core values into plain JS objects, built directly: the object `JSON.parse` gave for
//! serde_json's text of the value, without writing and parsing the text. Field names are the
//! contract's snake_case names, in the same order; numbers are the same `f64`s (a non-finite
//! one is `null`, as serde_json writes it; an `f32` is the `f64` nearest its shortest decimal,
//! as `JSON.parse` read it); `None` and unit are `null`; enums are tagged as serde_json tags
//! them; map keys are serde_json's (a key it refuses is refused with its message).
//!
//! Results are written per frame (an estimate is 800 to 2 000 numbers), so this keeps
//! serde_json's float writer off the hot path, and it is the same speed or faster.

use js_sys::{Array, Object, Reflect};
use serde::ser::{self, Serialize};
use std::fmt;
use wasm_bindgen::JsValue;

/// A serialisation error: serde_json's message for the same value.
#[derive(Debug)]
pub struct ToJsError(String);

impl fmt::Display for ToJsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ToJsError {}

impl ser::Error for ToJsError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        Self(msg.to_string())
    }
}

/// `value` as the plain JS object of its JSON.
///
/// # Errors
/// Those serde_json gives for the value (a custom error of a `Serialize` impl, a map key that
/// is not a string or a number), with its message.
pub fn to_js<T: Serialize + ?Sized>(value: &T) -> Result<JsValue, ToJsError> {
    value.serialize(Ser)
}

/// The serializer: each value becomes its `JsValue`.
struct Ser;

/// An array being filled (sequences and tuples); `variant` wraps it as `{ variant: [...] }`.
struct SeqOut {
    array: Array,
    variant: Option<&'static str>,
}

/// An object being filled (structs and maps); `variant` wraps it as `{ variant: {...} }`;
/// `key` is the map key waiting for its value.
struct MapOut {
    object: Object,
    variant: Option<&'static str>,
    key: Option<JsValue>,
}

/// `{ variant: inner }`, as serde_json writes a non-unit variant.
fn tagged(variant: &'static str, inner: &JsValue) -> JsValue {
    let object = Object::new();
    set(&object, &JsValue::from_str(variant), inner);
    object.into()
}

/// Sets a property of a plain object of our own (which cannot throw).
fn set(object: &Object, key: &JsValue, value: &JsValue) {
    let _ = Reflect::set(object, key, value);
}

/// A number as `JSON.parse` read serde_json's text of it.
fn number(v: f64) -> JsValue {
    if v.is_finite() {
        JsValue::from_f64(v)
    } else {
        JsValue::NULL
    }
}

/// A map key as serde_json writes it (strings as they are, numbers, bools and unit variants
/// as their text), read by serde_json itself (rare: the maps we return have string keys).
fn map_key<K: Serialize + ?Sized>(key: &K) -> Result<JsValue, ToJsError> {
    struct One<'a, K: ?Sized>(&'a K);
    impl<K: Serialize + ?Sized> Serialize for One<'_, K> {
        fn serialize<S: ser::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
            use ser::SerializeMap;
            let mut map = s.serialize_map(Some(1))?;
            map.serialize_entry(self.0, &())?;
            map.end()
        }
    }
    let value = serde_json::to_value(One(key)).map_err(|e| ToJsError(e.to_string()))?;
    match value {
        serde_json::Value::Object(map) => match map.into_iter().next() {
            Some((k, _)) => Ok(JsValue::from_str(&k)),
            None => Err(ToJsError("key must be a string".into())),
        },
        _ => Err(ToJsError("key must be a string".into())),
    }
}

impl ser::Serializer for Ser {
    type Ok = JsValue;
    type Error = ToJsError;
    type SerializeSeq = SeqOut;
    type SerializeTuple = SeqOut;
    type SerializeTupleStruct = SeqOut;
    type SerializeTupleVariant = SeqOut;
    type SerializeMap = MapOut;
    type SerializeStruct = MapOut;
    type SerializeStructVariant = MapOut;

    fn serialize_bool(self, v: bool) -> Result<JsValue, ToJsError> {
        Ok(JsValue::from_bool(v))
    }
    fn serialize_i8(self, v: i8) -> Result<JsValue, ToJsError> {
        self.serialize_i64(v.into())
    }
    fn serialize_i16(self, v: i16) -> Result<JsValue, ToJsError> {
        self.serialize_i64(v.into())
    }
    fn serialize_i32(self, v: i32) -> Result<JsValue, ToJsError> {
        self.serialize_i64(v.into())
    }
    fn serialize_i64(self, v: i64) -> Result<JsValue, ToJsError> {
        // The nearest f64, as `JSON.parse` reads the integer's digits.
        Ok(JsValue::from_f64(v as f64))
    }
    fn serialize_i128(self, v: i128) -> Result<JsValue, ToJsError> {
        Ok(JsValue::from_f64(v as f64))
    }
    fn serialize_u8(self, v: u8) -> Result<JsValue, ToJsError> {
        self.serialize_u64(v.into())
    }
    fn serialize_u16(self, v: u16) -> Result<JsValue, ToJsError> {
        self.serialize_u64(v.into())
    }
    fn serialize_u32(self, v: u32) -> Result<JsValue, ToJsError> {
        self.serialize_u64(v.into())
    }
    fn serialize_u64(self, v: u64) -> Result<JsValue, ToJsError> {
        Ok(JsValue::from_f64(v as f64))
    }
    fn serialize_u128(self, v: u128) -> Result<JsValue, ToJsError> {
        Ok(JsValue::from_f64(v as f64))
    }
    fn serialize_f32(self, v: f32) -> Result<JsValue, ToJsError> {
        if !v.is_finite() {
            return Ok(JsValue::NULL);
        }
        // serde_json writes the f32's shortest decimal, which JSON.parse reads as an f64.
        let text = serde_json::to_string(&v).map_err(|e| ToJsError(e.to_string()))?;
        Ok(number(text.parse().unwrap_or(f64::from(v))))
    }
    fn serialize_f64(self, v: f64) -> Result<JsValue, ToJsError> {
        Ok(number(v))
    }
    fn serialize_char(self, v: char) -> Result<JsValue, ToJsError> {
        Ok(JsValue::from_str(v.encode_utf8(&mut [0; 4])))
    }
    fn serialize_str(self, v: &str) -> Result<JsValue, ToJsError> {
        Ok(JsValue::from_str(v))
    }
    fn serialize_bytes(self, v: &[u8]) -> Result<JsValue, ToJsError> {
        let array = Array::new();
        for &b in v {
            array.push(&JsValue::from_f64(b.into()));
        }
        Ok(array.into())
    }
    fn serialize_none(self) -> Result<JsValue, ToJsError> {
        Ok(JsValue::NULL)
    }
    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<JsValue, ToJsError> {
        value.serialize(self)
    }
    fn serialize_unit(self) -> Result<JsValue, ToJsError> {
        Ok(JsValue::NULL)
    }
    fn serialize_unit_struct(self, _: &'static str) -> Result<JsValue, ToJsError> {
        Ok(JsValue::NULL)
    }
    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
    ) -> Result<JsValue, ToJsError> {
        Ok(JsValue::from_str(variant))
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<JsValue, ToJsError> {
        value.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<JsValue, ToJsError> {
        Ok(tagged(variant, &value.serialize(self)?))
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<SeqOut, ToJsError> {
        Ok(SeqOut {
            array: Array::new(),
            variant: None,
        })
    }
    fn serialize_tuple(self, len: usize) -> Result<SeqOut, ToJsError> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_struct(self, _: &'static str, len: usize) -> Result<SeqOut, ToJsError> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<SeqOut, ToJsError> {
        Ok(SeqOut {
            array: Array::new(),
            variant: Some(variant),
        })
    }
    fn serialize_map(self, _: Option<usize>) -> Result<MapOut, ToJsError> {
        Ok(MapOut {
            object: Object::new(),
            variant: None,
            key: None,
        })
    }
    fn serialize_struct(self, _: &'static str, len: usize) -> Result<MapOut, ToJsError> {
        self.serialize_map(Some(len))
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<MapOut, ToJsError> {
        Ok(MapOut {
            object: Object::new(),
            variant: Some(variant),
            key: None,
        })
    }
}

impl SeqOut {
    fn push<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), ToJsError> {
        self.array.push(&value.serialize(Ser)?);
        Ok(())
    }

    fn done(self) -> JsValue {
        match self.variant {
            Some(variant) => tagged(variant, &self.array),
            None => self.array.into(),
        }
    }
}

/// The four sequence traits of serde, all filled by [`SeqOut::push`]: they differ only in
/// the trait and its element method's name.
macro_rules! seq_out {
    ($($trait:ident :: $method:ident),*) => {$(
        impl ser::$trait for SeqOut {
            type Ok = JsValue;
            type Error = ToJsError;
            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), ToJsError> {
                self.push(value)
            }
            fn end(self) -> Result<JsValue, ToJsError> {
                Ok(self.done())
            }
        }
    )*};
}

seq_out!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field
);

impl MapOut {
    fn field<T: Serialize + ?Sized>(&mut self, key: &str, value: &T) -> Result<(), ToJsError> {
        let value = value.serialize(Ser)?;
        set(&self.object, &JsValue::from_str(key), &value);
        Ok(())
    }

    fn done(self) -> JsValue {
        match self.variant {
            Some(variant) => tagged(variant, &self.object),
            None => self.object.into(),
        }
    }
}

impl ser::SerializeMap for MapOut {
    type Ok = JsValue;
    type Error = ToJsError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), ToJsError> {
        self.key = Some(map_key(key)?);
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), ToJsError> {
        let value = value.serialize(Ser)?;
        let key = self.key.take().unwrap_or(JsValue::NULL);
        set(&self.object, &key, &value);
        Ok(())
    }
    fn end(self) -> Result<JsValue, ToJsError> {
        Ok(self.done())
    }
}

impl ser::SerializeStruct for MapOut {
    type Ok = JsValue;
    type Error = ToJsError;
    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> Result<(), ToJsError> {
        self.field(key, value)
    }
    fn end(self) -> Result<JsValue, ToJsError> {
        Ok(self.done())
    }
}

impl ser::SerializeStructVariant for MapOut {
    type Ok = JsValue;
    type Error = ToJsError;
    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> Result<(), ToJsError> {
        self.field(key, value)
    }
    fn end(self) -> Result<JsValue, ToJsError> {
        Ok(self.done())
    }
}
