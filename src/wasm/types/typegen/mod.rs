//! The generator of `../generated.d.ts`: the TypeScript types of the tracker configurations,
//! derived from the Rust types, so the two cannot drift apart.
//!
//! Each config struct is read from its source file (`parse.rs`, with `syn`: the serde keys, the
//! `///` docs, the field types, the serde attributes) and rendered as an interface (`render.rs`)
//! whose JSDoc is the Rust docs plus what the running code says: each option's default (the
//! struct's `Default`, serialised) and its range (`trackers::option_ranges`). The ids come from
//! the registry, each tracker's options interface from its `TrackerOptions` variant. The tests
//! below check what was read against serde's real behaviour (the keys of the serialised
//! default, which keys may be left out, unknown keys refused), and that the file is what the
//! generator writes now: after changing a config struct or its docs, run
//! `LANEPF_BLESS=1 cargo test --lib typegen` (or `make types`) and commit the file.
//!
//! Why not tsify (+ serde-wasm-bindgen): its derive would put wasm-bindgen code on the core's
//! config structs (the core carries none), its reader would replace the checked `JSON.stringify`
//! reader of `wasm::object` (bounded size, getters run once, NaN and `null` named by key path),
//! and it adds code to the wasm, whose size is a target. This generator runs only in tests: the
//! package gets the text and no code.

mod parse;
mod render;

use crate::camera::CameraFile;
use crate::synth::TestRoadConfig;
use crate::trackers::adachi::config::AdachiConfig;
use crate::trackers::danescu::config::DanescuConfig;
use crate::trackers::danescu::elevation::CurbConfig;
use crate::trackers::lee::config::LeeConfig;
use crate::trackers::liu::config::LiuConfig;
use crate::trackers::{
    option_ranges, EgoMotion, OptionRange, TrackerConfig, TrackerOptions, TRACKER_IDS,
};
use crate::vision::{
    CannyConfig, DensityConfig, DisparityConfig, DldConfig, HGradientConfig, TopViewConfig,
};
use parse::{Body, Field, Ty};
use render::{Shape, Types};
use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::Value;

/// Where the generated text lives, relative to the crate root.
const OUTPUT: &str = "src/wasm/types/generated.d.ts";

/// One Rust type the generated text names.
struct Spec {
    rust: &'static str,
    file: &'static str,
    shape: Shape,
    /// A value as JSON with every field, as serde writes it, when there is one.
    sample: Option<fn() -> Value>,
    /// Whether `sample`'s values are the defaults a left-out field takes (shown in the docs).
    defaults: bool,
    /// Deserialises JSON as the Rust type does (for the checks).
    parse: Option<fn(Value) -> Result<(), String>>,
}

/// JSON as serde writes it (f32 fields as their shortest text, not widened).
fn json<T: Serialize>(value: &T) -> Value {
    let text = serde_json::to_string(value).expect("a config serialises");
    serde_json::from_str(&text).expect("serde_json reads what it writes")
}

fn parses<T: DeserializeOwned>(value: Value) -> Result<(), String> {
    serde_json::from_value::<T>(value)
        .map(drop)
        .map_err(|e| e.to_string())
}

fn sample<T: Serialize + Default>() -> Value {
    json(&T::default())
}

macro_rules! options {
    ($rust:ident, $file:literal, $ts:literal) => {
        Spec {
            rust: stringify!($rust),
            file: $file,
            shape: Shape::Interface($ts),
            sample: Some(sample::<$rust>),
            defaults: true,
            parse: Some(parses::<$rust>),
        }
    };
}

macro_rules! inline {
    ($rust:literal, $file:literal) => {
        Spec {
            rust: $rust,
            file: $file,
            shape: Shape::Inline,
            sample: None,
            defaults: false,
            parse: None,
        }
    };
}

/// A camera with every field (distortion and baseline too, which serialise only when set).
fn camera_sample() -> Value {
    let mut camera = crate::synth::default_camera(320, 240)
        .expect("a camera")
        .to_file();
    (camera.k1, camera.k2, camera.p1, camera.p2, camera.k3) = (0.01, 0.001, 0.0001, 0.0001, 0.001);
    camera.baseline_m = Some(0.3);
    json(&camera)
}

/// A tracker config: its camera and seed (particles has no default but the tracker's).
fn base_sample() -> Value {
    let camera = json(
        &crate::synth::default_camera(320, 240)
            .expect("a camera")
            .to_file(),
    );
    let minimal = serde_json::json!({ "camera": camera });
    let config: TrackerConfig =
        serde_json::from_value(minimal).expect("a camera is a tracker config");
    serde_json::json!({ "camera": camera, "seed": config.seed })
}

