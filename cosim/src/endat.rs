//! The EnDat 2.2 encoder emulator: [`model::endat::Encoder`] behind its
//! cable (a clock pair and the half-duplex data pair).
//!
//! Configuration: the scenario's `[endat]` tables for the device:
//! `[encoder]`, `[cable]`, `[faults]`, `block_gap_clocks`, `positions` and
//! `step` (the position at transfer `k` is `positions[k % len] + k × step`
//! until the testbench sets one or a `[motion]` profile runs);
//! `[master]`, `[host]`, `commands`, `f_sys_mhz` are ignored, so a whole
//! scenario file can be given. Faults indexed by request count the
//! emulator's transfers (latching falling edges) from 0.
//!
//! Each emulator cycle: the master's clock crosses the clock pair; the
//! master's data driver (level and enable) and the encoder's cross the data
//! pair ([`model::line::HalfDuplexLine`]); the encoder steps. Out: bit 0 the
//! encoder's level at the master's end (the fail-safe idle high while it does
//! not drive), bit 1 its driver enable there.
//!
//! Statuses (`set_status`), each on its own: `f1` (the error word: F1 = 1),
//! `f2` (error message 2 from its separate detection unit, sent low-active
//! whatever F1 is), `warning` (the warning word: WRN of the additional data),
//! `busy` (the busy bit of the additional data).
//!
//! Checks of the master: a falling clock edge within the encoder's recovery
//! time I (seed 004, 2.3.2 and appendix A2: the next transfer only after
//! `t_m`), and both drivers on the data pair at once (contention: the master
//! must switch its driver off with the first falling edge, t_ST).

use serde::{Deserialize, Serialize};

use model::bits;
use model::endat::{frame_kind, BenchConfig, Encoder, EncoderSettings, FaultSettings, FrameKind};
use model::line::{CableConfig, DelayLine, Drive};

use crate::check::Checks;
use crate::config::{self, Error};
use crate::motion::{Motion, Running};
use crate::pair::Pair;
use crate::{Emulator, Pins, Result};

/// The fastest EnDat clock the seed's timing table gives with delay
/// compensation (seed 004, 2.3.2: `f_c` up to 8 MHz; 16 MHz with the
/// encoders that support it: set `emulator.max_line_clock_khz`).
pub const MAX_CLOCK_KHZ: f64 = 8000.0;

/// Both drivers on the data pair.
const CONTENTION: &str = "t_ST / bus contention (seed 004, 2.2: the master switches its data driver off with the first falling edge and on only while the encoder does not drive)";

/// The emulator's configuration (the scenario's EnDat device tables).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EndatConfig {
    /// The encoder.
    pub encoder: EncoderSettings,
    /// The cable (clock pair and data pair alike).
    pub cable: CableConfig,
    /// Clocks between the encoder's last bit and the master's parameter block (type 2.2).
    pub block_gap_clocks: u64,
    /// Raw positions at successive transfers (cycled).
    pub positions: Vec<u64>,
    /// Counts added per transfer.
    pub step: u64,
    /// Faults, indexed by transfer.
    pub faults: FaultSettings,
    /// A motion profile (see [`crate::motion`]).
    pub motion: Option<Motion>,
    /// The timing limits the master is held to.
    pub checks: EndatChecks,
}

/// The master's timing limits (`[checks]`), by default the seed's (seed 004,
/// 2.3.2: `t_b > 1 ms` between EnDat 2.1 commands; `f_c` up to 8 MHz with
/// delay compensation, 16 MHz for the encoders that support it).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EndatChecks {
    /// Least time between a type 2.1 transfer's last clock edge and the next transfer, µs.
    pub t_b_us: f64,
    /// Fastest clock: no clock phase within a transfer shorter than half its period, kHz.
    pub max_clock_khz: f64,
}

impl Default for EndatChecks {
    fn default() -> Self {
        EndatChecks {
            t_b_us: 1000.0,
            max_clock_khz: 8000.0,
        }
    }
}

