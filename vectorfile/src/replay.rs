//! What a replay needs of a vector file, read and checked before any
//! simulator starts: the header sizes the simulator's memory and clock and
//! sets the core's parameters, so a damaged one is refused here, naming the
//! file, its line and the fix (Icarus aborts on an array it cannot size; a
//! zero clock would divide by zero; a parameter `BITS=x` would reach the
//! simulator; a file cut inside its last record reads as zeros in
//! Verilator, a mask comparing nothing).

use std::fmt;
use std::path::Path;

const FIX_REGENERATE: &str =
    "regenerate the file with tbgen gen (or make vectors), which writes the header";

/// The header of a vector file, as a replay takes it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Replay {
    /// The core the file is for.
    pub core: String,
    /// The system clock, Hz (1 Hz to 1 GHz).
    pub f_sys_hz: u64,
    /// Records the file holds (at least the header's count).
    pub records: u64,
    /// Words in each record.
    pub words_per_record: u64,
    /// The run's cycles (0 when the header does not say).
    pub cycles: u64,
    /// The core's parameters, `NAME=value`, in order.
    pub params: Vec<(String, u64)>,
}

/// Why a vector file cannot be replayed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReplayError(pub String);

impl fmt::Display for ReplayError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ReplayError {}

/// A header line: its number (from 1) and value.
struct Field<'a> {
    line: usize,
    value: &'a str,
}

fn field<'a>(text: &'a str, key: &str) -> Option<Field<'a>> {
    let prefix = format!("// {key}: ");
    text.lines().enumerate().find_map(|(i, l)| {
        l.strip_prefix(&prefix).map(|value| Field {
            line: i + 1,
            value: value.trim_end(),
        })
    })
}

/// A decimal of 1 to `digits` digits, no leading zero.
fn decimal(s: &str, digits: usize) -> Option<u64> {
    let ok = !s.is_empty()
        && s.len() <= digits
        && s.bytes().all(|b| b.is_ascii_digit())
        && !s.starts_with('0');
    ok.then(|| s.parse().ok()).flatten()
}

/// `NAME=number`: an upper-case Verilog parameter name and a decimal.
fn parameter(p: &str) -> Option<(String, u64)> {
    let (name, value) = p.split_once('=')?;
    let mut chars = name.chars();
    let name_ok = chars.next().is_some_and(|c| c.is_ascii_uppercase())
        && chars.all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_');
    let value_ok =
        !value.is_empty() && value.len() <= 19 && value.bytes().all(|b| b.is_ascii_digit());
    (name_ok && value_ok).then(|| Some((name.to_string(), value.parse().ok()?)))?
}

impl Replay {
    /// Reads `path`'s header and checks it and the records against each
    /// other for a replay of `core`.
    pub fn read(path: &Path, core: &str) -> Result<Replay, ReplayError> {
        let shown = path.display();
        let text = std::fs::read_to_string(path)
            .map_err(|e| ReplayError(format!("{shown}: cannot read the vector file: {e}")))?;
        let bad = |f: &Field, key: &str, problem: String, fix: &str| {
            ReplayError(format!("{shown}:{}: {key}: {problem}; {fix}", f.line))
        };
        let (Some(records), Some(f_sys)) = (field(&text, "records"), field(&text, "f_sys_hz"))
        else {
            return Err(ReplayError(format!(
                "{shown} has no tbgen header (records:, f_sys_hz:)"
            )));
        };
        let header_core = field(&text, "core").map_or("", |f| f.value);
        if header_core != core {
            return Err(ReplayError(format!(
                "{shown} is for core '{header_core}', not '{core}'"
            )));
        }
        let f_sys_hz = decimal(f_sys.value, 10)
            .filter(|&f| f <= 1_000_000_000)
            .ok_or_else(|| {
                bad(
                    &f_sys,
                    "f_sys_hz",
                    format!("'{}' is not a clock from 1 Hz to 1 GHz", f_sys.value),
                    FIX_REGENERATE,
                )
            })?;
        let words = field(&text, "words_per_record").unwrap_or(Field { line: 1, value: "" });
        let words_per_record = decimal(words.value, 4).ok_or_else(|| {
            bad(
                &words,
                "words_per_record",
                format!("'{}' is not a word count", words.value),
                FIX_REGENERATE,
            )
        })?;
        // One pass over the records: how many, and the first whose word
        // count is not the header's.
        let mut held = 0u64;
        for (i, line) in text.lines().enumerate() {
            if !line.starts_with(|c: char| c.is_ascii_hexdigit()) {
                continue;
            }
            held += 1;
            let n = line.split_whitespace().count() as u64;
            if n != words_per_record {
                return Err(ReplayError(format!(
                    "{shown}:{}: a record of {n} words, where words_per_record is {words_per_record}; the file is cut or damaged: {FIX_REGENERATE}",
                    i + 1
                )));
            }
        }
        let count = decimal(records.value, 10)
            .filter(|&n| n <= held)
            .ok_or_else(|| {
                bad(
                    &records,
                    "records",
                    format!("'{}', but the file holds {held} records", records.value),
                    FIX_REGENERATE,
                )
            })?;
        let mut params = Vec::new();
        if let Some(p) = field(&text, "params") {
            for word in p.value.split_whitespace() {
                params.push(parameter(word).ok_or_else(|| {
                    bad(
                        &p,
                        "params",
                        format!("'{word}' is not NAME=number"),
                        "give each of the core's parameters as NAME=decimal (tbgen gen writes them)",
                    )
                })?);
            }
        }
        Ok(Replay {
            core: core.to_string(),
            f_sys_hz,
            records: count,
            words_per_record,
            cycles: field(&text, "cycles")
                .and_then(|f| f.value.parse().ok())
                .unwrap_or(0),
            params,
        })
    }

