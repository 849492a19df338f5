//! Whatever a testbench gives the emulators and monitors (a configuration
//! with any number in it, any emulator clock, any pin sequence, any
//! run-time call), they answer with values or errors, never a panic: a
//! panic inside a simulator is at best an "internal error" from the C ABI's
//! guard, at worst a dead simulation.
//!
//! From each closed-loop configuration of `hdl/tb_cosim/*/configs/`, for the
//! core's emulator and its monitor:
//! - every number, one at a time, set to each of a list of awkward values
//!   (the list of `tests/bad_values.rs`); an error names the file, the
//!   line and the field, an accepted one is stepped on random pins (a NaN may be taken
//!   here: the configuration is a whole scenario, and each of emulator and
//!   monitor reads only its own part of it);
//! - awkward emulator clocks;
//! - the configuration as written, stepped on random pins (levels held 1 to
//!   300 cycles, so that some edges look like real clocks and frames), with
//!   run-time calls of every kind between the steps, arguments out of range
//!   and TOML that is not.

use std::path::Path;

use cosim::{open, Emulator, Pins};
use toml::Value;

#[path = "../../../tests/support/sweep.rs"]
mod sweep;
use sweep::{awkward_values, caught, dotted, leaf_mut, numeric_leaves, quiet_panics, shown, Rng};

/// Each closed loop (`hdl/tb_cosim/<loop>/`) and its protocol's emulator
/// kind, from the descriptors; `<kind>_monitor` is its monitor.
fn kinds() -> Vec<(&'static str, &'static str)> {
    model::protocol::closed_loops()
        .map(|(p, l)| {
            let e = p.emulator.as_ref();
            (
                l.name,
                e.unwrap_or_else(|| panic!("{}: a closed loop without an emulator", l.name))
                    .kind,
            )
        })
        .collect()
}

/// `cycles` cycles of random pins (bits 0 to 3), each level held 1 to 300 cycles.
fn random_pins(emu: &mut dyn Emulator, rng: &mut Rng, cycles: u64) {
    let mut k = 0;
    while k < cycles {
        let pins = Pins(rng.below(16) as u32);
        let hold = 1 + rng.below(300) as u64;
        for _ in 0..hold {
            emu.step(pins);
        }
        k += hold;
    }
}

/// Every run-time call with arguments a testbench could pass, right or wrong.
fn poke(emu: &mut dyn Emulator, rng: &mut Rng) {
    let device = [0usize, 1, 7, usize::MAX][rng.below(4)];
    let _ = emu.set_position(device, rng.next());
    for name in ["error", "warning", "alarm", "power", "", "no such status"] {
        let _ = emu.set_status(device, name, rng.below(2) == 1);
        let _ = emu.last_status(device, name);
    }
    for text in [
        "",
        "x = ",
        "[motion]\nspeed = nan",
        "[motion]\nkind = \"ramp\"\nspeed_cps = 1e300",
        "[[faults]]\nkind = \"flip\"\nbit = -1",
        "[[flips]]\nframe = 18446744073709551615",
    ] {
        let _ = emu.set_motion(device, text);
        let _ = emu.schedule_fault(text);
    }
    let _ = (
        emu.count(),
        emu.last_value(device),
        emu.transcript(),
        emu.take_violation(),
    );
}

#[derive(Default)]
struct Tally {
    tried: usize,
    refused: usize,
    stepped: usize,
    panics: Vec<String>,
    unnamed: Vec<String>,
    /// Opens that took a NaN: counted, not failed, since an emulator does
    /// not read the master's fields (`[ssi.master]`) and a monitor not the
    /// encoder's, and a field nobody reads may hold anything.
    took_nan: Vec<String>,
}

impl Tally {
    /// Opens `kind` on `text` at `f_emu_hz`; an error must name `origin`,
    /// the line and the field (or the clock), an accepted emulator is
    /// stepped a while.
    fn try_open(
        &mut self,
        kind: &str,
        text: &str,
        origin: &str,
        f_emu_hz: u64,
        nan: bool,
        rng: &mut Rng,
    ) {
        self.tried += 1;
        let run = caught(|| match open(kind, text, origin, f_emu_hz) {
            Err(e) => Err(e.to_string()),
            Ok(mut emu) => {
                random_pins(emu.as_mut(), rng, 3_000);
                Ok(())
            }
        });
        match run {
            Err(p) => self
                .panics
                .push(format!("{kind} {origin} f_emu {f_emu_hz} Hz: {p}")),
            Ok(Err(message)) => {
                self.refused += 1;
                // The file, then the line (`<origin>:<line>:`, or the TOML
                // parser's `at line <n>`) and the field in backticks; an
                // emulator clock, which no file holds, by name.
                let clock = message.contains("emulator clock");
                let line = message
                    .strip_prefix(&format!("{origin}:"))
                    .is_some_and(|rest| rest.starts_with(|c: char| c.is_ascii_digit()))
                    || message.contains(" line ");
                if !message.starts_with(origin) || !(clock || line && message.contains('`')) {
                    self.unnamed.push(format!("{kind}: {message}"));
                }
            }
            Ok(Ok(())) => {
                self.stepped += 1;
                if nan {
                    self.took_nan.push(format!("{kind} {origin}"));
                }
            }
        }
    }
}

