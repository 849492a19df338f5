//! The rule probes: for every rule of the rule book ([`model::rules::all`]),
//! pin-level stimuli of a master that meet its limit by a small margin and
//! that break it by a small margin, and the harness that runs them through
//! a protocol's emulator and monitor as a simulator would: one step per
//! rising edge of their clock, the emulator seeing the master's pins, the
//! monitor the master's pins and the emulator's answer.
//!
//! The probes are data ([`Probe`]: the master's pins as timed segments), so
//! that the same stimuli run here through the [`Emulator`] trait (the suite
//! `cosim/tests/unit/rules.rs`, which writes `docs/rules.md`) and can be
//! written out for the simulators' and cocotb's probe runs.
//!
//! A protocol's probes live in `probe/<kind>.rs` with its [`Kit`]. A
//! stimulus is the master's pins in the emulator's input layout
//! ([`Pins`]: bit 0 the line clock, bit 1 the master's data, bit 2 its
//! driver enable); the monitor's pins are wired from it and from the
//! emulator's answer as [`Kit::monitor`] lists, data that the simulators'
//! testbenches read too, so the wiring is written once.

pub mod biss;
pub mod can;
pub mod canopen;
pub mod endat;
pub mod esl;
mod half_duplex;
pub mod modbus;
pub mod sar;
pub mod ssi;
pub mod tformat;
mod uart;

use serde_json::Value;

use crate::{open, Pins};
use model::rules;

/// Nanoseconds in ps.
pub const NS: u64 = 1_000;
/// Microseconds in ps.
pub const US: u64 = 1_000_000;

/// The master's pins as `(levels, ps)` segments, in the layout of the
/// protocol's [`Kit::wire`].
pub type Stimulus = Vec<(u32, u64)>;

/// One stimulus: what it shows, the rule it probes, whether it must pass.
#[derive(Debug, Clone)]
pub struct Probe {
    /// The emulator kind (`cosim::open`), `<kind>_monitor` its monitor.
    pub protocol: &'static str,
    /// The rule's name in the protocol's rule book.
    pub rule: &'static str,
    /// The stimulus meets the rule (no report from either side) or breaks
    /// it (exactly that rule from both).
    pub legal: bool,
    /// What the stimulus is, as `docs/rules.md` says it.
    pub what: &'static str,
    /// The emulator's (and monitor's) configuration.
    pub toml: &'static str,
    /// The emulator and monitor clock.
    pub f_hz: u64,
    /// The master's pins.
    pub line: Stimulus,
    /// Pins the master leaves unknown (X in a four-state simulator) from
    /// time 0 until [`Probe::unknown_ps`], a master in reset before it
    /// drives them: the library run reads them as 0, as the wrappers read
    /// X or Z on a driver enable (not driving).
    pub unknown: u32,
    /// The end of the unknown stretch, ps.
    pub unknown_ps: u64,
    /// Positions the emulator must have latched and the monitor decoded, in
    /// order (none: not checked).
    pub reads: &'static [u64],
}

/// Where a monitor pin comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Src {
    /// A pin of the master (a bit of the stimulus).
    Master(u32),
    /// A pin of the emulator's output at the master's end of the line
    /// (bit 0 its data, bit 1 its driver enable).
    Emulator(u32),
    /// The half-duplex line at the master's receiver: the emulator's data
    /// while it drives, else the master's data (bit 1) while the master
    /// drives (bit 2), else high (the RS-485 fail-safe bias of an idle line).
    Bus,
    /// A wired-AND bus (CAN, dominant low): the master's pin `n` and the
    /// emulator's data.
    WiredAnd(u32),
}

impl Src {
    /// The level of the source, given the master's and the emulator's pins.
    pub fn level(self, master: u32, answer: Pins) -> bool {
        let bit = |v: u32, n: u32| v >> n & 1 != 0;
        match self {
            Src::Master(n) => bit(master, n),
            Src::Emulator(n) => bit(answer.0, n),
            Src::Bus => crate::half_duplex::receiver(bit(master, 1), bit(master, 2), answer),
            Src::WiredAnd(n) => bit(master, n) && answer.data(),
        }
    }
}

