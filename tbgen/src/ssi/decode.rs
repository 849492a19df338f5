//! `tbgen decode ssi`: the reads of an SSI line from its clock and data, as
//! the master sees them (a `tbgen gen` VCD, or the RTL's own waves from
//! `make sim WAVES=1` with `--clk tb_ssi_master.o_ssi_clk --data
//! tb_ssi_master.i_ssi_data`).
//!
//! A read is one burst of the clock: its first falling edge from the idle
//! high line stores the value in the encoder (the seed's `T_cs`, SAR58K24
//! manual, SSI section (4)), and each following low phase carries one bit,
//! MSB first, which the master samples in that low phase. The decoder reads
//! each bit at the end of its low phase (just before the rising edge): the
//! encoder changes its output on rising edges, so the bit is settled there
//! however long the cable. A read ends at a rising edge followed by more
//! than three half periods of high clock (the pause, `T_m`).

use std::path::Path;

use serde::Serialize;

use crate::capture;
use crate::{Error, Result};

/// How the reads are laid out.
#[derive(Debug, Clone)]
pub struct Layout {
    /// Value bits per read; `None`: every sampled bit (less a copy or a wire-check bit).
    pub bits: Option<u32>,
    /// The value is Gray-coded.
    pub gray: bool,
    /// Each read carries the value twice.
    pub double_read: bool,
    /// Each read carries one more bit, which must be 0.
    pub wire_check: bool,
}

/// One read seen on the line.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ReadSeen {
    /// 0-based read number.
    pub index: usize,
    /// The first falling edge (the encoder stores its value), ps.
    pub start_ps: u64,
    /// The last rising edge, ps.
    pub end_ps: u64,
    /// The bits read, in order.
    pub received_bits: String,
    /// The value, binary.
    pub position: Option<u64>,
    /// `double_read_mismatch`, `wire_check_failed`.
    pub errors: Vec<String>,
}

/// The bits a Gray or binary word of `bits` carries, as a binary value.
fn value(bits: &str, gray: bool) -> u64 {
    let mut v = 0u64;
    let mut last = false;
    for c in bits.chars() {
        let b = c == '1';
        let bin = if gray { last ^ b } else { b };
        last = bin;
        v = (v << 1) | bin as u64;
    }
    v
}

