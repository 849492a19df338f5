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

pub use crate::registry::Visitor;
pub use crate::Setup;
use crate::registry::Protocol;
use crate::ScenarioFile;

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
            let (line, column) = e.span().map(|s| line_column(text, s.start)).unwrap_or((1, 1));
            let mut message = e.message().trim().to_string();
            if let Some(field) = field_on_line(text, line) {
                if !message.contains(&field) {
                    message = format!("field `{field}`: {message}");
                }
            }
            Error::ScenarioSyntax { file: origin.into(), line, column, message }
        })?;
        if file.name.is_empty() || !file.name.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_') {
            return Err(Error::Scenario {
                file: origin.into(),
                message: format!("name `{}`: use lower-case letters, digits and `_` (it names the output files)", file.name),
            });
        }
        let mut setups = file.setups();
        if setups.len() != 1 {
            let tables: Vec<String> = crate::PROTOCOLS.iter().map(|p| format!("`[{}]`", p.table)).collect();
            let (last, rest) = tables.split_last().expect("at least one protocol is registered");
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
        let scenario = Scenario { name: file.name, description: file.description, setup, origin: origin.into(), text: text.into() };
        scenario.check()?;
        Ok(scenario)
    }

    /// Reads and checks a scenario file.
    pub fn load(path: &Path) -> Result<Scenario> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        Scenario::parse(&text, &path.display().to_string())
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
        self.setup.accept(Validate).map_err(|source| self.value_error(source))
    }

    /// A model error placed on the line of the field it names.
    pub fn value_error(&self, source: model::ConfigError) -> Error {
        Error::ScenarioValue {
            file: self.origin.clone(),
            line: self.line_of(&format!("{}.{}", self.table(), source.field())),
            source,
        }
    }

    /// The 1-based line where a dotted field (`ssi.master.clock_khz`) is set,
    /// or else where its table starts, or else 1.
    pub fn line_of(&self, dotted: &str) -> usize {
        let dotted = dotted.split('[').next().unwrap_or(dotted);
        let (table, key) = match dotted.rsplit_once('.') {
            Some((t, k)) => (t, k),
            None => ("", dotted),
        };
        let mut current = String::new();
        let mut table_line = None;
        for (i, raw) in self.text.lines().enumerate() {
            let line = raw.trim();
            if let Some(header) = line.strip_prefix('[').and_then(|l| l.split(']').next()) {
                current = header.trim().to_string();
                if current == table {
                    table_line = Some(i + 1);
                }
                continue;
            }
            let in_table = current == table;
            let dotted_key = line.split('=').next().unwrap_or("").trim();
            let full = if current.is_empty() { dotted_key.to_string() } else { format!("{current}.{dotted_key}") };
            if (in_table && dotted_key == key) || full == dotted {
                return i + 1;
            }
        }
        table_line.unwrap_or(1)
    }
}

/// The dotted name (`ssi.master.bits`) of the key set on 1-based `line`, if any.
fn field_on_line(text: &str, line: usize) -> Option<String> {
    let mut table = String::new();
    for (i, raw) in text.lines().enumerate() {
        let l = raw.trim();
        if let Some(header) = l.strip_prefix('[').and_then(|h| h.split(']').next()) {
            table = header.trim().to_string();
        } else if i + 1 == line {
            let key = l.split_once('=')?.0.trim();
            return Some(if table.is_empty() { key.to_string() } else { format!("{table}.{key}") });
        }
    }
    None
}

fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map(|l| l.chars().count()).unwrap_or(0) + 1;
    (line, column)
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = "name = \"t\"\n[ssi]\npositions = [1]\n[ssi.master]\nbits = 12\nclock_khz = 250\n";

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
        assert!(msg.starts_with("t.toml:6: field `master.clock_khz`"), "{msg}");
        assert!(msg.contains("use "), "{msg}");
    }

    #[test]
    fn a_file_without_a_protocol_table_says_what_to_add() {
        let msg = Scenario::parse("name = \"x\"\n", "x.toml").unwrap_err().to_string();
        for p in crate::PROTOCOLS {
            assert!(msg.contains(&format!("`[{}]`", p.table)), "{msg}");
        }
    }

    #[test]
    fn a_file_with_two_protocol_tables_is_refused() {
        let msg = Scenario::parse(&format!("{GOOD}[uart]\nbaud = 10e6\n"), "x.toml").unwrap_err().to_string();
        assert!(msg.contains("2 protocol tables"), "{msg}");
    }
}
