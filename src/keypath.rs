//! Reads a `serde_json::Value` into a typed value and names the key path of the first value it
//! refuses (`dld.gama`, `process_sd[5]`): the tracker options, the camera and the binding's
//! option objects all come through here.
//!
//! One small deserializer over `&Value` instead of `serde_path_to_error` wrapped around
//! serde_json's own: the errors are serde_json's (the same constructors, so the same messages)
//! and the path is the one `serde_path_to_error` gives (the deepest key or index the error
//! passed through, `.` for the whole), but each type's reader is instantiated once, not once
//! per wrapper layer, which took about 45 kB off the wasm (CHANGELOG, issue 21 part 5).
//! Every `deserialize_*` but option, enum, newtype struct, identifier and struct goes through
//! `deserialize_any`: for a JSON value that calls the visitor method serde_json's typed
//! methods call, and the visitor's default refusal gives the message serde_json's typed
//! methods give. One difference on purpose: a struct must be a JSON object (serde_json also
//! read an array as the fields in order, which no one writes on purpose and which kept a
//! second reader of every struct in the wasm); an array there is refused with `invalid type:
//! sequence, expected struct ...`.

use serde::de::{self, DeserializeOwned, DeserializeSeed, Unexpected, Visitor};
use serde_json::{Map, Value};
use std::cell::RefCell;
use std::fmt::{self, Write as _};

/// What went wrong, in serde_json's words: its error messages, written here rather than by
/// serde's `Unexpected` (whose `{:?}` of a string the wasm then need not carry; issue 21
/// part 5). A string is quoted as Rust's `{:?}` quotes it, but for characters beyond ASCII,
/// which are written as they are. Boxed, a thin pointer as serde_json's error is: a wider
/// error makes every reader's result wider (14.5 kB more wasm).
#[derive(Debug)]
#[allow(clippy::box_collection)] // the thin pointer is the point
pub(crate) struct Error(Box<String>);

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Error {}

impl de::Error for Error {
    #[cold]
    fn custom<T: fmt::Display>(msg: T) -> Self {
        Error(Box::new(msg.to_string()))
    }

    #[cold]
    fn invalid_type(unexp: Unexpected, exp: &dyn de::Expected) -> Self {
        Error(Box::new(format!(
            "invalid type: {}, expected {exp}",
            Shown(unexp)
        )))
    }

    #[cold]
    fn invalid_value(unexp: Unexpected, exp: &dyn de::Expected) -> Self {
        Error(Box::new(format!(
            "invalid value: {}, expected {exp}",
            Shown(unexp)
        )))
    }
}

/// An unexpected value as serde_json's errors name it.
struct Shown<'a>(Unexpected<'a>);

impl fmt::Display for Shown<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            Unexpected::Unit => f.write_str("null"),
            // serde_json's float writer (zmij), as its message has it, through serde_json's
            // `Number` (a direct call would build a second, larger copy of zmij into the wasm).
            Unexpected::Float(v) => match serde_json::Number::from_f64(v) {
                Some(n) => write!(f, "floating point `{n}`"),
                None if v.is_nan() => f.write_str("floating point `NaN`"),
                None if v > 0.0 => f.write_str("floating point `inf`"),
                None => f.write_str("floating point `-inf`"),
            },
            Unexpected::Bool(b) => write!(f, "boolean `{b}`"),
            Unexpected::Unsigned(i) => write!(f, "integer `{i}`"),
            Unexpected::Signed(i) => write!(f, "integer `{i}`"),
            Unexpected::Char(c) => write!(f, "character `{c}`"),
            Unexpected::Str(s) => write!(f, "string {}", quoted(s)),
            Unexpected::Other(other) => f.write_str(other),
            Unexpected::Bytes(_) => f.write_str("byte array"),
            Unexpected::Option => f.write_str("Option value"),
            Unexpected::NewtypeStruct => f.write_str("newtype struct"),
            Unexpected::Seq => f.write_str("sequence"),
            Unexpected::Map => f.write_str("map"),
            Unexpected::Enum => f.write_str("enum"),
            Unexpected::UnitVariant => f.write_str("unit variant"),
            Unexpected::NewtypeVariant => f.write_str("newtype variant"),
            Unexpected::TupleVariant => f.write_str("tuple variant"),
            Unexpected::StructVariant => f.write_str("struct variant"),
        }
    }
}