/// Reads every SSI read of `path`.
pub fn decode(path: &Path, clk: &str, data: &str, layout: &Layout) -> Result<Vec<ReadSeen>> {
    let signals = capture::read(path, &[(clk, "--clk"), (data, "--data")])?;
    let (clk_line, data_line) = (&signals[0], &signals[1]);
    let edges = clk_line.edges();
    let mut reads = Vec::new();
    let mut i = 0;
    while i < edges.len() {
        if edges[i].1 {
            i += 1;
            continue;
        }
        // A burst: from this falling edge, edges no further apart than three
        // of its half periods (the first low phase, T_cs, may be longer: the
        // half period is taken from the second gap on).
        let mut j = i + 1;
        let mut half: Option<u64> = None;
        while j < edges.len() {
            let gap = edges[j].0 - edges[j - 1].0;
            if j > i + 1 && gap > 3 * *half.get_or_insert(gap) {
                break;
            }
            j += 1;
        }
        let burst = &edges[i..j];
        // Low phases after the first: (falling, rising) pairs from the second falling edge.
        let mut bits = String::new();
        for w in burst.windows(2).skip(1) {
            if !w[0].1 && w[1].1 {
                bits.push(if data_line.level_at(w[1].0.saturating_sub(1)) { '1' } else { '0' });
            }
        }
        let end_ps = burst.last().map_or(burst[0].0, |e| e.0);
        reads.push((burst[0].0, end_ps, bits));
        i = j;
    }
    let copies = if layout.double_read { 2 } else { 1 };
    let extra = layout.wire_check as u32;
    let mut out = Vec::new();
    for (index, (start_ps, end_ps, bits)) in reads.into_iter().enumerate() {
        let n = bits.len() as u32;
        let width = match layout.bits {
            Some(b) => {
                if b * copies + extra != n {
                    let fits = n.checked_sub(extra).filter(|m| m % copies == 0 && *m > 0).map(|m| m / copies);
                    let hint = fits.map_or_else(|| "no --bits fits with these options".to_string(), |b| format!("--bits {b} would fit"));
                    return Err(Error::Decode(format!(
                        "{}: read {index} at {start_ps} ps carries {n} bits, but --bits {b}{}{} reads {}: {hint}",
                        path.display(),
                        if layout.double_read { " with --double-read" } else { "" },
                        if layout.wire_check { " with --wire-check" } else { "" },
                        b * copies + extra
                    )));
                }
                b
            }
            None => n.saturating_sub(extra) / copies,
        };
        let mut errors = Vec::new();
        let position = (width > 0 && width <= 64).then(|| value(&bits[..width as usize], layout.gray));
        if layout.double_read && n >= 2 * width && bits[..width as usize] != bits[width as usize..2 * width as usize] {
            errors.push("double_read_mismatch".to_string());
        }
        if layout.wire_check && bits.ends_with('1') {
            errors.push("wire_check_failed".to_string());
        }
        out.push(ReadSeen { index, start_ps, end_ps, received_bits: bits, position, errors });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{builtin, generate, Setup};

    fn layout_of(cfg: &model::ssi::BenchConfig) -> Layout {
        Layout { bits: Some(cfg.master.bits), gray: cfg.master.code == model::ssi::Code::Gray, double_read: cfg.master.double_read, wire_check: cfg.master.wire_check }
    }

    /// Every SSI scenario: the reads on the line at the master carry the
    /// bits the model's reader sampled, and give its position and flags.
    #[test]
    fn every_read_of_every_ssi_scenario_equals_the_gen_transcript() {
        let scenarios: Vec<_> = builtin::all().unwrap().into_iter().filter(|s| matches!(s.setup, Setup::Ssi(_))).collect();
        assert!(scenarios.len() >= 10);
        let mut compared = 0;
        for s in &scenarios {
            let Setup::Ssi(cfg) = &s.setup else { unreachable!() };
            let dir = tempfile::tempdir().unwrap();
            let summary = generate::generate(s, dir.path()).unwrap();
            let vcd = summary.files.iter().find(|f| f.extension().is_some_and(|x| x == "vcd")).unwrap();
            let json = summary.files.iter().find(|f| f.extension().is_some_and(|x| x == "json")).unwrap();
            let model: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap();
            // A refused start (line low) never clocks: the line shows no read.
            let model: Vec<&serde_json::Value> = model["transactions"].as_array().unwrap().iter().filter(|t| !t["received_bits"].as_str().unwrap().is_empty()).collect();
            let seen = decode(vcd, "top.line.ssi_clk_master", "top.line.ssi_data_master", &layout_of(cfg)).unwrap();
            assert_eq!(seen.len(), model.len(), "{}: reads", s.name);
            for (d, m) in seen.iter().zip(&model) {
                assert_eq!(d.received_bits, m["received_bits"].as_str().unwrap(), "{} read {}", s.name, d.index);
                assert_eq!(d.position, m["position"].as_u64(), "{} read {}", s.name, d.index);
                let flags: Vec<String> = m["errors"].as_array().unwrap().iter().map(|e| e.as_str().unwrap().to_string()).collect();
                assert_eq!(d.errors, flags, "{} read {}", s.name, d.index);
                compared += 1;
            }
        }
        assert!(compared >= 30, "{compared} reads compared");
    }

    /// The seed's example (SAR58K24 manual, SSI section (4)): DATA+ 0 0 0 1 1 1 1 0 1 1 1 1 = 495.
    #[test]
    fn the_seed_example_reads_495() {
        let s = builtin::resolve("ssi_seed_12bit").unwrap();
        let dir = tempfile::tempdir().unwrap();
        let summary = generate::generate(&s, dir.path()).unwrap();
        let vcd = summary.files.iter().find(|f| f.extension().is_some_and(|x| x == "vcd")).unwrap();
        let layout = Layout { bits: Some(12), gray: false, double_read: false, wire_check: false };
        let seen = decode(vcd, "top.line.ssi_clk_master", "top.line.ssi_data_master", &layout).unwrap();
        assert_eq!(seen[0].received_bits, "000111101111");
        assert_eq!(seen[0].position, Some(495));
        let wrong = Layout { bits: Some(13), ..layout };
        let msg = decode(vcd, "top.line.ssi_clk_master", "top.line.ssi_data_master", &wrong).unwrap_err().to_string();
        assert!(msg.contains("carries 12 bits, but --bits 13 reads 13: --bits 12 would fit"), "{msg}");
    }
}