/// Every type the generated text names, in the order it declares them.
fn specs() -> Vec<Spec> {
    vec![
        Spec {
            rust: "TrackerConfig",
            file: "src/trackers/config.rs",
            shape: Shape::Interface("TrackerBaseConfig"),
            sample: Some(base_sample),
            defaults: true,
            parse: Some(parses::<TrackerConfig>),
        },
        Spec {
            rust: "CameraFile",
            file: "src/camera/file.rs",
            shape: Shape::Interface("CameraConfig"),
            sample: Some(camera_sample),
            defaults: false,
            parse: Some(parses::<CameraFile>),
        },
        options!(EgoMotion, "src/trackers/ego_motion.rs", "EgoMotion"),
        options!(TestRoadConfig, "src/synth/test_road.rs", "TestRoadOptions"),
        options!(DldConfig, "src/vision/dld.rs", "DldConfig"),
        options!(CannyConfig, "src/vision/canny.rs", "CannyConfig"),
        options!(TopViewConfig, "src/vision/ipm.rs", "TopViewConfig"),
        options!(
            HGradientConfig,
            "src/vision/hgradient.rs",
            "HGradientConfig"
        ),
        options!(DensityConfig, "src/vision/density.rs", "DensityConfig"),
        options!(
            CurbConfig,
            "src/trackers/danescu/elevation.rs",
            "CurbConfig"
        ),
        options!(
            DisparityConfig,
            "src/vision/disparity.rs",
            "DisparityConfig"
        ),
        inline!("Polarity", "src/trackers/adachi/config.rs"),
        inline!("EdgeResponse", "src/trackers/adachi/config.rs"),
        inline!("LaneShape", "src/trackers/adachi/config.rs"),
        options!(
            AdachiConfig,
            "src/trackers/adachi/config.rs",
            "AdachiOptions"
        ),
        options!(
            DanescuConfig,
            "src/trackers/danescu/config.rs",
            "DanescuOptions"
        ),
        inline!("Variant", "src/trackers/lee/config.rs"),
        options!(LeeConfig, "src/trackers/lee/config.rs", "LeeOptions"),
        options!(LiuConfig, "src/trackers/liu/config.rs", "LiuOptions"),
    ]
}

/// The Rust type of a tracker's options.
fn rust_type(options: &TrackerOptions) -> &'static str {
    let full = match options {
        TrackerOptions::AdachiMmpf(c) => std::any::type_name_of_val(c),
        TrackerOptions::DanescuMono(c) | TrackerOptions::DanescuStereo(c) => {
            std::any::type_name_of_val(c)
        }
        TrackerOptions::LeeCpf(c) => std::any::type_name_of_val(c),
        TrackerOptions::LiuPpf(c) | TrackerOptions::LiuPpfNokernel(c) => {
            std::any::type_name_of_val(c)
        }
    };
    full.rsplit("::").next().unwrap_or(full)
}

/// The tracker ids whose options are the Rust type `rust`, in the registry's order.
fn ids_of(rust: &str) -> Vec<&'static str> {
    TRACKER_IDS
        .iter()
        .copied()
        .filter(|id| rust_type(&TrackerOptions::defaults(id).expect("a registered id")) == rust)
        .collect()
}