/// `s` in double quotes with Rust's `{:?}` escapes for ASCII (`\"`, `\\`, `\n`, `\r`, `\t`,
/// `\0`, other control characters as `\u{1b}`); characters beyond ASCII as they are.
pub(crate) fn quoted(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            '\0' => out.push_str("\\0"),
            c if c.is_ascii_control() => {
                let _ = write!(out, "\\u{{{:x}}}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Reads `value` into `T`.
///
/// # Errors
/// The key path of the first value `T` refuses (`.` for the whole value) and serde_json's
/// error.
pub(crate) fn deserialize<T: DeserializeOwned>(value: &Value) -> Result<T, (String, Error)> {
    let track = Track(RefCell::new(None));
    T::deserialize(ValueDe {
        value,
        chain: &Chain::Root,
        track: &track,
    })
    .map_err(|e| {
        let path = track.0.into_inner().unwrap_or_default();
        (if path.is_empty() { ".".into() } else { path }, e)
    })
}

/// Where a value sits in the whole, innermost last.
enum Chain<'a> {
    Root,
    Key(&'a Chain<'a>, &'a str),
    Index(&'a Chain<'a>, usize),
}

impl Chain<'_> {
    fn write(&self, out: &mut String) {
        match self {
            Chain::Root => {}
            Chain::Key(parent, key) => {
                parent.write(out);
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(key);
            }
            Chain::Index(parent, index) => {
                parent.write(out);
                let _ = write!(out, "[{index}]");
            }
        }
    }
}

/// The path of the first error, kept by the innermost place it passed through.
struct Track(RefCell<Option<String>>);

impl Track {
    /// Keeps `chain` as the error's path unless a deeper place has already.
    #[inline(never)]
    fn mark(&self, chain: &Chain) {
        let mut path = self.0.borrow_mut();
        if path.is_none() {
            let mut out = String::new();
            chain.write(&mut out);
            *path = Some(out);
        }
    }

    fn trigger(&self, chain: &Chain, error: Error) -> Error {
        self.mark(chain);
        error
    }
}

/// A result leaving the value at `chain`: an error there gets that path (unless it has a
/// deeper one). Checked in place rather than by `map_err`, which moved every read value.
trait At {
    fn at(self, track: &Track, chain: &Chain) -> Self;
}

impl<T> At for Result<T, Error> {
    #[inline(always)]
    fn at(self, track: &Track, chain: &Chain) -> Self {
        if self.is_err() {
            track.mark(chain);
        }
        self
    }
}

struct ValueDe<'a, 'de> {
    value: &'de Value,
    chain: &'a Chain<'a>,
    track: &'a Track,
}

fn unexpected(value: &Value) -> Unexpected<'_> {
    match value {
        Value::Null => Unexpected::Unit,
        Value::Bool(b) => Unexpected::Bool(*b),
        Value::Number(n) => match (n.as_u64(), n.as_i64()) {
            (Some(u), _) => Unexpected::Unsigned(u),
            (None, Some(i)) => Unexpected::Signed(i),
            _ => Unexpected::Float(n.as_f64().unwrap_or(f64::NAN)),
        },
        Value::String(s) => Unexpected::Str(s),
        Value::Array(_) => Unexpected::Seq,
        Value::Object(_) => Unexpected::Map,
    }
}

impl<'a, 'de> ValueDe<'a, 'de> {
    fn fail(&self, error: Error) -> Error {
        self.track.trigger(self.chain, error)
    }

    fn seq<V: Visitor<'de>>(&self, items: &'de [Value], visitor: V) -> Result<V::Value, Error> {
        let mut access = SeqDe {
            items: items.iter(),
            index: 0,
            chain: self.chain,
            track: self.track,
        };
        let out = visitor.visit_seq(&mut access)?;
        match access.items.len() {
            0 => Ok(out),
            _ => Err(de::Error::invalid_length(
                items.len(),
                &"fewer elements in array",
            )),
        }
    }

    fn map<V: Visitor<'de>>(
        &self,
        map: &'de Map<String, Value>,
        visitor: V,
    ) -> Result<V::Value, Error> {
        let mut access = MapDe {
            entries: map.iter(),
            value: None,
            chain: self.chain,
            track: self.track,
        };
        let out = visitor.visit_map(&mut access)?;
        match access.entries.len() {
            0 => Ok(out),
            _ => Err(de::Error::invalid_length(
                map.len(),
                &"fewer elements in map",
            )),
        }
    }

    fn any<V: Visitor<'de>>(&self, visitor: V) -> Result<V::Value, Error> {
        match self.value {
            Value::Null => visitor.visit_unit(),
            Value::Bool(b) => visitor.visit_bool(*b),
            Value::Number(n) => match (n.as_u64(), n.as_i64(), n.as_f64()) {
                (Some(u), _, _) => visitor.visit_u64(u),
                (None, Some(i), _) => visitor.visit_i64(i),
                (None, None, Some(f)) => visitor.visit_f64(f),
                _ => visitor.visit_unit(),
            },
            Value::String(s) => visitor.visit_borrowed_str(s),
            Value::Array(items) => self.seq(items, visitor),
            Value::Object(map) => self.map(map, visitor),
        }
    }
}

