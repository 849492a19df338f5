//! `tbgen fields <protocol>` and `docs/scenarios.md`: the reference of every
//! scenario field, made from one source, the model's configuration structs.
//!
//! - The fields, their nesting and their types are the structs' own
//!   (`model::<proto>::BenchConfig` and the structs its fields name), read
//!   from the model's source, which `build.rs` compiles in.
//! - The meaning is the field's doc comment; the unit is the name's suffix
//!   (`_khz`, `_us`, `_m` ...), the convention every scenario field follows;
//!   the values a field takes come from its type (an enum's choices by their
//!   serde names, a whole number's width) and the doc comment says any
//!   tighter limit the seed sets.
//! - The default is what the model itself fills in: the set-up a table left
//!   empty deserialises to, serialised back.
//!
//! A field without a doc comment is an error of the reference (tested), so
//! a new field cannot slip in undocumented. `make test` holds the committed
//! `docs/scenarios.md` to [`document`] (the `scenarios_md_is_current` test).

use std::fmt::Write as _;

use crate::registry::{Protocol, Visitor};
use crate::{Error, Result};

/// `(path under model/src, text)` of every model source file.
const MODEL_SOURCES: &[(&str, &str)] = include!(concat!(env!("OUT_DIR"), "/model_sources.rs"));

/// The committed reference, relative to the repository root.
pub const DOC_PATH: &str = "docs/scenarios.md";

/// One field of a configuration struct, as its source declares it.
#[derive(Debug, Clone)]
struct Field {
    /// The name in the scenario file (the field name, or its serde rename).
    name: String,
    /// The Rust type as written.
    ty: String,
    /// The doc comment, joined into one line.
    doc: String,
    /// `#[serde(flatten)]`: its fields sit in the parent table.
    flatten: bool,
    /// The field may be left out (`Option`, or a serde default).
    optional: bool,
    /// The field's own serde default, when it has one: `#[serde(default =
    /// "f")]` gives `f`'s body, a bare `#[serde(default)]` the type's.
    own_default: Option<String>,
}

/// The body of a one-line `fn name() -> T { literal }` in `text`.
fn default_fn(lines: &[&str], name: &str) -> Option<String> {
    let at = lines
        .iter()
        .position(|l| l.trim_start().starts_with(&format!("fn {name}() ->")))?;
    let body = lines.get(at + 1)?.trim();
    (lines.get(at + 2)?.trim() == "}").then(|| body.to_string())
}

/// The `Default` of a scalar type, as a scenario writes it.
fn type_default(ty: &str) -> Option<String> {
    Some(match ty {
        "bool" => "false".into(),
        "f32" | "f64" => "0.0".into(),
        t if t.starts_with("Vec<") => "[]".into(),
        t if values_of(t).is_some_and(|v| v.starts_with("whole")) => "0".into(),
        _ => return None,
    })
}

/// A configuration struct: its doc comment and fields.
#[derive(Debug, Clone)]
struct Struct {
    doc: String,
    fields: Vec<Field>,
}

/// An enum's choices as a scenario writes them, with their doc comments.
#[derive(Debug, Clone)]
struct Enum {
    choices: Vec<(String, String)>,
}

/// The folder of a type path such as `model::ssi::bench::BenchConfig` (`ssi`).
fn folder_of(type_name: &str) -> &str {
    type_name.split("::").nth(1).unwrap_or("")
}

/// The model's source files split into lines once, and where each type is
/// declared: `pub struct Name` and `pub enum Name` lines by name, as
/// `(file, line)` in file order. tbgen is compiled unoptimised (Cargo.toml);
/// looking types up here rather than walking every file for every field
/// took the two reference tests from 11 s each to well under one.
struct SourceIndex {
    lines: Vec<Vec<&'static str>>,
    declared: std::collections::HashMap<&'static str, Vec<(usize, usize)>>,
}

fn source_index() -> &'static SourceIndex {
    static INDEX: std::sync::OnceLock<SourceIndex> = std::sync::OnceLock::new();
    INDEX.get_or_init(|| {
        let mut index = SourceIndex {
            lines: Vec::new(),
            declared: Default::default(),
        };
        for (file, (_, text)) in MODEL_SOURCES.iter().enumerate() {
            let lines: Vec<&'static str> = text.lines().collect();
            for (at, l) in lines.iter().enumerate() {
                let t = l.trim_start();
                if let Some(rest) = t
                    .strip_prefix("pub struct ")
                    .or_else(|| t.strip_prefix("pub enum "))
                {
                    let name = rest
                        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                        .next()
                        .unwrap_or("");
                    index.declared.entry(name).or_default().push((file, at));
                }
            }
            index.lines.push(lines);
        }
        index
    })
}

