//! The SAR58K24 asynchronous-serial emulator: one to three
//! [`model::sar58k24::Encoder`]s on a half-duplex cable.
//!
//! Configuration: the scenario's `[sar]` table (`baud`, `parity`, `mode`,
//! `[[encoders]]`, `[cable]`); `[host]`, `[[ops]]`, `[[second_drivers]]` and
//! `f_sys_mhz` belong to the host side and are ignored, so a whole scenario
//! file can be given. Two tables of the emulator's own:
//! * `[random] count = N, seed = S`: each encoder's `positions` list becomes
//!   `N` random positions below `2^bits` (a closed-loop test's source), from
//!   the seed `S` (encoder `i` uses `S + i`).
//! * `[checks]`: the limits the host is held to (see [`SarChecks`]): the
//!   rule book [`model::sar58k24::rules`], fed every cycle exactly as the
//!   monitor feeds it, so both print the same rule and text.
//!
//! The position an encoder reads is the next entry of its `positions` list
//! (one per acquisition, the last holding), exactly as in the model, until
//! a testbench calls `set_position(device, raw)` (every acquisition from
//! then on reads `raw`, less the zero offset: the next frame carries it) or
//! `set_motion(device, toml)` (a [`crate::motion`] profile, from the
//! emulator's cycle of the call). [`Emulator::last_value`] is what the
//! encoder last sent (binary, after zeroing).
//!
//! Pins (`emu_step`): in bit 0 the trigger line (CLK of 3.1.3, idle high),
//! bit 1 the host's driver level, bit 2 its driver enable, bit 3 CLR (idle
//! high); out bit 0 the encoders' driver level at the host's end of the
//! cable, bit 1 their driver enable there, bit 2 the resolved line level at
//! the host's end (the nearer driver wins, fail-safe high when undriven: what
//! the host's receiver sees).

use serde::{Deserialize, Serialize};

use model::bits::hex;
use model::line::DelayLine;
use model::sar58k24::rules::{HostPins, Limits, Settings, Watch};
use model::sar58k24::{BenchConfig, Encoder, EncoderIn, Mode};

use crate::check::Checks;
use crate::config::{self, Error};
use crate::half_duplex::{
    character_limits, randomize, receiver, rule_limit, uart_bench, wire, Bus, RandomPositions, IDLE,
};
use crate::monitor::{host_timeout_us, proto_table};
use crate::{Emulator, Pins, Result};

/// The limits the host is held to (`[checks]`, and `[monitor]` for a
/// monitor's own: the first given wins), each optional: the rule book's
/// defaults, the host's and the first encoder's settings.
#[derive(Debug, Clone, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct SarChecks {
    /// The host's answer timeout, µs (else `[host] timeout_us`, 5000).
    pub timeout_us: Option<f64>,
    /// The baud rate tolerance of the host's characters, % (2).
    pub baud_tolerance_percent: Option<f64>,
    /// The longest time from the command's last stop bit to DE off, bit times (1).
    pub release_bits: Option<f64>,
    /// The shortest trigger pulse, µs (else `encoders[0].trigger_min_low_us`).
    pub t2_us: Option<f64>,
    /// The shortest CLR pulse, µs (else `encoders[0].clr_min_low_us`).
    pub clr_min_low_us: Option<f64>,
    /// The longest silence inside a command, bit times (else `encoders[0].command_gap_bits`).
    pub command_gap_bits: Option<f64>,
}

