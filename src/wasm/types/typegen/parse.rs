//! Reads a Rust type's definition from its source file with `syn`: a struct's fields (serde
//! key, `///` docs, type, serde attributes) or a unit enum's variants (serde name, docs). What
//! the generator renders as TypeScript; the tests in `mod.rs` check what it reads against the
//! type's real serde behaviour.

use std::path::Path;
use syn::{Attribute, Expr, Fields, GenericArgument, Item, Lit, PathArguments, Type};

/// A type as the source defines it.
#[derive(Debug)]
pub struct Def {
    /// Its `///` docs, one string with `\n` between lines.
    pub docs: String,
    /// Container-level serde attributes.
    pub serde: Container,
    /// Fields or variants.
    pub body: Body,
}

/// A struct's fields or an enum's variants.
#[derive(Debug)]
pub enum Body {
    /// A struct with named fields.
    Struct(Vec<Field>),
    /// An enum of unit variants (a string in JSON).
    Enum(Vec<Variant>),
}

/// The container-level `#[serde(...)]` attributes the generator understands.
#[derive(Debug, Default)]
pub struct Container {
    /// `#[serde(default)]`: every field may be left out.
    pub default: bool,
    /// `#[serde(deny_unknown_fields)]`.
    pub deny_unknown_fields: bool,
    /// `#[serde(rename_all = "...")]`.
    pub rename_all: Option<String>,
}

/// One field of a struct.
#[derive(Debug)]
pub struct Field {
    /// Its key in JSON.
    pub key: String,
    /// Its `///` docs.
    pub docs: String,
    /// Its type.
    pub ty: Ty,
    /// `#[serde(default)]` or `#[serde(default = "...")]`.
    pub default: bool,
    /// `#[serde(flatten)]`.
    pub flatten: bool,
    /// `#[serde(skip_serializing_if = "...")]`.
    pub skip_serializing_if: bool,
}

/// One unit variant of an enum.
#[derive(Debug)]
pub struct Variant {
    /// Its name in JSON.
    pub name: String,
    /// Its `///` docs.
    pub docs: String,
}

/// A field's type, as far as JSON is concerned.
#[derive(Debug, Clone, PartialEq)]
pub enum Ty {
    /// Any Rust number.
    Number,
    /// `bool`.
    Bool,
    /// `String`, `&str`.
    String,
    /// `[T; n]`: a JSON array of exactly n.
    Tuple(Box<Ty>, usize),
    /// `Vec<T>`.
    Array(Box<Ty>),
    /// `Option<T>`.
    Option(Box<Ty>),
    /// Another type, by its Rust name.
    Named(String),
}

/// Reads type `name` from the source file `file` (relative to the crate root).
///
/// # Errors
/// A message when the file does not parse, has no such type, or uses a field type or a serde
/// attribute the generator does not know (so nothing is rendered wrong without a word).
pub fn read(file: &str, name: &str) -> Result<Def, String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{file}: {e}"))?;
    let ast = syn::parse_file(&text).map_err(|e| format!("{file}: {e}"))?;
    let at = |e: String| format!("{file}: {name}: {e}");
    for item in &ast.items {
        match item {
            Item::Struct(s) if s.ident == name => {
                let serde = container(&s.attrs).map_err(at)?;
                let Fields::Named(named) = &s.fields else {
                    return Err(at("not a struct with named fields".into()));
                };
                let fields = named
                    .named
                    .iter()
                    .map(|f| field(f, &serde))
                    .collect::<Result<_, _>>()
                    .map_err(at)?;
                return Ok(Def {
                    docs: docs(&s.attrs),
                    serde,
                    body: Body::Struct(fields),
                });
            }
            Item::Enum(e) if e.ident == name => {
                let serde = container(&e.attrs).map_err(at)?;
                let mut variants = Vec::new();
                for v in &e.variants {
                    if !matches!(v.fields, Fields::Unit) {
                        return Err(at(format!("variant {} has data", v.ident)));
                    }
                    if v.attrs.iter().any(|a| a.path().is_ident("serde")) {
                        return Err(at(format!("variant {}: serde attributes", v.ident)));
                    }
                    variants.push(Variant {
                        name: rename(&v.ident.to_string(), serde.rename_all.as_deref())
                            .map_err(at)?,
                        docs: docs(&v.attrs),
                    });
                }
                return Ok(Def {
                    docs: docs(&e.attrs),
                    serde,
                    body: Body::Enum(variants),
                });
            }
            _ => {}
        }
    }
    Err(at("not found".into()))
}