impl Default for EndatConfig {
    fn default() -> Self {
        let b = BenchConfig::default();
        EndatConfig {
            encoder: b.encoder,
            cable: b.cable,
            block_gap_clocks: b.block_gap_clocks,
            positions: vec![0],
            step: 0,
            faults: FaultSettings::default(),
            motion: None,
            checks: EndatChecks::default(),
        }
    }
}

/// One transfer as the emulator saw and answered it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// 0-based transfer number.
    pub index: u64,
    /// Emulator cycle of the latching falling edge (at the encoder's pins).
    pub cycle: u64,
    /// The six mode bits the master sent.
    pub mode: String,
    /// The position the encoder latched (datum shift applied).
    pub position: u64,
    /// The bits after the start bit as they left the encoder ("" when no start bit was sent).
    pub sent_bits: String,
    /// How the encoder answered (`ok`, `type_i`, `type_ii`, `ignored`).
    pub answer: &'static str,
    /// F1 as sent (position and test frames).
    pub f1: Option<bool>,
    /// F2 as sent (low active; type 2.2 position frames).
    pub f2: Option<bool>,
    /// The warning word was non-zero at the latch.
    pub warning: bool,
    /// The busy status was set at the latch.
    pub busy: bool,
}

/// An EnDat encoder and its cable, on the emulator clock.
pub struct EndatEmulator {
    f_emu_hz: u64,
    tb: model::Timebase,
    cfg: EndatConfig,
    encoder: Encoder,
    clk_line: DelayLine,
    pair: Pair,
    enc_drive: Drive,
    owned: Option<u64>,
    motion: Option<Running>,
    stuck: Option<bool>,
    cycle: u64,
    entries: Vec<Entry>,
    warning: bool,
    busy: bool,
    seen_violations: u64,
    reported_violations: u64,
    reported_at_latch: u64,
    seen_decodes: u64,
    seen_answer: &'static str,
    last_clk: bool,
    last_clk_edge: u64,
    after_21: bool,
    limits: (f64, f64),
    checks: Checks,
}