/// The rule limits of the configuration `text`, set up as `cfg`: what the
/// emulator and the monitor both hold the host to.
pub(crate) fn rule_limits(text: &str, origin: &str, cfg: &BenchConfig) -> Result<Limits> {
    let whole = proto_table(text, origin, "sar")?;
    let mon: SarChecks = config::decode_in(&whole, "monitor", origin)?;
    let chk: SarChecks = config::decode_in(&whole, "checks", origin)?;
    let host = config::sub(&whole, "host", origin)?;
    let enc = cfg.encoders.first().cloned().unwrap_or_default();
    let timeout = host_timeout_us(mon.timeout_us.or(chk.timeout_us), &host, origin, 5000.0)?;
    let pick =
        |m, c, (field, v): (&'static str, f64)| rule_limit(origin, [m, c, (field, Some(v))], v);
    let [tolerance_percent, release_bits] = character_limits(
        origin,
        [mon.baud_tolerance_percent, mon.release_bits],
        [chk.baud_tolerance_percent, chk.release_bits],
    )?;
    let settings = Settings {
        baud: cfg.baud,
        parity: cfg.parity,
        tolerance_percent,
        command_gap_bits: pick(
            ("monitor.command_gap_bits", mon.command_gap_bits),
            ("checks.command_gap_bits", chk.command_gap_bits),
            ("encoders[0].command_gap_bits", enc.command_gap_bits),
        )?,
        release_bits,
        timeout_us: timeout,
        t2_us: pick(
            ("monitor.t2_us", mon.t2_us),
            ("checks.t2_us", chk.t2_us),
            ("encoders[0].trigger_min_low_us", enc.trigger_min_low_us),
        )?,
        clr_us: pick(
            ("monitor.clr_min_low_us", mon.clr_min_low_us),
            ("checks.clr_min_low_us", chk.clr_min_low_us),
            ("encoders[0].clr_min_low_us", enc.clr_min_low_us),
        )?,
        handshake: matches!(cfg.mode, Mode::Handshake | Mode::HandshakeClear),
        answer_zeroing: enc.answer_zeroing,
    };
    Limits::new(&settings).map_err(|e| Error::config(origin, e))
}

/// The tables the emulator reads.
#[derive(Debug, Clone, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
struct Own {
    random: RandomPositions,
    /// Checked here for unknown fields; [`rule_limits`] reads it.
    #[allow(dead_code)]
    checks: SarChecks,
}

/// One frame an encoder sent.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// 0-based frame number over all encoders.
    pub index: u64,
    /// The encoder (index in `[[encoders]]`).
    pub device: usize,
    /// Its bus address.
    pub address: u8,
    /// Emulator cycle the frame was queued.
    pub cycle: u64,
    /// The position in it (binary, after zeroing).
    pub position: u64,
    /// The bytes as meant, hex.
    pub bytes: String,
}

/// One to three SAR58K24 encoders on their cable, on the emulator clock.
pub struct SarEmulator {
    f_emu_hz: u64,
    mode: Mode,
    addresses: Vec<u8>,
    encoders: Vec<Encoder>,
    seen: Vec<usize>,
    bus: Bus,
    trigger: DelayLine,
    clr: DelayLine,
    entries: Vec<Entry>,
    last: Vec<Option<u64>>,
    /// The rule book's watcher, fed the host's pins.
    watch: Watch,
    /// The pins out of the last step (the line at the host's receiver).
    out: Pins,
}

impl SarEmulator {
    /// An emulator from TOML text (`origin` names it in errors) at `f_emu_hz`.
    pub fn from_toml(text: &str, origin: &str, f_emu_hz: u64) -> Result<Self> {
        let (tb, own, mut bench) =
            uart_bench::<Own, BenchConfig>(text, origin, f_emu_hz, "sar", "SAR58K24", 115_200.0)?;
        let bits = randomize(
            &own.random,
            bench
                .encoders
                .iter_mut()
                .map(|e| (e.bits, &mut e.positions)),
            origin,
            "encoders",
            "[[encoders]]",
        )?;
        bench
            .cable
            .validate("cable")
            .map_err(|e| Error::config(origin, e))?;
        let encoders = (0..bench.encoders.len())
            .map(|i| {
                bench
                    .encoder_config(i)
                    .and_then(Encoder::new)
                    .map_err(|e| Error::config(origin, e))
            })
            .collect::<Result<Vec<_>>>()?;
        let n = encoders.len();
        let delay = bench.cable.delay_cycles(&tb);
        let limits = rule_limits(text, origin, &bench)?;
        let mut bus = Bus::new(&bench.cable, &tb, bits, "encoder");
        for note in model::rules::resolution_notes(f_emu_hz, &limits.least()) {
            bus.checks.note(note);
        }
        Ok(SarEmulator {
            f_emu_hz,
            mode: bench.mode,
            addresses: bench.encoders.iter().map(|e| e.address).collect(),
            encoders,
            seen: vec![0; n],
            bus,
            trigger: DelayLine::new(delay, true),
            clr: DelayLine::new(delay, true),
            entries: Vec::new(),
            last: vec![None; n],
            watch: Watch::new(limits),
            out: Pins(IDLE.level as u32),
        })
    }

