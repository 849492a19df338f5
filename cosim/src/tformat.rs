//! The Tamagawa T-format encoder emulator: [`model::tformat::Encoder`] behind
//! the half-duplex RS-485 pair of its cable.
//!
//! Configuration: the scenario's `[tformat]` device tables: `[encoder]`
//! (positions, alarms, EEPROM, answer delay, answer flips and truncation,
//! baud error, jitter), `[cable]`, `baud` (default 2.5 Mbps) and a
//! `[motion]` profile; `[host]`, `ops`, `line_faults`, `f_sys_mhz` are
//! ignored, so a whole scenario file can be given. The encoder samples the
//! host's request at `f_emu / baud` cycles per bit, so `f_emu` must be a
//! whole multiple of the baud rate.
//!
//! Pins: in, bit 1 the host's driver level, bit 2 its driver enable (no
//! clock: bit 0 is ignored); out, bit 0 the encoder's level at the host's end
//! of the cable (the fail-safe idle high while it does not drive), bit 1 its
//! driver enable there.
//!
//! A position is `multi_turn << 17 | single_turn` (17-bit ABS, 16-bit ABM).
//! Statuses (`set_status`), each on its own: the seven ALMC flags
//! `over_speed`, `full_absolute`, `counting_error`, `counter_overflow`,
//! `multi_turn_error`, `battery_error`, `battery_alarm` (ea0 and ea1 of the
//! status field follow from them, seed 002 6.3.2).
//!
//! Checks of the master: the rule book [`model::tformat::rules`], whose
//! watcher this emulator and the T-format monitor both feed with the host's
//! transceiver pins (its driver's level and enable, and what its receiver
//! hears: the encoder's answer at the host's end while the encoder drives),
//! so both report the same rule with the same text.

use serde::{Deserialize, Serialize};

use model::line::{CableConfig, Drive};
use model::tformat::frames::{Alarms, DataId};
use model::tformat::rules::{watch, Limits, Watch};
use model::tformat::{AnswerFlip, BenchConfig, Encoder, EncoderSettings};

use crate::check::Checks;
use crate::config::{self, Error};
use crate::monitor::half_duplex::emulator_step;
use crate::motion::Motions;
use crate::pair::Pair;
use crate::{Emulator, Pins, Result};

/// The T-format bit rate (seed 002: 2.5 Mbps), the emulator's "line clock".
pub const MAX_CLOCK_KHZ: f64 = 2500.0;

/// The emulator's configuration (the scenario's T-format device tables).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TformatConfig {
    /// The encoder.
    pub encoder: EncoderSettings,
    /// The cable.
    pub cable: CableConfig,
    /// Bit rate, bits per second.
    pub baud: f64,
}

impl Default for TformatConfig {
    fn default() -> Self {
        let b = BenchConfig::default();
        TformatConfig {
            encoder: b.encoder,
            cable: b.cable,
            baud: b.baud,
        }
    }
}

/// One answer as the emulator sent it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// 0-based answer number.
    pub index: u64,
    /// Emulator cycle of its first start bit (at the encoder).
    pub cycle: u64,
    /// The Data ID answered.
    pub data_id: u8,
    /// The fields as the encoder built them (before any scheduled flip), CRC last.
    pub fields: Vec<u8>,
    /// ABS (single turn) when the answer carries it.
    pub abs: Option<u32>,
    /// ABM (multi turn) when the answer carries it.
    pub abm: Option<u16>,
    /// ALMC when the answer carries it.
    pub almc: Option<u8>,
    /// The status field.
    pub sf: u8,
}

/// A T-format encoder and its cable, on the emulator clock.
pub struct TformatEmulator {
    f_emu_hz: u64,
    period_ps: u64,
    encoder: Encoder,
    pair: Pair,
    enc_drive: Drive,
    motions: Motions,
    cycle: u64,
    entries: Vec<Entry>,
    checks: Checks,
    watch: Watch,
    /// The pins out of the last step: the encoder at the host's end.
    out: Pins,
}

fn le(bytes: &[u8]) -> u32 {
    bytes.iter().rev().fold(0u32, |a, &b| (a << 8) | b as u32)
}

