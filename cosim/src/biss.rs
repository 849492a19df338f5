//! The BiSS-C slave-chain emulator: [`model::biss::Chain`] behind its cable.
//!
//! Configuration: the scenario's `[[slaves]]`, `[cable]`, `[[flips]]`,
//! `[stuck]` and `[delay_step]` tables, as in a scenario's `[biss]` table
//! (`[master]`, `[host]` and `f_sys_mhz` are ignored). Frame `k` of the
//! tables is the emulator's `k`-th latch (first rising MA edge); the
//! position of slave `i` in frame `k` is the scenario's
//! `positions[k % len] + k × step` until the testbench sets one, and its
//! error and warning bits are the scenario's until the testbench sets them.
//!
//! The master's timing is held to the rule book [`model::biss::rules`] (the
//! monitor holds it to the same). The emulator expects MA idle high before
//! the first frame: until it has seen MA high, the slaves see MA idle, so a
//! master holding reset (MA at 0) from time 0 starts no frame.
//!
//! Each emulator cycle: MA crosses the cable to the chain, the chain steps
//! (SLO changes after the first slave's `output_delay_ns`), SLO crosses the
//! cable back (plus a `delay_step`'s extra delay from its frame on). A stuck
//! fault holds SLO at the master's end from the end of frame `from_frame - 1`.

use serde::{Deserialize, Serialize};

use model::biss::rules::{self, Limits, Watch};
use model::biss::{
    BenchConfig, Chain, DelayStep, FlipFault, Slave, SlaveSettings, StuckFault, MAX_SLAVES,
};
use model::bits;
use model::line::{CableConfig, DelayLine};
use model::rules::Unit;
use model::Timebase;

use crate::check::{Checks, VIOLATION_PENDING};
use crate::config::{self, Error};
use crate::motion::Motions;
use crate::{Emulator, Pins, Result};

/// The fastest MA the seed allows (`TMAS > 100 ns`).
pub const MAX_CLOCK_KHZ: f64 = 10_000.0;

/// The emulator's configuration (the scenario's BiSS-C tables).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BissConfig {
    /// The slaves in chain order (1 to 3).
    pub slaves: Vec<SlaveSettings>,
    /// The cable.
    pub cable: CableConfig,
    /// Wire corruptions.
    pub flips: Vec<FlipFault>,
    /// A stuck SLO line.
    pub stuck: Option<StuckFault>,
    /// A change of the line delay.
    pub delay_step: Option<DelayStep>,
    /// The timing limits the master is held to.
    pub checks: BissChecks,
}

/// The master's timing limits (`[checks]`), by default the seed's
/// ([`model::biss::rules`]): each may be set within the seed's range only
/// (a tighter limit for a slower slave), never looser.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BissChecks {
    /// Least MA period within a frame, ns (`TMAS`, seed: 100).
    pub min_tmas_ns: f64,
    /// Least MA high phase within a frame, ns, exclusive (`TMASH`, seed: 25).
    pub min_tmash_ns: f64,
    /// Least MA low phase within a frame, ns, exclusive (`TMASL`, seed: 25).
    pub min_tmasl_ns: f64,
}

impl Default for BissChecks {
    fn default() -> Self {
        BissChecks {
            min_tmas_ns: 100.0,
            min_tmash_ns: 25.0,
            min_tmasl_ns: 25.0,
        }
    }
}

/// The rule limits in force for slaves that time out after `timeout_us`,
/// the MA phase limits given as `(field, ns)` for `TMAS`, `TMASH` and
/// `TMASL`, each refused outside the seed's range.
pub fn limits(
    timeout_us: f64,
    given: [(&str, f64); 3],
) -> std::result::Result<Limits, model::ConfigError> {
    let mut l = Limits::seed(timeout_us);
    let [tmas, tmash, tmasl] = given;
    l.tmas = Unit::Ns.ps(rules::TMAS.setting(tmas.0, tmas.1)?);
    l.tmash = Unit::Ns.ps(rules::TMASH.setting(tmash.0, tmash.1)?);
    l.tmasl = Unit::Ns.ps(rules::TMASL.setting(tmasl.0, tmasl.1)?);
    Ok(l)
}

impl Default for BissConfig {
    fn default() -> Self {
        BissConfig {
            slaves: vec![SlaveSettings::default()],
            cable: CableConfig::default(),
            flips: Vec::new(),
            stuck: None,
            delay_step: None,
            checks: BissChecks::default(),
        }
    }
}

