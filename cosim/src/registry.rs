//! Which emulator and monitor each protocol has: one line per protocol
//! with an emulator, its descriptor (`model::<module>::descriptor`, which
//! names the kinds `open` takes) and the two constructors. [`open`](crate::open)
//! finds a kind here, and its error lists the kinds from here.

use crate::{monitor, Emulator, Result};

/// An emulator or monitor made from TOML text, its origin and `f_emu_hz`.
pub type Open = fn(&str, &str, u64) -> Result<Box<dyn Emulator>>;

/// A protocol's emulator and monitor.
pub struct Kind {
    /// The protocol's descriptor: the emulator's kind and aliases, its table.
    pub protocol: &'static model::protocol::Protocol,
    /// Makes the emulator.
    pub emulator: Open,
    /// Makes the monitor.
    pub monitor: Open,
}

/// `kind!(module::Emulator, monitor module::Monitor)`: one line of
/// [`KINDS`]; the emulator's module is the model's (`sar58k24`), whose
/// descriptor names the kinds.
macro_rules! kind {
    ($module:ident :: $emulator:ident, $monitor_module:ident :: $monitor:ident) => {
        Kind {
            protocol: &model::$module::descriptor::PROTOCOL,
            emulator: |t, o, f| Ok(Box::new(crate::$module::$emulator::from_toml(t, o, f)?)),
            monitor: |t, o, f| {
                Ok(Box::new(monitor::$monitor_module::$monitor::from_toml(
                    t, o, f,
                )?))
            },
        }
    };
}

/// Every protocol with an emulator, in the model's listing order.
pub static KINDS: &[Kind] = &[
    kind!(ssi::SsiEmulator, ssi::SsiMonitor),
    kind!(tformat::TformatEmulator, tformat::TformatMonitor),
    kind!(biss::BissEmulator, biss::BissMonitor),
    kind!(endat::EndatEmulator, endat::EndatMonitor),
    kind!(esl::EslEmulator, esl::EslMonitor),
    kind!(sar58k24::SarEmulator, sar::SarMonitor),
    kind!(modbus::ModbusEmulator, modbus::ModbusMonitor),
    kind!(can::CanEmulator, can::CanMonitor),
    // Its alias `sar58k24_can`: the SAR58K24 in CAN mode shares the CANopen
    // bus and its [canopen] table ([[canopen.sar]]).
    kind!(canopen::CanopenEmulator, canopen::CanopenMonitor),
];

/// The emulator kind and its aliases of `k`.
fn names(k: &Kind) -> impl Iterator<Item = &'static str> {
    let e = k.protocol.emulator.as_ref();
    e.map(|e| e.kind)
        .into_iter()
        .chain(e.map_or(&[][..], |e| e.aliases).iter().copied())
}

/// The protocol, and whether a monitor is meant, of `kind` (`sar`,
/// `sar58k24_monitor`).
pub fn find(kind: &str) -> Option<(&'static Kind, bool)> {
    let (name, monitor) = match kind.strip_suffix("_monitor") {
        Some(name) => (name, true),
        None => (kind, false),
    };
    KINDS
        .iter()
        .find(|k| names(k).any(|n| n == name))
        .map(|k| (k, monitor))
}

/// What `open` takes, for its error: every emulator (with its aliases) and
/// every monitor.
pub fn choices() -> String {
    let emulators: Vec<String> = KINDS
        .iter()
        .map(|k| {
            let mut all = names(k);
            let kind = all.next().unwrap_or_default();
            let aliases: Vec<&str> = all.collect();
            match aliases.is_empty() {
                true => kind.to_string(),
                false => format!("{kind} (alias {})", aliases.join(", ")),
            }
        })
        .collect();
    let monitors: Vec<String> = KINDS
        .iter()
        .filter_map(|k| k.protocol.monitor_kind())
        .collect();
    format!(
        "give one of: {}, or a monitor: {}",
        emulators.join(", "),
        monitors.join(", ")
    )
}
