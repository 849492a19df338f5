//! The SSI encoder emulator: [`model::ssi::Encoder`] behind its cable.
//!
//! Configuration: the scenario's `[encoder]`, `[cable]` and `[fault]`
//! tables, plus `positions` and `step` (the position at read `k` is
//! `positions[k % len] + k × step` until the testbench sets one), as in a
//! scenario's `[ssi]` table; `[master]`, `[host]`, `f_sys_mhz` and `reads`
//! are ignored, so a whole scenario file can be given.
//!
//! The master's timing is held to the rule book [`model::ssi::rules`] (the
//! monitor holds it to the same). The emulator expects the clock idle high
//! before the first read: until it has seen the clock high, the encoder
//! sees it idle, so a master holding reset (its clock at 0) from time 0
//! starts no read and the first read stores the first position.
//!
//! Each emulator cycle: the clock crosses the cable to the encoder, the
//! encoder steps (and after its output delay drives data), the data crosses
//! the cable back. A stuck fault holds the data at the master's end from the
//! idle time before read `from_read` on, as in [`model::ssi::Bench`].

use serde::{Deserialize, Serialize};

use model::bits;
use model::gray::from_gray;
use model::line::{CableConfig, DelayLine};
use model::rules::Unit;
use model::ssi::rules::{self, Limits, Watch};
use model::ssi::{BenchConfig, Encoder, EncoderSettings, StuckFault};

use crate::check::{Checks, VIOLATION_PENDING};
use crate::config::{self, Error};
use crate::motion::Motions;
use crate::{Emulator, Pins, Result};

/// The fastest SSI clock the seed allows (SAR58K24: `f_clk < 250 kHz`).
pub const MAX_CLOCK_KHZ: f64 = 250.0;

/// The emulator's configuration (the scenario's SSI tables).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SsiConfig {
    /// The encoder.
    pub encoder: EncoderSettings,
    /// The cable.
    pub cable: CableConfig,
    /// A stuck data line.
    pub fault: Option<StuckFault>,
    /// Positions at successive reads (cycled).
    pub positions: Vec<u64>,
    /// Counts added per read.
    pub step: u64,
    /// The timing limits the master is held to.
    pub checks: SsiChecks,
}

impl Default for SsiConfig {
    fn default() -> Self {
        SsiConfig {
            encoder: EncoderSettings::default(),
            cable: CableConfig::default(),
            fault: None,
            positions: vec![0],
            step: 0,
            checks: SsiChecks::default(),
        }
    }
}

/// The master's timing limits (`[checks]`), by default the seed's
/// ([`model::ssi::rules`]; the monoflop `T_m` is the encoder's own
/// `monoflop_us`): each may be set within its rule's settable range (the
/// seed lets these vary by product; a reader beyond the seed's encoder says
/// so here).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SsiChecks {
    /// Slowest clock, kHz (seed: 100), held on every period of a read.
    pub min_clock_khz: f64,
    /// Fastest clock, kHz (seed: 250), held on every period of a read.
    pub max_clock_khz: f64,
    /// Least first low phase (the storing edge to the first rising edge), µs (seed: 4).
    pub t_cs_min_us: f64,
}

impl Default for SsiChecks {
    fn default() -> Self {
        SsiChecks {
            min_clock_khz: 100.0,
            max_clock_khz: 250.0,
            t_cs_min_us: 4.0,
        }
    }
}

impl SsiChecks {
    /// The rule limits in force with the encoder's monoflop time `t_m_us`,
    /// each limit refused outside the seed's range.
    pub fn limits(&self, t_m_us: f64) -> std::result::Result<Limits, model::ConfigError> {
        let mut l = Limits::seed(t_m_us);
        l.t_cs = Unit::Us.ps(rules::T_CS.setting("checks.t_cs_min_us", self.t_cs_min_us)?);
        l.set_clock(
            ["checks.min_clock_khz", "checks.max_clock_khz"],
            self.min_clock_khz,
            self.max_clock_khz,
        )?;
        Ok(l)
    }
}

