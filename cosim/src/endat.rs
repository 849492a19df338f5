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
//! The master's timing is held to the rule book [`model::endat::rules`]
//! (the monitor holds it to the same, from the same limits: [`rule_config`]):
//! the watcher sees the master's pins and the encoder's level at the
//! master's end as the master's receiver had it, the answer of the cycle
//! before, which is what the monitor beside the master sees. Both drivers on
//! the pair at once is the send-block rule's break, reported by it (the
//! transcript counts the cycles, `contention_cycles`). The emulator expects
//! the clock idle high before the first transfer: until it has seen the
//! clock high, the encoder sees its clock idle, so a master holding reset
//! (its clock at 0) from time 0 starts no transfer.

use serde::{Deserialize, Serialize};

use model::bits;
use model::endat::rules::{self, Limits, Watch};
use model::endat::{
    frame_kind, BenchConfig, Encoder, EncoderSettings, FaultSettings, FrameKind, MasterSettings,
};
use model::line::{CableConfig, DelayLine, Drive};
use model::rules::Unit;

use crate::check::Checks;
use crate::config::{self, Error};
use crate::monitor::{first_given, limit, proto_table};
use crate::motion::{Motion, Running};
use crate::pair::Pair;
use crate::{Emulator, Pins, Result};

/// The fastest EnDat clock the seed's timing table gives with delay
/// compensation (seed 004, 2.3.2: `f_c` up to 8 MHz; 16 MHz with the
/// encoders that support it: set `emulator.max_line_clock_khz`).
pub const MAX_CLOCK_KHZ: f64 = 8000.0;

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

/// The master's timing limits (`[checks]`), by default the seed's
/// ([`model::endat::rules`]): each may be set within the seed's range only.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EndatChecks {
    /// Time between a type 2.1 transfer's last clock edge and the next transfer, µs, exclusive
    /// (`t_b`, seed: more than 1000).
    pub t_b_us: f64,
    /// Fastest clock with delay compensation, kHz: no clock phase within a transfer shorter than
    /// `1 / (2 f_c)` (`f_c`, seed: 8000, 16000 for special applications).
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

/// The limits' own table (`[monitor]`), every field optional: a monitor's
/// settings, read by the emulator too, so that both hold the master to the
/// same limits.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct MonitorTable {
    pos_bits: Option<u32>,
    delay_comp: Option<bool>,
    max_clock_khz: Option<f64>,
    min_clock_khz: Option<f64>,
    on_off_percent: Option<f64>,
    t_st_us: Option<f64>,
    t_m_us: Option<f64>,
    t_m21_us: Option<f64>,
    t_r_us: Option<f64>,
    round_trip_ns: Option<f64>,
    t_err_us: Option<f64>,
    t_b_us: Option<f64>,
    meas_clock_khz: Option<f64>,
    meas_frame_below_khz: Option<f64>,
    meas_frames_min: Option<u32>,
}

/// The rule limits of a configuration and what a decoder of the line needs.
#[derive(Debug, Clone)]
pub struct RuleConfig {
    /// The limits in force.
    pub limits: Limits,
    /// Position bits (`monitor.pos_bits`, else the encoder's), not checked.
    pub pos_bits: u32,
    /// The master's measuring clock, kHz (`monitor.meas_clock_khz`, else `master.meas_clock_khz`).
    pub meas_clock_khz: f64,
}