/// The files declaring a type `name` (a line that `is_declaration`), those
/// in `folder` first, each with its lines and the first such line: where a
/// type name is found in its protocol's folder before the shared modules.
fn declarations(
    name: &str,
    folder: &str,
    is_declaration: impl Fn(&str) -> bool,
) -> Vec<(&'static [&'static str], usize)> {
    let index = source_index();
    let prefix = format!("{folder}/");
    let mut found: Vec<(bool, usize, usize)> = Vec::new();
    for &(file, at) in index.declared.get(name).map(Vec::as_slice).unwrap_or(&[]) {
        if found.iter().any(|&(_, f, _)| f == file)
            || !is_declaration(index.lines[file][at].trim_start())
        {
            continue;
        }
        found.push((!MODEL_SOURCES[file].0.starts_with(&prefix), file, at));
    }
    found.sort();
    found
        .into_iter()
        .map(|(_, file, at)| (index.lines[file].as_slice(), at))
        .collect()
}

/// The doc comment and attribute lines just above line `at`.
fn preamble(lines: &[&str], at: usize) -> (String, Vec<String>) {
    let mut doc = Vec::new();
    let mut attrs = Vec::new();
    let mut i = at;
    while i > 0 {
        let l = lines[i - 1].trim();
        if let Some(d) = l.strip_prefix("///") {
            doc.push(d.trim().to_string());
        } else if l.starts_with("#[") {
            attrs.push(l.to_string());
        } else {
            break;
        }
        i -= 1;
    }
    doc.reverse();
    (doc.join(" "), attrs)
}

/// The value of `key = "..."` inside a `#[serde(...)]` attribute.
fn serde_arg(attr: &str, key: &str) -> Option<String> {
    let rest = attr.split(&format!("{key} = \"")).nth(1)?;
    Some(rest.split('"').next()?.to_string())
}

/// A serde attribute list holds the bare word `word` (`default`, `flatten`).
fn serde_word(attrs: &[String], word: &str) -> bool {
    attrs.iter().filter(|a| a.starts_with("#[serde(")).any(|a| {
        a.trim_start_matches("#[serde(")
            .trim_end_matches(")]")
            .split(',')
            .any(|p| {
                let p = p.trim();
                p == word || p.starts_with(&format!("{word} ="))
            })
    })
}

/// The struct `name`, looked for in `folder` first.
fn find_struct(name: &str, folder: &str) -> Option<Struct> {
    let declaration = format!("pub struct {name} {{");
    for (lines, at) in declarations(name, folder, |t| t.starts_with(&declaration)) {
        let (doc, attrs) = preamble(lines, at);
        if !attrs.iter().any(|a| a.contains("Deserialize")) {
            continue;
        }
        let struct_default = serde_word(&attrs, "default");
        let mut fields = Vec::new();
        let mut field_doc = Vec::new();
        let mut field_attrs: Vec<String> = Vec::new();
        for l in &lines[at + 1..] {
            let t = l.trim();
            if t.starts_with('}') {
                break;
            }
            if let Some(d) = t.strip_prefix("///") {
                field_doc.push(d.trim().to_string());
            } else if t.starts_with("#[") {
                field_attrs.push(t.to_string());
            } else if let Some(decl) = t.strip_prefix("pub ") {
                let (fname, ty) = decl.split_once(':').unwrap_or((decl, ""));
                let ty = ty.trim().trim_end_matches(',').trim().to_string();
                let rename = field_attrs.iter().find_map(|a| serde_arg(a, "rename"));
                let own_default = match field_attrs.iter().find_map(|a| serde_arg(a, "default")) {
                    Some(f) => default_fn(lines, &f),
                    None if serde_word(&field_attrs, "default") => type_default(&ty),
                    None => None,
                };
                fields.push(Field {
                    name: rename.unwrap_or_else(|| fname.trim().to_string()),
                    optional: struct_default
                        || serde_word(&field_attrs, "default")
                        || ty.starts_with("Option<"),
                    flatten: serde_word(&field_attrs, "flatten"),
                    ty,
                    own_default,
                    doc: field_doc.join(" "),
                });
                field_doc.clear();
                field_attrs.clear();
            }
        }
        return Some(Struct { doc, fields });
    }
    None
}