impl TformatEmulator {
    /// An emulator from TOML text (`origin` names it in errors) at `f_emu_hz`.
    pub fn from_toml(text: &str, origin: &str, f_emu_hz: u64) -> Result<Self> {
        let mut tables = config::tables(text, origin, "tformat")?;
        for key in ["ops", "line_faults"] {
            tables.device.remove(key);
        }
        let tb = config::emulator_clock(
            f_emu_hz,
            &tables.emulator,
            MAX_CLOCK_KHZ,
            "T-format",
            origin,
        )?;
        let cfg: TformatConfig = config::decode(tables.device, origin)?;
        cfg.cable
            .validate("cable")
            .map_err(|e| Error::config(origin, e))?;
        let bench = BenchConfig {
            f_sys_mhz: tb.f_sys_hz() as f64 / 1e6,
            baud: cfg.baud,
            encoder: cfg.encoder.clone(),
            ..BenchConfig::default()
        };
        let enc_cfg = bench.encoder_config().map_err(|e| match e.field() {
            "baud" => Error::Usage(format!(
                "{origin}: emulator clock f_emu = {f_emu_hz} Hz is not a whole multiple of the bit rate {} bit/s: the encoder samples the request at f_emu / baud cycles per bit; give f_emu = k x {} Hz (e.g. {} Hz)",
                cfg.baud, cfg.baud, (cfg.baud * 32.0) as u64
            )),
            _ => Error::config(origin, e),
        })?;
        let delay = cfg.cable.delay_cycles(&tb);
        let limits = Limits::seed(cfg.baud, cfg.encoder.reset_interval_us);
        let mut checks = Checks::new(tb.period_ps());
        for note in model::rules::resolution_notes(f_emu_hz, &limits.least()) {
            checks.note(note);
        }
        Ok(TformatEmulator {
            f_emu_hz,
            period_ps: tb.period_ps(),
            encoder: Encoder::new(enc_cfg),
            pair: Pair::new(delay),
            enc_drive: Drive {
                enable: false,
                level: true,
            },
            motions: Motions::default(),
            cycle: 0,
            entries: Vec::new(),
            checks,
            watch: watch(limits),
            out: Pins(1),
        })
    }

    /// The entries so far.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    fn on_answer(&mut self) {
        let Some((at, fields)) = self.encoder.answered().last() else {
            return;
        };
        let id = (fields[0] >> 3) & 0xF;
        let (mut abs, mut abm, mut almc) = (None, None, None);
        match DataId::from_code(id) {
            Some(DataId::Id0 | DataId::Id7 | DataId::Id8 | DataId::IdC) => {
                abs = Some(le(&fields[2..5]))
            }
            Some(DataId::Id1) => abm = Some(le(&fields[2..5]) as u16),
            Some(DataId::Id3) => {
                abs = Some(le(&fields[2..5]));
                abm = Some(le(&fields[6..9]) as u16);
                almc = Some(fields[9]);
            }
            _ => {}
        }
        self.entries.push(Entry {
            index: self.entries.len() as u64,
            cycle: *at,
            data_id: id,
            sf: fields.get(1).copied().unwrap_or(0),
            fields: fields.clone(),
            abs,
            abm,
            almc,
        });
    }
}

/// The ALMC flags by name and bit (seed 002, Table 3).
pub(crate) const ALARMS: [(&str, u8); 7] = [
    ("over_speed", 0),
    ("full_absolute", 1),
    ("counting_error", 2),
    ("counter_overflow", 3),
    ("multi_turn_error", 5),
    ("battery_error", 6),
    ("battery_alarm", 7),
];

fn alarm_bit(name: &str) -> Option<u8> {
    ALARMS.iter().find(|(n, _)| *n == name).map(|(_, b)| *b)
}

fn alarms_of(almc: u8) -> Alarms {
    let on = |b: u8| almc >> b & 1 == 1;
    Alarms {
        over_speed: on(0),
        full_absolute: on(1),
        counting_error: on(2),
        counter_overflow: on(3),
        multi_turn_error: on(5),
        battery_error: on(6),
        battery_alarm: on(7),
    }
}

const ALARM_NAMES: &str = "over_speed, full_absolute, counting_error, counter_overflow, multi_turn_error, battery_error, battery_alarm";