fn configs() -> Vec<(String, &'static str, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../hdl/tb_cosim");
    let mut out = Vec::new();
    for (core, kind) in kinds() {
        let dir = root.join(core).join("configs");
        let mut files: Vec<_> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.expect("a directory entry").path())
            .collect();
        files.sort();
        for f in files {
            let text = std::fs::read_to_string(&f).expect("a configuration reads");
            out.push((
                format!(
                    "hdl/tb_cosim/{core}/configs/{}",
                    f.file_name().unwrap().to_string_lossy()
                ),
                kind,
                text,
            ));
        }
    }
    out
}

/// The configuration's system clock in Hz: the closed loops run the emulator on it.
fn f_sys_hz(doc: &Value) -> u64 {
    doc.as_table()
        .and_then(|t| t.values().find_map(|v| v.get("f_sys_mhz")))
        .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
        .map_or(50_000_000, |mhz| (mhz * 1e6) as u64)
}

#[test]
fn emulators_and_monitors_answer_any_configuration_clock_and_pins_without_a_panic() {
    quiet_panics();
    let mut tally = Tally::default();
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let configs = configs();
    assert!(configs.len() >= 30, "{} configurations", configs.len());
    for (origin, kind, text) in &configs {
        let doc: Value = toml::from_str(text).expect("a configuration is TOML");
        let f = f_sys_hz(&doc);
        let monitor = format!("{kind}_monitor");
        for k in [*kind, monitor.as_str()] {
            // As written, on random pins with every run-time call between.
            let run = caught(|| {
                let mut emu = open(k, text, origin, f)
                    .unwrap_or_else(|e| panic!("a closed-loop configuration opens: {e}"));
                for _ in 0..20 {
                    random_pins(emu.as_mut(), &mut rng, 1_000);
                    poke(emu.as_mut(), &mut rng);
                }
            });
            if let Err(p) = run {
                tally
                    .panics
                    .push(format!("{k} {origin} on random pins and calls: {p}"));
            }
            for hz in [0, 1, 999_999_999, 1_000_000_001, u64::MAX] {
                tally.try_open(k, text, origin, hz, false, &mut rng);
            }
        }
        let mut leaves = Vec::new();
        numeric_leaves(&doc, &mut Vec::new(), &mut leaves);
        for (path, integer) in leaves {
            for new in awkward_values(integer) {
                let nan = matches!(new, Value::Float(v) if v.is_nan());
                let origin = format!("{origin}+{}={}", dotted(&path), shown(&new));
                let mut changed = doc.clone();
                *leaf_mut(&mut changed, &path) = new;
                let text = toml::to_string(&changed).expect("a TOML document serialises");
                for k in [*kind, monitor.as_str()] {
                    tally.try_open(k, &text, &origin, f, nan, &mut rng);
                }
            }
        }
    }
    println!("{} opens tried: {} refused, {} accepted and stepped on random pins ({} with a NaN in a field)", tally.tried, tally.refused, tally.stepped, tally.took_nan.len());
    assert!(
        tally.panics.is_empty(),
        "{} panics:\n{}",
        tally.panics.len(),
        tally.panics.join("\n")
    );
    assert!(
        tally.unnamed.is_empty(),
        "{} errors without the file, the line and the field:\n{}",
        tally.unnamed.len(),
        tally.unnamed.join("\n")
    );
    assert!(
        tally.refused > tally.tried / 4 && tally.stepped > tally.tried / 10,
        "the sweep reaches both sides"
    );
}

/// An emulator's or a monitor's error places its field on its line, as
/// `tbgen`'s do: a value the model refuses, and one of the wrong type.
#[test]
fn a_bad_field_is_named_on_its_line_by_emulator_and_monitor() {
    let text = "name = \"t\"\n[ssi]\nf_sys_mhz = 4\n\n[ssi.encoder]\ncode = \"gray\"\nbits = 70\n";
    for kind in ["ssi", "ssi_monitor"] {
        let e = open(kind, text, "t.toml", 4_000_000)
            .err()
            .expect("70 bits are refused")
            .to_string();
        assert!(
            e.starts_with("t.toml:7: ") && e.contains("bits"),
            "{kind}: {e}"
        );
        let e = open(kind, &text.replace("70", "-1"), "t.toml", 4_000_000)
            .err()
            .expect("-1 bits are refused")
            .to_string();
        assert!(
            e.starts_with("t.toml:7: ") && e.contains("encoder.bits`"),
            "{kind}: {e}"
        );
    }
}