/// Faults a testbench schedules at run time (the scenario's `[fault]` table).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct FaultTables {
    fault: StuckFault,
}

/// One read as the emulator saw and answered it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// 0-based read number.
    pub index: u64,
    /// Emulator cycle of the storing falling edge (at the encoder's pin).
    pub cycle: u64,
    /// The position stored (binary).
    pub position: u64,
    /// The code word on the wire (Gray or binary), MSB first.
    pub sent_bits: String,
    /// Rising clock edges the encoder answered (bits put on the line,
    /// including any after the LSB).
    pub clocks: u32,
}

/// An SSI encoder and its cable, on the emulator clock.
pub struct SsiEmulator {
    f_emu_hz: u64,
    tb: model::Timebase,
    cfg: SsiConfig,
    encoder: Encoder,
    gray: bool,
    bits: u32,
    to_encoder: DelayLine,
    to_master: DelayLine,
    owned: Option<u64>,
    stuck: Option<bool>,
    cycle: u64,
    entries: Vec<Entry>,
    watch: Watch,
    checks: Checks,
    motions: Motions,
}

impl SsiEmulator {
    /// The `[encoder]` table as read from the scenario, defaults filled in.
    pub fn config(&self) -> &SsiConfig {
        &self.cfg
    }

    /// An emulator from TOML text (`origin` names it in errors) at `f_emu_hz`.
    pub fn from_toml(text: &str, origin: &str, f_emu_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "ssi")?;
        let tb = config::emulator_clock(f_emu_hz, &tables.emulator, MAX_CLOCK_KHZ, "SSI", origin)?;
        let cfg: SsiConfig = config::decode(tables.device, origin)?;
        cfg.cable
            .validate("cable")
            .map_err(|e| Error::config(origin, e))?;
        // The model converts the encoder's times to cycles of its clock: here the emulator's.
        let bench = BenchConfig {
            f_sys_mhz: tb.f_sys_hz() as f64 / 1e6,
            encoder: cfg.encoder.clone(),
            ..BenchConfig::default()
        };
        let enc_cfg = bench
            .encoder_config()
            .map_err(|e| Error::config(origin, e))?;
        let limit = if enc_cfg.bits == 64 {
            u64::MAX
        } else {
            (1u64 << enc_cfg.bits) - 1
        };
        if let Some((i, p)) = cfg.positions.iter().enumerate().find(|(_, p)| **p > limit) {
            return Err(Error::field(
                origin,
                format!("positions[{i}]"),
                format!("{p} does not fit a {}-bit encoder", enc_cfg.bits),
                format!("give positions from 0 to {limit}"),
            ));
        }
        let (to_encoder, to_master) = cfg.cable.lines(&tb, true);
        let (gray, bits) = (enc_cfg.gray, enc_cfg.bits);
        let limits = cfg
            .checks
            .limits(cfg.encoder.monoflop_us)
            .map_err(|e| Error::config(origin, e))?;
        let mut checks = Checks::for_clock(&tb);
        for note in model::rules::resolution_notes(f_emu_hz, &limits.least()) {
            checks.note(note);
        }
        let encoder = Encoder::new(enc_cfg).map_err(|e| Error::config(origin, e))?;
        let watch = Watch::new(limits);
        let mut emu = SsiEmulator {
            f_emu_hz,
            tb,
            cfg,
            encoder,
            gray,
            bits,
            to_encoder,
            to_master,
            owned: None,
            stuck: None,
            cycle: 0,
            entries: Vec::new(),
            watch,
            checks,
            motions: Motions::default(),
        };
        emu.prepare(0);
        Ok(emu)
    }

    /// The position for read `k` and the fault state of the idle time before it.
    fn prepare(&mut self, k: u64) {
        let p = match self.owned {
            Some(p) => p,
            None => {
                let list = &self.cfg.positions;
                let listed = if list.is_empty() {
                    0
                } else {
                    list[(k % list.len() as u64) as usize]
                };
                listed.wrapping_add(k.wrapping_mul(self.cfg.step))
            }
        };
        self.encoder.set_position(p);
    }

    fn apply_fault(&mut self) {
        if let Some(f) = &self.cfg.fault {
            if self.encoder.is_idle() && self.encoder.reads() >= f.from_read as u64 {
                self.stuck = Some(f.level);
            }
        }
    }

    /// The entries so far.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }
}

