//! The Modbus RTU emulator: one to three [`model::modbus::Device`]s (the
//! SAR58K24 in its seventh mode) on a half-duplex cable.
//!
//! Configuration: the scenario's `[modbus]` table (`baud`, `parity`,
//! `[[devices]]`, `[cable]`; `[master]` gives the t1.5/t3.5 the devices keep,
//! as in the scenario); `[[ops]]`, `[[second_drivers]]` and `f_sys_mhz` are
//! ignored. The emulator's own tables are `[random]` (as for the SAR58K24:
//! `count` random positions per device from `seed`) and `[checks]`, the
//! limits of the rule book [`model::modbus::rules`], whose watcher the
//! emulator feeds every cycle exactly as the monitor does, so both print
//! the same rule and text.
//!
//! As in the model, a device answers the next entry of its `positions`
//! list (the last holding), until a testbench calls `set_position(device,
//! raw)` (every answer from then on carries `raw`) or `set_motion(device,
//! toml)` (a [`crate::motion`] profile from the call's cycle on);
//! [`Emulator::last_value`] is the value of the device's last function-03
//! answer, as on the wire (Gray when `gray`).
//! Statuses readable with `last_status`: `answered`, `discarded`,
//! `exception` (the last request the device saw).
//!
//! Pins as every half-duplex emulator's ([`crate::half_duplex`]): in bit 1
//! the master's driver level, bit 2 its enable; out bit 0 the devices'
//! level at the master's end, bit 1 their enable, bit 2 the resolved line
//! level.

use serde::{Deserialize, Serialize};

use model::bits::hex;
use model::modbus::rules::{Limits, Settings, Watch};
use model::modbus::{BenchConfig, Device, Verdict};

use crate::check::Checks;
use crate::config::{self, Error};
use crate::half_duplex::{
    character_limits, randomize, receiver, rule_limit, uart_bench, wire, Bus, RandomPositions, IDLE,
};
use crate::monitor::{field, proto_table};
use crate::{Emulator, Pins, Result};

/// The limits the master is held to (`[checks]`, and `[monitor]` for a
/// monitor's own: the first given wins), each optional.
#[derive(Debug, Clone, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct ModbusChecks {
    /// The master's answer timeout, µs (else `[master] timeout_us`, 5000).
    pub timeout_us: Option<f64>,
    /// The baud rate tolerance of the master's characters, % (2).
    pub baud_tolerance_percent: Option<f64>,
    /// The longest time from the request's last stop bit to DE off, bit times (1).
    pub release_bits: Option<f64>,
}

#[derive(Debug, Clone, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
struct Own {
    random: RandomPositions,
    /// Checked here for unknown fields; [`rule_limits`] reads it.
    #[allow(dead_code)]
    checks: ModbusChecks,
}

/// The rule limits of the configuration `text`, set up as `cfg`: what the
/// emulator and the monitor both hold the master to.
pub(crate) fn rule_limits(text: &str, origin: &str, cfg: &BenchConfig) -> Result<Limits> {
    let whole = proto_table(text, origin, "modbus")?;
    let mon: ModbusChecks = config::decode_in(&whole, "monitor", origin)?;
    let chk: ModbusChecks = config::decode_in(&whole, "checks", origin)?;
    let master = config::sub(&whole, "master", origin)?;
    let timeout = rule_limit(
        origin,
        [
            ("monitor.timeout_us", mon.timeout_us),
            ("checks.timeout_us", chk.timeout_us),
            (
                "master.timeout_us",
                field(&master, "timeout_us", origin, "master.timeout_us")?,
            ),
        ],
        5000.0,
    )?;
    let [tolerance_percent, release_bits] = character_limits(
        origin,
        [mon.baud_tolerance_percent, mon.release_bits],
        [chk.baud_tolerance_percent, chk.release_bits],
    )?;
    let settings = Settings {
        baud: cfg.baud,
        parity: cfg.parity,
        tolerance_percent,
        release_bits,
        timeout_us: timeout.1,
    };
    Limits::new(&settings).map_err(|e| Error::config(origin, e))
}

/// One request a device saw, and its answer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// The device (index in `[[devices]]`).
    pub device: usize,
    /// Emulator cycle the request ended (t3.5 of silence).
    pub cycle: u64,
    /// The request, hex.
    pub request: String,
    /// What the device did.
    pub verdict: Verdict,
    /// The answer meant (before faults), hex.
    pub answer: String,
    /// The value of a function-03 answer.
    pub value: Option<u64>,
}

/// The value in a function-03 answer `addr 03 n d.. crc crc`.
fn value_of(answer: &[u8]) -> Option<u64> {
    if answer.len() < 5 || answer[1] != 0x03 {
        return None;
    }
    let n = answer[2] as usize;
    let data = answer.get(3..3 + n)?;
    Some(data.iter().fold(0u64, |v, &b| (v << 8) | b as u64))
}

/// One to three Modbus devices on their cable, on the emulator clock.
pub struct ModbusEmulator {
    f_emu_hz: u64,
    devices: Vec<Device>,
    seen: Vec<usize>,
    bus: Bus,
    entries: Vec<Entry>,
    last: Vec<Option<usize>>,
    last_value: Vec<Option<u64>>,
    /// The rule book's watcher, fed the master's pins.
    watch: Watch,
    /// The pins out of the last step (the line at the master's receiver).
    out: Pins,
}

