//! The ESL encoder emulator (QS35, seed 000): [`model::esl::Encoder`]s
//! (one, or a daisy chain on one bus) behind the half-duplex RS-485 pair of
//! their cable.
//!
//! Configuration: the scenario's `[esl]` device tables: `[[encoders]]`
//! (address, position, alarms, temperature, memory, answer delay, EEPROM
//! times, repeat window, baud error and the faults `flips`, `truncations`,
//! `sequence_jumps`, `foreign_address_answers`, `rs_offset`), `[cable]`,
//! `baud` (default 10 Mbps), `broadcast_address` (the address every encoder
//! obeys and none answers; none by default) and the emulator's own
//! `[checks]`; `[host]`, `ops`, `repeat_ops`, `request_flips`, `intruders`
//! and `f_sys_mhz` are ignored, so a whole scenario file can be given. The
//! encoders sample the host's request at `f_emu / baud` cycles per bit (any
//! ratio, rounded bit by bit), so `f_emu` need not be a multiple of the bit
//! rate; it must be at least 4 x the bit rate (40 MHz at 10 Mbps).
//!
//! Pins: in, bit 1 the host's driver level, bit 2 its driver enable (no
//! clock: bit 0 is ignored); out, bit 0 the encoders' level at the host's end
//! of the cable (the fail-safe idle high while none drives), bit 1 their
//! driver enable there.
//!
//! Devices are the encoders in the order of `[[encoders]]` (0 for a single
//! one). A position is `multi_turn << 24 | single_turn` (24-bit ABS, 16-bit
//! ABM, seed 000 "40 bits"). Statuses (`set_status`), each on its own: the
//! ALM flags of Table 7 `xc`, `mt`, `led`, `lis` (LED and LIS share ALM bit
//! 2), `overspeed`, `mem`, `st`, `uv`, `ov` (EA0 and EA1 of the status field
//! follow from them, Table 5), and `temp_warning` (DD0). `last_status` also
//! reads `ea0`, `ea1`, `ready` of the last answer's SF.
//!
//! Checks of the host: the rule book [`model::esl::rules`], whose watcher
//! this emulator and the ESL monitor both feed with the host's transceiver
//! pins (its driver's level and enable, and what its receiver hears: the
//! encoders' answer at the host's end while one drives), so both report the
//! same rule with the same text; `[checks] bit_tolerance_percent` (3) is the
//! drift allowed on the host's bit edges, and each encoder's times bound the
//! spacing of the requests to its address.

use serde::{Deserialize, Serialize};

use model::esl::frames::{self, Alarms, DataId, Field};
use model::esl::rules::{watch, Limits, Spacing, Watch};
use model::esl::{BenchConfig, Encoder, EncoderSettings};
use model::line::{CableConfig, Drive};

use crate::check::Checks;
use crate::config::{self, Error};
use crate::monitor::half_duplex::emulator_step;
use crate::motion::Motions;
use crate::pair::Pair;
use crate::{Emulator, Pins, Result};

/// The emulator's own limits (`[checks]`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EslChecks {
    /// Largest drift of the host's bit edges, percent of the time since the
    /// field's start edge (the seed gives none; 3 % is what an RS-485 UART
    /// sampling mid-bit takes with room for the encoder's own error).
    pub bit_tolerance_percent: f64,
}

impl Default for EslChecks {
    fn default() -> Self {
        EslChecks {
            bit_tolerance_percent: 3.0,
        }
    }
}

/// The emulator's configuration (the scenario's ESL device tables).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EslConfig {
    /// The encoders on the bus.
    pub encoders: Vec<EncoderSettings>,
    /// The cable.
    pub cable: CableConfig,
    /// Bit rate, bits per second.
    pub baud: f64,
    /// The broadcast address (none: no encoder obeys a foreign address).
    pub broadcast_address: Option<u8>,
    /// The checks' limits.
    pub checks: EslChecks,
}

impl Default for EslConfig {
    fn default() -> Self {
        let b = BenchConfig::default();
        EslConfig {
            encoders: b.encoders,
            cable: b.cable,
            baud: b.baud,
            broadcast_address: None,
            checks: EslChecks::default(),
        }
    }
}