impl EndatEmulator {
    /// An emulator from TOML text (`origin` names it in errors) at `f_emu_hz`.
    pub fn from_toml(text: &str, origin: &str, f_emu_hz: u64) -> Result<Self> {
        let mut tables = config::tables(text, origin, "endat")?;
        tables.device.remove("commands");
        let tb =
            config::emulator_clock(f_emu_hz, &tables.emulator, MAX_CLOCK_KHZ, "EnDat", origin)?;
        let cfg: EndatConfig = config::decode(tables.device, origin)?;
        cfg.cable
            .validate("cable")
            .map_err(|e| Error::config(origin, e))?;
        if let Some(m) = &cfg.motion {
            m.validate(origin)?;
        }
        let bench = BenchConfig {
            f_sys_mhz: tb.f_sys_hz() as f64 / 1e6,
            encoder: cfg.encoder.clone(),
            block_gap_clocks: cfg.block_gap_clocks,
            ..BenchConfig::default()
        };
        let enc_cfg = bench
            .encoder_config()
            .map_err(|e| Error::config(origin, e))?;
        let bits = enc_cfg.pos_bits();
        let limit = (1u64 << bits) - 1;
        if let Some((i, p)) = cfg.positions.iter().enumerate().find(|(_, p)| **p > limit) {
            return Err(Error::field(
                origin,
                format!("positions[{i}]"),
                format!("{p} does not fit a {bits}-bit encoder"),
                format!("give positions from 0 to {limit}"),
            ));
        }
        let mut encoder = Encoder::new(enc_cfg).map_err(|e| Error::config(origin, e))?;
        encoder.set_errors(cfg.encoder.errors);
        encoder.set_warnings(cfg.encoder.warnings);
        if let Some(w) = cfg.encoder.write_protect {
            encoder
                .memory_mut()
                .areas
                .get_mut(&0xB9)
                .expect("status area")[2] = w;
        }
        let (clk_line, _) = cfg.cable.lines(&tb, true);
        let delay = cfg.cable.delay_cycles(&tb);
        let motion = cfg
            .motion
            .clone()
            .map(|motion| Running { motion, since: 0 });
        let c = &cfg.checks;
        if !(c.t_b_us >= 0.0 && c.t_b_us < 1e7 && c.max_clock_khz > 0.0 && c.max_clock_khz < 1e6) {
            return Err(Error::field(
                origin,
                "checks",
                format!("t_b_us = {}, max_clock_khz = {}", c.t_b_us, c.max_clock_khz),
                "give t_b_us >= 0 (seed: 1000) and max_clock_khz > 0 (seed: 8000)",
            ));
        }
        let checks = Checks::for_clock(&tb);
        // t_b and the shortest half period in emulator cycles, one cycle of tolerance.
        let limits = (
            checks.cycles_of_ns(c.t_b_us * 1e3) - 1.0,
            checks.cycles_of_ns(1e6 / (2.0 * c.max_clock_khz)) - 1.0,
        );
        let mut emu = EndatEmulator {
            f_emu_hz,
            tb,
            warning: cfg.encoder.warnings != 0,
            busy: false,
            cfg,
            encoder,
            clk_line,
            pair: Pair::new(delay),
            enc_drive: Drive {
                enable: true,
                level: true,
            },
            owned: None,
            motion,
            stuck: None,
            cycle: 0,
            entries: Vec::new(),
            seen_violations: 0,
            reported_violations: 0,
            reported_at_latch: u64::MAX,
            seen_decodes: 0,
            seen_answer: "ok",
            last_clk: true,
            last_clk_edge: 0,
            after_21: false,
            limits,
            checks,
        };
        emu.prepare(0);
        Ok(emu)
    }

    fn bits(&self) -> u32 {
        self.encoder.config().pos_bits()
    }

    /// The position for transfer `k` (list and step, unless the testbench owns it).
    fn prepare(&mut self, k: u64) {
        if self.owned.is_some() || self.motion.is_some() {
            return;
        }
        let list = &self.cfg.positions;
        let listed = if list.is_empty() {
            0
        } else {
            list[(k % list.len() as u64) as usize]
        };
        self.encoder
            .set_position(listed.wrapping_add(k.wrapping_mul(self.cfg.step)));
    }

    /// The faults of transfer `k`, applied right after its latch (before its frame is built).
    fn apply_faults(&mut self, k: usize) {
        let f = &self.cfg.faults;
        if let Some(flip) = f.flips.iter().find(|x| x.request == k) {
            self.encoder.flips = flip.bits.clone();
        }
        if f.dead_from == Some(k) {
            self.encoder.dead = true;
        }
        if f.absent_from == Some(k) {
            self.encoder.absent = true;
        }
        self.encoder.ad_stale = f.stale_ad.contains(&k);
        self.encoder.early_start = f.early_start.unwrap_or(0);
        if let Some((word, at)) = f.errors_at {
            if at == k {
                self.encoder.set_errors(word);
            }
        }
        if let (Some(ns), true) = (f.line.drift_ns, f.line.drift_from == k) {
            let base = self.cfg.encoder.output_delay_ns;
            let cycles = self.tb.cycles_nearest_ns(base + ns);
            self.encoder.set_output_delay(cycles);
        }
        if let (Some(level), true) = (f.line.stuck_level, f.line.stuck_from == k) {
            self.stuck = Some(level);
        }
    }

