//! Scenario files: TOML read with serde, checked before anything is written.
//!
//! ```toml
//! name = "ssi_seed_12bit"            # file names of the outputs; [a-z0-9_]
//! description = "what it shows"
//!
//! [ssi]                              # the protocol's table: its fields are
//! f_sys_mhz = 50                     # model::ssi::BenchConfig's
//! positions = [495]
//! [ssi.master]
//! bits = 12
//! clock_khz = 250
//! ```

use std::path::Path;

use crate::{Error, Result};
use model::toml_place::line_column;

use crate::registry::Protocol;
pub use crate::registry::Visitor;
use crate::ScenarioFile;
pub use crate::Setup;

struct CoreAndTable;
impl Visitor for CoreAndTable {
    type Output = (&'static str, &'static str);
    fn visit<S: Protocol>(self, _: &S) -> Self::Output {
        (S::CORE, S::TABLE)
    }
}

struct Validate;
impl Visitor for Validate {
    type Output = model::Result<()>;
    fn visit<S: Protocol>(self, setup: &S) -> Self::Output {
        setup.validate()
    }
}

/// A checked scenario.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// Output file stem, `[a-z0-9_]+`.
    pub name: String,
    /// One line on what the scenario shows.
    pub description: String,
    /// The set-up.
    pub setup: Setup,
    /// Where it came from (`path` or `builtin:<name>`), for messages.
    pub origin: String,
    text: String,
}

impl Scenario {
    /// Parses and checks a scenario; `origin` is named in every message.
    pub fn parse(text: &str, origin: &str) -> Result<Scenario> {
        let file: ScenarioFile = toml::from_str(text).map_err(|e| {
            let mut offset = e.span().map(|s| s.start);
            let mut message = e.message().trim().to_string();
            let mut field = offset.and_then(|o| path_at(text, o));
            if field.is_none() {
                if let Some((f, at)) = offset.and_then(|o| field_by_quoted_value(text, o, &message))
                {
                    (field, offset) = (Some(f), Some(at));
                }
            }
            let (line, column) = offset.map(|o| line_column(text, o)).unwrap_or((1, 1));
            if let Some(field) = field.or_else(|| field_on_line(text, line)) {
                if !message.contains(&field) {
                    message = format!("field `{field}`: {message}");
                }
            }
            // The top level's one required field: say where and how it goes.
            if message == "missing field `name`" {
                message.push_str("; add `name = \"my_scenario\"` above the protocol's table (it names the output files: lower-case letters, digits and `_`)");
            }
            Error::ScenarioSyntax {
                file: origin.into(),
                line,
                column,
                message,
            }
        })?;
        if file.name.is_empty()
            || !file
                .name
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
        {
            return Err(Error::Scenario {
                file: origin.into(),
                message: format!(
                    "name `{}`: use lower-case letters, digits and `_` (it names the output files)",
                    file.name
                ),
            });
        }
        let mut setups = file.setups();
        if setups.len() != 1 {
            let tables: Vec<String> = crate::PROTOCOLS
                .iter()
                .map(|p| format!("`[{}]`", p.table))
                .collect();
            let (last, rest) = tables
                .split_last()
                .expect("at least one protocol is registered");
            return Err(Error::Scenario {
                file: origin.into(),
                message: format!(
                    "{} protocol tables: give exactly one, e.g. {} or {last} with its fields (see scenarios/)",
                    setups.len(),
                    rest.join(", ")
                ),
            });
        }
        let setup = setups.remove(0);
        let scenario = Scenario {
            name: file.name,
            description: file.description,
            setup,
            origin: origin.into(),
            text: text.into(),
        };
        scenario.check()?;
        Ok(scenario)
    }

    /// Reads and checks a scenario file.
    pub fn load(path: &Path) -> Result<Scenario> {
        let origin = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| match e.kind() {
            std::io::ErrorKind::NotFound => Error::Scenario {
                file: origin.clone(),
                message: "no such scenario file: check the path (`tbgen list` shows the built-in scenarios, named without .toml)".into(),
            },
            std::io::ErrorKind::InvalidData => Error::Scenario {
                file: origin.clone(),
                message: "not a text file: a scenario is a UTF-8 TOML text file (see scenarios/ for examples)".into(),
            },
            _ => Error::io(path, e),
        })?;
        Scenario::parse(&text, &origin)
    }

    /// The scenario file's text (the emulators and monitors read their
    /// limits from it).
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The core the scenario's vectors drive (`ssi_master`...).
    pub fn core(&self) -> &'static str {
        self.setup.accept(CoreAndTable).0
    }

    /// The protocol table's name in the file.
    pub fn table(&self) -> &'static str {
        self.setup.accept(CoreAndTable).1
    }

    /// Runs the model's own checks and places any error on a line of the file.
    fn check(&self) -> Result<()> {
        self.setup
            .accept(Validate)
            .map_err(|source| self.value_error(source))
    }

    /// A model error placed on the line of the field it names.
    pub fn value_error(&self, source: model::ConfigError) -> Error {
        Error::ScenarioValue {
            file: self.origin.clone(),
            line: self.line_of(&format!("{}.{}", self.table(), source.field())),
            source,
        }
    }

    /// The 1-based line where a dotted field (`ssi.master.clock_khz`,
    /// `endat.commands[2].command`) is set, or else where the deepest part
    /// of it that the file writes is (its table, its array entry), or else 1.
    pub fn line_of(&self, dotted: &str) -> usize {
        model::toml_place::line_of(&self.text, dotted).unwrap_or(1)
    }
}