/// One answer as the emulator sent it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// 0-based answer number (all encoders).
    pub index: u64,
    /// The encoder (device index, its order in `[[encoders]]`).
    pub device: usize,
    /// Emulator cycle of its first start bit (at the encoder).
    pub cycle: u64,
    /// The Data ID answered.
    pub data_id: u8,
    /// The fields as the encoder built them (before any scheduled flip or truncation).
    pub fields: Vec<u8>,
    /// A communication-error answer (CA0 or CA1 set: CF, SF, CRC only).
    pub comm_error: bool,
    /// ABS (single turn) when the answer carries it.
    pub abs: Option<u32>,
    /// ABM (multi turn) when the answer carries it.
    pub abm: Option<u16>,
    /// ALM1 when the answer carries it.
    pub alm: Option<u8>,
    /// SF1 (0 for a memory answer, which has none).
    pub sf: u8,
    /// SC1 and SC2 when the answer carries them.
    pub sc: Option<(u8, u8)>,
}

/// ESL encoders and their cable, on the emulator clock.
pub struct EslEmulator {
    f_emu_hz: u64,
    period_ps: u64,
    encoders: Vec<Encoder>,
    pair: Pair,
    bus: Drive,
    motions: Motions,
    cycle: u64,
    entries: Vec<Entry>,
    last: Vec<Option<usize>>,
    checks: Checks,
    watch: Watch,
    /// The pins out of the last step: the encoders at the host's end.
    out: Pins,
}

/// The ALM flags by name (Table 7) and their bit in ALM.
pub(crate) const ALARMS: [(&str, u8); 9] = [
    ("xc", 0),
    ("mt", 1),
    ("led", 2),
    ("lis", 2),
    ("overspeed", 3),
    ("mem", 4),
    ("st", 5),
    ("uv", 6),
    ("ov", 7),
];

const STATUS_NAMES: &str = "xc, mt, led, lis, overspeed, mem, st, uv, ov, temp_warning";

fn set_alarm(a: &mut Alarms, name: &str, v: bool) -> bool {
    let f = match name {
        "xc" => &mut a.xc,
        "mt" => &mut a.mt,
        "led" => &mut a.led,
        "lis" => &mut a.lis,
        "overspeed" => &mut a.overspeed,
        "mem" => &mut a.mem,
        "st" => &mut a.st,
        "uv" => &mut a.uv,
        "ov" => &mut a.ov,
        _ => return false,
    };
    *f = v;
    true
}

/// The bit rate of a configuration (`[esl] baud`, the seed's 10 Mbit/s by
/// default), 1 kbit/s to 50 Mbit/s: the emulator's and the monitor's one
/// reading of it (a value of another type is refused, not taken for the
/// default).
pub(crate) fn baud(text: &str, origin: &str) -> Result<f64> {
    let whole = crate::monitor::proto_table(text, origin, "esl")?;
    let baud: f64 = crate::monitor::field::<f64>(&whole, "baud", origin, "baud")?.unwrap_or(10e6);
    if !(1e3..=50e6).contains(&baud) {
        return Err(Error::field(
            origin,
            "baud",
            format!("{baud} bit/s"),
            "give the bit rate in bit/s (seed 000: 10e6)",
        ));
    }
    Ok(baud)
}

impl EslEmulator {
    /// An emulator from TOML text (`origin` names it in errors) at `f_emu_hz`.
    pub fn from_toml(text: &str, origin: &str, f_emu_hz: u64) -> Result<Self> {
        let mut tables = config::tables(text, origin, "esl")?;
        for key in ["ops", "repeat_ops", "request_flips", "intruders"] {
            tables.device.remove(key);
        }
        let baud = baud(text, origin)?;
        if tables.emulator.max_line_clock_khz.is_none() {
            tables.emulator.max_line_clock_khz = Some(baud / 1e3);
        }
        let tb = config::emulator_clock(
            f_emu_hz,
            &tables.emulator,
            baud / 1e3,
            "ESL (its line clock is the bit rate)",
            origin,
        )?;
        let cfg: EslConfig = config::decode(tables.device, origin)?;
        cfg.cable
            .validate("cable")
            .map_err(|e| Error::config(origin, e))?;
        if cfg.encoders.is_empty() || cfg.encoders.len() > 8 {
            return Err(Error::field(
                origin,
                "encoders",
                format!("{} encoders", cfg.encoders.len()),
                "list 1 to 8 [[encoders]]",
            ));
        }
        for (i, e) in cfg.encoders.iter().enumerate() {
            if cfg.encoders[..i].iter().any(|o| o.address == e.address)
                || Some(e.address) == cfg.broadcast_address
            {
                return Err(Error::field(origin, format!("encoders[{i}].address"), "used twice (or the broadcast address)", "give every encoder on the bus its own address, and keep broadcast_address free"));
            }
        }
        if cfg.broadcast_address.is_some_and(|a| a > 7) {
            return Err(Error::field(
                origin,
                "broadcast_address",
                "above 7",
                "give an address 0..7",
            ));
        }
        if !(0.0..=20.0).contains(&cfg.checks.bit_tolerance_percent) {
            return Err(Error::field(
                origin,
                "checks.bit_tolerance_percent",
                format!("{}", cfg.checks.bit_tolerance_percent),
                "give 0 to 20 %",
            ));
        }
        let bench = BenchConfig {
            f_sys_mhz: tb.f_sys_hz() as f64 / 1e6,
            baud: cfg.baud,
            encoders: cfg.encoders.clone(),
            ..BenchConfig::default()
        };
        let mut encoders = Vec::new();
        let mut limits = Limits::seed(cfg.baud, cfg.checks.bit_tolerance_percent);
        for (i, e) in cfg.encoders.iter().enumerate() {
            let mut c = bench
                .encoder_config(i)
                .map_err(|e| Error::config(origin, e))?;
            c.broadcast_address = cfg.broadcast_address;
            encoders.push(Encoder::new(c));
            limits.spacing[usize::from(e.address & 7)] = Spacing::of(e);
        }
        let mut checks = Checks::new(tb.period_ps());
        for note in model::rules::resolution_notes(f_emu_hz, &limits.least()) {
            checks.note(note);
        }
        let delay = cfg.cable.delay_cycles(&tb);
        let n = encoders.len();
        Ok(EslEmulator {
            f_emu_hz,
            period_ps: tb.period_ps(),
            encoders,
            pair: Pair::new(delay),
            bus: Drive {
                enable: false,
                level: true,
            },
            motions: Motions::default(),
            cycle: 0,
            entries: Vec::new(),
            last: vec![None; n],
            checks,
            watch: watch(limits),
            out: Pins(1),
        })
    }

