//! `tbgen fields <protocol>` and `docs/scenarios.md`: the reference of every
//! scenario field, made from one source, the model's configuration types.
//!
//! - The fields, their nesting, their types and their meanings are the
//!   schema the types derive (`schemars::JsonSchema` beside `Deserialize`,
//!   so it follows serde's names, defaults and flattening): a field's doc
//!   comment is its meaning, an enum's variants are its choices.
//! - The values a field takes are its type's as a scenario writes them (a
//!   pair is `[a, b]`), narrowed by the range the type declares for it
//!   (`#[schemars(range(...))]` on the same constant the model's check
//!   reads), so the reference shows the limit `tbgen gen` enforces.
//! - The unit is the name's suffix (`_khz`, `_us`, `_m` ...), the
//!   convention every scenario field follows.
//! - The default is what the model itself fills in (the types' `Default`,
//!   serialised).
//!
//! A field without a doc comment is an error of the reference (tested), so
//! a new field cannot slip in undocumented. `make test` holds the committed
//! `docs/scenarios.md` to [`document`] (the `scenarios_md_is_current` test).
//! On a terminal the reference is plain text wrapped to its width;
//! `--markdown` gives the tables the docs hold.

use std::fmt::Write as _;

use serde_json::{Map, Value};

use crate::{Error, Result};

/// The committed reference, relative to the repository root.
pub const DOC_PATH: &str = "docs/scenarios.md";

/// One field of a table.
#[derive(Debug, Clone, PartialEq)]
struct Row {
    /// The name in the scenario file.
    name: String,
    /// The values it takes, as a scenario writes them.
    values: String,
    unit: &'static str,
    default: String,
    meaning: String,
}

/// One table of the reference: its path, doc and rows.
#[derive(Debug, Clone)]
struct Section {
    path: String,
    array: bool,
    doc: String,
    rows: Vec<Row>,
}

/// A doc comment as one line.
fn one_line(text: Option<&Value>) -> String {
    text.and_then(Value::as_str)
        .unwrap_or("")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// The schema of the types, with its definitions to resolve `$ref`s in.
struct Schema<'a> {
    defs: &'a Map<String, Value>,
}