/// The `///` lines of `attrs`, without the one space after `///`.
fn docs(attrs: &[Attribute]) -> String {
    attrs
        .iter()
        .filter(|a| a.path().is_ident("doc"))
        .filter_map(|a| match &a.meta {
            syn::Meta::NameValue(nv) => match &nv.value {
                Expr::Lit(syn::ExprLit {
                    lit: Lit::Str(s), ..
                }) => Some(s.value()),
                _ => None,
            },
            _ => None,
        })
        .map(|line| line.strip_prefix(' ').unwrap_or(&line).to_string())
        .collect::<Vec<_>>()
        .join("\n")
}

fn container(attrs: &[Attribute]) -> Result<Container, String> {
    let mut c = Container::default();
    for attr in attrs.iter().filter(|a| a.path().is_ident("serde")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("default") {
                c.default = true;
            } else if meta.path.is_ident("deny_unknown_fields") {
                c.deny_unknown_fields = true;
            } else if meta.path.is_ident("rename_all") {
                c.rename_all = Some(meta.value()?.parse::<syn::LitStr>()?.value());
            } else {
                return Err(meta.error("a serde attribute the TypeScript generator does not know"));
            }
            Ok(())
        })
        .map_err(|e| e.to_string())?;
    }
    Ok(c)
}

fn field(f: &syn::Field, container: &Container) -> Result<Field, String> {
    let ident = f
        .ident
        .as_ref()
        .ok_or("a field without a name")?
        .to_string();
    if container.rename_all.is_some() {
        return Err("rename_all on a struct".into());
    }
    let mut out = Field {
        key: ident.clone(),
        docs: docs(&f.attrs),
        ty: ty(&f.ty).map_err(|e| format!("{ident}: {e}"))?,
        default: false,
        flatten: false,
        skip_serializing_if: false,
    };
    for attr in f.attrs.iter().filter(|a| a.path().is_ident("serde")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("default") {
                if meta.input.peek(syn::Token![=]) {
                    meta.value()?.parse::<syn::LitStr>()?;
                }
                out.default = true;
            } else if meta.path.is_ident("flatten") {
                out.flatten = true;
            } else if meta.path.is_ident("skip_serializing_if") {
                meta.value()?.parse::<syn::LitStr>()?;
                out.skip_serializing_if = true;
            } else if meta.path.is_ident("rename") {
                out.key = meta.value()?.parse::<syn::LitStr>()?.value();
            } else {
                return Err(meta.error("a serde attribute the TypeScript generator does not know"));
            }
            Ok(())
        })
        .map_err(|e| format!("{ident}: {e}"))?;
    }
    Ok(out)
}

fn ty(t: &Type) -> Result<Ty, String> {
    match t {
        Type::Array(a) => {
            let n = match &a.len {
                Expr::Lit(syn::ExprLit {
                    lit: Lit::Int(n), ..
                }) => n.base10_parse::<usize>().map_err(|e| e.to_string())?,
                _ => return Err("an array whose length is not a literal".into()),
            };
            Ok(Ty::Tuple(Box::new(ty(&a.elem)?), n))
        }
        Type::Reference(r) => match ty(&r.elem)? {
            Ty::Named(s) if s == "str" => Ok(Ty::String),
            _ => Err("a reference".into()),
        },
        Type::Path(p) => {
            let last = p.path.segments.last().ok_or("an empty path")?;
            let name = last.ident.to_string();
            let inner = || match &last.arguments {
                PathArguments::AngleBracketed(a) => match a.args.first() {
                    Some(GenericArgument::Type(t)) if a.args.len() == 1 => ty(t),
                    _ => Err(format!("{name}: one type argument expected")),
                },
                _ => Err(format!("{name}: a type argument expected")),
            };
            Ok(match name.as_str() {
                "f32" | "f64" | "u8" | "u16" | "u32" | "u64" | "usize" | "i8" | "i16" | "i32"
                | "i64" | "isize" => Ty::Number,
                "bool" => Ty::Bool,
                "String" => Ty::String,
                "Vec" => Ty::Array(Box::new(inner()?)),
                "Option" => Ty::Option(Box::new(inner()?)),
                _ if matches!(last.arguments, PathArguments::None) => Ty::Named(name),
                _ => return Err(format!("a generic type {name}")),
            })
        }
        _ => Err("a type the TypeScript generator does not know".into()),
    }
}

/// A variant's name under `rename_all`.
fn rename(ident: &str, rule: Option<&str>) -> Result<String, String> {
    let words = || {
        let mut out: Vec<String> = Vec::new();
        for c in ident.chars() {
            if c.is_uppercase() || out.is_empty() {
                out.push(c.to_lowercase().collect());
            } else if let Some(last) = out.last_mut() {
                last.push(c);
            }
        }
        out
    };
    match rule {
        None => Ok(ident.to_string()),
        Some("kebab-case") => Ok(words().join("-")),
        Some("snake_case") => Ok(words().join("_")),
        Some("lowercase") => Ok(ident.to_lowercase()),
        Some(other) => Err(format!("rename_all = {other:?}")),
    }
}