/// The field path (`endat.commands[2].command`) of the key or value at byte
/// `offset` of `text`, if the text parses as TOML and one is there.
fn path_at(text: &str, offset: usize) -> Option<String> {
    use toml::de::DeValue;
    fn walk(v: &DeValue, path: &str, offset: usize, out: &mut Option<String>) {
        let scalar = |v: &DeValue| !matches!(v, DeValue::Table(_) | DeValue::Array(_));
        match v {
            DeValue::Table(t) => {
                for (k, val) in t {
                    let p = if path.is_empty() {
                        k.get_ref().to_string()
                    } else {
                        format!("{path}.{}", k.get_ref())
                    };
                    if k.span().contains(&offset)
                        || (scalar(val.get_ref()) && val.span().contains(&offset))
                    {
                        *out = Some(p.clone());
                    }
                    walk(val.get_ref(), &p, offset, out);
                }
            }
            DeValue::Array(a) => {
                for (i, e) in a.iter().enumerate() {
                    let p = format!("{path}[{i}]");
                    if e.span().contains(&offset) {
                        *out = Some(p.clone());
                    }
                    walk(e.get_ref(), &p, offset, out);
                }
            }
            _ => {}
        }
    }
    let (doc, _) = toml::de::DeTable::parse_recoverable(text);
    let mut out = None;
    walk(&DeValue::Table(doc.into_inner()), "", offset, &mut out);
    out
}

/// The field holding the value a message quotes (``invalid value: integer
/// `-1`, expected usize``) among the plain values of the table at byte
/// `offset`, and the offset of its key: serde places an error in a table
/// whose struct takes another's fields (`#[serde(flatten)]`, as
/// `[endat.faults]` takes the cable's fault fields) at the table, not at
/// the key. Only a value that one field alone holds is taken.
fn field_by_quoted_value(text: &str, offset: usize, message: &str) -> Option<(String, usize)> {
    use toml::de::{DeTable, DeValue};
    let quoted = message.split('`').nth(1)?;
    let same = |raw: &str| {
        let raw = raw.trim().trim_matches('"');
        let number = |t: &str| t.replace('_', "").parse::<f64>().ok();
        match (number(raw), number(quoted)) {
            (Some(a), Some(b)) => a == b || (a.is_nan() && b.is_nan()),
            _ => raw == quoted,
        }
    };
    // Every table with its dotted path and span. A `[a.b]` table's span
    // need not lie inside `[a]`'s, so all are searched, not one branch.
    fn tables<'a>(
        t: &'a DeTable<'a>,
        path: &str,
        out: &mut Vec<(String, std::ops::Range<usize>, &'a DeTable<'a>)>,
    ) {
        for (k, v) in t {
            let p = if path.is_empty() {
                k.get_ref().to_string()
            } else {
                format!("{path}.{}", k.get_ref())
            };
            match v.get_ref() {
                DeValue::Table(inner) => {
                    out.push((p.clone(), v.span(), inner));
                    tables(inner, &p, out);
                }
                DeValue::Array(a) => {
                    for (i, e) in a.iter().enumerate() {
                        if let DeValue::Table(inner) = e.get_ref() {
                            let pi = format!("{p}[{i}]");
                            out.push((pi.clone(), e.span(), inner));
                            tables(inner, &pi, out);
                        }
                    }
                }
                _ => {}
            }
        }
    }
    let doc = DeTable::parse(text).ok()?;
    let mut all = Vec::new();
    tables(doc.get_ref(), "", &mut all);
    // The table that starts at `offset`, else the innermost one holding it.
    let (path, _, table) = all
        .iter()
        .find(|(_, span, _)| span.start == offset)
        .or_else(|| {
            all.iter()
                .filter(|(_, span, _)| span.contains(&offset))
                .max_by_key(|(_, span, _)| span.start)
        })?;
    let mut hits = table.iter().filter(|(_, v)| {
        !matches!(v.get_ref(), DeValue::Table(_) | DeValue::Array(_)) && same(&text[v.span()])
    });
    let (key, _) = hits.next()?;
    if hits.next().is_some() {
        return None;
    }
    Some((format!("{path}.{}", key.get_ref()), key.span().start))
}