/// A protocol's probes and wiring.
#[derive(Debug, Clone, Copy)]
pub struct Kit {
    /// The emulator kind.
    pub protocol: &'static str,
    /// The monitor's pins, bit 0 first: where each comes from.
    pub monitor: &'static [Src],
    /// The emulator's output before its first step (its line idle).
    pub idle: Pins,
    /// The probes.
    pub probes: fn() -> Vec<Probe>,
}

impl Kit {
    /// The monitor's pins, given the master's and the emulator's.
    pub fn monitor_pins(&self, master: u32, answer: Pins) -> Pins {
        Pins(
            self.monitor
                .iter()
                .enumerate()
                .map(|(i, s)| (s.level(master, answer) as u32) << i)
                .sum(),
        )
    }
}

/// Every protocol's kit.
pub fn kits() -> Vec<Kit> {
    vec![
        ssi::KIT,
        tformat::KIT,
        biss::KIT,
        endat::KIT,
        esl::KIT,
        sar::KIT,
        modbus::KIT,
        can::KIT,
        canopen::KIT,
    ]
}

/// Every probe of every protocol.
pub fn all() -> Vec<Probe> {
    kits().iter().flat_map(|k| (k.probes)()).collect()
}

/// The kit of the emulator kind `protocol`.
pub fn kit(protocol: &str) -> Option<Kit> {
    kits().into_iter().find(|k| k.protocol == protocol)
}

/// What the emulator and the monitor reported, as `(rule name, text)`, and
/// the positions each saw.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The emulator's reports.
    pub emulator: Vec<(String, String)>,
    /// The monitor's reports.
    pub monitor: Vec<(String, String)>,
    /// Positions the emulator latched.
    pub latched: Vec<u64>,
    /// Positions the monitor decoded (`None`: a transaction without one).
    pub decoded: Vec<Option<u64>>,
}

/// The rule of the book a report's label names; `Err` with the label when
/// the book holds no such rule (a report without a rule).
pub fn named(label: &str) -> Result<String, String> {
    rules::all()
        .iter()
        .find(|r| r.label() == label)
        .map(|r| r.name.to_string())
        .ok_or_else(|| format!("a report names no rule of the rule book: `{label}`"))
}

/// The position of a transcript entry: its own, or its first slave's.
fn position(x: &Value) -> Option<u64> {
    x.get("position")
        .or_else(|| x.get("slaves").and_then(|s| s.get(0)?.get("position")))
        .and_then(Value::as_u64)
}

/// The list of a transcript: the first of `keys` it has.
fn entries<'a>(t: &'a Value, keys: &[&str]) -> &'a [Value] {
    keys.iter()
        .find_map(|k| t.get(*k).and_then(Value::as_array))
        .map(Vec::as_slice)
        .unwrap_or(&[])
}

/// Runs `p` through the library: every sample of the emulator clock, the
/// monitor first (it sees the answer the master sees now), then the
/// emulator.
pub fn run(p: &Probe) -> Result<Outcome, String> {
    let kit = kit(p.protocol).ok_or_else(|| format!("no probe kit for `{}`", p.protocol))?;
    let mut emu = open(p.protocol, p.toml, "probe.toml", p.f_hz).map_err(|e| e.to_string())?;
    let mut mon = open(
        &format!("{}_monitor", p.protocol),
        p.toml,
        "probe.toml",
        p.f_hz,
    )
    .map_err(|e| e.to_string())?;
    let mut answer = kit.idle;
    for (levels, unknown) in samples(p) {
        let master = if unknown { levels & !p.unknown } else { levels };
        mon.step(kit.monitor_pins(master, answer));
        answer = emu.step(Pins(master));
    }
    outcome(&emu.transcript(), &mon.transcript())
}