impl Emulator for TformatEmulator {
    fn kind(&self) -> &'static str {
        "tformat"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let host = Pair::master_drive(pins);
        if self.motions.any() {
            if let Some(p) = self.motions.position(0, self.cycle, self.period_ps, 33) {
                self.encoder
                    .set_position((p & 0x1_FFFF) as u32, (p >> 17) as u16);
            }
        }
        let at_encoder = emulator_step(
            &mut self.watch,
            &mut self.pair,
            &mut self.checks,
            self.cycle,
            self.f_emu_hz,
            host,
            self.enc_drive,
            self.out,
        );
        let answers = self.encoder.answered().len();
        self.enc_drive = self.encoder.step(at_encoder);
        if self.encoder.answered().len() != answers {
            self.on_answer();
        }
        self.cycle += 1;
        self.out = self.pair.pins_out(self.enc_drive, &self.checks, None);
        self.out
    }

    fn set_position(&mut self, device: usize, position: u64) -> Result<()> {
        if device != 0 || position >> 33 != 0 {
            return Err(Error::Usage(format!(
                "set_position({device}, {position}): T-format has one encoder (device 0) and 33-bit positions (multi_turn << 17 | single_turn)"
            )));
        }
        self.motions.stop(0);
        self.encoder
            .set_position((position & 0x1_FFFF) as u32, (position >> 17) as u16);
        Ok(())
    }

    fn set_motion(&mut self, device: usize, toml: &str) -> Result<()> {
        if device != 0 {
            return Err(Error::Usage(format!(
                "T-format has one encoder (device 0), not device {device}"
            )));
        }
        self.motions.set(0, toml, self.cycle)
    }

    fn set_status(&mut self, device: usize, name: &str, value: bool) -> Result<()> {
        match (device, alarm_bit(name)) {
            (0, Some(bit)) => {
                let almc = self.encoder.alarms().byte() & !(1 << bit) | (value as u8) << bit;
                self.encoder.set_alarms(alarms_of(almc));
                Ok(())
            }
            _ => Err(Error::Usage(format!(
                "T-format encoder (device 0) has no status `{name}` on device {device}; give one of {ALARM_NAMES}"
            ))),
        }
    }

    fn schedule_fault(&mut self, toml: &str) -> Result<()> {
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct T {
            flips: Vec<AnswerFlip>,
        }
        let tables = config::tables(toml, "fault", "tformat")?;
        let t: T = config::decode(tables.device, "fault")?;
        for (i, f) in t.flips.iter().enumerate() {
            if f.bit > 9 || f.field >= 11 {
                return Err(Error::field(
                    "fault",
                    format!("flips[{i}]"),
                    "field above 10 or bit above 9",
                    "give field 0..10 and bit 0..9 (0 start, 1..8 data, 9 delimiter)",
                ));
            }
        }
        for f in t.flips {
            self.encoder.add_flip(f);
        }
        Ok(())
    }

    fn count(&self) -> u64 {
        self.entries.len() as u64
    }

    fn last_value(&self, device: usize) -> Option<u64> {
        let e = self.entries.last().filter(|_| device == 0)?;
        match (e.abs, e.abm) {
            (Some(s), Some(m)) => Some((m as u64) << 17 | s as u64),
            (Some(s), None) => Some(s as u64),
            (None, Some(m)) => Some((m as u64) << 17),
            (None, None) => None,
        }
    }

    fn last_status(&self, device: usize, name: &str) -> Result<bool> {
        let e =
            self.entries.last().filter(|_| device == 0).ok_or_else(|| {
                Error::Usage(format!("no T-format answer of device {device} yet"))
            })?;
        let almc = e.almc.ok_or_else(|| {
            Error::Usage(format!(
                "the last answer (Data ID {:X}) carried no ALMC",
                e.data_id
            ))
        })?;
        alarm_bit(name).map(|b| almc >> b & 1 == 1).ok_or_else(|| {
            Error::Usage(format!(
                "T-format has no status `{name}`; give one of {ALARM_NAMES}"
            ))
        })
    }

    fn transcript(&self) -> serde_json::Value {
        serde_json::json!({
            "protocol": "tformat",
            "f_emu_hz": self.f_emu_hz,
            "answers": self.entries,
            "contention_cycles": self.pair.contention_cycles(),
            "violations": self.checks.all(),
            "notes": self.checks.notes(),
        })
    }

    fn checks(&mut self) -> &mut Checks {
        &mut self.checks
    }
}