/// `Variant` as serde writes it under `rename_all`.
fn rename(variant: &str, rule: Option<&str>) -> String {
    let snake = || {
        let mut s = String::new();
        for (i, c) in variant.chars().enumerate() {
            if c.is_ascii_uppercase() && i > 0 {
                s.push('_');
            }
            s.push(c.to_ascii_lowercase());
        }
        s
    };
    match rule {
        Some("snake_case") => snake(),
        Some("lowercase") => variant.to_lowercase(),
        Some("SCREAMING_SNAKE_CASE") => snake().to_uppercase(),
        Some("kebab-case") => snake().replace('_', "-"),
        _ => variant.to_string(),
    }
}

/// The enum `name` that scenarios name by its variants, looked for in `folder` first.
fn find_enum(name: &str, folder: &str) -> Option<Enum> {
    let declaration = format!("pub enum {name} {{");
    for (lines, at) in declarations(name, folder, |t| t == declaration) {
        let (_, attrs) = preamble(lines, at);
        if !attrs.iter().any(|a| a.contains("Deserialize")) {
            continue;
        }
        let rule = attrs.iter().find_map(|a| serde_arg(a, "rename_all"));
        let mut choices = Vec::new();
        let mut doc = Vec::new();
        let mut rename_one = None;
        let mut depth = 0i32;
        for l in &lines[at + 1..] {
            let t = l.trim();
            if depth == 0 && t.starts_with('}') {
                break;
            }
            if depth == 0 {
                if let Some(d) = t.strip_prefix("///") {
                    doc.push(d.trim().to_string());
                } else if t.starts_with("#[") {
                    if let Some(r) = serde_arg(t, "rename") {
                        rename_one = Some(r);
                    }
                } else if t.starts_with(|c: char| c.is_ascii_uppercase()) {
                    let ident: String = t
                        .chars()
                        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                        .collect();
                    choices.push((
                        rename_one
                            .take()
                            .unwrap_or_else(|| rename(&ident, rule.as_deref())),
                        doc.join(" "),
                    ));
                    doc.clear();
                }
            }
            depth += t.matches('{').count() as i32 - t.matches('}').count() as i32;
        }
        return Some(Enum { choices });
    }
    None
}

/// `Option<T>` → `T`, `Vec<T>` → `T` (with whether it was a list).
fn inner(ty: &str) -> (&str, bool) {
    let t = ty
        .strip_prefix("Option<")
        .and_then(|r| r.strip_suffix('>'))
        .unwrap_or(ty);
    match t.strip_prefix("Vec<").and_then(|r| r.strip_suffix('>')) {
        Some(r) => (r, true),
        None => (t, false),
    }
}

/// Units per unit that field names use (`ns_per_m`).
const PER: &[(&str, &str, &str)] = &[("ns", "m", "ns/m"), ("ps", "m", "ps/m")];

/// The unit the name's suffix says.
fn unit(name: &str) -> &'static str {
    const UNITS: &[(&str, &str)] = &[
        ("_mhz", "MHz"),
        ("_khz", "kHz"),
        ("_hz", "Hz"),
        ("_ms", "ms"),
        ("_us", "µs"),
        ("_ns", "ns"),
        ("_ps", "ps"),
        ("_s", "s"),
        ("_m", "m"),
        ("_ppm", "ppm"),
        ("_percent", "%"),
        ("_deg", "°"),
        ("_baud", "baud"),
        ("_bits", "bits"),
        ("_clocks", "system-clock cycles"),
        ("_cycles", "system-clock cycles"),
    ];
    if name == "baud" {
        return "baud";
    }
    // `ns_per_m`: a unit per unit.
    if let Some((a, b)) = name.split_once("per_") {
        let (a, b) = (
            unit(&format!(
                "_{}",
                a.trim_end_matches('_').rsplit('_').next().unwrap_or("")
            )),
            unit(&format!("_{b}")),
        );
        if !a.is_empty() && !b.is_empty() {
            return PER
                .iter()
                .find(|(x, y, _)| *x == a && *y == b)
                .map(|(_, _, u)| *u)
                .unwrap_or("");
        }
    }
    UNITS
        .iter()
        .find(|(s, _)| name.ends_with(s))
        .map(|(_, u)| *u)
        .unwrap_or("")
}

