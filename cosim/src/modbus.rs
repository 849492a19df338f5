//! The Modbus RTU emulator: one to three [`model::modbus::Device`]s (the
//! SAR58K24 in its seventh mode) on a half-duplex cable.
//!
//! Configuration: the scenario's `[modbus]` table (`baud`, `parity`,
//! `[[devices]]`, `[cable]`; `[master]` gives the t1.5/t3.5 the devices keep,
//! as in the scenario); `[[ops]]`, `[[second_drivers]]` and `f_sys_mhz` are
//! ignored. The emulator's own tables are `[random]` (as for the SAR58K24:
//! `count` random positions per device from `seed`) and `[checks]`.
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
use model::modbus::{BenchConfig, Device, Verdict};

use crate::check::Checks;
use crate::config::Error;
use crate::half_duplex::{randomize, uart_bench, wire, Bus, RandomPositions, IDLE};
use crate::{Emulator, Pins, Result};

/// The limits the master is held to (`[checks]`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ModbusChecks {
    /// Two drivers on the line at once is a violation.
    pub contention: bool,
    /// A request the device discards (a silence over t1.5 inside it, a bad
    /// CRC, a parity or framing error) is a violation.
    pub discarded: bool,
}

impl Default for ModbusChecks {
    fn default() -> Self {
        ModbusChecks {
            contention: true,
            discarded: true,
        }
    }
}

#[derive(Debug, Clone, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
struct Own {
    random: RandomPositions,
    checks: ModbusChecks,
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
    /// Report a discarded request (`checks.discarded`).
    discarded: bool,
    entries: Vec<Entry>,
    last: Vec<Option<usize>>,
    last_value: Vec<Option<u64>>,
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
        Ok(ModbusEmulator {
            f_emu_hz,
            devices,
            seen: vec![0; n],
            bus: Bus::new(
                &bench.cable,
                &tb,
                bits,
                "device",
                own.checks.contention.then_some((
                    "one driver at a time (seed 001, 3.1.7: half-duplex RS-485, the master releases the line after its request)",
                    "the master and a device drive the line together",
                )),
            ),
            discarded: own.checks.discarded,
            entries: Vec::new(),
            last: vec![None; n],
            last_value: vec![None; n],
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
                    if s.verdict == Verdict::Discarded && self.discarded {
                        self.bus.checks.push(
                            self.bus.cycle,
                            "RTU framing (seed 001, 3.1.7 and Modbus over serial line 2.5.1.1: a frame is sent as a continuous stream, silences inside it under t1.5, CRC-16)",
                            format!("device {i} discarded the request {}", hex(&s.request)),
                        );
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
        self.bus.end(drive)
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
        })
    }

    fn checks(&mut self) -> &mut Checks {
        &mut self.bus.checks
    }
}
