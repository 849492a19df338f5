//! The SSI encoder emulator: [`model::ssi::Encoder`] behind its cable.
//!
//! Configuration: the scenario's `[encoder]`, `[cable]` and `[fault]`
//! tables, plus `positions` and `step` (the position at read `k` is
//! `positions[k % len] + k × step` until the testbench sets one), as in a
//! scenario's `[ssi]` table; `[master]`, `[host]`, `f_sys_mhz` and `reads`
//! are ignored, so a whole scenario file can be given.
//!
//! Each emulator cycle: the clock crosses the cable to the encoder, the
//! encoder steps (and after its output delay drives data), the data crosses
//! the cable back. A stuck fault holds the data at the master's end from the
//! idle time before read `from_read` on, as in [`model::ssi::Bench`].

use serde::{Deserialize, Serialize};

use model::bits;
use model::gray::from_gray;
use model::line::{CableConfig, DelayLine};
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
/// (SAR58K24 manual, SSI: `100 kHz < f_clk < 250 kHz`, `T_cs > 4 µs`,
/// `T_m > 500 µs`; the monoflop is the encoder's own `monoflop_us`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SsiChecks {
    /// Slowest clock: no half period of a read may exceed half its period.
    pub min_clock_khz: f64,
    /// Fastest clock: no half period of a read may be shorter than half its period.
    pub max_clock_khz: f64,
    /// Least first low phase (the storing edge to the first rising edge), µs.
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

/// The checker's state: the master's clock as it leaves the master.
#[derive(Debug, Clone, Default)]
struct Watch {
    last_clk: bool,
    last_edge: u64,
    in_read: bool,
    first_low: bool,
    read_end: Option<u64>,
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
    monoflop: u64,
    limits: (f64, f64, f64),
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
        let (gray, bits, monoflop) = (enc_cfg.gray, enc_cfg.bits, enc_cfg.monoflop_clocks);
        let c = &cfg.checks;
        if !(c.min_clock_khz > 0.0 && c.min_clock_khz <= c.max_clock_khz && c.max_clock_khz < 1e6) {
            return Err(Error::field(
                origin,
                "checks.min_clock_khz",
                format!("{} to {} kHz", c.min_clock_khz, c.max_clock_khz),
                "give 0 < min_clock_khz <= max_clock_khz (seed: 100 and 250)",
            ));
        }
        if !(c.t_cs_min_us >= 0.0 && c.t_cs_min_us < 1e6) {
            return Err(Error::field(
                origin,
                "checks.t_cs_min_us",
                format!("{}", c.t_cs_min_us),
                "give the least T_cs in µs (seed: 4)",
            ));
        }
        let checks = Checks::for_clock(&tb);
        // Half periods and T_cs in emulator cycles, one cycle of tolerance.
        let limits = (
            checks.cycles_of_ns(1e6 / (2.0 * c.max_clock_khz)) - 1.0,
            checks.cycles_of_ns(1e6 / (2.0 * c.min_clock_khz)) + 1.0,
            checks.cycles_of_ns(c.t_cs_min_us * 1e3) - 1.0,
        );
        let encoder = Encoder::new(enc_cfg).map_err(|e| Error::config(origin, e))?;
        let watch = Watch {
            last_clk: true,
            ..Watch::default()
        };
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
            monoflop,
            limits,
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

    /// Holds the master's clock (at its own pin) to the seed's limits.
    fn check(&mut self, clk: bool) {
        let (half_min, half_max, t_cs_min) = self.limits;
        let now = self.cycle;
        let w = &mut self.watch;
        if clk != w.last_clk {
            let len = now - w.last_edge;
            let lasted = self.checks.us(len);
            if !clk {
                if !w.in_read {
                    if let Some(end) = w.read_end {
                        if now - end < self.monoflop {
                            self.checks.push(
                                now,
                                "T_m (seed 001, SSI: a new read only after the monoflop time T_m)",
                                format!("read started {:.3} us after the last clock edge of the previous read; the encoder's T_m is {:.3} us", self.checks.us(now - end), self.checks.us(self.monoflop)),
                            );
                        }
                    }
                    w.in_read = true;
                    w.first_low = true;
                } else if (len as f64) < half_min || (len as f64) > half_max {
                    self.checks.push(
                        now,
                        "clock range (seed 001, SSI: 100 kHz < f_clk < 250 kHz)",
                        format!("clock high for {lasted:.3} us within a read"),
                    );
                }
            } else if w.first_low {
                w.first_low = false;
                if (len as f64) < t_cs_min {
                    self.checks.push(
                        now,
                        "T_cs (seed 001, SSI: T_cs > 4 us)",
                        format!("first low phase {lasted:.3} us"),
                    );
                }
            } else if (len as f64) < half_min || (len as f64) > half_max {
                self.checks.push(
                    now,
                    "clock range (seed 001, SSI: 100 kHz < f_clk < 250 kHz)",
                    format!("clock low for {lasted:.3} us within a read"),
                );
            }
            w.last_clk = clk;
            w.last_edge = now;
        } else if clk && w.in_read && (now - w.last_edge) as f64 > half_max {
            // A high phase longer than any half period: the read is over.
            w.in_read = false;
            w.read_end = Some(w.last_edge);
        }
    }
}

impl Emulator for SsiEmulator {
    fn kind(&self) -> &'static str {
        "ssi"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        self.check(pins.data());
        if self.motions.any() {
            if let Some(p) = self.motions.position_on(0, self.cycle, &self.tb, self.bits) {
                self.encoder.set_position(p);
            }
        }
        let clk = self.to_encoder.step(pins.data());
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
        })
    }

    fn checks(&mut self) -> &mut Checks {
        &mut self.checks
    }
}