/// Checks `o` against `p`: a legal probe draws no report from either side,
/// an illegal one exactly its rule from both, with the same text; the
/// positions are the ones the probe names. `Err` says what differs.
pub fn verdict(p: &Probe, o: &Outcome) -> Result<(), String> {
    let label = format!("{} {} `{}`", p.protocol, p.rule, p.what);
    if !rules::all()
        .iter()
        .any(|r| r.protocol == p.protocol && r.name == p.rule)
    {
        return Err(format!(
            "{label}: names `{}`, which the {} rule book lacks",
            p.rule, p.protocol
        ));
    }
    if p.legal {
        if !o.emulator.is_empty() {
            return Err(format!("{label}: the emulator reported {:?}", o.emulator));
        }
        if !o.monitor.is_empty() {
            return Err(format!("{label}: the monitor reported {:?}", o.monitor));
        }
    } else {
        for (side, list) in [("emulator", &o.emulator), ("monitor", &o.monitor)] {
            if list.is_empty() {
                return Err(format!("{label}: the {side} saw no break"));
            }
            if list.iter().any(|(r, _)| r != p.rule) {
                return Err(format!(
                    "{label}: the {side} reported other rules: {list:?}"
                ));
            }
        }
        if o.emulator != o.monitor {
            return Err(format!(
                "{label}: the emulator and the monitor say it differently: {:?} against {:?}",
                o.emulator, o.monitor
            ));
        }
    }
    if !p.reads.is_empty() {
        if o.latched != p.reads {
            return Err(format!(
                "{label}: the emulator latched {:?}, not {:?}",
                o.latched, p.reads
            ));
        }
        let want: Vec<Option<u64>> = p.reads.iter().map(|&v| Some(v)).collect();
        if o.decoded != want {
            return Err(format!(
                "{label}: the monitor decoded {:?}, not {:?}",
                o.decoded, want
            ));
        }
    }
    Ok(())
}

/// The master's pins at each sample of the emulator clock (sample `n` at
/// [`rules::ps_at`]`(n, f_hz)`, the level of the segment holding that
/// instant) and whether the probe's `unknown` pins are still unknown
/// there: the one sampling of a probe, which [`run`] steps the library
/// through and the simulators' stimulus files are written from.
pub fn samples(p: &Probe) -> impl Iterator<Item = (u32, bool)> + '_ {
    let total: u64 = p.line.iter().map(|s| s.1).sum();
    let (mut seg, mut seg_end) = (0, p.line.first().map_or(0, |s| s.1));
    (0..)
        .map(move |n| rules::ps_at(n, p.f_hz))
        .take_while(move |&t| t < total)
        .map(move |t| {
            while t >= seg_end {
                seg += 1;
                seg_end += p.line[seg].1;
            }
            (p.line[seg].0, t < p.unknown_ps)
        })
}

/// The [`Outcome`] of a run from the emulator's and the monitor's
/// transcripts (the JSON the library, the Verilog wrappers and the Python
/// module write alike): their `violations` as `(rule name, detail)`, the
/// positions latched and decoded. `Err` names a report whose rule is not in
/// the rule book.
pub fn outcome(emulator: &Value, monitor: &Value) -> Result<Outcome, String> {
    let reports = |t: &Value| -> Result<Vec<(String, String)>, String> {
        entries(t, &["violations"])
            .iter()
            .map(|v| {
                let field = |k: &str| v.get(k).and_then(Value::as_str).unwrap_or_default();
                Ok((named(field("rule"))?, field("detail").to_string()))
            })
            .collect()
    };
    Ok(Outcome {
        emulator: reports(emulator)?,
        monitor: reports(monitor)?,
        latched: entries(emulator, &["reads", "frames", "transfers", "transactions"])
            .iter()
            .filter_map(position)
            .collect(),
        decoded: entries(monitor, &["transactions"])
            .iter()
            .map(position)
            .collect(),
    })
}