/// Faults a testbench schedules at run time (the scenario's fault tables).
#[derive(Debug, Clone, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
struct FaultTables {
    flips: Vec<FlipFault>,
    stuck: Option<StuckFault>,
    delay_step: Option<DelayStep>,
}

/// One slave's part of a frame as the emulator sent it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SlaveEntry {
    /// The position latched.
    pub position: u64,
    /// The error condition (sent as nE = 0).
    pub error: bool,
    /// The warning condition (sent as nW = 0).
    pub warning: bool,
    /// The section as it left the slave: CDS, data, nE, nW, CRC (after any flips).
    pub sent_bits: String,
}

/// One frame as the emulator saw and answered it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// 0-based frame (latch) number.
    pub index: u64,
    /// Emulator cycle of the latching MA edge (at the slaves' pins).
    pub cycle: u64,
    /// The slaves in chain order.
    pub slaves: Vec<SlaveEntry>,
}

#[derive(Debug, Clone, Copy, Default)]
struct Owned {
    position: Option<u64>,
    error: Option<bool>,
    warning: Option<bool>,
}

/// A chain of BiSS-C slaves and its cable, on the emulator clock.
pub struct BissEmulator {
    f_emu_hz: u64,
    tb: Timebase,
    cfg: BissConfig,
    chain: Chain,
    owned: Vec<Owned>,
    to_slaves: DelayLine,
    to_master: DelayLine,
    extra: Option<DelayLine>,
    stuck: Option<bool>,
    cycle: u64,
    entries: Vec<Entry>,
    /// The master's MA has been seen idle high: before that (a master in
    /// reset), the slaves see MA idle.
    ma_seen_idle: bool,
    watch: Watch,
    checks: Checks,
    motions: Motions,
}

impl BissEmulator {
    /// The `[biss]` table as read from the scenario, defaults filled in.
    pub fn config(&self) -> &BissConfig {
        &self.cfg
    }