/// The values a scalar type takes.
fn values_of(ty: &str) -> Option<String> {
    let whole = |bits: u32| {
        if bits <= 16 {
            format!("whole number, 0 to {}", (1u32 << bits) - 1)
        } else {
            format!("whole number, 0 to 2^{bits}−1")
        }
    };
    Some(match ty {
        "bool" => "`true` or `false`".into(),
        "u8" => whole(8),
        "u16" => whole(16),
        "u32" => whole(32),
        "u64" | "usize" => whole(64),
        "i8" | "i16" | "i32" | "i64" => "whole number (signed)".into(),
        "f32" | "f64" => "number".into(),
        "String" => "text".into(),
        _ => return None,
    })
}

/// One table of the reference: its path, doc and rows.
struct Section {
    path: String,
    array: bool,
    doc: String,
    rows: Vec<[String; 5]>,
}

/// A default value as a scenario writes it.
fn show(v: &toml::Value) -> String {
    let s = v.to_string();
    if s.len() > 60 {
        format!(
            "`{}…`",
            &s[..s
                .char_indices()
                .take(57)
                .last()
                .map(|(i, c)| i + c.len_utf8())
                .unwrap_or(0)]
        )
    } else {
        format!("`{s}`")
    }
}

/// The defaults a table gets when it is written empty: the model's own
/// `Default`, through the scenario reader. `chain` is the table and the
/// tables above it below the protocol's, each with whether it is a list of
/// tables (written once, empty). `None` when a table cannot be empty (a
/// required field).
fn defaults(table: &str, chain: &[(String, bool)]) -> Option<toml::Value> {
    let mut text = format!("name = \"x\"\n[{table}]\n");
    for (path, array) in chain {
        text.push_str(&if *array {
            format!("[[{path}]]\n")
        } else {
            format!("[{path}]\n")
        });
    }
    let file: crate::ScenarioFile = toml::from_str(&text).ok()?;
    let setup = file.setups().into_iter().next()?;
    struct ToToml;
    impl Visitor for ToToml {
        type Output = Option<toml::Value>;
        fn visit<S: Protocol>(self, setup: &S) -> Self::Output {
            toml::Value::try_from(setup).ok()
        }
    }
    let mut v = setup.accept(ToToml)?;
    for (path, array) in chain {
        let key = path.rsplit('.').next()?;
        v = v.get(key)?.clone();
        if *array {
            v = v.as_array()?.first()?.clone();
        }
    }
    Some(v)
}

/// The struct name of a config type path (`model::ssi::bench::BenchConfig` → `BenchConfig`).
fn last(type_name: &str) -> &str {
    type_name.rsplit("::").next().unwrap_or(type_name)
}