    /// The entries so far.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    fn on_latch(&mut self) {
        let k = self.entries.len();
        self.entries.push(Entry {
            index: k as u64,
            cycle: self.cycle,
            mode: bits::string_of(self.encoder.mode() as u128, 6),
            position: self.encoder.latched_position,
            sent_bits: String::new(),
            answer: "ok",
            f1: None,
            f2: None,
            warning: self.warning,
            busy: self.busy,
        });
        self.apply_faults(k);
        self.prepare(k as u64 + 1);
    }

    fn on_frame(&mut self, sent: &[bool]) {
        let mode = self.encoder.mode();
        let Some(e) = self.entries.last_mut() else {
            return;
        };
        e.mode = bits::string_of(mode as u128, 6);
        e.sent_bits = sent.iter().map(|&b| if b { '1' } else { '0' }).collect();
        match frame_kind(mode) {
            FrameKind::Pos21 | FrameKind::Test21 => e.f1 = sent.first().copied(),
            FrameKind::Pos22 | FrameKind::Block22 => {
                e.f1 = sent.first().copied();
                e.f2 = sent.get(1).copied();
            }
            FrameKind::Param21 => {}
        }
    }

    /// The master's clock as the encoder sees it (the cable shifts every edge alike):
    /// `t_b` after a type 2.1 transfer, and the fastest clock within a transfer.
    fn check_clock(&mut self, clk: bool, gap: u64, latched: bool) {
        let (t_b, half_min) = self.limits;
        if latched {
            if self.after_21 && (gap as f64) < t_b {
                self.checks.push(
                    self.cycle,
                    "t_b (seed 004, 2.3.2: t_b > 1 ms between EnDat 2.1 commands)",
                    format!(
                        "next transfer {:.3} us after the last clock edge of a type 2.1 transfer",
                        self.checks.us(gap)
                    ),
                );
            }
        } else if (gap as f64) < half_min {
            self.checks.push(
                self.cycle,
                "f_c (seed 004, 2.3.2: clock frequency up to 8 MHz with delay compensation)",
                format!(
                    "clock {} for {:.3} us within a transfer",
                    if clk { "low" } else { "high" },
                    self.checks.us(gap)
                ),
            );
        }
        if latched {
            self.after_21 = false;
        }
        self.last_clk = clk;
        self.last_clk_edge = self.cycle;
    }

    fn watch(&mut self) {
        if self.encoder.violations != self.seen_violations {
            self.seen_violations = self.encoder.violations;
        }
        // One report per recovery time, however many edges fell into it.
        if self.seen_violations != self.reported_violations
            && self.encoder.latches != self.reported_at_latch
        {
            self.reported_violations = self.seen_violations;
            self.reported_at_latch = self.encoder.latches;
            self.checks.push(
                self.cycle,
                "t_m (seed 004, 2.3.2 and appendix A2 4.2.1: a new transfer only after the recovery time I t_m)",
                "falling clock edge at the encoder while it still held the data line low for t_m".into(),
            );
        }
    }
}