    /// An emulator from TOML text (`origin` names it in errors) at `f_emu_hz`.
    pub fn from_toml(text: &str, origin: &str, f_emu_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "biss")?;
        let tb =
            config::emulator_clock(f_emu_hz, &tables.emulator, MAX_CLOCK_KHZ, "BiSS-C", origin)?;
        let cfg: BissConfig = config::decode(tables.device, origin)?;
        if cfg.slaves.is_empty() || cfg.slaves.len() > MAX_SLAVES {
            return Err(Error::field(
                origin,
                "slaves",
                format!("{} slaves", cfg.slaves.len()),
                "give 1 to 3 [[slaves]] tables",
            ));
        }
        cfg.cable
            .validate("cable")
            .map_err(|e| Error::config(origin, e))?;
        // The model converts the slaves' times to cycles of its clock: here
        // the emulator's. A slave's default t_busy is 2 TMAS (seed 001,
        // BiSS-C); the emulator cannot know the user's MA clock, so TMAS is
        // that of the fastest clock the master declares
        // (`emulator.max_line_clock_khz`), the shortest busy time the seed
        // allows at any clock the master uses. A slower master wanting the
        // seed's minimum at its own clock sets `busy_ns`.
        let mut bench = BenchConfig {
            f_sys_mhz: tb.f_sys_hz() as f64 / 1e6,
            slaves: cfg.slaves.clone(),
            ..BenchConfig::default()
        };
        bench.master.clock_khz = tables.emulator.max_line_clock_khz.unwrap_or(MAX_CLOCK_KHZ);
        let mut slaves = Vec::new();
        for (i, s) in cfg.slaves.iter().enumerate() {
            let limit = if s.bits == 64 {
                u64::MAX
            } else {
                (1u64 << s.bits.min(63)) - 1
            };
            let sc = bench
                .slave_config(i)
                .map_err(|e| Error::config(origin, e))?;
            if let Some((j, p)) = s.positions.iter().enumerate().find(|(_, p)| **p > limit) {
                return Err(Error::field(
                    origin,
                    format!("slaves[{i}].positions[{j}]"),
                    format!("{p} does not fit {} bits", s.bits),
                    format!("give positions from 0 to {limit}"),
                ));
            }
            slaves.push(Slave::new(sc).map_err(|e| Error::config(origin, e))?);
        }
        let faults = FaultTables {
            flips: cfg.flips.clone(),
            stuck: cfg.stuck.clone(),
            delay_step: cfg.delay_step.clone(),
        };
        check_faults(&faults, &cfg.slaves, origin)?;
        let chain = Chain::new(slaves, tb.cycles_nearest_ns(cfg.slaves[0].output_delay_ns));
        let (to_slaves, to_master) = cfg.cable.lines(&tb, true);
        let owned = vec![Owned::default(); cfg.slaves.len()];
        let longest = cfg.slaves.iter().map(|s| s.timeout_us).fold(0.0, f64::max);
        let c = &cfg.checks;
        let limits = limits(
            longest,
            [
                ("checks.min_tmas_ns", c.min_tmas_ns),
                ("checks.min_tmash_ns", c.min_tmash_ns),
                ("checks.min_tmasl_ns", c.min_tmasl_ns),
            ],
        )
        .map_err(|e| Error::config(origin, e))?;
        let mut checks = Checks::for_clock(&tb);
        for note in model::rules::resolution_notes(f_emu_hz, &limits.least()) {
            checks.note(note);
        }
        let mut emu = BissEmulator {
            f_emu_hz,
            tb,
            cfg,
            chain,
            owned,
            to_slaves,
            to_master,
            extra: None,
            stuck: None,
            cycle: 0,
            entries: Vec::new(),
            ma_seen_idle: false,
            watch: Watch::new(limits),
            checks,
            motions: Motions::default(),
        };
        emu.prepare(0);
        emu.apply_line_faults();
        Ok(emu)
    }

    /// Positions, flags and flips of frame `k`, before its latch.
    fn prepare(&mut self, k: u64) {
        let bench = BenchConfig {
            slaves: self.cfg.slaves.clone(),
            ..BenchConfig::default()
        };
        for i in 0..self.cfg.slaves.len() {
            let s = &self.cfg.slaves[i];
            let o = self.owned[i];
            let kk = k as usize;
            let position = o.position.unwrap_or_else(|| bench.position_at(i, kk));
            let error = o.error.unwrap_or(s.error || s.error_frames.contains(&kk));
            let warning = o
                .warning
                .unwrap_or(s.warning || s.warning_frames.contains(&kk));
            let flips: Vec<u32> = self
                .cfg
                .flips
                .iter()
                .filter(|f| f.frame == kk && f.slave == i)
                .flat_map(|f| f.bits.clone())
                .collect();
            let slave = &mut self.chain.slaves_mut()[i];
            slave.set_position(position);
            slave.set_flags(error, warning);
            slave.set_flips(flips);
        }
    }

    fn apply_line_faults(&mut self) {
        let done = self.chain.frames() as usize;
        if let Some(f) = &self.cfg.stuck {
            if done >= f.from_frame {
                self.stuck = Some(f.level);
            }
        }
        if let (Some(d), None) = (&self.cfg.delay_step, &self.extra) {
            if done >= d.from_frame {
                self.extra = Some(DelayLine::new(self.tb.cycles_nearest_ns(d.extra_ns), true));
            }
        }
    }

    /// The entries so far.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    fn slave_index(&self, device: usize) -> Result<usize> {
        if device < self.owned.len() {
            Ok(device)
        } else {
            Err(Error::Usage(format!(
                "the chain has {} slave(s), 0 to {}; there is no slave {device}",
                self.owned.len(),
                self.owned.len() - 1
            )))
        }
    }
}

fn check_faults(f: &FaultTables, slaves: &[SlaveSettings], origin: &str) -> Result<()> {
    for (j, flip) in f.flips.iter().enumerate() {
        let Some(s) = slaves.get(flip.slave) else {
            return Err(Error::field(
                origin,
                format!("flips[{j}].slave"),
                format!("slave {}", flip.slave),
                "name a slave of the chain (0-based)",
            ));
        };
        let len = s.bits + 2 + s.crc_width;
        if let Some(b) = flip.bits.iter().find(|&&b| b >= len) {
            return Err(Error::field(
                origin,
                format!("flips[{j}].bits"),
                format!("bit {b}"),
                format!("give bits 0 to {}", len - 1),
            ));
        }
    }
    if let Some(d) = &f.delay_step {
        if !(d.extra_ns >= 0.0 && d.extra_ns < 1e7) {
            return Err(Error::field(
                origin,
                "delay_step.extra_ns",
                format!("{}", d.extra_ns),
                "give a non-negative time",
            ));
        }
    }
    Ok(())
}