    /// The build a replay shares with other files: the parameters and the
    /// clock (files that agree on both replay on one simulator build).
    pub fn build_key(&self) -> (String, u64) {
        (crate::params_text(&self.params), self.f_sys_hz)
    }
}

/// The header fields a replay plans by, read from the first lines of a
/// file only (the committed files of a core are many megabytes in all).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Summary {
    /// The core the file is for.
    pub core: String,
    /// The parameters, as the header writes them.
    pub params: String,
    /// The system clock, Hz.
    pub f_sys_hz: u64,
    /// The run's cycles.
    pub cycles: u64,
}

impl Summary {
    /// Reads the first 40 lines of `path` (`None`: unreadable).
    pub fn read(path: &Path) -> Option<Summary> {
        use std::io::{BufRead, BufReader};
        let file = std::fs::File::open(path).ok()?;
        let mut s = Summary::default();
        for line in BufReader::new(file).lines().take(40) {
            let line = line.ok()?;
            let Some((key, value)) = line.strip_prefix("// ").and_then(|l| l.split_once(": "))
            else {
                continue;
            };
            let value = value.trim_end();
            match key {
                "core" => s.core = value.to_string(),
                "params" => s.params = value.to_string(),
                "f_sys_hz" => s.f_sys_hz = value.parse().unwrap_or(0),
                "cycles" => s.cycles = value.parse().unwrap_or(0),
                _ => {}
            }
        }
        Some(s)
    }

    /// The build a replay shares with other files: the parameters and the
    /// clock (files that agree on both replay on one simulator build).
    pub fn build_key(&self) -> (String, u64) {
        (self.params.clone(), self.f_sys_hz)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = "// tbgen-vectors 1\n// core: c\n// scenario: s\n// f_sys_hz: 50000000\n// records: 2\n// cycles: 10\n// params: BITS=12 GRAY=0\n// words_per_record: 3\n// record: cycle | a | b mask\n00000000 1 0\n00000009 0 1\n";

    fn read(text: &str) -> Result<Replay, ReplayError> {
        static N: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
        let n = N.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("vectorfile-{}-{n}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("f.hex");
        std::fs::write(&path, text).unwrap();
        let r = Replay::read(&path, "c");
        std::fs::remove_dir_all(&dir).ok();
        r
    }

    #[test]
    fn a_good_header_is_read() {
        let r = read(GOOD).unwrap();
        assert_eq!(
            (r.f_sys_hz, r.records, r.words_per_record, r.cycles),
            (50_000_000, 2, 3, 10)
        );
        assert_eq!(r.params, vec![("BITS".into(), 12), ("GRAY".into(), 0)]);
    }

    #[test]
    fn each_damage_is_named_with_its_line() {
        for (from, to, says) in [
            (
                "f_sys_hz: 50000000",
                "f_sys_hz: 0",
                "f.hex:4: f_sys_hz: '0' is not a clock",
            ),
            (
                "f_sys_hz: 50000000",
                "f_sys_hz: 2000000000",
                "is not a clock",
            ),
            (
                "records: 2",
                "records: 3",
                "f.hex:5: records: '3', but the file holds 2 records",
            ),
            (
                "words_per_record: 3",
                "words_per_record: x",
                "f.hex:8: words_per_record: 'x' is not a word count",
            ),
            (
                "BITS=12",
                "BITS=x",
                "f.hex:7: params: 'BITS=x' is not NAME=number",
            ),
            ("BITS=12", "bits=12", "'bits=12' is not NAME=number"),
            (
                "00000009 0 1",
                "00000009 0",
                "f.hex:11: a record of 2 words",
            ),
            ("core: c", "core: d", "is for core 'd', not 'c'"),
            ("// records: 2\n", "", "has no tbgen header"),
        ] {
            let e = read(&GOOD.replace(from, to)).unwrap_err().0;
            assert!(e.contains(says), "{to}: {e}");
        }
    }
}
