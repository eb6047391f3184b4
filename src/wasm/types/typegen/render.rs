//! Renders what `parse` read as TypeScript: an interface per struct with each field's docs as
//! JSDoc (Rust's intra-doc links turned into code spans), followed by what the generator adds
//! from the running code (the default, the range); unit enums inline as string unions with
//! each variant's docs in the field's.

use super::parse::{Body, Def, Field, Ty};
use serde_json::Value;
use std::collections::BTreeMap;

/// How a Rust type appears in TypeScript.
#[derive(Debug, Clone, Copy)]
pub enum Shape {
    /// An interface of this name, rendered here.
    Interface(&'static str),
    /// A unit enum written out where it is used, as a union of its names.
    Inline,
}

/// Every Rust type the rendered ones refer to, by Rust name.
pub type Types = BTreeMap<&'static str, (Def, Shape)>;

/// The TypeScript type of `ty`.
///
/// # Errors
/// A Rust type not in `types`.
pub fn ts_type(ty: &Ty, types: &Types) -> Result<String, String> {
    Ok(match ty {
        Ty::Number => "number".into(),
        Ty::Bool => "boolean".into(),
        Ty::String => "string".into(),
        Ty::Tuple(t, n) => format!("[{}]", vec![ts_type(t, types)?; *n].join(", ")),
        Ty::Array(t) => match ts_type(t, types)? {
            s if s.contains(' ') => format!("({s})[]"),
            s => format!("{s}[]"),
        },
        Ty::Option(t) => ts_type(t, types)?,
        Ty::Named(name) => match types.get(name.as_str()) {
            Some((_, Shape::Interface(ts))) => (*ts).to_string(),
            Some((def, Shape::Inline)) => match &def.body {
                Body::Enum(variants) => variants
                    .iter()
                    .map(|v| format!("'{}'", v.name))
                    .collect::<Vec<_>>()
                    .join(" | "),
                Body::Struct(_) => return Err(format!("{name}: a struct cannot be inline")),
            },
            None => return Err(format!("{name}: add it to the generator's list of types")),
        },
    })
}

/// The docs of an inline enum's variants, one line each, for the field that has that type.
fn variant_docs(ty: &Ty, types: &Types) -> Vec<String> {
    let Ty::Named(name) = ty else {
        return Vec::new();
    };
    match types.get(name.as_str()) {
        Some((
            Def {
                body: Body::Enum(variants),
                ..
            },
            Shape::Inline,
        )) => variants
            .iter()
            .map(|v| format!("- `'{}'`: {}", v.name, clean(&v.docs).replace('\n', " ")))
            .collect(),
        _ => Vec::new(),
    }
}

/// `export interface NAME { ... }` for the struct `def`: each field optional when `optional`
/// says so, its docs followed by the lines `extra` gives for it.
///
/// # Errors
/// A field type not in `types`, or `def` not a struct.
pub fn interface(
    name: &str,
    def: &Def,
    heading: &[String],
    types: &Types,
    optional: &dyn Fn(&Field) -> bool,
    extra: &dyn Fn(&Field) -> Vec<String>,
) -> Result<String, String> {
    let Body::Struct(fields) = &def.body else {
        return Err(format!("{name}: not a struct"));
    };
    let mut docs: Vec<String> = clean(&def.docs).lines().map(String::from).collect();
    docs.extend(heading.iter().cloned());
    let mut out = jsdoc(&docs, "");
    out += &format!("export interface {name} {{\n");
    for f in fields.iter().filter(|f| !f.flatten) {
        let mut lines: Vec<String> = clean(&f.docs).lines().map(String::from).collect();
        let variants = variant_docs(&f.ty, types);
        if !variants.is_empty() {
            lines.push(String::new());
            lines.extend(variants);
        }
        let more = extra(f);
        if !more.is_empty() {
            lines.push(String::new());
            lines.extend(more);
        }
        out += &jsdoc(&lines, "  ");
        let mark = if optional(f) { "?" } else { "" };
        out += &format!("  {}{mark}: {};\n", f.key, ts_type(&f.ty, types)?);
    }
    out += "}\n";
    Ok(out)
}

/// A JSDoc block of `lines` at `indent`.
pub fn jsdoc(lines: &[String], indent: &str) -> String {
    let mut out = format!("{indent}/**\n");
    for line in lines {
        let line = line.replace("*/", "*\\/");
        if line.is_empty() {
            out += &format!("{indent} *\n");
        } else {
            out += &format!("{indent} * {line}\n");
        }
    }
    out + &format!("{indent} */\n")
}

/// Rust docs as plain Markdown: an intra-doc link ``[`path::Name`]`` becomes `` `Name` ``
/// (``[`x`](url)`` too); other brackets (`[min, max]`, `[0, 1)`) stay as they are.
pub fn clean(docs: &str) -> String {
    let mut out = String::new();
    let mut rest = docs;
    while let Some(start) = rest.find("[`") {
        out += &rest[..start];
        let after = &rest[start + 2..];
        match after.find("`]") {
            Some(end) if !after[..end].contains(['[', ']', '`']) => {
                let target = &after[..end];
                let short = target.rsplit("::").next().unwrap_or(target);
                out += &format!("`{short}`");
                rest = &after[end + 2..];
                // A Markdown link's target goes.
                if rest.starts_with('(') {
                    if let Some(close) = rest.find(')') {
                        rest = &rest[close + 1..];
                    }
                }
            }
            _ => {
                out += "[`";
                rest = after;
            }
        }
    }
    out + rest
}

/// A JSON value as a TypeScript literal: `{ window: 3, gamma: 20 }`, `[2.5, 4.8]`, `'both'`.
pub fn literal(value: &Value) -> String {
    match value {
        Value::Null => "null".into(),
        Value::Bool(b) => b.to_string(),
        Value::Number(n) => n.as_f64().map_or_else(|| n.to_string(), number),
        Value::String(s) => format!("'{s}'"),
        Value::Array(items) => format!(
            "[{}]",
            items.iter().map(literal).collect::<Vec<_>>().join(", ")
        ),
        Value::Object(map) => format!(
            "{{ {} }}",
            map.iter()
                .map(|(k, v)| format!("{k}: {}", literal(v)))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// A number as a reader writes it: `20`, `0.15`, `1e-9`, `200000`.
pub fn number(x: f64) -> String {
    if x != 0.0 && x.abs() < 1e-4 {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}