impl<'de> de::Deserializer<'de> for ValueDe<'_, 'de> {
    type Error = Error;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        self.any(visitor).at(self.track, self.chain)
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.value {
            Value::Null => visitor.visit_none(),
            _ => visitor.visit_some(ValueDe { ..self }),
        }
        .at(self.track, self.chain)
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, Error> {
        visitor
            .visit_newtype_struct(ValueDe { ..self })
            .at(self.track, self.chain)
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        let (variant, value) = match self.value {
            Value::String(s) => (s.as_str(), None),
            Value::Object(map) => {
                let mut entries = map.iter();
                match (entries.next(), entries.next()) {
                    (Some((k, v)), None) => (k.as_str(), Some(v)),
                    _ => {
                        return Err(self.fail(de::Error::invalid_value(
                            Unexpected::Map,
                            &"map with a single key",
                        )))
                    }
                }
            }
            other => {
                return Err(self.fail(de::Error::invalid_type(unexpected(other), &"string or map")))
            }
        };
        visitor
            .visit_enum(EnumDe {
                variant,
                value,
                chain: self.chain,
                track: self.track,
            })
            .at(self.track, self.chain)
    }

    fn deserialize_identifier<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Error> {
        match self.value {
            Value::String(s) => visitor.visit_borrowed_str(s),
            other => Err(de::Error::invalid_type(unexpected(other), &visitor)),
        }
        .at(self.track, self.chain)
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        match self.value {
            Value::Object(map) => self.map(map, visitor),
            other => Err(de::Error::invalid_type(unexpected(other), &visitor)),
        }
        .at(self.track, self.chain)
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string
        bytes byte_buf unit unit_struct seq tuple tuple_struct map ignored_any
    }
}

struct SeqDe<'a, 'de> {
    items: std::slice::Iter<'de, Value>,
    index: usize,
    chain: &'a Chain<'a>,
    track: &'a Track,
}

impl<'de> de::SeqAccess<'de> for SeqDe<'_, 'de> {
    type Error = Error;

    #[inline(never)]
    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, Error> {
        let Some(value) = self.items.next() else {
            return Ok(None);
        };
        let chain = Chain::Index(self.chain, self.index);
        self.index += 1;
        seed.deserialize(ValueDe {
            value,
            chain: &chain,
            track: self.track,
        })
        .map(Some)
        .at(self.track, &chain)
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.items.len())
    }
}

struct MapDe<'a, 'de> {
    entries: serde_json::map::Iter<'de>,
    value: Option<(&'de str, &'de Value)>,
    chain: &'a Chain<'a>,
    track: &'a Track,
}

impl<'de> de::MapAccess<'de> for MapDe<'_, 'de> {
    type Error = Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, Error> {
        let Some((key, value)) = self.entries.next() else {
            return Ok(None);
        };
        self.value = Some((key, value));
        let key_de = de::value::BorrowedStrDeserializer::<Error>::new(key);
        seed.deserialize(key_de)
            .map(Some)
            .at(self.track, &Chain::Key(self.chain, key))
    }

    #[inline(never)]
    fn next_value_seed<V: DeserializeSeed<'de>>(&mut self, seed: V) -> Result<V::Value, Error> {
        let Some((key, value)) = self.value.take() else {
            return Err(de::Error::custom("value is missing"));
        };
        let chain = Chain::Key(self.chain, key);
        seed.deserialize(ValueDe {
            value,
            chain: &chain,
            track: self.track,
        })
        .at(self.track, &chain)
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.entries.len())
    }
}

struct EnumDe<'a, 'de> {
    variant: &'de str,
    value: Option<&'de Value>,
    chain: &'a Chain<'a>,
    track: &'a Track,
}