    /// The entries so far.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    fn device(&self, device: usize) -> Result<()> {
        if device < self.encoders.len() {
            Ok(())
        } else {
            Err(Error::Usage(format!(
                "ESL: no device {device}; the bus has {} encoder(s), devices 0..{}",
                self.encoders.len(),
                self.encoders.len() - 1
            )))
        }
    }

    fn on_answer(&mut self, device: usize) {
        let Some((at, fields)) = self.encoders[device].answered().last() else {
            return;
        };
        let code = frames::parse_control_field(fields[0]).code;
        let memory = DataId::from_code(code).is_some_and(|d| d.is_memory());
        let sf = if memory {
            0
        } else {
            fields.get(1).copied().unwrap_or(0)
        };
        let comm_error =
            fields.len() == frames::COMM_ERROR_FIELDS && sf & frames::STATUS_CA_MASK != 0;
        let id = DataId::from_code(code).filter(|_| !comm_error);
        let d = id.map(|id| frames::decode(id, fields)).unwrap_or_default();
        let has = |f: fn(&Field) -> bool| id.is_some_and(|id| id.channel1().fields.iter().any(f));
        self.last[device] = Some(self.entries.len());
        self.entries.push(Entry {
            index: self.entries.len() as u64,
            device,
            cycle: *at,
            data_id: code,
            fields: fields.clone(),
            comm_error,
            abs: has(|f| matches!(f, Field::Abs(_))).then_some(d.abs),
            abm: has(|f| matches!(f, Field::Abm(_))).then_some(d.abm),
            alm: has(|f| matches!(f, Field::Alm)).then_some(d.alm1),
            sf,
            sc: has(|f| matches!(f, Field::Sc1)).then_some((d.sc1, d.sc2)),
        });
    }
}