impl Emulator for EndatEmulator {
    fn kind(&self) -> &'static str {
        "endat"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let master = Pair::master_drive(pins);
        if let Some(m) = &self.motion {
            let p = m.position_on(self.cycle, &self.tb, self.bits());
            self.encoder.set_position(p);
        }
        let clk = self.clk_line.step(pins.data());
        let edge = (clk != self.last_clk).then(|| self.cycle - self.last_clk_edge);
        let at_encoder = self.pair.step(
            master,
            self.enc_drive,
            self.cycle,
            &mut self.checks,
            CONTENTION,
        );
        let latches = self.encoder.latches;
        self.enc_drive = self.encoder.step(clk, at_encoder);
        let latched = self.encoder.latches != latches;
        if let Some(gap) = edge {
            self.check_clock(clk, gap, latched);
        }
        if latched {
            self.on_latch();
        }
        if let Some((_, sent)) = self.encoder.frames.pop_front() {
            self.on_frame(&sent);
            self.encoder.frames.clear();
        }
        if self.encoder.decodes != self.seen_decodes
            || self.encoder.answer_name() != self.seen_answer
        {
            self.seen_decodes = self.encoder.decodes;
            self.seen_answer = self.encoder.answer_name();
            let mode = bits::string_of(self.encoder.mode() as u128, 6);
            self.after_21 = model::endat::Command::from_code(self.encoder.mode())
                .is_some_and(|c| !c.is_type22());
            if let Some(e) = self.entries.last_mut() {
                e.mode = mode;
                e.answer = self.seen_answer;
            }
        }
        self.watch();
        self.cycle += 1;
        self.pair.pins_out(self.enc_drive, &self.checks, self.stuck)
    }

    fn set_position(&mut self, device: usize, position: u64) -> Result<()> {
        if device != 0 {
            return Err(Error::Usage(format!(
                "EnDat has one encoder (device 0), not device {device}"
            )));
        }
        let limit = (1u64 << self.bits()) - 1;
        if position > limit {
            return Err(Error::Usage(format!(
                "set_position: {position} does not fit the {}-bit encoder; give 0 to {limit}",
                self.bits()
            )));
        }
        self.owned = Some(position);
        self.motion = None;
        self.encoder.set_position(position);
        Ok(())
    }

    fn set_status(&mut self, device: usize, name: &str, value: bool) -> Result<()> {
        if device != 0 {
            return Err(Error::Usage(format!(
                "EnDat has one encoder (device 0), not device {device}"
            )));
        }
        match name {
            "f1" | "error" => self.encoder.set_errors(if value { 0x0001 } else { 0 }),
            "f2" => self.encoder.error2 = Some(value),
            "warning" => {
                self.warning = value;
                self.encoder.set_warnings(if value { 0x0001 } else { 0 });
            }
            "busy" => {
                self.busy = value;
                self.encoder.busy_forced = value;
            }
            other => {
                return Err(Error::Usage(format!(
                "an EnDat encoder has no status `{other}`; give f1 (or error), f2, warning or busy"
            )))
            }
        }
        Ok(())
    }

    fn set_motion(&mut self, device: usize, toml: &str) -> Result<()> {
        if device != 0 {
            return Err(Error::Usage(format!(
                "EnDat has one encoder (device 0), not device {device}"
            )));
        }
        let motion = Motion::from_toml(toml, "set_motion")?;
        self.motion = Some(Running {
            motion,
            since: self.cycle,
        });
        self.owned = None;
        Ok(())
    }

    fn schedule_fault(&mut self, toml: &str) -> Result<()> {
        let tables = config::tables(toml, "fault", "endat")?;
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct T {
            faults: FaultSettings,
        }
        let t: T = config::decode(tables.device, "fault")?;
        self.cfg.faults = t.faults;
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

    fn last_status(&self, device: usize, name: &str) -> Result<bool> {
        let e = self
            .entries
            .last()
            .filter(|_| device == 0)
            .ok_or_else(|| Error::Usage(format!("no EnDat transfer of device {device} yet")))?;
        let sent = |v: Option<bool>, what: &str| {
            v.ok_or_else(|| {
                Error::Usage(format!(
                    "the last EnDat frame (mode {}) carried no {what}",
                    e.mode
                ))
            })
        };
        match name {
            "f1" | "error" => sent(e.f1, "F1"),
            // As the master reads the wire: 1 = no error message 2.
            "f2" => sent(e.f2, "F2"),
            "warning" => Ok(e.warning),
            "busy" => Ok(e.busy),
            other => Err(Error::Usage(format!(
                "an EnDat encoder has no status `{other}`; give f1, f2, warning or busy"
            ))),
        }
    }

    fn transcript(&self) -> serde_json::Value {
        serde_json::json!({
            "protocol": "endat",
            "f_emu_hz": self.f_emu_hz,
            "transfers": self.entries,
            "contention_cycles": self.pair.contention_cycles(),
            "violations": self.checks.all(),
        })
    }

    fn checks(&mut self) -> &mut Checks {
        &mut self.checks
    }
}