/// The dotted name (`ssi.master.bits`) of the key set on 1-based `line`, if
/// any: the fallback where the file does not parse as TOML.
fn field_on_line(text: &str, line: usize) -> Option<String> {
    let mut table = String::new();
    for (i, raw) in text.lines().enumerate() {
        let l = raw.trim();
        if let Some(header) = l.strip_prefix('[').and_then(|h| h.split(']').next()) {
            table = header.trim_start_matches('[').trim().to_string();
        } else if i + 1 == line {
            let key = l.split_once('=')?.0.trim();
            return Some(if table.is_empty() {
                key.to_string()
            } else {
                format!("{table}.{key}")
            });
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str =
        "name = \"t\"\n[ssi]\npositions = [1]\n[ssi.master]\nbits = 12\nclock_khz = 250\n";

    #[test]
    fn a_good_file_parses() {
        let s = Scenario::parse(GOOD, "t.toml").unwrap();
        assert_eq!(s.core(), "ssi_master");
    }

    #[test]
    fn a_misspelt_field_is_named_with_its_line() {
        let text = GOOD.replace("clock_khz", "clock_kHz");
        let err = Scenario::parse(&text, "t.toml").unwrap_err();
        let msg = err.to_string();
        assert!(msg.starts_with("t.toml:6:"), "{msg}");
        assert!(msg.contains("clock_kHz"), "{msg}");
    }

    #[test]
    fn an_impossible_value_is_placed_on_its_line_with_the_fix() {
        let text = GOOD.replace("250", "300");
        let msg = Scenario::parse(&text, "t.toml").unwrap_err().to_string();
        assert!(
            msg.starts_with("t.toml:6: field `master.clock_khz`"),
            "{msg}"
        );
        assert!(msg.contains("use "), "{msg}");
    }

    #[test]
    fn a_value_in_an_array_of_tables_is_placed_on_its_own_line() {
        let text = "name = \"t\"\n[biss]\n[biss.host]\nframes = 6\n\n[[biss.flips]]\nframe = 0\nbits = [0]\n\n[[biss.flips]]\nframe = 1\nbits = [1]\n\n[[biss.flips]]\nbits = [2]\nframe = 40\n";
        let msg = Scenario::parse(text, "flip.toml").unwrap_err().to_string();
        assert!(
            msg.starts_with(
                "flip.toml:16: field `flips[2].frame`: frame 40, but the run has 6 frames"
            ),
            "{msg}"
        );
    }

    #[test]
    fn a_value_in_an_inline_array_is_placed_on_its_own_line() {
        let text = "name = \"t\"\n[endat]\n[[endat.commands]]\ncommand = \"pos22\"\nrepeat = 3\n[endat.faults]\nflips = [\n  { request = 1, bits = [2] },\n  { request = 44, bits = [3] },\n]\n";
        let msg = Scenario::parse(text, "f.toml").unwrap_err().to_string();
        assert!(
            msg.starts_with("f.toml:9: field `faults.flips[1].request`"),
            "{msg}"
        );
    }

    #[test]
    fn a_bad_value_in_a_flattened_table_is_named_and_placed_on_its_own_line() {
        // `stuck_from` is the cable's field, which [endat.faults] takes in
        // (serde's flatten): serde alone places the error at the table.
        let text = "name = \"t\"\n[endat]\n[[endat.commands]]\ncommand = \"pos22\"\n[endat.faults]\nabsent_from = 1\nstuck_from = -1\n";
        let msg = Scenario::parse(text, "f.toml").unwrap_err().to_string();
        assert!(
            msg.starts_with("f.toml:7:1: field `endat.faults.stuck_from`"),
            "{msg}"
        );
        let text = text.replace("-1", "nan");
        let msg = Scenario::parse(&text, "f.toml").unwrap_err().to_string();
        assert!(
            msg.starts_with("f.toml:7:1: field `endat.faults.stuck_from`"),
            "{msg}"
        );
    }

    #[test]
    fn a_bad_field_in_an_array_entry_is_named_with_its_index_and_no_stray_bracket() {
        let text = "name = \"t\"\n[endat]\n[[endat.commands]]\ncommand = \"pos22\"\n[[endat.commands]]\ncommand = \"pos99\"\n";
        let msg = Scenario::parse(text, "c.toml").unwrap_err().to_string();
        assert!(msg.starts_with("c.toml:6:"), "{msg}");
        assert!(msg.contains("field `endat.commands[1].command`"), "{msg}");
        assert!(!msg.contains("`[endat"), "{msg}");
    }

    #[test]
    fn a_file_without_a_protocol_table_says_what_to_add() {
        let msg = Scenario::parse("name = \"x\"\n", "x.toml")
            .unwrap_err()
            .to_string();
        for p in crate::PROTOCOLS {
            assert!(msg.contains(&format!("`[{}]`", p.table)), "{msg}");
        }
    }

    #[test]
    fn a_file_with_two_protocol_tables_is_refused() {
        let msg = Scenario::parse(&format!("{GOOD}[uart]\nbaud = 10e6\n"), "x.toml")
            .unwrap_err()
            .to_string();
        assert!(msg.contains("2 protocol tables"), "{msg}");
    }
}
