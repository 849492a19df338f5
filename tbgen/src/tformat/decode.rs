//! `tbgen decode tformat`: the line at a T-format host, captured as a VCD,
//! turned into the transactions of the `gen` transcript. The decode core is
//! [`model::tformat::decode`] (shared with the co-simulation monitor
//! `tformat_monitor`); this module reads the capture's two scalars, the
//! line at the host and the host's driver enable (the bytes alone cannot
//! say who sent them: the answer begins with the request's own control
//! field, and the driver enable is what a capture at a half-duplex
//! transceiver has beside the line).

use std::path::Path;

use crate::capture;
use crate::transcript::Decoded;
use crate::Result;

pub use model::tformat::decode::Transaction;

/// What the decoder needs besides the file.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Dotted path of the line at the host.
    pub line: String,
    /// Dotted path of the host's driver enable.
    pub tx_en: String,
    /// Bit rate, bit/s.
    pub baud: u64,
    /// The host's answer timeout, µs (`[tformat.host] timeout_us`).
    pub timeout_us: f64,
}

impl Default for Options {
    fn default() -> Self {
        Options { line: "top.line.line_at_host".into(), tx_en: "top.line.tx_en_host".into(), baud: 2_500_000, timeout_us: 10.0 }
    }
}

/// Decodes `path` with `options`.
pub fn decode(path: &Path, options: &Options) -> Result<Vec<Transaction>> {
    let signals = capture::read(path, &[(&options.line, "--line"), (&options.tx_en, "--tx-en")])?;
    Ok(model::tformat::decode::decode(&signals[0], &signals[1], options.baud, options.timeout_us))
}

/// The JSON `tbgen decode tformat` prints.
pub fn to_json(path: &Path, options: &Options, transactions: &[Transaction]) -> Result<String> {
    let decoded = Decoded::new("tformat", path, &[("line", &options.line), ("tx_en", &options.tx_en)], transactions);
    serde_json::to_string_pretty(&decoded).map_err(|e| crate::Error::Decode(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Setup;
    use crate::{builtin, generate};

    #[test]
    fn decoding_the_line_of_every_tformat_scenario_gives_back_every_field_of_gens_transcript() {
        let dir = tempfile::tempdir().unwrap();
        let (mut scenarios, mut compared) = (0, 0);
        for s in builtin::all().unwrap().into_iter().filter(|s| s.core() == "tformat_host") {
            let Setup::Tformat(cfg) = &s.setup else { unreachable!("{} runs tformat_host", s.name) };
            let summary = generate::generate(&s, dir.path()).unwrap();
            let gen: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
            let options = Options { baud: cfg.baud as u64, timeout_us: cfg.host.timeout_us, ..Options::default() };
            let decoded = decode(&summary.files[1], &options).unwrap();
            let gen = gen["transactions"].as_array().unwrap();
            assert_eq!(decoded.len(), gen.len(), "{}: transactions", s.name);
            let period_ps = 1_000_000 / cfg.f_sys_mhz as u64;
            for (d, g) in decoded.iter().zip(gen) {
                // The driver turns on at the edge that takes the start pulse.
                assert_eq!(d.start_ps, g["start_cycle"].as_u64().unwrap() * period_ps, "{} #{}: start", s.name, d.index);
                for (key, value) in serde_json::to_value(d).unwrap().as_object().unwrap() {
                    if key != "start_ps" {
                        assert_eq!(value, &g[key], "{} #{}: `{key}` decoded vs gen", s.name, d.index);
                        compared += 1;
                    }
                }
            }
            scenarios += 1;
        }
        assert!(scenarios >= 15 && compared >= 15 * 20, "{scenarios} scenarios, {compared} fields compared");
    }

    #[test]
    fn a_capture_without_the_driver_enable_names_the_option_that_fixes_it() {
        let s = builtin::find("tformat_no_answer").unwrap();
        let dir = tempfile::tempdir().unwrap();
        let summary = generate::generate(&s, dir.path()).unwrap();
        let options = Options { tx_en: "top.line.de".into(), ..Options::default() };
        let e = decode(&summary.files[1], &options).unwrap_err().to_string();
        assert!(e.contains("top.line.de") && e.contains("--tx-en") && e.contains("tformat_no_answer.vcd"), "{e}");
    }
}