fn quoted(ids: &[&str]) -> String {
    let quoted: Vec<String> = ids.iter().map(|id| format!("`{id}`")).collect();
    match quoted.as_slice() {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

/// The ranges of option `key` (and of its entries and fields) as a JSDoc line.
fn range_line(key: &str, ranges: &[OptionRange], array: bool) -> Option<String> {
    let own: Vec<&OptionRange> = ranges
        .iter()
        .filter(|r| {
            r.option == key
                || r.option
                    .strip_prefix(key)
                    .is_some_and(|rest| rest.starts_with(['.', '[']))
        })
        .collect();
    let span = |r: &OptionRange| format!("{} to {}", render::number(r.min), render::number(r.max));
    match own.as_slice() {
        [] => None,
        [one] if one.option == key && array => Some(format!("Range: {} (each entry).", span(one))),
        [one] if one.option == key => Some(format!("Range: {}.", span(one))),
        many => Some(format!(
            "Ranges: {}.",
            many.iter()
                .map(|r| format!("`{}` {}", r.option, span(r)))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// Whether a field may be left out of the JSON.
fn optional(container_default: bool, f: &Field) -> bool {
    container_default || f.default || matches!(f.ty, Ty::Option(_))
}

/// The generated text.
fn generate() -> Result<String, String> {
    let specs = specs();
    let mut types = Types::new();
    for s in &specs {
        types.insert(s.rust, (parse::read(s.file, s.rust)?, s.shape));
    }
    let mut out = String::from(
        "// Generated from the Rust types by src/wasm/types/typegen (`LANEPF_BLESS=1 cargo test \
         --lib typegen`,\n// or `make types`): do not edit. Each option's docs are its Rust docs; \
         the defaults and ranges\n// are the running code's.\n\n",
    );
    out += &render::jsdoc(
        &["The ids `new Tracker(id, ...)` accepts (see `trackerIds()`).".into()],
        "",
    );
    out += &format!(
        "export type TrackerId =\n  | {};\n\n",
        TRACKER_IDS
            .iter()
            .map(|id| format!("'{id}'"))
            .collect::<Vec<_>>()
            .join(" | ")
    );
    out += &render::jsdoc(
        &[
            "The named option sets `trackerPreset(id, preset)` accepts: `paper` (each paper's \
           filter, the defaults) and `real-roads` (our options beyond the papers for real \
           footage)."
                .into(),
        ],
        "",
    );
    out += &format!(
        "export type TrackerPreset =\n  | {};\n\n",
        crate::trackers::PRESET_NAMES
            .iter()
            .map(|p| format!("'{p}'"))
            .collect::<Vec<_>>()
            .join(" | ")
    );
    for s in &specs {
        let Shape::Interface(ts) = s.shape else {
            continue;
        };
        let (def, _) = &types[s.rust];
        let defaults = s.sample.filter(|_| s.defaults).map(|f| f());
        let ids = ids_of(s.rust);
        let (heading, ranges) = if let Some(first) = ids.first() {
            let ranges = option_ranges(first).map_err(|e| e.to_string())?;
            for other in &ids[1..] {
                if option_ranges(other).map_err(|e| e.to_string())? != ranges {
                    return Err(format!("{first} and {other} share {ts} but not its ranges"));
                }
            }
            let heading = vec![
                String::new(),
                format!(
                    "The options of {} in `new Tracker(id, {{ camera, ...options }})`:",
                    quoted(&ids)
                ),
                "all optional (a key left out takes its default); an option of another tracker is"
                    .into(),
                "a type error, and refused at run time.".into(),
            ];
            (heading, ranges)
        } else if s.rust == "TrackerConfig" {
            (Vec::new(), Vec::new())
        } else {
            let Body::Struct(fields) = &def.body else {
                return Err(format!("{ts}: not a struct"));
            };
            let left_out = fields
                .iter()
                .filter(|f| optional(def.serde.default, f))
                .count();
            let note = if left_out == fields.len() {
                "A field left out takes its default."
            } else if left_out == 0 {
                "Every field is required when the object is given."
            } else {
                "A field marked optional takes its default when left out."
            };
            (vec![String::new(), note.to_string()], Vec::new())
        };
        let container_default = def.serde.default;
        let extra = |f: &Field| {
            let mut lines = Vec::new();
            let array = matches!(f.ty, Ty::Tuple(..) | Ty::Array(_));
            lines.extend(range_line(&f.key, &ranges, array));
            if optional(container_default, f) {
                if let Some(v) = defaults.as_ref().and_then(|d| d.get(&f.key)) {
                    lines.push(format!("@defaultValue `{}`", render::literal(v)));
                }
            }
            lines
        };
        out += &render::interface(
            ts,
            def,
            &heading,
            &types,
            &|f| optional(container_default, f),
            &extra,
        )?;
        out += "\n";
    }
    out += &render::jsdoc(&["Each tracker's own options, by id.".into()], "");
    out += "export interface TrackerOptionsById {\n";
    for id in TRACKER_IDS {
        let rust = rust_type(&TrackerOptions::defaults(id).map_err(|e| e.to_string())?);
        let ts = match types.get(rust) {
            Some((_, Shape::Interface(ts))) => *ts,
            _ => {
                return Err(format!(
                    "{id}: its options {rust} are not in the generator's list"
                ))
            }
        };
        out += &format!("  '{id}': {ts};\n");
    }
    out += "}\n\n";
    out += &render::jsdoc(
        &[
            "`new Tracker(id, config)`: the camera, particles and seed, and the options of tracker `Id`".into(),
            "(`TrackerOptionsById`). With a literal id (`new Tracker('lee-cpf', { ... })`) an option of".into(),
            "another tracker is a type error; `TrackerConfig` without `Id` is any one tracker's config.".into(),
        ],
        "",
    );
    out += "export type TrackerConfig<Id extends TrackerId = TrackerId> =\n  Id extends TrackerId ? TrackerBaseConfig & TrackerOptionsById[Id] : never;\n\n";
    out += &render::jsdoc(
        &["`trackerDefaults(id)`: every option of tracker `Id` with its default, `particles` included.".into()],
        "",
    );
    out += "export type TrackerDefaults<Id extends TrackerId = TrackerId> =\n  Id extends TrackerId ? Required<TrackerOptionsById[Id]> & { particles: number } : never;\n";
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;

    /// The checked-in file is what the generator writes now (`LANEPF_BLESS=1` rewrites it).
    #[test]
    fn typegen_output_is_current() {
        let text = generate().unwrap();
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(OUTPUT);
        if std::env::var_os("LANEPF_BLESS").is_some() {
            std::fs::write(&path, &text).unwrap();
        }
        let on_disk = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            on_disk == text,
            "{OUTPUT} is stale: run `LANEPF_BLESS=1 cargo test --lib typegen` (or `make types`) \
             and commit it"
        );
    }

    /// What the generator read from the source is what serde does: the keys are the keys of
    /// the serialised default, a key is optional in TypeScript exactly when serde accepts the
    /// object without it, and unknown keys are refused.
    #[test]
    fn typegen_reads_the_real_serde_keys_and_defaults() {
        for s in specs() {
            let def = parse::read(s.file, s.rust).unwrap();
            let Body::Struct(fields) = &def.body else {
                continue;
            };
            let (Some(sample), Some(parse)) = (s.sample, s.parse) else {
                continue;
            };
            let sample = sample();
            let object = sample.as_object().unwrap();
            let keys: BTreeSet<&str> = fields
                .iter()
                .filter(|f| !f.flatten)
                .map(|f| f.key.as_str())
                .collect();
            let serialised: BTreeSet<&str> = object.keys().map(String::as_str).collect();
            if s.rust == "TrackerConfig" {
                // No Serialize: the sample holds the required camera and the defaulted seed.
                assert!(serialised.is_subset(&keys), "{}: {serialised:?}", s.rust);
            } else {
                assert_eq!(keys, serialised, "{}", s.rust);
            }
            parse(sample.clone()).unwrap_or_else(|e| panic!("{}: {e}", s.rust));
            for f in fields.iter().filter(|f| object.contains_key(&f.key)) {
                let mut without = object.clone();
                without.remove(&f.key);
                assert_eq!(
                    parse(Value::Object(without)).is_ok(),
                    optional(def.serde.default, f),
                    "{}.{}: optional in TypeScript exactly when serde takes the object without it",
                    s.rust,
                    f.key
                );
            }
            let mut unknown = object.clone();
            unknown.insert("no_such_option".into(), Value::from(1));
            assert_eq!(
                parse(Value::Object(unknown)).is_err(),
                def.serde.deny_unknown_fields,
                "{}: unknown keys refused exactly when deny_unknown_fields",
                s.rust
            );
        }
    }

    /// Every range names an option of its tracker, so none is lost from the docs.
    #[test]
    fn typegen_every_range_names_an_option() {
        for id in TRACKER_IDS {
            let rust = rust_type(&TrackerOptions::defaults(id).unwrap());
            let spec = specs().into_iter().find(|s| s.rust == rust).unwrap();
            let Body::Struct(fields) = parse::read(spec.file, spec.rust).unwrap().body else {
                panic!("{rust} is a struct");
            };
            for r in option_ranges(id).unwrap() {
                let key = r.option.split(['.', '[']).next().unwrap();
                assert!(fields.iter().any(|f| f.key == key), "{id}: {}", r.option);
            }
        }
    }

    #[test]
    fn typegen_docs_lose_rust_links_but_keep_brackets() {
        assert_eq!(
            render::clean("see [`super::road_shape`]; [min, max] in [0, 1) [`x`](http://a)."),
            "see `road_shape`; [min, max] in [0, 1) `x`."
        );
        assert_eq!(render::number(1e-9), "1e-9");
        assert_eq!(render::number(200_000.0), "200000");
        assert_eq!(render::number(0.15), "0.15");
    }
}