impl<'a> Schema<'a> {
    /// `schema` with its `$ref` followed (the reference's own keys, such as
    /// its description and default, are kept by the caller).
    fn resolve(&self, schema: &'a Value) -> &'a Value {
        match schema.get("$ref").and_then(Value::as_str) {
            Some(r) => r
                .rsplit('/')
                .next()
                .and_then(|name| self.defs.get(name))
                .unwrap_or(schema),
            None => schema,
        }
    }

    /// `Option<T>`'s schema → `T`'s (`anyOf [T, null]`, or `type: [t, "null"]`).
    fn non_null(&self, schema: &'a Value) -> std::borrow::Cow<'a, Value> {
        if let Some(any) = schema.get("anyOf").and_then(Value::as_array) {
            let rest: Vec<&Value> = any
                .iter()
                .filter(|v| v.get("type").and_then(Value::as_str) != Some("null"))
                .collect();
            if let [one] = rest.as_slice() {
                return std::borrow::Cow::Borrowed(one);
            }
        }
        if let Some(types) = schema.get("type").and_then(Value::as_array) {
            let rest: Vec<&Value> = types.iter().filter(|t| *t != "null").collect();
            if let [one] = rest.as_slice() {
                let mut v = schema.clone();
                v["type"] = (*one).clone();
                return std::borrow::Cow::Owned(v);
            }
        }
        std::borrow::Cow::Borrowed(schema)
    }

    /// A table's schema: one with properties.
    fn table(&self, schema: &'a Value) -> Option<&'a Map<String, Value>> {
        self.resolve(schema)
            .get("properties")
            .and_then(Value::as_object)
    }

    /// An enum's choices and their doc comments (`oneOf` of constants, or `enum`).
    fn choices(&self, schema: &Value) -> Option<Vec<(String, String)>> {
        let schema = match schema.get("$ref") {
            Some(_) => self.resolve_owned(schema),
            None => schema.clone(),
        };
        if let Some(e) = schema.get("enum").and_then(Value::as_array) {
            return Some(e.iter().map(|c| (text_of(c), String::new())).collect());
        }
        let one_of = schema.get("oneOf")?.as_array()?;
        one_of
            .iter()
            .map(|v| {
                let c = v
                    .get("const")
                    .or_else(|| v.get("enum").and_then(|e| e.get(0)))?;
                Some((text_of(c), one_line(v.get("description"))))
            })
            .collect()
    }

    fn resolve_owned(&self, schema: &Value) -> Value {
        match schema.get("$ref").and_then(Value::as_str) {
            Some(r) => r
                .rsplit('/')
                .next()
                .and_then(|name| self.defs.get(name))
                .cloned()
                .unwrap_or_else(|| schema.clone()),
            None => schema.clone(),
        }
    }

    /// The values a field of this schema takes, as a scenario writes them.
    fn values(&self, schema: &Value) -> String {
        let schema = self.non_null(schema).into_owned();
        if let Some(choices) = self.choices(&schema) {
            let each: Vec<String> = choices.iter().map(|(c, _)| format!("`\"{c}\"`")).collect();
            return format!("one of {}", each.join(", "));
        }
        let schema = self.resolve_owned(&schema);
        match schema.get("type").and_then(Value::as_str) {
            Some("boolean") => "`true` or `false`".into(),
            Some("string") => "text".into(),
            Some("number") => match range(&schema) {
                Some(r) => format!("number, {r}"),
                None => "number".into(),
            },
            Some("integer") => match range(&schema) {
                Some(r) => format!("whole number, {r}"),
                None => "whole number".into(),
            },
            Some("array") => {
                if let Some(items) = schema.get("prefixItems").and_then(Value::as_array) {
                    // A tuple: TOML writes it as a list of its items.
                    let each: Vec<String> = items.iter().map(|it| self.values(it)).collect();
                    let marks = vec!["·"; items.len()].join(", ");
                    format!("`[{marks}]`: {}", each.join("; "))
                } else {
                    match schema.get("items") {
                        Some(items) => format!("list of: {}", self.values(items)),
                        None => "list".into(),
                    }
                }
            }
            Some("object") => "table".into(),
            _ => "any".into(),
        }
    }
}

/// A JSON string or value as text.
fn text_of(v: &Value) -> String {
    v.as_str().map_or_else(|| v.to_string(), str::to_string)
}

/// The range a schema declares, beyond a whole number's sign: `1 to 64`,
/// `at least 1`, `at most 48` (an unsigned type's bare `minimum: 0` says
/// nothing a whole number does not).
fn range(schema: &Value) -> Option<String> {
    let num = |k: &str| {
        schema
            .get(k)
            .filter(|v| v.is_number())
            .map(Value::to_string)
    };
    let min = num("minimum")
        .filter(|m| !(m == "0" && schema.get("type") == Some(&Value::from("integer"))));
    match (min, num("maximum")) {
        (Some(a), Some(b)) => Some(format!("{a} to {b}")),
        (None, Some(b)) if schema.get("minimum").is_some() => Some(format!("0 to {b}")),
        (None, Some(b)) => Some(format!("at most {b}")),
        (Some(a), None) => Some(format!("at least {a}")),
        (None, None) => None,
    }
}

/// A default as a scenario writes it (TOML), cut at 60 characters.
fn show(v: &Value) -> String {
    let s = toml_text(v);
    if s.chars().count() > 60 {
        format!("`{}…`", s.chars().take(57).collect::<String>())
    } else {
        format!("`{s}`")
    }
}

/// A JSON value in TOML's inline notation.
fn toml_text(v: &Value) -> String {
    match v {
        Value::String(s) => format!("{s:?}"),
        Value::Array(a) => format!(
            "[{}]",
            a.iter().map(toml_text).collect::<Vec<_>>().join(", ")
        ),
        Value::Object(o) => format!(
            "{{ {} }}",
            o.iter()
                .filter(|(_, v)| !v.is_null())
                .map(|(k, v)| format!("{k} = {}", toml_text(v)))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        Value::Number(n) if n.is_f64() => {
            let f = n.as_f64().unwrap_or_default();
            if f.fract() == 0.0 && f.abs() < 1e15 {
                format!("{f:.1}")
            } else {
                f.to_string()
            }
        }
        other => other.to_string(),
    }
}

/// Walks the table `schema` at `path`, adding its section and those of the
/// tables its fields hold.
fn walk(
    types: &Schema,
    schema: &Value,
    path: &str,
    array: bool,
    out: &mut Vec<Section>,
) -> Result<()> {
    let resolved = types.resolve(schema);
    let props = types
        .table(schema)
        .ok_or_else(|| Error::Fields(format!("`[{path}]`: the schema has no fields")))?;
    let required: Vec<&str> = resolved
        .get("required")
        .and_then(Value::as_array)
        .map(|r| r.iter().filter_map(Value::as_str).collect())
        .unwrap_or_default();
    let mut section = Section {
        path: path.to_string(),
        array,
        doc: one_line(resolved.get("description")),
        rows: Vec::new(),
    };
    let mut nested = Vec::new();
    for (name, field) in props {
        let inner = types.non_null(field).into_owned();
        let doc = one_line(field.get("description"));
        if doc.is_empty() {
            return Err(Error::Fields(format!("field `{name}` of `[{path}]` has no doc comment: write one on the field in model/src (it is the reference's meaning column)")));
        }
        let sub_path = format!("{path}.{name}");
        let items = inner
            .get("items")
            .filter(|_| inner.get("type") == Some(&Value::from("array")));
        let (values, sub) = if types.table(&inner).is_some() {
            (
                format!("table `[{sub_path}]`"),
                Some((inner.clone(), false)),
            )
        } else if let Some(it) = items.filter(|it| types.table(it).is_some()) {
            (
                format!("list of tables `[[{sub_path}]]`"),
                Some((it.clone(), true)),
            )
        } else {
            (types.values(field), None)
        };
        let default = match field.get("default") {
            Some(Value::Null) => "none".into(),
            Some(Value::Object(_)) if sub.is_some() => "see below".into(),
            Some(v) => show(v),
            None if required.contains(&name.as_str()) => "required".into(),
            None if field.get("type").and_then(Value::as_array).is_some()
                || field.get("anyOf").is_some() =>
            {
                "none".into()
            }
            None => "—".into(),
        };
        let meaning = match types.choices(&inner) {
            Some(c) if c.iter().any(|(_, d)| !d.is_empty()) => {
                let each: Vec<String> = c
                    .iter()
                    .filter(|(_, d)| !d.is_empty())
                    .map(|(c, d)| format!("`{c}`: {}", d.trim_end_matches('.')))
                    .collect();
                format!("{doc} ({})", each.join("; "))
            }
            _ => doc,
        };
        section.rows.push(Row {
            name: name.clone(),
            values,
            unit: unit(name),
            default,
            meaning,
        });
        if let Some((s, list)) = sub {
            nested.push((s, sub_path, list));
        }
    }
    out.push(section);
    for (s, sub_path, list) in nested {
        walk(types, &s, &sub_path, list, out)?;
    }
    Ok(())
}

/// The sections of protocol `table`'s reference.
fn sections(table: &str) -> Result<(&'static str, Vec<Section>)> {
    let entry = crate::registry::by_table(table).ok_or_else(|| {
        let tables: Vec<&str> = crate::PROTOCOLS.iter().map(|p| p.table).collect();
        Error::Fields(format!(
            "no protocol `{table}`: the protocols are {}",
            tables.join(", ")
        ))
    })?;
    let schema = (entry.schema)();
    let root = schema.as_value();
    let empty = Map::new();
    let types = Schema {
        defs: root
            .get("$defs")
            .and_then(Value::as_object)
            .unwrap_or(&empty),
    };
    let mut out = Vec::new();
    walk(&types, root, table, false, &mut out)?;
    Ok((entry.core, out))
}

/// The reference of one protocol table, in Markdown.
pub fn protocol(table: &str) -> Result<String> {
    let (core, sections) = sections(table)?;
    let mut out = String::new();
    writeln!(out, "## `[{table}]`: core `{core}`\n").unwrap();
    for s in sections {
        writeln!(out, "### `{}`\n", head(&s)).unwrap();
        if !s.doc.is_empty() {
            writeln!(out, "{}\n", s.doc).unwrap();
        }
        writeln!(out, "| field | values | unit | default | meaning |").unwrap();
        writeln!(out, "|---|---|---|---|---|").unwrap();
        for r in s.rows {
            let cells: Vec<String> = [
                format!("`{}`", r.name),
                r.values,
                r.unit.to_string(),
                r.default,
                r.meaning,
            ]
            .iter()
            .map(|c| c.replace('|', "\\|"))
            .collect();
            writeln!(out, "| {} |", cells.join(" | ")).unwrap();
        }
        writeln!(out).unwrap();
    }
    Ok(out)
}

fn head(s: &Section) -> String {
    if s.array {
        format!("[[{}]]", s.path)
    } else {
        format!("[{}]", s.path)
    }
}

/// The reference of one protocol table as plain text for a terminal
/// `width` columns wide: each field on a line of its own with its values,
/// unit and default, its meaning below it, indented and wrapped.
pub fn plain(table: &str, width: usize) -> Result<String> {
    let (core, sections) = sections(table)?;
    let width = width.max(40);
    let mut out = String::new();
    writeln!(out, "[{table}]: core {core}").unwrap();
    for s in sections {
        writeln!(out).unwrap();
        writeln!(out, "{}", head(&s)).unwrap();
        if !s.doc.is_empty() {
            out.push_str(&wrap(&s.doc, 2, width, false));
        }
        for r in s.rows {
            let mut facts = vec![plain_text(&r.values)];
            if !r.unit.is_empty() {
                facts.push(r.unit.to_string());
            }
            facts.push(format!("default {}", plain_text(&r.default)));
            out.push_str(&wrap(
                &format!("{} = {}", r.name, facts.join(", ")),
                2,
                width,
                true,
            ));
            out.push_str(&wrap(&plain_text(&r.meaning), 6, width, false));
        }
    }
    Ok(out)
}

/// Markdown's code marks dropped: `` `"gray"` `` reads `"gray"` on a terminal.
fn plain_text(s: &str) -> String {
    s.replace('`', "")
}

/// `text` wrapped at word boundaries to `width` columns, the first line
/// indented by `indent`, the others by two more when `hang` (a word longer
/// than a line stands alone).
fn wrap(text: &str, indent: usize, width: usize, hang: bool) -> String {
    let mut pad = " ".repeat(indent);
    let mut out = String::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && pad.len() + line.chars().count() + 1 + word.chars().count() > width {
            writeln!(out, "{pad}{line}").unwrap();
            line.clear();
            if hang {
                pad = " ".repeat(indent + 2);
            }
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        writeln!(out, "{pad}{line}").unwrap();
    }
    out
}

/// The whole reference, `docs/scenarios.md`.
pub fn document() -> Result<String> {
    let mut out = String::from(
        "# Scenario fields\n\n\
Generated by `tbgen fields --all` from the model's configuration types (the schema they derive: fields,\n\
types, doc comments, declared limits, and the defaults the model fills in); `make test` checks that this\n\
file is current. Do not edit it by hand: change the doc comment in `model/src/` and run\n\n\
```sh\ntarget/release/tbgen fields --all > docs/scenarios.md\n```\n\n\
A scenario file holds `name`, an optional `description` and exactly one protocol table below. A field left\n\
out takes its default; \"required\" fields have none; \"none\" means the feature is off unless the field is\n\
given. The unit is the field name's suffix. A range in the values column is the one `tbgen gen` enforces;\n\
limits that depend on other fields are in the meaning, and `tbgen gen` checks every one with a message\n\
that names the field.\n\n",
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

    /// The defaults a protocol's table gets when written empty, as the
    /// scenario reader fills them in and serde writes them back: read
    /// without the schema, so the reference is checked against the model.
    fn defaults(table: &str) -> toml::Value {
        let file: crate::ScenarioFile =
            toml::from_str(&format!("name = \"x\"\n[{table}]\n")).unwrap();
        struct ToToml;
        impl crate::registry::Visitor for ToToml {
            type Output = toml::Value;
            fn visit<S: crate::registry::Protocol>(self, setup: &S) -> toml::Value {
                toml::Value::try_from(setup).unwrap()
            }
        }
        file.setups().into_iter().next().unwrap().accept(ToToml)
    }

    /// Every field the model fills in by default is in the reference
    /// (a field serde knows but the reference does not would be a lie by
    /// omission).
    #[test]
    fn every_default_field_of_every_protocol_is_listed() {
        for p in crate::PROTOCOLS {
            let text = protocol(p.table).unwrap();
            let d = defaults(p.table);
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

    /// A pair is shown as TOML writes it, not as the Rust tuple it is.
    #[test]
    fn a_pair_is_shown_in_its_toml_form() {
        let text = protocol("endat").unwrap();
        let row = text
            .lines()
            .find(|l| l.starts_with("| `errors_at` |"))
            .unwrap();
        assert!(
            row.contains("`[·, ·]`: whole number, 0 to 65535; whole number"),
            "{row}"
        );
        assert!(row.contains("errors_at = [word, request]"), "{row}");
        assert!(
            !text.contains("(u16, usize)") && !text.contains("2^"),
            "Rust types or a type's range in the reference"
        );
    }

    /// The reference's range for a BiSS-C slave's `bits` is the one `tbgen
    /// gen` enforces: probed on both sides of each limit through the
    /// scenario reader, which does not read the reference.
    #[test]
    fn a_declared_range_is_the_one_the_check_enforces() {
        let text = protocol("biss").unwrap();
        let row = text
            .split("### `[[biss.slaves]]`")
            .nth(1)
            .and_then(|s| s.lines().find(|l| l.starts_with("| `bits` |")))
            .unwrap();
        let (lo, hi) = row
            .split("whole number, ")
            .nth(1)
            .and_then(|r| r.split(" |").next())
            .and_then(|r| r.split_once(" to "))
            .unwrap_or_else(|| panic!("no range in {row}"));
        let (lo, hi): (u32, u32) = (lo.parse().unwrap(), hi.parse().unwrap());
        let refused = |bits: u32| {
            crate::scenario::Scenario::parse(
                &format!("name = \"x\"\n[biss]\n[[biss.slaves]]\nbits = {bits}\n"),
                "x.toml",
            )
            .and_then(|s| {
                crate::generate::generate(&s, tempfile::tempdir().unwrap().path()).map(|_| ())
            })
            .is_err()
        };
        assert!(refused(lo - 1) && !refused(lo), "lower limit {lo}");
        assert!(!refused(hi) && refused(hi + 1), "upper limit {hi}");
    }

    /// On a terminal: no Markdown table, no line wider than asked but for
    /// a single word too long for any line.
    #[test]
    fn plain_text_fits_the_terminal() {
        for p in crate::PROTOCOLS {
            let text = plain(p.table, 80).unwrap();
            for l in text.lines() {
                assert!(
                    l.chars().count() <= 80 || !l.trim().contains(' '),
                    "{}: {} columns: {l}",
                    p.table,
                    l.chars().count()
                );
                assert!(!l.starts_with('|'), "{}: a table row: {l}", p.table);
            }
        }
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
