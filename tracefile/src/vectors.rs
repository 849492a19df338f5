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

pub use vectorfile::{Header, VectorFile, FORMAT};

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
        let ins: Vec<String> = self.inputs.iter().map(port_label).collect();
        let outs: Vec<String> = self
            .outputs
            .iter()
            .map(|p| format!("{} mask", port_label(p)))
            .collect();
        let layout = format!("cycle | {} | {}", ins.join(" "), outs.join(" "));
        header.write(
            &vectorfile::Records {
                records: self.records,
                cycles: self.last_cycle.map_or(0, |c| c + 1),
                words_per_record: 1 + self.inputs.len() + 2 * self.outputs.len(),
                layout: &layout,
            },
            out,
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