impl Emulator for BissEmulator {
    fn kind(&self) -> &'static str {
        "biss"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let ma_at_master = pins.data();
        self.ma_seen_idle |= ma_at_master;
        if self.motions.any() {
            for i in 0..self.cfg.slaves.len() {
                if let Some(p) =
                    self.motions
                        .position_on(i, self.cycle, &self.tb, self.cfg.slaves[i].bits)
                {
                    self.chain.slaves_mut()[i].set_position(p);
                }
            }
        }
        let ma = self.to_slaves.step(ma_at_master || !self.ma_seen_idle);
        let latches = self.chain.latches();
        let frames = self.chain.frames();
        let slo = self.chain.step(ma);
        if self.chain.latches() != latches {
            let slaves = self
                .chain
                .slaves()
                .iter()
                .zip(&self.cfg.slaves)
                .map(|(s, set)| {
                    let sec = s.last_section();
                    let n = set.bits as usize;
                    let value = sec[1..1 + n].iter().fold(0u64, |a, &b| (a << 1) | b as u64);
                    SlaveEntry {
                        position: value,
                        error: !sec[1 + n],
                        warning: !sec[2 + n],
                        sent_bits: bits::string(sec),
                    }
                })
                .collect();
            self.entries.push(Entry {
                index: latches,
                cycle: self.cycle,
                slaves,
            });
            self.prepare(latches + 1);
        }
        if self.chain.frames() != frames {
            self.apply_line_faults();
        }
        let mut at_master = self.to_master.step(slo);
        if let Some(extra) = self.extra.as_mut() {
            at_master = extra.step(at_master);
        }
        let slo_at_master = self.stuck.unwrap_or(at_master);
        let seen = self
            .watch
            .sample(self.tb.ps_at(self.cycle), ma_at_master, slo_at_master);
        for b in &seen.breaches {
            self.checks.breach(self.cycle, b);
        }
        self.cycle += 1;
        let flag = if self.checks.pending() {
            VIOLATION_PENDING
        } else {
            0
        };
        Pins(slo_at_master as u32 | flag)
    }

    fn set_position(&mut self, device: usize, position: u64) -> Result<()> {
        let i = self.slave_index(device)?;
        self.owned[i].position = Some(position);
        self.motions.stop(i);
        self.chain.slaves_mut()[i].set_position(position);
        Ok(())
    }

    fn set_motion(&mut self, device: usize, toml: &str) -> Result<()> {
        let i = self.slave_index(device)?;
        self.owned[i].position = Some(0);
        self.motions.set(i, toml, self.cycle)
    }

    fn set_status(&mut self, device: usize, name: &str, value: bool) -> Result<()> {
        let i = self.slave_index(device)?;
        match name {
            "error" => self.owned[i].error = Some(value),
            "warning" => self.owned[i].warning = Some(value),
            other => {
                return Err(Error::Usage(format!(
                    "a BiSS-C slave reports `error` and `warning`, not `{other}`"
                )))
            }
        }
        let k = self.chain.latches();
        // Re-arm the next frame with the new flags (flips of that frame stay scheduled).
        self.prepare(k);
        Ok(())
    }

    fn schedule_fault(&mut self, toml: &str) -> Result<()> {
        let tables = config::tables(toml, "fault", "biss")?;
        let f: FaultTables = config::decode(tables.device, "fault")?;
        check_faults(&f, &self.cfg.slaves, "fault")?;
        self.cfg.flips.extend(f.flips);
        if f.stuck.is_some() {
            self.cfg.stuck = f.stuck;
            self.stuck = None;
        }
        if f.delay_step.is_some() {
            self.cfg.delay_step = f.delay_step;
            self.extra = None;
        }
        let k = self.chain.latches();
        self.prepare(k);
        self.apply_line_faults();
        Ok(())
    }

    fn count(&self) -> u64 {
        self.entries.len() as u64
    }

    fn last_value(&self, device: usize) -> Option<u64> {
        self.entries
            .last()
            .and_then(|e| e.slaves.get(device))
            .map(|s| s.position)
    }

    fn last_status(&self, device: usize, name: &str) -> Result<bool> {
        let i = self.slave_index(device)?;
        let Some(e) = self.entries.last() else {
            return Err(Error::Usage("no frame has been latched yet".into()));
        };
        match name {
            "error" => Ok(e.slaves[i].error),
            "warning" => Ok(e.slaves[i].warning),
            other => Err(Error::Usage(format!(
                "a BiSS-C slave reports `error` and `warning`, not `{other}`"
            ))),
        }
    }

    fn transcript(&self) -> serde_json::Value {
        serde_json::json!({
            "protocol": "biss",
            "f_emu_hz": self.f_emu_hz,
            "frames": self.entries,
            "violations": self.checks.all(),
            "notes": self.checks.notes(),
        })
    }

    fn checks(&mut self) -> &mut Checks {
        &mut self.checks
    }
}
