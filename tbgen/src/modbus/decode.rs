//! `tbgen decode modbus`: the line at a Modbus RTU master, captured as a
//! VCD, turned into the polls of the `gen` transcript. The decode core is
//! [`model::modbus::decode`] (shared with the co-simulation monitor
//! `modbus_monitor`); this module reads the capture's two scalars.
//!
//! Two scalars are read: the line at the master and the master's driver
//! enable (the bytes alone cannot say who sent them). Every character is read
//! with its parity and stop bit ([`crate::uart::line::chars`]). A poll runs
//! from the driver turning on to the next time it does: the characters
//! sent while it is on are the request, the others the answers on the wire.
//! The answer is judged as `model::modbus::Master` judges it: it begins
//! within the timeout after the request, ends after t3.5 of silence (counted,
//! as the master counts it, from each stop bit's middle), is spoiled by a
//! parity or framing error or a silence over t1.5 inside it, and is then
//! checked for length, CRC, address, exception, function and count (or, for
//! the address change, the echo). What only the model knows is left out:
//! cycle numbers and the operation the master meant (the request on the
//! wire says it, unless another driver spoiled it).

use std::path::Path;

use model::uart::Parity;

use crate::capture;
use crate::uart::line;
use crate::Result;

pub use model::modbus::decode::Transaction;

/// What the decoder needs besides the file.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Dotted path of the line at the master.
    pub line: String,
    /// Dotted path of the master's driver enable.
    pub tx_en: String,
    /// Baud.
    pub baud: f64,
    /// Character format.
    pub parity: Parity,
    /// The master's answer timeout, µs (`[modbus.master] timeout_us`).
    pub timeout_us: f64,
    /// The devices send Gray code (`[[modbus.devices]] gray`).
    pub gray: bool,
}

/// Decodes `path` with `options`.
pub fn decode(path: &Path, options: &Options) -> Result<Vec<Transaction>> {
    let signals = capture::read(path, &[(&options.line, "--line"), (&options.tx_en, "--tx-en")])?;
    let o = model::modbus::decode::Options { baud: options.baud, parity: options.parity, timeout_us: options.timeout_us, gray: options.gray };
    Ok(model::modbus::decode::decode(&signals[0], &signals[1], &o))
}

/// The JSON `tbgen decode modbus` prints.
pub fn to_json(path: &Path, options: &Options, transactions: &[Transaction]) -> Result<String> {
    line::to_json("modbus", path, &options.line, &options.tx_en, transactions)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builtin;
    use crate::scenario::Setup;
    use crate::uart::line::generated;

    fn options(cfg: &model::modbus::BenchConfig) -> Options {
        Options {
            line: "top.line.line_at_master".into(),
            tx_en: "top.line.tx_en_master".into(),
            baud: cfg.baud,
            parity: cfg.parity,
            timeout_us: cfg.master.timeout_us,
            gray: cfg.devices[0].gray,
        }
    }

    #[test]
    fn decoding_the_line_of_every_modbus_scenario_gives_back_every_field_of_gens_transcript() {
        let dir = tempfile::tempdir().unwrap();
        let (mut scenarios, mut compared, mut faults) = (0, 0, 0);
        for name in builtin::all().unwrap().into_iter().filter(|s| s.core() == "modbus_master").map(|s| s.name) {
            let (s, vcd, gen) = generated(&name, dir.path());
            let Setup::Modbus(cfg) = &s.setup else { unreachable!("{} runs modbus_master", s.name) };
            let decoded = decode(&vcd, &options(cfg)).unwrap();
            let gen = gen["transactions"].as_array().unwrap();
            assert_eq!(decoded.len(), gen.len(), "{}: transactions", s.name);
            for (d, g) in decoded.iter().zip(gen) {
                for (key, value) in serde_json::to_value(d).unwrap().as_object().unwrap() {
                    // The query names no station, and only a read has a count: the
                    // transcript's are the scenario's unused defaults.
                    if key == "start_ps" || (key == "address" && d.op == "query") || (key == "count" && d.op != "read") {
                        continue;
                    }
                    assert_eq!(value, &g[key], "{} #{}: `{key}` decoded vs gen", s.name, d.index);
                    compared += 1;
                }
                faults += d.errors.len();
            }
            scenarios += 1;
        }
        assert!(scenarios >= 5 && compared >= 5 * 20 && faults >= 10, "{scenarios} scenarios, {compared} fields, {faults} faults compared");
    }

    #[test]
    fn a_capture_without_the_named_line_lists_the_captures_signals() {
        let dir = tempfile::tempdir().unwrap();
        let (s, vcd, _) = generated("modbus_seed_19200", dir.path());
        let Setup::Modbus(cfg) = &s.setup else { unreachable!() };
        let e = decode(&vcd, &Options { line: "top.line.rx".into(), ..options(cfg) }).unwrap_err().to_string();
        assert!(e.contains("top.line.rx") && e.contains("--line") && e.contains("modbus_seed_19200.vcd") && e.contains("line.line_at_master"), "{e}");
    }
}