impl<'a, 'de> de::EnumAccess<'de> for EnumDe<'a, 'de> {
    type Error = Error;
    type Variant = VariantDe<'a, 'de>;

    fn variant_seed<V: DeserializeSeed<'de>>(
        self,
        seed: V,
    ) -> Result<(V::Value, Self::Variant), Error> {
        let name = de::value::BorrowedStrDeserializer::<Error>::new(self.variant);
        let tag = seed.deserialize(name)?;
        Ok((
            tag,
            VariantDe {
                variant: self.variant,
                value: self.value,
                chain: self.chain,
                track: self.track,
            },
        ))
    }
}

struct VariantDe<'a, 'de> {
    variant: &'de str,
    value: Option<&'de Value>,
    chain: &'a Chain<'a>,
    track: &'a Track,
}

impl<'de> de::VariantAccess<'de> for VariantDe<'_, 'de> {
    type Error = Error;

    fn unit_variant(self) -> Result<(), Error> {
        match self.value {
            Some(value) => de::Deserialize::deserialize(ValueDe {
                value,
                chain: &Chain::Key(self.chain, self.variant),
                track: self.track,
            }),
            None => Ok(()),
        }
    }

    fn newtype_variant_seed<T: DeserializeSeed<'de>>(self, seed: T) -> Result<T::Value, Error> {
        let chain = Chain::Key(self.chain, self.variant);
        match self.value {
            Some(value) => seed
                .deserialize(ValueDe {
                    value,
                    chain: &chain,
                    track: self.track,
                })
                .at(self.track, &chain),
            None => Err(self.track.trigger(
                &chain,
                de::Error::invalid_type(Unexpected::UnitVariant, &"newtype variant"),
            )),
        }
    }

    fn tuple_variant<V: Visitor<'de>>(self, _len: usize, visitor: V) -> Result<V::Value, Error> {
        let chain = Chain::Key(self.chain, self.variant);
        let at = ValueDe {
            value: &Value::Null,
            chain: &chain,
            track: self.track,
        };
        match self.value {
            Some(Value::Array(items)) if items.is_empty() => visitor.visit_unit(),
            Some(Value::Array(items)) => at.seq(items, visitor),
            Some(other) => Err(de::Error::invalid_type(unexpected(other), &"tuple variant")),
            None => Err(de::Error::invalid_type(
                Unexpected::UnitVariant,
                &"tuple variant",
            )),
        }
        .at(at.track, at.chain)
    }

    fn struct_variant<V: Visitor<'de>>(
        self,
        _fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Error> {
        let chain = Chain::Key(self.chain, self.variant);
        let at = ValueDe {
            value: &Value::Null,
            chain: &chain,
            track: self.track,
        };
        match self.value {
            Some(Value::Object(map)) => at.map(map, visitor),
            Some(other) => Err(de::Error::invalid_type(
                unexpected(other),
                &"struct variant",
            )),
            None => Err(de::Error::invalid_type(
                Unexpected::UnitVariant,
                &"struct variant",
            )),
        }
        .at(at.track, at.chain)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trackers::{TrackerConfig, TrackerOptions, TRACKER_IDS};
    use serde_json::json;
    use std::fmt::Debug;

    /// What `serde_path_to_error` over serde_json's own `Value` deserializer gives (what this
    /// module replaced): the value's `Debug` text, or the path and message.
    fn reference<T: DeserializeOwned + Debug>(value: &Value) -> Result<String, (String, String)> {
        serde_path_to_error::deserialize::<_, T>(value.clone())
            .map(|t| format!("{t:?}"))
            .map_err(|e| (e.path().to_string(), e.into_inner().to_string()))
    }

    fn ours<T: DeserializeOwned + Debug>(value: &Value) -> Result<String, (String, String)> {
        deserialize::<T>(value)
            .map(|t| format!("{t:?}"))
            .map_err(|(path, e)| (path, e.to_string()))
    }

    /// Every value in `whole`, each replaced in turn by wrong ones, and an unknown key and a
    /// missing key at every object.
    fn variants(whole: &Value) -> Vec<Value> {
        let wrong = [
            json!(null),
            json!(true),
            json!("x"),
            json!(-3),
            json!(7),
            json!(1.5),
            json!(1e300),
            json!(-2.5e-7),
            json!([]),
            json!([1, 2, 3]),
            json!(["a"]),
            json!({}),
            json!({ "first-order": 1 }),
            json!({ "a": 1, "b": 2 }),
            json!("first-order"),
            json!("full-model"),
        ];
        let mut out = vec![whole.clone()];
        fn walk(
            value: &Value,
            at: &mut Vec<Value>,
            wrong: &[Value],
            rebuild: &dyn Fn(Value) -> Value,
        ) {
            for w in wrong {
                at.push(rebuild(w.clone()));
            }
            match value {
                Value::Object(map) => {
                    let mut extra = map.clone();
                    extra.insert("gama".into(), json!(1));
                    at.push(rebuild(Value::Object(extra)));
                    for key in map.keys() {
                        let mut less = map.clone();
                        less.remove(key);
                        at.push(rebuild(Value::Object(less)));
                        let inner = |v: Value| {
                            let mut m = map.clone();
                            m.insert(key.clone(), v);
                            rebuild(Value::Object(m))
                        };
                        walk(&map[key], at, wrong, &inner);
                    }
                }
                Value::Array(items) => {
                    for i in 0..items.len() {
                        let inner = |v: Value| {
                            let mut a = items.clone();
                            a[i] = v;
                            rebuild(Value::Array(a))
                        };
                        walk(&items[i], at, wrong, &inner);
                    }
                    let mut more = items.clone();
                    more.push(json!(0));
                    at.push(rebuild(Value::Array(more)));
                }
                _ => {}
            }
        }
        walk(whole, &mut out, &wrong, &|v| v);
        out
    }

    /// The value at `path` (as the errors name it) in `value`.
    fn at<'v>(value: &'v Value, path: &str) -> Option<&'v Value> {
        if path == "." {
            return Some(value);
        }
        let mut here = value;
        for part in path.split('.') {
            let (key, indices) = part.split_once('[').unwrap_or((part, ""));
            if !key.is_empty() {
                here = here.get(key)?;
            }
            for index in indices.split('[').filter(|s| !s.is_empty()) {
                here = here.get(index.trim_end_matches(']').parse::<usize>().ok()?)?;
            }
        }
        Some(here)
    }

    /// Ours agrees with the reference, but for one difference on purpose: a struct given as an
    /// array (which serde reads field by field in order) is refused.
    fn same<T: DeserializeOwned + Debug>(whole: Value) -> usize {
        let all = variants(&whole);
        for v in &all {
            let (ours, reference) = (ours::<T>(v), reference::<T>(v));
            if let Err((path, message)) = &ours {
                if message.starts_with("invalid type: sequence, expected struct ") {
                    assert!(matches!(at(v, path), Some(Value::Array(_))), "{v}: {path}");
                    continue;
                }
            }
            assert_eq!(ours, reference, "{v}");
        }
        all.len()
    }

    /// The same values, paths and messages as `serde_path_to_error` over serde_json, for every
    /// option object the trackers and the binding read, each value made wrong in turn.
    #[test]
    fn reads_and_refuses_as_serde_path_to_error_did() {
        let camera = crate::synth::default_camera(320, 240).unwrap().to_file();
        let mut n = 0;
        for id in TRACKER_IDS {
            let options = serde_json::to_value(TrackerOptions::defaults(id).unwrap()).unwrap();
            n += match TrackerOptions::defaults(id).unwrap() {
                TrackerOptions::AdachiMmpf(_) => {
                    same::<crate::trackers::adachi::config::AdachiConfig>(options.clone())
                }
                TrackerOptions::DanescuMono(_) | TrackerOptions::DanescuStereo(_) => {
                    same::<crate::trackers::danescu::config::DanescuConfig>(options.clone())
                }
                TrackerOptions::LeeCpf(_) => {
                    same::<crate::trackers::lee::config::LeeConfig>(options.clone())
                }
                TrackerOptions::LiuPpf(_) | TrackerOptions::LiuPpfNokernel(_) => {
                    same::<crate::trackers::liu::config::LiuConfig>(options.clone())
                }
            };
            let mut config = options.as_object().unwrap().clone();
            config.insert("camera".into(), serde_json::to_value(&camera).unwrap());
            config.insert("particles".into(), json!(20));
            n += same::<TrackerConfig>(Value::Object(config));
        }
        n += same::<crate::camera::CameraFile>(serde_json::to_value(&camera).unwrap());
        n += same::<crate::trackers::EgoMotion>(
            json!({ "t_s": 1.0, "speed_mps": 2.0, "yaw_rate": 0.1 }),
        );
        n += same::<crate::synth::TestRoadConfig>(
            serde_json::to_value(crate::synth::TestRoadConfig::default()).unwrap(),
        );
        n += same::<crate::calib::CalibratorConfig>(
            serde_json::to_value(crate::calib::CalibratorConfig::default()).unwrap(),
        );
        n += same::<crate::synth::SceneConfig>(
            serde_json::to_value(crate::synth::scenario("highway-curve").unwrap()).unwrap(),
        );
        assert!(n > 5000, "{n}");
    }
}
