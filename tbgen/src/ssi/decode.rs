//! `tbgen decode ssi`: the reads of an SSI line from its clock and data, as
//! the master sees them (a `tbgen gen` VCD, or the RTL's own waves from
//! `make sim WAVES=1` with `--clk tb_ssi_master.o_ssi_clk --data
//! tb_ssi_master.i_ssi_data`).
//!
//! The decode core (what a read is, where each bit is sampled) is
//! [`model::ssi::decode`], shared with the co-simulation monitor.

use std::path::Path;

pub use model::ssi::decode::{Layout, ReadSeen};

use crate::capture;
use crate::{Error, Result};

/// Reads every SSI read of `path` with the model's decode core
/// ([`model::ssi::decode`], which the co-simulation monitor shares).
pub fn decode(path: &Path, clk: &str, data: &str, layout: &Layout) -> Result<Vec<ReadSeen>> {
    let signals = capture::read(path, &[(clk, "--clk"), (data, "--data")])?;
    model::ssi::decode::decode(&signals[0], &signals[1], layout).map_err(|e| Error::Decode(format!("{}: {e}", path.display())))
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
