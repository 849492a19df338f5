//! Golden vector files for `$readmemh` (format: `docs/vectors.md`).
//!
//! One record per cycle in which an input or an expected output changes,
//! plus the first and the last cycle. A record is one line of hex words:
//!
//! ```text
//! <cycle> <in_0> ... <in_k> <out_0> <mask_0> ... <out_m> <mask_m>
//! ```
//!
//! Each word is one `$readmemh` memory entry (the testbench memory is 64 bits
//! wide), so a record of `k + 1` inputs and `m + 1` outputs fills
//! `1 + (k + 1) + 2 (m + 1)` consecutive entries. The header comment (which
//! `$readmemh` skips) says which core, scenario, `f_sys`, record count,
//! cycle count and Verilog parameters the file is for.

use std::fmt::Write as _;
use std::io::Write;

use model::trace::{Sample, Sink};
use model::Port;

/// Format version written in the header; readers refuse other versions.
pub const FORMAT: &str = "tbgen-vectors 1";

/// What the header of a vector file says.
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

/// Collects records from a bench run; [`VectorWriter::finish`] writes the file.
pub struct VectorWriter {
    inputs: Vec<Port>,
    outputs: Vec<Port>,
    body: String,
    records: u64,
    previous: Option<Sample>,
    last_cycle: Option<u64>,
    last_written: Option<u64>,
}

impl VectorWriter {
    /// A writer for a core with these ports.
    pub fn new(inputs: &[Port], outputs: &[Port]) -> Self {
        VectorWriter {
            inputs: inputs.to_vec(),
            outputs: outputs.to_vec(),
            body: String::new(),
            records: 0,
            previous: None,
            last_cycle: None,
            last_written: None,
        }
    }

    fn record(&mut self, cycle: u64, s: &Sample) {
        let _ = write!(self.body, "{cycle:08x}");
        for (port, v) in self.inputs.iter().zip(&s.inputs) {
            let _ = write!(
                self.body,
                " {:0w$x}",
                v & port.mask(),
                w = hex_digits(port.width)
            );
        }
        for ((port, v), care) in self.outputs.iter().zip(&s.outputs).zip(&s.care) {
            let w = hex_digits(port.width);
            let _ = write!(
                self.body,
                " {:0w$x} {:0w$x}",
                v & port.mask(),
                care & port.mask(),
                w = w
            );
        }
        self.body.push('\n');
        self.records += 1;
        self.last_written = Some(cycle);
    }

    /// Writes the header and the records. The last cycle always has a record,
    /// so the testbench knows where the run ends.
    pub fn finish(mut self, header: &Header, out: &mut impl Write) -> std::io::Result<u64> {
        if let (Some(last), Some(prev)) = (self.last_cycle, self.previous.take()) {
            if self.last_written != Some(last) {
                self.record(last, &prev);
            }
        }
        let cycles = self.last_cycle.map_or(0, |c| c + 1);
        writeln!(out, "// {FORMAT}")?;
        writeln!(out, "// core: {}", header.core)?;
        writeln!(out, "// scenario: {}", header.scenario)?;
        writeln!(out, "// f_sys_hz: {}", header.f_sys_hz)?;
        writeln!(out, "// records: {}", self.records)?;
        writeln!(out, "// cycles: {cycles}")?;
        let params: Vec<String> = header
            .params
            .iter()
            .map(|(k, v)| format!("{k}={v}"))
            .collect();
        writeln!(out, "// params: {}", params.join(" "))?;
        writeln!(
            out,
            "// words_per_record: {}",
            1 + self.inputs.len() + 2 * self.outputs.len()
        )?;
        let ins: Vec<String> = self.inputs.iter().map(port_label).collect();
        let outs: Vec<String> = self
            .outputs
            .iter()
            .map(|p| format!("{} mask", port_label(p)))
            .collect();
        writeln!(
            out,
            "// record: cycle | {} | {}",
            ins.join(" "),
            outs.join(" ")
        )?;
        out.write_all(self.body.as_bytes())?;
        Ok(self.records)
    }
}

impl Sink for VectorWriter {
    type Error = std::io::Error;

    fn sample(&mut self, cycle: u64, s: &Sample) -> std::io::Result<()> {
        if cycle > u32::MAX as u64 {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "the run is longer than 2^32 cycles, which the vector format's 32-bit cycle stamp cannot hold; shorten the scenario",
            ));
        }
        let changed = match &self.previous {
            None => true,
            Some(p) => p.inputs != s.inputs || p.outputs != s.outputs || p.care != s.care,
        };
        if changed {
            self.record(cycle, s);
            match &mut self.previous {
                Some(p) => {
                    // Same lengths every cycle: copy in place, no allocation.
                    p.inputs.copy_from_slice(&s.inputs);
                    p.outputs.copy_from_slice(&s.outputs);
                    p.care.copy_from_slice(&s.care);
                }
                None => self.previous = Some(s.clone()),
            }
        }
        self.last_cycle = Some(cycle);
        Ok(())
    }
}

fn hex_digits(width: u32) -> usize {
    width.div_ceil(4).max(1) as usize
}

fn port_label(p: &Port) -> String {
    if p.width == 1 {
        p.name.to_string()
    } else {
        format!("{}[{}:0]", p.name, p.width - 1)
    }
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