/// Walks struct `name` as the table at `path`, adding its section and those
/// of the structs its fields name.
fn walk(
    table: &str,
    folder: &str,
    name: &str,
    chain: &[(String, bool)],
    out: &mut Vec<Section>,
) -> Result<()> {
    let (path, array) = chain
        .last()
        .map(|(p, a)| (p.as_str(), *a))
        .unwrap_or((table, false));
    let defaults_at = defaults(table, chain);
    let s = find_struct(name, folder).ok_or_else(|| {
        Error::Fields(format!(
            "no configuration struct `{name}` deriving Deserialize in model/src (table `[{path}]`)"
        ))
    })?;
    let mut section = Section {
        path: path.into(),
        array,
        doc: s.doc.clone(),
        rows: Vec::new(),
    };
    let mut nested = Vec::new();
    let mut fields = s.fields.clone();
    // Flattened structs lend their fields to this table.
    while let Some(i) = fields.iter().position(|f| f.flatten) {
        let f = fields.remove(i);
        let (ty, _) = inner(&f.ty);
        let sub = find_struct(ty, folder).ok_or_else(|| {
            Error::Fields(format!(
                "`[{path}]` flattens `{ty}`, which is not a configuration struct in model/src"
            ))
        })?;
        for (k, g) in sub.fields.into_iter().enumerate() {
            fields.insert(i + k, g);
        }
    }
    for f in fields {
        if f.doc.is_empty() {
            return Err(Error::Fields(format!("field `{}` of `[{path}]` ({name}) has no doc comment: write one in model/src (it is the reference's meaning column)", f.name)));
        }
        let default = defaults_at.as_ref().and_then(|d| d.get(&f.name));
        let (ty, list) = inner(&f.ty);
        let is_table = find_struct(ty, folder).is_some() && values_of(ty).is_none();
        let shown = match default {
            Some(_) if is_table && !list => "see below".into(),
            Some(v) => show(v),
            None if f.own_default.is_some() => {
                format!("`{}`", f.own_default.as_deref().unwrap_or_default())
            }
            None if f.ty.starts_with("Option<") => "none".into(),
            None if !f.optional => "required".into(),
            None => "—".into(),
        };
        let (values, sub) = if let Some(v) = values_of(ty) {
            (v, None)
        } else if let Some(e) = find_enum(ty, folder) {
            let choices: Vec<String> = e
                .choices
                .iter()
                .map(|(c, _)| format!("`\"{c}\"`"))
                .collect();
            (format!("one of {}", choices.join(", ")), None)
        } else if find_struct(ty, folder).is_some() {
            let sub_path = format!("{path}.{}", f.name);
            let shape = if list {
                format!("list of tables `[[{sub_path}]]`")
            } else {
                format!("table `[{sub_path}]`")
            };
            (shape, Some((ty.to_string(), sub_path, list)))
        } else {
            (format!("`{ty}`"), None)
        };
        let values = if list && sub.is_none() {
            format!("list of: {values}")
        } else {
            values
        };
        let meaning = match find_enum(ty, folder) {
            Some(e) if e.choices.iter().any(|(_, d)| !d.is_empty()) => {
                let each: Vec<String> = e
                    .choices
                    .iter()
                    .filter(|(_, d)| !d.is_empty())
                    .map(|(c, d)| format!("`{c}`: {}", d.trim_end_matches('.')))
                    .collect();
                format!("{} ({})", f.doc, each.join("; "))
            }
            _ => f.doc.clone(),
        };
        section.rows.push([
            format!("`{}`", f.name),
            values,
            unit(&f.name).to_string(),
            shown,
            meaning,
        ]);
        if let Some(n) = sub {
            nested.push(n);
        }
    }
    out.push(section);
    for (ty, sub_path, list) in nested {
        let mut sub = chain.to_vec();
        sub.push((sub_path, list));
        walk(table, folder, &ty, &sub, out)?;
    }
    Ok(())
}

/// The reference of one protocol table, in Markdown.
pub fn protocol(table: &str) -> Result<String> {
    let entry = crate::registry::by_table(table).ok_or_else(|| {
        let tables: Vec<&str> = crate::PROTOCOLS.iter().map(|p| p.table).collect();
        Error::Fields(format!(
            "no protocol `{table}`: the protocols are {}",
            tables.join(", ")
        ))
    })?;
    let type_name = (entry.config_type)();
    let mut sections = Vec::new();
    walk(
        table,
        folder_of(type_name),
        last(type_name),
        &[],
        &mut sections,
    )?;
    let mut out = String::new();
    writeln!(out, "## `[{table}]`: core `{}`\n", entry.core).unwrap();
    for s in sections {
        let head = if s.array {
            format!("[[{}]]", s.path)
        } else {
            format!("[{}]", s.path)
        };
        writeln!(out, "### `{head}`\n").unwrap();
        if !s.doc.is_empty() {
            writeln!(out, "{}\n", s.doc).unwrap();
        }
        writeln!(out, "| field | values | unit | default | meaning |").unwrap();
        writeln!(out, "|---|---|---|---|---|").unwrap();
        for r in s.rows {
            let cells: Vec<String> = r.iter().map(|c| c.replace('|', "\\|")).collect();
            writeln!(out, "| {} |", cells.join(" | ")).unwrap();
        }
        writeln!(out).unwrap();
    }
    Ok(out)
}