/// The rule limits a configuration sets (a whole scenario file will do):
/// `[monitor]` first, then `[checks]`, `[master]` (`delay_comp`,
/// `meas_clock_khz`), `[encoder]` (`t_m_us`, `t_m21_us`, `recovery_short`,
/// `output_delay_ns`) and `[cable]`; every bound the seed states refused
/// outside the seed's range, naming the field.
pub fn rule_config(text: &str, origin: &str) -> Result<RuleConfig> {
    let whole = proto_table(text, origin, "endat")?;
    let checks: EndatChecks = config::decode_in(&whole, "checks", origin)?;
    let encoder: EncoderSettings = config::decode_in(&whole, "encoder", origin)?;
    let master: MasterSettings = config::decode_in(&whole, "master", origin)?;
    let cable: CableConfig = config::decode_in(&whole, "cable", origin)?;
    let mon: MonitorTable = config::decode_in(&whole, "monitor", origin)?;
    let cfg = |e| Error::config(origin, e);
    let short = encoder.recovery_short;
    let (t_m22, t_m22_field) = first_given(
        [
            ("monitor.t_m_us", mon.t_m_us),
            ("encoder.t_m_us", encoder.t_m_us),
        ],
        if short { 2.0 } else { 15.0 },
    );
    let t_m22 = limit(origin, t_m22_field, t_m22, "give the encoder's recovery time I of type 2.2 frames in µs (seed: 10 to 30, or 1.25 to 3.75)")?;
    let (t_m21, t_m21_field) = first_given(
        [
            ("monitor.t_m21_us", mon.t_m21_us),
            ("encoder.t_m21_us", Some(encoder.t_m21_us)),
        ],
        0.0,
    );
    let t_m21 = limit(
        origin,
        t_m21_field,
        t_m21,
        "give the encoder's recovery time I of type 2.1 frames in µs (seed: 10 to 30)",
    )?;
    let round_trip = mon
        .round_trip_ns
        .unwrap_or(2.0 * cable.length_m * cable.ns_per_m + encoder.output_delay_ns);
    let round_trip = limit(
        origin,
        "monitor.round_trip_ns",
        round_trip,
        "give the round trip (cable both ways and the encoder's output delay) in ns",
    )?;
    let delay_comp = mon.delay_comp.unwrap_or(master.delay_comp);
    let mut l = Limits::seed(delay_comp, t_m22, t_m21, round_trip);
    // The fastest clock: `[checks]` holds the one with delay compensation.
    let max = first_given(
        [
            ("monitor.max_clock_khz", mon.max_clock_khz),
            (
                "checks.max_clock_khz",
                delay_comp.then_some(checks.max_clock_khz),
            ),
        ],
        l.max_clock_khz,
    );
    l.set_max_clock(max.1, max.0).map_err(cfg)?;
    if let Some(khz) = mon.min_clock_khz {
        let khz = rules::F_C_MIN
            .setting("monitor.min_clock_khz", khz)
            .map_err(cfg)?;
        if khz > l.max_clock_khz {
            return Err(Error::field(
                origin,
                "monitor.min_clock_khz",
                format!("{khz} kHz above the fastest clock, {} kHz", l.max_clock_khz),
                "give min_clock_khz <= max_clock_khz (seed: 100 kHz, and 2000 without or 8000 with delay compensation)",
            ));
        }
        l.period_max = Unit::KHz.ps(khz);
    }
    if let Some(v) = mon.on_off_percent {
        l.on_off = rules::ON_OFF
            .setting("monitor.on_off_percent", v)
            .map_err(cfg)?
            / 100.0;
    }
    if let Some(v) = mon.t_st_us {
        l.t_st = Some(Unit::Us.ps(rules::T_ST.setting("monitor.t_st_us", v).map_err(cfg)?));
    }
    if let Some(v) = mon.t_r_us {
        l.t_r = Unit::Us.ps(rules::T_R.setting("monitor.t_r_us", v).map_err(cfg)?);
    }
    if let Some(v) = mon.t_err_us {
        l.t_err = Unit::Us.ps(rules::T_ERR.setting("monitor.t_err_us", v).map_err(cfg)?);
    }
    let t_b = first_given(
        [
            ("monitor.t_b_us", mon.t_b_us),
            ("checks.t_b_us", Some(checks.t_b_us)),
        ],
        checks.t_b_us,
    );
    l.t_b = Unit::Us.ps(rules::T_B.setting(t_b.1, t_b.0).map_err(cfg)?);
    if let Some(v) = mon.meas_frame_below_khz {
        l.meas_below_khz = limit(
            origin,
            "monitor.meas_frame_below_khz",
            v,
            "give the clock below which a 000111 transfer is a delay measurement, kHz",
        )?;
    }
    if let Some(n) = mon.meas_frames_min {
        l.meas_frames_min = rules::MEAS_COUNT
            .setting("monitor.meas_frames_min", n as f64)
            .map_err(cfg)? as u32;
    }
    let meas_clock_khz = mon.meas_clock_khz.unwrap_or(master.meas_clock_khz);
    if !(meas_clock_khz > 0.0 && meas_clock_khz < 1e6) {
        return Err(Error::field(
            origin,
            "monitor.meas_clock_khz",
            format!("{meas_clock_khz} kHz"),
            "give the master's measuring clock in kHz (seed: 100 to 200)",
        ));
    }
    Ok(RuleConfig {
        limits: l,
        pos_bits: mon
            .pos_bits
            .unwrap_or(encoder.singleturn_bits + encoder.multiturn_bits),
        meas_clock_khz,
    })
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
    seen_decodes: u64,
    seen_answer: &'static str,
    watch: Watch,
    /// The pins out of the cycle before: the encoder's level the master's
    /// receiver has now.
    last_out: Pins,
    checks: Checks,
    /// Where the pair records contention: the send-block rule reports it.
    contention: Checks,
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
        let limits = rule_config(text, origin)?.limits;
        let mut checks = Checks::for_clock(&tb);
        for note in model::rules::resolution_notes(f_emu_hz, &limits.least()) {
            checks.note(note);
        }
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
            seen_decodes: 0,
            seen_answer: "ok",
            watch: Watch::new(limits),
            last_out: Pins(1),
            checks,
            contention: Checks::for_clock(&tb),
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
}

impl Emulator for EndatEmulator {
    fn kind(&self) -> &'static str {
        "endat"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let master = Pair::master_drive(pins);
        let seen = self.watch.sample(
            self.tb.ps_at(self.cycle),
            rules::Pins {
                clk: pins.data(),
                d: master.level,
                de: master.enable,
                r: self.last_out.data(),
            },
        );
        for b in &seen.breaches {
            let cycle = (b.at_ps as u128 * self.f_emu_hz as u128
                + model::time::PS_PER_S as u128 / 2)
                / model::time::PS_PER_S as u128;
            self.checks.breach(cycle as u64, b);
        }
        if let Some(m) = &self.motion {
            let p = m.position_on(self.cycle, &self.tb, self.bits());
            self.encoder.set_position(p);
        }
        // Before the clock is seen idle high (a master in reset), the encoder sees it idle.
        let clk = self.clk_line.step(pins.data() || !self.watch.seen_idle());
        let at_encoder = self.pair.step(
            master,
            self.enc_drive,
            self.cycle,
            &mut self.contention,
            rules::SEND_BLOCK.label(),
        );
        let latches = self.encoder.latches;
        self.enc_drive = self.encoder.step(clk, at_encoder);
        let latched = self.encoder.latches != latches;
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
            if let Some(e) = self.entries.last_mut() {
                e.mode = mode;
                e.answer = self.seen_answer;
            }
        }
        self.cycle += 1;
        self.last_out = self.pair.pins_out(self.enc_drive, &self.checks, self.stuck);
        self.last_out
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
            "notes": self.checks.notes(),
        })
    }

    fn checks(&mut self) -> &mut Checks {
        &mut self.checks
    }
}