impl Emulator for SsiEmulator {
    fn kind(&self) -> &'static str {
        "ssi"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let seen = self.watch.sample(self.tb.ps_at(self.cycle), pins.data());
        for b in &seen.breaches {
            self.checks.breach(self.cycle, b);
        }
        if self.motions.any() {
            if let Some(p) = self.motions.position_on(0, self.cycle, &self.tb, self.bits) {
                self.encoder.set_position(p);
            }
        }
        // Before the clock has been seen idle high (a master in reset), the
        // encoder sees it idle.
        let clk = self.to_encoder.step(pins.data() || !self.watch.seen_idle());
        let reads = self.encoder.reads();
        let data = self.encoder.step(clk);
        if self.encoder.reads() != reads {
            let code = self.encoder.stored();
            self.entries.push(Entry {
                index: reads,
                cycle: self.cycle,
                position: if self.gray { from_gray(code) } else { code },
                sent_bits: bits::string_of(code as u128, self.bits),
                clocks: 0,
            });
            self.prepare(reads + 1);
        } else if let Some(e) = self.entries.last_mut() {
            e.clocks = self.encoder.bits_sent();
        }
        if self.stuck.is_none() && self.cfg.fault.is_some() {
            self.apply_fault();
        }
        let at_master = self.to_master.step(data);
        self.cycle += 1;
        let flag = if self.checks.pending() {
            VIOLATION_PENDING
        } else {
            0
        };
        Pins(self.stuck.unwrap_or(at_master) as u32 | flag)
    }

    fn set_position(&mut self, device: usize, position: u64) -> Result<()> {
        if device != 0 {
            return Err(Error::Usage(format!(
                "SSI has one encoder (device 0), not device {device}"
            )));
        }
        self.owned = Some(position);
        self.motions.stop(0);
        self.encoder.set_position(position);
        Ok(())
    }

    fn set_motion(&mut self, device: usize, toml: &str) -> Result<()> {
        if device != 0 {
            return Err(Error::Usage(format!(
                "SSI has one encoder (device 0), not device {device}"
            )));
        }
        self.owned = Some(0);
        self.motions.set(0, toml, self.cycle)
    }

    fn set_status(&mut self, _device: usize, name: &str, _value: bool) -> Result<()> {
        Err(Error::Usage(format!(
            "an SSI encoder reports no status (`{name}`): its frame is the position alone"
        )))
    }

    fn schedule_fault(&mut self, toml: &str) -> Result<()> {
        let tables = config::tables(toml, "fault", "ssi")?;
        let f: FaultTables = config::decode(tables.device, "fault")?;
        self.cfg.fault = Some(f.fault);
        self.stuck = None;
        Ok(())
    }

    fn count(&self) -> u64 {
        self.entries.len() as u64
    }

    fn last_value(&self, device: usize) -> Option<u64> {
        (device == 0)
            .then(|| self.entries.last().map(|e| e.position))
            .flatten()
    }

    fn last_status(&self, _device: usize, name: &str) -> Result<bool> {
        Err(Error::Usage(format!(
            "an SSI encoder reports no status (`{name}`)"
        )))
    }

    fn transcript(&self) -> serde_json::Value {
        serde_json::json!({
            "protocol": "ssi",
            "f_emu_hz": self.f_emu_hz,
            "reads": self.entries,
            "violations": self.checks.all(),
            "notes": self.checks.notes(),
        })
    }

    fn checks(&mut self) -> &mut Checks {
        &mut self.checks
    }
}