/// The whole reference, `docs/scenarios.md`.
pub fn document() -> Result<String> {
    let mut out = String::from(
        "# Scenario fields\n\n\
Generated by `tbgen fields --all` from the model's configuration structs (their fields, types and doc\n\
comments, and the defaults the model fills in); `make test` checks that this file is current. Do not edit\n\
it by hand: change the doc comment in `model/src/` and run\n\n\
```sh\ntarget/release/tbgen fields --all > docs/scenarios.md\n```\n\n\
A scenario file holds `name`, an optional `description` and exactly one protocol table below. A field left\n\
out takes its default; \"required\" fields have none; \"none\" means the feature is off unless the field is\n\
given. The unit is the field name's suffix. Limits a seed sets beyond the type's are in the meaning, and\n\
`tbgen gen` checks every one with a message that names the field.\n\n",
    );
    let tables: Vec<&str> = crate::PROTOCOLS.iter().map(|p| p.table).collect();
    writeln!(
        out,
        "Protocols: {}.\n",
        tables
            .iter()
            .map(|t| format!("`[{t}]`"))
            .collect::<Vec<_>>()
            .join(", ")
    )
    .unwrap();
    for t in tables {
        out.push_str(&protocol(t)?);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn repo_root() -> std::path::PathBuf {
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .parent()
            .unwrap()
            .to_path_buf()
    }

    #[test]
    fn scenarios_md_is_current() {
        let fresh = document().unwrap();
        let committed = std::fs::read_to_string(repo_root().join(DOC_PATH)).unwrap_or_default();
        assert!(
            committed == fresh,
            "{DOC_PATH} is not what `tbgen fields --all` writes: run `cargo build --release -p tbgen && target/release/tbgen fields --all > {DOC_PATH}` and commit it"
        );
    }

    /// Every field the model fills in by default is in the reference: the
    /// source reading misses none (a field `serde` knows but the reference
    /// does not would be a lie by omission).
    #[test]
    fn every_default_field_of_every_protocol_is_listed() {
        for p in crate::PROTOCOLS {
            let text = protocol(p.table).unwrap();
            let d = defaults(p.table, &[]).expect("an empty table deserialises");
            fn keys(v: &toml::Value, path: String, out: &mut Vec<(String, String)>) {
                if let Some(t) = v.as_table() {
                    for (k, v) in t {
                        out.push((path.clone(), k.clone()));
                        if v.is_table() {
                            keys(v, format!("{path}.{k}"), out);
                        }
                    }
                }
            }
            let mut all = Vec::new();
            keys(&d, p.table.to_string(), &mut all);
            assert!(all.len() >= 3, "{}: defaults read", p.table);
            for (path, k) in all {
                let section = text
                    .split(&format!("### `[{path}]`"))
                    .nth(1)
                    .unwrap_or_else(|| panic!("{}: section [{path}] listed", p.table));
                let section = section.split("\n### ").next().unwrap();
                assert!(
                    section.contains(&format!("| `{k}` |")),
                    "{}: field {k} of [{path}] listed",
                    p.table
                );
            }
        }
    }

    /// The SSI seed fields exactly: unit, default and values from the
    /// struct, meaning from its doc comment (model/src/ssi/bench.rs).
    #[test]
    fn ssi_rows_come_from_the_structs() {
        let text = protocol("ssi").unwrap();
        assert!(
            text.contains("| `f_sys_mhz` | number | MHz | `50.0` | System clock in MHz. |"),
            "{text}"
        );
        assert!(text.contains("| `clock_khz` | number | kHz |"), "{text}");
        assert!(
            text.contains("| `code` | one of `\"binary\"`, `\"gray\"` |"),
            "{text}"
        );
        assert!(text.contains("### `[ssi.cable]`"), "{text}");
        assert!(
            text.contains("| `level` | `true` or `false` |  | required |"),
            "{text}"
        );
        assert!(
            text.contains("| `fault` | table `[ssi.fault]` |  | none |"),
            "{text}"
        );
    }

    #[test]
    fn an_unknown_protocol_lists_the_protocols() {
        let e = protocol("endat_master").unwrap_err().to_string();
        assert!(
            e.contains("no protocol `endat_master`") && e.contains("ssi") && e.contains("endat"),
            "{e}"
        );
    }

    #[test]
    fn units_follow_the_suffix() {
        assert_eq!(unit("t_cs_us"), "µs");
        assert_eq!(unit("length_m"), "m");
        assert_eq!(unit("f_sys_mhz"), "MHz");
        assert_eq!(unit("positions"), "");
    }
}