impl Emulator for EslEmulator {
    fn kind(&self) -> &'static str {
        "esl"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let host = Pair::master_drive(pins);
        if self.motions.any() {
            for i in 0..self.encoders.len() {
                if let Some(p) = self.motions.position(i, self.cycle, self.period_ps, 40) {
                    self.encoders[i].set_position((p & 0xFF_FFFF) as u32, (p >> 24) as u16);
                }
            }
        }
        let at_encoder = emulator_step(
            &mut self.watch,
            &mut self.pair,
            &mut self.checks,
            self.cycle,
            self.f_emu_hz,
            host,
            self.bus,
            self.out,
        );
        // Two drivers on the bus: a low wins (as the model's bench).
        let (mut enable, mut level) = (false, true);
        for i in 0..self.encoders.len() {
            let answers = self.encoders[i].answered().len();
            let d = self.encoders[i].step(at_encoder);
            if d.enable {
                enable = true;
                level &= d.level;
            }
            if self.encoders[i].answered().len() != answers {
                self.on_answer(i);
            }
        }
        self.bus = Drive { enable, level };
        self.cycle += 1;
        self.out = self.pair.pins_out(self.bus, &self.checks, None);
        self.out
    }

    fn set_position(&mut self, device: usize, position: u64) -> Result<()> {
        self.device(device)?;
        if position >> 40 != 0 {
            return Err(Error::Usage(format!(
                "set_position({device}, {position}): ESL positions have 40 bits (multi_turn << 24 | single_turn)"
            )));
        }
        self.motions.stop(device);
        self.encoders[device].set_position((position & 0xFF_FFFF) as u32, (position >> 24) as u16);
        Ok(())
    }

    fn set_motion(&mut self, device: usize, toml: &str) -> Result<()> {
        self.device(device)?;
        self.motions.set(device, toml, self.cycle)
    }

    fn set_status(&mut self, device: usize, name: &str, value: bool) -> Result<()> {
        self.device(device)?;
        let e = &mut self.encoders[device];
        if name == "temp_warning" {
            e.set_temp_warning(value);
            return Ok(());
        }
        let mut a = e.alarms();
        if !set_alarm(&mut a, name, value) {
            return Err(Error::Usage(format!(
                "ESL encoder has no status `{name}`; give one of {STATUS_NAMES}"
            )));
        }
        e.set_alarms(a);
        Ok(())
    }

    fn schedule_fault(&mut self, toml: &str) -> Result<()> {
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct T {
            #[serde(default)]
            device: usize,
            #[serde(default)]
            flips: Vec<model::esl::AnswerFlip>,
            #[serde(default)]
            truncations: Vec<model::esl::Truncation>,
            #[serde(default)]
            sequence_jumps: Vec<model::esl::SequenceJump>,
            #[serde(default)]
            foreign_address_answers: Vec<usize>,
            rs_offset: Option<i32>,
        }
        let tables = config::tables(toml, "fault", "esl")?;
        let t: T = config::decode(tables.device, "fault")?;
        self.device(t.device)?;
        for (i, f) in t.flips.iter().enumerate() {
            if f.bit > 9 || f.field >= 18 {
                return Err(Error::field(
                    "fault",
                    format!("flips[{i}]"),
                    "field above 17 or bit above 9",
                    "give field 0..17 and bit 0..9 (0 start, 1..8 data, 9 stop)",
                ));
            }
        }
        for (i, j) in t.sequence_jumps.iter().enumerate() {
            if !(1..=2).contains(&j.channel) {
                return Err(Error::field(
                    "fault",
                    format!("sequence_jumps[{i}].channel"),
                    format!("{}", j.channel),
                    "give channel 1 or 2",
                ));
            }
        }
        let faults = EncoderSettings {
            flips: t.flips,
            truncations: t.truncations,
            sequence_jumps: t.sequence_jumps,
            foreign_address_answers: t.foreign_address_answers,
            ..EncoderSettings::default()
        };
        self.encoders[t.device].add_faults(&faults, t.rs_offset);
        Ok(())
    }

    fn count(&self) -> u64 {
        self.entries.len() as u64
    }

    fn last_value(&self, device: usize) -> Option<u64> {
        let e = &self.entries[(*self.last.get(device)?)?];
        match (e.abs, e.abm) {
            (Some(s), Some(m)) => Some((m as u64) << 24 | s as u64),
            (Some(s), None) => Some(s as u64),
            (None, Some(m)) => Some((m as u64) << 24),
            (None, None) => None,
        }
    }

    fn last_status(&self, device: usize, name: &str) -> Result<bool> {
        self.device(device)?;
        let e = self.last[device]
            .map(|i| &self.entries[i])
            .ok_or_else(|| Error::Usage(format!("no ESL answer of device {device} yet")))?;
        let sf = frames::Status::from_byte(e.sf);
        match name {
            "ea0" => return Ok(sf.ea0),
            "ea1" => return Ok(sf.ea1),
            "ready" => return Ok(sf.ready),
            "temp_warning" => return Ok(sf.temp_warning),
            _ => {}
        }
        let bit = ALARMS
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, b)| *b)
            .ok_or_else(|| {
                Error::Usage(format!(
                    "ESL has no status `{name}`; give one of {STATUS_NAMES}, ea0, ea1, ready"
                ))
            })?;
        let alm = e.alm.ok_or_else(|| {
            Error::Usage(format!(
                "the last answer (Data ID {:X}) carried no ALM",
                e.data_id
            ))
        })?;
        Ok(alm >> bit & 1 == 1)
    }

    fn transcript(&self) -> serde_json::Value {
        serde_json::json!({
            "protocol": "esl",
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