    /// The frames sent so far.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }
}

impl Emulator for SarEmulator {
    fn kind(&self) -> &'static str {
        "sar58k24"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let (tx, de) = (pins.0 & 2 != 0, pins.0 & 4 != 0);
        let host = HostPins {
            rx: receiver(tx, de, self.out),
            tx,
            de,
            trigger: pins.0 & 1 != 0,
            clr: pins.0 & 8 != 0,
        };
        let t_ps = model::rules::ps_at(self.bus.cycle, self.f_emu_hz);
        for b in self.watch.sample(t_ps, host) {
            self.bus.breach(self.f_emu_hz, &b);
        }
        let input = EncoderIn {
            rx: self.bus.begin(pins),
            trigger: self.trigger.step(pins.0 & 1 != 0),
            clr: self.clr.step(pins.0 & 8 != 0),
        };
        for (i, p) in self.bus.moving() {
            // A motion profile wraps at the encoder's resolution: always fits.
            let _ = self.encoders[i].set_position(p);
        }
        let mut drive = IDLE;
        for (i, e) in self.encoders.iter_mut().enumerate() {
            drive = wire(drive, e.step(&input));
            if e.sent().len() > self.seen[i] {
                for f in &e.sent()[self.seen[i]..] {
                    self.entries.push(Entry {
                        index: self.entries.len() as u64,
                        device: i,
                        address: self.addresses[i],
                        cycle: f.cycle,
                        position: f.position,
                        bytes: hex(&f.bytes),
                    });
                    self.last[i] = Some(f.position);
                }
                self.seen[i] = e.sent().len();
            }
        }
        if !self.mode.is_bus() {
            drive.enable = true;
        }
        self.out = self.bus.end(drive);
        self.out
    }

    fn set_position(&mut self, device: usize, position: u64) -> Result<()> {
        let encoders = &mut self.encoders;
        self.bus
            .set_position(device, position, |p| encoders[device].set_position(p))
    }

    fn set_motion(&mut self, device: usize, toml: &str) -> Result<()> {
        self.bus.set_motion(device, toml)
    }

    fn set_status(&mut self, _device: usize, name: &str, _value: bool) -> Result<()> {
        Err(Error::Usage(format!(
            "a SAR58K24 frame carries no status bits (`{name}`): FF 81, the position and a checksum"
        )))
    }

    fn schedule_fault(&mut self, _toml: &str) -> Result<()> {
        Err(Error::Usage(
            "SAR58K24 frame faults are scheduled in the configuration (encoders[i].faults, by frame number)".into(),
        ))
    }

    fn count(&self) -> u64 {
        self.entries.len() as u64
    }

    fn last_value(&self, device: usize) -> Option<u64> {
        self.last.get(device).copied().flatten()
    }

    fn last_status(&self, _device: usize, name: &str) -> Result<bool> {
        Err(Error::Usage(format!(
            "a SAR58K24 frame carries no status bits (`{name}`)"
        )))
    }

    fn transcript(&self) -> serde_json::Value {
        serde_json::json!({
            "protocol": "sar58k24",
            "f_emu_hz": self.f_emu_hz,
            "frames": self.entries,
            "contention_cycles": self.bus.contention_cycles(),
            "violations": self.bus.checks.all(),
            "notes": self.bus.checks.notes(),
        })
    }

    fn checks(&mut self) -> &mut Checks {
        &mut self.bus.checks
    }
}
