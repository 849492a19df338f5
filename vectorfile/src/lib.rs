//! The golden vector file (format: `docs/vectors.md`): its header written
//! and read in one place, for the writer (`tracefile::vectors`), the tests
//! and tools that read a file back ([`VectorFile`]), and the replay driver,
//! which sizes a simulator's memory and clock and sets the core's
//! parameters from the header ([`Replay`], `xtask vector-header`).
//!
//! ```text
//! // tbgen-vectors 1
//! // core: ssi_master
//! // scenario: ssi_double_read_binary
//! // f_sys_hz: 50000000
//! // records: 225
//! // cycles: 122316
//! // params: BITS=12 CLOCKS_PER_BIT=200 ...
//! // words_per_record: 17
//! // record: cycle | i_start i_ssi_data | o_ssi_clk mask ...
//! 00000000 1 1 0 1 ...
//! ```

mod replay;

pub use replay::{Replay, ReplayError, Summary};

use std::io::Write;

/// Format version written in the header; readers refuse other versions.
pub const FORMAT: &str = "tbgen-vectors 1";

/// What the header of a vector file says about the run it holds.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Header {
    /// The core (`ssi_master`).
    pub core: String,
    /// The scenario name.
    pub scenario: String,
    /// The system clock in Hz.
    pub f_sys_hz: u64,
    /// Verilog parameters of the core, in order.
    pub params: Vec<(String, u64)>,
}

/// The header's lines about the records that follow it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Records<'a> {
    /// How many records the file holds.
    pub records: u64,
    /// How many cycles the run lasts (the last record's cycle + 1).
    pub cycles: u64,
    /// Words in each record.
    pub words_per_record: usize,
    /// The record's layout: `cycle | <inputs> | <output> mask ...`.
    pub layout: &'a str,
}

impl Header {
    /// Writes the header's comment lines.
    pub fn write(&self, r: &Records, out: &mut impl Write) -> std::io::Result<()> {
        writeln!(out, "// {FORMAT}")?;
        writeln!(out, "// core: {}", self.core)?;
        writeln!(out, "// scenario: {}", self.scenario)?;
        writeln!(out, "// f_sys_hz: {}", self.f_sys_hz)?;
        writeln!(out, "// records: {}", r.records)?;
        writeln!(out, "// cycles: {}", r.cycles)?;
        writeln!(out, "// params: {}", params_text(&self.params))?;
        writeln!(out, "// words_per_record: {}", r.words_per_record)?;
        writeln!(out, "// record: {}", r.layout)
    }
}

/// Parameters as the header writes them: `NAME=value`, space-separated.
pub fn params_text(params: &[(String, u64)]) -> String {
    params
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A vector file read back: its header fields and records (for tests and tools).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VectorFile {
    /// `key: value` lines of the header, in order.
    pub header: Vec<(String, String)>,
    /// The records, each as its words.
    pub records: Vec<Vec<u64>>,
}

impl VectorFile {
    /// Parses a vector file's text.
    pub fn parse(text: &str) -> Result<VectorFile, String> {
        let mut header = Vec::new();
        let mut records = Vec::new();
        for (i, line) in text.lines().enumerate() {
            if let Some(comment) = line.strip_prefix("// ") {
                if let Some((k, v)) = comment.split_once(": ") {
                    header.push((k.to_string(), v.to_string()));
                }
                continue;
            }
            let words: Result<Vec<u64>, _> = line
                .split_whitespace()
                .map(|w| u64::from_str_radix(w, 16))
                .collect();
            records.push(words.map_err(|e| format!("line {}: {e}", i + 1))?);
        }
        Ok(VectorFile { header, records })
    }

    /// A header field.
    pub fn get(&self, key: &str) -> Option<&str> {
        self.header
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// The word index of port `name` in a record (an output's value word; its mask follows), from the
    /// `record:` header line.
    pub fn column(&self, name: &str) -> Option<usize> {
        let layout = self.get("record")?;
        layout
            .split_whitespace()
            .filter(|w| *w != "|")
            .position(|w| w.split('[').next() == Some(name))
    }

    /// The value of the word at `column` in cycle `cycle` (records hold until the next one).
    pub fn value_at(&self, column: usize, cycle: u64) -> Option<u64> {
        let i = self
            .records
            .partition_point(|r| r.first().is_some_and(|c| *c <= cycle));
        self.records.get(i.checked_sub(1)?)?.get(column).copied()
    }

    /// The cycles in which the word at `column` rises from 0 to non-zero (a strobe's pulses).
    pub fn rises(&self, column: usize) -> Vec<u64> {
        let mut last = 0;
        let mut out = Vec::new();
        for r in &self.records {
            let v = r.get(column).copied().unwrap_or(0);
            if v != 0 && last == 0 {
                out.push(r[0]);
            }
            last = v;
        }
        out
    }
}