impl ModbusEmulator {
    /// An emulator from TOML text (`origin` names it in errors) at `f_emu_hz`.
    pub fn from_toml(text: &str, origin: &str, f_emu_hz: u64) -> Result<Self> {
        let (tb, own, mut bench) = uart_bench::<Own, BenchConfig>(
            text,
            origin,
            f_emu_hz,
            "modbus",
            "Modbus RTU",
            19_200.0,
        )?;
        let bits = randomize(
            &own.random,
            bench.devices.iter_mut().map(|d| (d.bits, &mut d.positions)),
            origin,
            "devices",
            "[[devices]]",
        )?;
        bench
            .cable
            .validate("cable")
            .map_err(|e| Error::config(origin, e))?;
        let devices = (0..bench.devices.len())
            .map(|i| {
                bench
                    .device_config(i)
                    .and_then(Device::new)
                    .map_err(|e| Error::config(origin, e))
            })
            .collect::<Result<Vec<_>>>()?;
        let n = devices.len();
        let limits = rule_limits(text, origin, &bench)?;
        let mut bus = Bus::new(&bench.cable, &tb, bits, "device");
        for note in model::rules::resolution_notes(f_emu_hz, &limits.least()) {
            bus.checks.note(note);
        }
        Ok(ModbusEmulator {
            f_emu_hz,
            devices,
            seen: vec![0; n],
            bus,
            entries: Vec::new(),
            last: vec![None; n],
            last_value: vec![None; n],
            watch: Watch::new(limits),
            out: Pins(IDLE.level as u32),
        })
    }

    /// The requests seen so far.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    fn device(&self, device: usize) -> Result<()> {
        if device < self.devices.len() {
            Ok(())
        } else {
            Err(Error::Usage(format!(
                "the Modbus emulator has {} device(s), not device {device}",
                self.devices.len()
            )))
        }
    }
}

impl Emulator for ModbusEmulator {
    fn kind(&self) -> &'static str {
        "modbus"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let (tx, de) = (pins.0 & 2 != 0, pins.0 & 4 != 0);
        let t_ps = model::rules::ps_at(self.bus.cycle, self.f_emu_hz);
        for b in self.watch.sample(t_ps, receiver(tx, de, self.out), tx, de) {
            self.bus.breach(self.f_emu_hz, &b);
        }
        let at_device = self.bus.begin(pins);
        for (i, p) in self.bus.moving() {
            // A motion profile wraps at the device's resolution: always fits.
            let _ = self.devices[i].set_position(p);
        }
        let mut drive = IDLE;
        for (i, d) in self.devices.iter_mut().enumerate() {
            drive = wire(drive, d.step(at_device));
            if d.seen().len() > self.seen[i] {
                for s in &d.seen()[self.seen[i]..] {
                    let value = value_of(&s.answer);
                    if value.is_some() {
                        self.last_value[i] = value;
                    }
                    self.last[i] = Some(self.entries.len());
                    self.entries.push(Entry {
                        device: i,
                        cycle: s.cycle,
                        request: hex(&s.request),
                        verdict: s.verdict.clone(),
                        answer: hex(&s.answer),
                        value,
                    });
                }
                self.seen[i] = d.seen().len();
            }
        }
        self.out = self.bus.end(drive);
        self.out
    }

    fn set_position(&mut self, device: usize, position: u64) -> Result<()> {
        let devices = &mut self.devices;
        self.bus
            .set_position(device, position, |p| devices[device].set_position(p))
    }

    fn set_motion(&mut self, device: usize, toml: &str) -> Result<()> {
        self.bus.set_motion(device, toml)
    }

    fn set_status(&mut self, _device: usize, name: &str, _value: bool) -> Result<()> {
        Err(Error::Usage(format!(
            "a Modbus device's answers are set by its configuration (`{name}`): exceptions follow from the request, faults from devices[i].faults"
        )))
    }

    fn schedule_fault(&mut self, _toml: &str) -> Result<()> {
        Err(Error::Usage(
            "Modbus answer faults are scheduled in the configuration (devices[i].faults, by answer number)".into(),
        ))
    }

    fn count(&self) -> u64 {
        self.seen.first().copied().unwrap_or(0) as u64
    }

    fn last_value(&self, device: usize) -> Option<u64> {
        self.last_value.get(device).copied().flatten()
    }

    fn last_status(&self, device: usize, name: &str) -> Result<bool> {
        self.device(device)?;
        let e = self.last[device].map(|k| &self.entries[k]);
        match name {
            "answered" => Ok(e.is_some_and(|e| e.verdict == Verdict::Answered)),
            "discarded" => Ok(e.is_some_and(|e| e.verdict == Verdict::Discarded)),
            "exception" => Ok(e.is_some_and(|e| {
                e.verdict == Verdict::Answered
                    && u8::from_str_radix(e.answer.split(' ').nth(1).unwrap_or("0"), 16)
                        .is_ok_and(|f| f & 0x80 != 0)
            })),
            other => Err(Error::Usage(format!(
                "a Modbus device reports `answered`, `discarded` and `exception`, not `{other}`"
            ))),
        }
    }

    fn transcript(&self) -> serde_json::Value {
        serde_json::json!({
            "protocol": "modbus",
            "f_emu_hz": self.f_emu_hz,
            "requests": self.entries,
            "contention_cycles": self.bus.contention_cycles(),
            "violations": self.bus.checks.all(),
            "notes": self.bus.checks.notes(),
        })
    }

    fn checks(&mut self) -> &mut Checks {
        &mut self.bus.checks
    }
}
