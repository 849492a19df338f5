//! `tbgen probes`: the rule probes of `cosim::probe` for the simulators.
//!
//! [`export`] writes every kit's probes into a folder, all or nothing:
//!
//! | file | what it is |
//! |---|---|
//! | `probes.tsv` | one line per probe: kind, emulator clock (Hz), stimulus depth of the kind, folder |
//! | `<kind>/probe_wiring.vh` | the emulator and monitor wrappers wired for `hdl/tb_probe/tb_probe.v` ([`wiring`]) |
//! | `<kind>/probe_wiring.vhd` | their VHDL twins wired for `hdl/tb_probe/tb_probe.vhd` (GHDL) |
//! | `<kind>/probe_pins.v` | the cocotb top level: the master's pins under the emulator's port names |
//! | `<kind>/wiring.json` | the same wiring for Python: input ports by layout bit, the monitor's sources |
//! | `<kind>/<NN>_<rule>_<legal\|illegal>/probe.toml` | the emulator's and monitor's configuration |
//! | `.../stimulus.mem` | the master's pins on the emulator clock ([`stimulus`]) |
//! | `.../monitor.mem` | the kit's monitor wiring, one byte per pin ([`wiring::src_byte`]) |
//! | `.../probe.json` | the probe and its expected verdict |
//!
//! A simulator's run of a probe leaves `emulator.json`, `monitor.json`
//! (the wrappers' transcripts) and `sim.log` in `<probe>/<simulator>/`;
//! [`check`] reads them into a `cosim::probe::Outcome` and judges it with
//! `cosim::probe::verdict`, the judgement of the library's own run.

mod check;
mod export;
pub mod wiring;

pub use check::check;
pub use export::{export, stimulus};

/// The manifest of an export folder.
pub const MANIFEST: &str = "probes.tsv";

/// The simulators a probe run can come from (each its folder in a probe's).
pub const SIMULATORS: &[&str] = &["icarus", "verilator", "cocotb", "ghdl"];

/// A probe's folder name: its index in the kit, its rule, legal or not.
pub fn folder(index: usize, p: &cosim::probe::Probe) -> String {
    let rule: String = p
        .rule
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    format!(
        "{index:02}_{rule}_{}",
        if p.legal { "legal" } else { "illegal" }
    )
}

/// What `probe.json` holds for `p`, the `index`th of its kit.
pub fn description(index: usize, p: &cosim::probe::Probe) -> serde_json::Value {
    serde_json::json!({
        "protocol": p.protocol,
        "index": index,
        "rule": p.rule,
        "legal": p.legal,
        "what": p.what,
        "f_hz": p.f_hz,
        "unknown": p.unknown,
        "unknown_ps": p.unknown_ps,
        "reads": p.reads,
        "expect": if p.legal {
            "quiet: no report from the emulator or the monitor".to_string()
        } else {
            format!("flagged: {} and no other rule, from both, with the same text", p.rule)
        },
    })
}
