//! The core under test (`can_controller`, node `dut`) on a CAN bus with
//! emulated nodes, a script of frames for the core to send, and faults on
//! the receive lines. Implements [`Setup`]/[`Testbench`] for `tbgen`.
//!
//! The transcript has one transaction per frame on the bus as a
//! listen-only receiver at the core's `i_can_rx` pin decodes it (the view
//! sigrok's `can` decoder has of the `can_rx` line), with the core's pulses
//! during that frame.
//!
//! Fast-forward ([`Testbench::quiet_cycles`]): quiet while every receive
//! level holds (no change on its way through the bus's delay lines, no
//! stuck or flip window opening or closing) and every controller only
//! counts its bit clock ([`Controller::quiet`]): in bus idle with nothing
//! to send, sample points read recessive and do nothing; in a frame, up to
//! the next sample point or bit end of any controller on the bus. Only the
//! bit clocks run ([`super::BitClock::skip`]). A skip ends before the next
//! scripted frame, fault window or the run's end. The samples' `tq_cnt`
//! (the core's quantum count) is the one value that runs on through a skip
//! ([`Testbench::counters`]); `tbgen gen` steps every cycle, so the waves
//! show it counting.

use serde::{Deserialize, Serialize};

use super::bus::{Bus, Place};
use super::controller::{Controller, ControllerConfig, In, Out, State};
use super::emulator::{Emulator, NodeSettings, Scripted};
use super::frame::{pack, unpack};
use super::timing::BitTiming;
use crate::ports::Port;
use crate::testbench::{self, Setup, Testbench};
use crate::trace::{Layout, Sample};
use crate::{ConfigError, Ports, Result, Timebase};

/// Bit rate and bit timing (`[can.timing]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TimingSettings {
    /// Nominal bit rate, kbit/s.
    pub bit_rate_kbps: f64,
    /// Time quanta per bit (8 to 25).
    pub tq_per_bit: u32,
    /// Sample point, fraction of the bit (e.g. 0.875).
    pub sample_point: f64,
    /// Synchronisation jump width, quanta.
    pub sjw: u32,
}

impl Default for TimingSettings {
    fn default() -> Self {
        TimingSettings { bit_rate_kbps: 250.0, tq_per_bit: 16, sample_point: 0.875, sjw: 1 }
    }
}

/// The core under test (`[can.dut]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DutSettings {
    /// Position along the cable, metres.
    pub position_m: f64,
    /// Transceiver loop delay, ns.
    pub loop_delay_ns: f64,
    /// Acceptance filter identifier.
    pub filter_id: u32,
    /// Acceptance filter mask (0: accept every frame).
    pub filter_mask: u32,
    /// Standard frames the core sends (`i_tx_start` when `o_tx_busy` is low).
    pub frames: Vec<Scripted>,
}

impl Default for DutSettings {
    fn default() -> Self {
        DutSettings { position_m: 0.0, loop_delay_ns: 150.0, filter_id: 0, filter_mask: 0, frames: Vec::new() }
    }
}

impl DutSettings {
    /// Where the core sits.
    pub fn place(&self) -> Place {
        Place { position_m: self.position_m, loop_delay_ns: self.loop_delay_ns }
    }
}

/// A disturbance of receive lines (`[[can.faults]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fault {
    /// `flip` (the target reads the other level for one bit) or
    /// `stuck_dominant` (every node reads dominant for a while).
    pub kind: FaultKind,
    /// Nodes whose RXD is disturbed (`dut` or node names; empty: all).
    #[serde(default)]
    pub targets: Vec<String>,
    /// Flip: the frame, counted from 0 by SOF at each target.
    #[serde(default)]
    pub frame: u32,
    /// Flip: how many frames in a row.
    #[serde(default = "one")]
    pub count: u32,
    /// Flip: the bit, counted from SOF = 0 on the wire (stuff bits included).
    #[serde(default)]
    pub bit: u32,
    /// Stuck dominant: start, µs.
    #[serde(default)]
    pub at_us: f64,
    /// Stuck dominant: duration, µs.
    #[serde(default)]
    pub width_us: f64,
}

fn one() -> u32 {
    1
}

impl Fault {
    /// Checks `faults` (`faults[k]` in errors): every target one of `names` (`hint` says which).
    pub(crate) fn validate_all(faults: &[Fault], names: &[&str], hint: &str) -> Result<()> {
        for (k, f) in faults.iter().enumerate() {
            for t in &f.targets {
                if !names.contains(&t.as_str()) {
                    return Err(ConfigError::invalid(format!("faults[{k}].targets"), format!("no node `{t}`"), hint));
                }
            }
            if f.kind == FaultKind::StuckDominant && !(f.width_us > 0.0 && f.at_us >= 0.0) {
                return Err(ConfigError::invalid(format!("faults[{k}].width_us"), format!("{}", f.width_us), "give a stuck line a positive width_us and at_us ≥ 0"));
            }
            if f.kind == FaultKind::Flip && (f.bit > 200 || f.count == 0) {
                return Err(ConfigError::invalid(format!("faults[{k}].bit"), format!("bit {} count {}", f.bit, f.count), "give a bit from 0 to 200 and count ≥ 1"));
            }
        }
        Ok(())
    }
}

/// Kinds of [`Fault`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FaultKind {
    /// One bit read inverted at the targets.
    Flip,
    /// The bus reads dominant everywhere.
    StuckDominant,
}

/// Everything a scenario says about a CAN set-up (`[can]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BenchConfig {
    /// System clock, MHz.
    pub f_sys_mhz: f64,
    /// Bit timing.
    pub timing: TimingSettings,
    /// Flops of the core's `i_can_rx` synchroniser (2 or 3).
    pub sync_stages: u32,
    /// Cable propagation delay, ns/m.
    pub ns_per_m: f64,
    /// The core.
    pub dut: DutSettings,
    /// Emulated nodes.
    pub nodes: Vec<NodeSettings>,
    /// Faults.
    pub faults: Vec<Fault>,
    /// Longest run, µs (the run ends earlier once every script is sent and the bus is idle).
    pub max_us: f64,
}

impl Default for BenchConfig {
    fn default() -> Self {
        BenchConfig {
            f_sys_mhz: 40.0,
            timing: TimingSettings::default(),
            sync_stages: 2,
            ns_per_m: 5.0,
            dut: DutSettings::default(),
            nodes: Vec::new(),
            faults: Vec::new(),
            max_us: 100_000.0,
        }
    }
}

impl BenchConfig {
    /// The bit timing in quanta of f_sys cycles.
    pub fn bit_timing(&self) -> Result<BitTiming> {
        let t = &self.timing;
        if !(0.5..0.95).contains(&t.sample_point) {
            return Err(ConfigError::invalid("timing.sample_point", format!("{}", t.sample_point), "give a sample point between 0.5 and 0.95"));
        }
        if !(10.0..=1000.0).contains(&t.bit_rate_kbps) {
            return Err(ConfigError::invalid("timing.bit_rate_kbps", format!("{}", t.bit_rate_kbps), "give 10 to 1000 kbit/s"));
        }
        BitTiming::for_rate(self.timebase()?.f_sys_hz(), t.bit_rate_kbps * 1e3, t.tq_per_bit, t.sample_point, t.sjw)
    }

    /// The core's configuration (the Verilog parameters).
    pub fn controller_config(&self) -> Result<ControllerConfig> {
        let c = ControllerConfig { timing: self.bit_timing()?, sync_stages: self.sync_stages };
        c.validate()?;
        Ok(c)
    }

    fn check(&self) -> Result<()> {
        self.controller_config()?;
        if !(0.0..=50.0).contains(&self.ns_per_m) {
            return Err(ConfigError::invalid("ns_per_m", format!("{}", self.ns_per_m), "give the cable delay in ns/m (5 for twisted pair)"));
        }
        self.dut.place().validate("dut")?;
        for (k, s) in self.dut.frames.iter().enumerate() {
            s.frame().validate(&format!("dut.frames[{k}]"))?;
            if s.ide {
                return Err(ConfigError::invalid(format!("dut.frames[{k}].ide"), "the core sends standard frames only", "send extended frames from an emulated node"));
            }
        }
        if self.dut.filter_id >= 1 << 29 || self.dut.filter_mask >= 1 << 29 {
            return Err(ConfigError::invalid("dut.filter_id", "wider than 29 bits", "give 29-bit filter_id and filter_mask"));
        }
        for (k, n) in self.nodes.iter().enumerate() {
            n.validate(&format!("nodes[{k}]"))?;
            if n.name == "dut" || self.nodes[..k].iter().any(|m| m.name == n.name) {
                return Err(ConfigError::invalid(format!("nodes[{k}].name"), format!("`{}` is taken", n.name), "give each node its own name (not `dut`)"));
            }
        }
        let names: Vec<&str> = std::iter::once("dut").chain(self.nodes.iter().map(|n| n.name.as_str())).collect();
        Fault::validate_all(&self.faults, &names, "name `dut` or a node of [[can.nodes]]")?;
        if !(1.0..=1e7).contains(&self.max_us) {
            return Err(ConfigError::invalid("max_us", format!("{}", self.max_us), "give 1 to 10 000 000 µs"));
        }
        Ok(())
    }
}

impl Setup for BenchConfig {
    type Bench = Bench;
    const CORE: &'static str = "can_controller";
    const TABLE: &'static str = "can";

    fn validate(&self) -> Result<()> {
        self.check()
    }

    fn timebase(&self) -> Result<Timebase> {
        Timebase::from_mhz(self.f_sys_mhz)
    }

    fn verilog_parameters(&self) -> Result<Vec<(&'static str, u64)>> {
        let c = self.controller_config()?;
        let t = c.timing;
        Ok(vec![
            ("BRP", t.brp as u64),
            ("PROP_SEG", t.prop_seg as u64),
            ("PHASE_SEG1", t.phase_seg1 as u64),
            ("PHASE_SEG2", t.phase_seg2 as u64),
            ("SJW", t.sjw as u64),
            ("SYNC_STAGES", c.sync_stages as u64),
        ])
    }

    fn bench(&self) -> Result<Bench> {
        Bench::new(self)
    }
}

/// One outcome at the core: a frame sent (`o_tx_done`), a frame received
/// (`o_rx_valid`) or an error detected (`o_err_*`), with the frame on the
/// bus as a listen-only receiver at the core's `i_can_rx` pin decoded it
/// (the view sigrok's `can` decoder has of the `can_rx` line).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Transaction {
    /// 0-based.
    pub index: usize,
    /// `tx_done`, `rx_valid`, `err_bit`, `err_stuff`, `err_crc`, `err_form` or `err_ack`.
    pub outcome: &'static str,
    /// Cycle the listen-only receiver read the frame's SOF.
    pub sof_cycle: u64,
    /// Cycle of the core's pulse.
    pub cycle: u64,
    /// Arbitration lost during the frame (`o_arb_lost`).
    pub arb_lost: bool,
    /// Overload frames the core saw since the previous outcome.
    pub overloads: u32,
    /// `o_rx_id` of a received frame (only with `rx_valid`).
    pub rx_id: Option<u32>,
    /// The frame reached the end of its CRC sequence at the pin.
    pub complete: bool,
    /// Identifier (as far as received).
    pub id: u32,
    /// Extended frame.
    pub ide: bool,
    /// Remote frame.
    pub rtr: bool,
    /// DLC.
    pub dlc: u8,
    /// Data bytes.
    pub data: Vec<u8>,
    /// CRC sequence as received (when complete).
    pub crc: Option<u16>,
    /// ACK slot dominant (when it passed).
    pub ack: bool,
    /// Errors the listen-only receiver detected during the frame.
    pub errors: Vec<&'static str>,
    /// The core's TEC, REC and error state after the outcome.
    pub tec: u16,
    /// REC.
    pub rec: u16,
    /// 0 active, 1 passive, 2 bus-off.
    pub err_state: u8,
}

/// The frame at the pin as the listen-only receiver sees it.
#[derive(Debug, Clone, Default)]
pub(crate) struct OnBus {
    /// Cycle of its SOF.
    pub(crate) sof_cycle: u64,
    /// It reached its CRC delimiter.
    pub(crate) complete: bool,
    /// What the receiver read of it.
    pub(crate) seen: super::controller::Seen,
    /// The receiver passed its ACK slot.
    pub(crate) ack_passed: bool,
    /// Errors the receiver detected in it.
    pub(crate) errors: Vec<&'static str>,
    /// The core lost arbitration in it (CAN bench only).
    pub(crate) arb_lost: bool,
    /// Begun by a SOF and not yet taken (a default frame is not).
    pub(crate) active: bool,
}

/// The listen-only receiver at a core's pin and the frame it is reading:
/// the transcripts of the CAN and CANopen benches.
pub(crate) struct PinMonitor {
    monitor: Controller,
    /// The frame being read.
    pub(crate) frame: OnBus,
}

impl PinMonitor {
    /// A listen-only receiver of `cc`.
    pub(crate) fn new(cc: ControllerConfig) -> Result<PinMonitor> {
        let mut monitor = Controller::new(cc)?;
        monitor.set_listen_only();
        Ok(PinMonitor { monitor, frame: OnBus::default() })
    }

    /// The receiver.
    pub(crate) fn controller(&self) -> &Controller {
        &self.monitor
    }

    /// Advances `n` cycles of an idle receiver ([`Controller::quiet`]).
    pub(crate) fn skip(&mut self, n: u64) {
        self.monitor.skip(n);
    }

    /// One cycle at `rx` (cycle `cycle`): a SOF begins a new frame (the one
    /// it replaces is returned), the CRC delimiter completes it, the end of
    /// the ACK slot records the acknowledgement, and the receiver's errors
    /// (with `overload`, its overload flags too) go with the frame while it
    /// is active. Returns the receiver's outputs, its state before and after,
    /// and the replaced frame.
    pub(crate) fn step(&mut self, rx: bool, cycle: u64, overload: bool) -> (Out, State, State, Option<OnBus>) {
        let before = self.monitor.state();
        let m = self.monitor.step(&In { i_can_rx: rx, ..In::default() });
        let now = self.monitor.state();
        let mut replaced = None;
        if now == State::Frame && before != State::Frame && self.monitor.pos() <= 1 {
            replaced = Some(std::mem::replace(&mut self.frame, OnBus { sof_cycle: cycle, active: true, ..OnBus::default() }));
        }
        if now == State::CrcDelim && before == State::Frame {
            self.frame.complete = true;
            self.frame.seen = self.monitor.seen();
        }
        if before == State::AckSlot && now != State::AckSlot {
            self.frame.ack_passed = true;
            self.frame.seen.ack = self.monitor.seen().ack;
        }
        for (flag, name) in [(m.o_err_bit, "bit"), (m.o_err_stuff, "stuff"), (m.o_err_crc, "crc"), (m.o_err_form, "form"), (m.o_err_ack, "ack"), (m.o_overload && overload, "overload")] {
            if flag && self.frame.active {
                self.frame.errors.push(name);
            }
        }
        (m, before, now, replaced)
    }
}

impl testbench::Transaction for Transaction {
    fn span(&self) -> (u64, u64) {
        (self.sof_cycle, self.cycle)
    }
}

/// Per-target flip windows driven from SOF detection on the undisturbed line
/// (also the CANopen bench's `[[canopen.faults]]`).
#[derive(Debug, Clone)]
pub(crate) struct Disturber {
    /// (first frame, count, bit)
    flips: Vec<(u32, u32, u32)>,
    recessive_run: u64,
    prev: bool,
    frames: i64,
    sof: u64,
}

impl Disturber {
    /// The flips of `faults` aimed at the node `name` (a fault without targets hits every node).
    pub(crate) fn new(faults: &[Fault], name: &str) -> Disturber {
        Disturber {
            flips: faults.iter().filter(|f| f.kind == FaultKind::Flip && (f.targets.is_empty() || f.targets.iter().any(|t| t == name))).map(|f| (f.frame, f.count, f.bit)).collect(),
            recessive_run: 0,
            prev: true,
            frames: -1,
            sof: 0,
        }
    }

    /// The stuck-dominant windows of `faults`, in cycles [from, to).
    pub(crate) fn stuck_windows(faults: &[Fault], tb: &Timebase) -> Vec<(u64, u64)> {
        faults
            .iter()
            .filter(|f| f.kind == FaultKind::StuckDominant)
            .map(|f| {
                let a = tb.cycles_nearest_ns(f.at_us * 1e3);
                (a, a + tb.cycles_nearest_ns(f.width_us * 1e3).max(1))
            })
            .collect()
    }

    /// The level the target reads at `cycle`, given the undisturbed `level`.
    pub(crate) fn step(&mut self, level: bool, cycle: u64, cpb: u64) -> bool {
        if self.prev && !level && self.recessive_run >= 10 * cpb {
            self.frames += 1;
            self.sof = cycle;
        }
        self.recessive_run = if level { self.recessive_run + 1 } else { 0 };
        self.prev = level;
        if self.frames < 0 {
            return level;
        }
        let k = self.frames as u32;
        let off = cycle - self.sof;
        let flip = self.flips.iter().any(|&(f, n, bit)| k >= f && k < f + n && off / cpb == bit as u64);
        level ^ flip
    }
}

/// Node `j`'s receive level at `cycle` before its flips: the bus, held
/// dominant in a stuck window (`stuck`, [`Disturber::stuck_windows`]).
pub(crate) fn undisturbed_rx(bus: &Bus, stuck: &[(u64, u64)], j: usize, cycle: u64) -> bool {
    bus.rx(j) && !stuck.iter().any(|&(a, b)| (a..b).contains(&cycle))
}

/// Node `j`'s receive level at `cycle` as its `disturber` delivers it, and
/// for how many cycles from `cycle` on it holds while every node keeps its
/// transmit level: until a change on its way through the bus arrives, a
/// stuck window opens or closes, or a flip window does. `None` on an edge
/// the disturber may count as a frame start. (The CAN and CANopen benches'
/// fast-forward.)
pub(crate) fn steady_rx(bus: &Bus, stuck: &[(u64, u64)], disturber: &Disturber, j: usize, cycle: u64, cpb: u64) -> Option<(bool, u64)> {
    let mut q = bus.steady(j);
    for &(a, b) in stuck {
        if cycle < a {
            q = q.min(a - cycle);
        } else if cycle < b {
            q = q.min(b - cycle);
        }
    }
    let (level, flips) = disturber.steady(undisturbed_rx(bus, stuck, j, cycle), cycle, cpb)?;
    Some((level, q.min(flips)))
}

impl Disturber {
    /// The level the target reads at `cycle` from the undisturbed `level`,
    /// and for how many cycles from `cycle` on it keeps reading it while
    /// `level` holds: `None` when `level` is an edge (`step` may count a
    /// frame start on it), else until the next flip window of the frame
    /// being counted opens or closes.
    pub(crate) fn steady(&self, level: bool, cycle: u64, cpb: u64) -> Option<(bool, u64)> {
        if level != self.prev {
            return None;
        }
        let (flip, q) = self.window(cycle, cpb);
        Some((level ^ flip, q))
    }

    /// Whether `cycle` falls in a flip window of the frame being counted,
    /// and how many cycles from `cycle` on that stays so: until the window
    /// it is in closes, or the next one opens (`u64::MAX` when none is
    /// ahead).
    fn window(&self, cycle: u64, cpb: u64) -> (bool, u64) {
        if self.frames < 0 {
            return (false, u64::MAX);
        }
        let k = self.frames as u32;
        let mut flip = false;
        let mut q = u64::MAX;
        for &(_, _, bit) in self.flips.iter().filter(|&&(f, n, _)| k >= f && k < f + n) {
            let (from, to) = (self.sof + bit as u64 * cpb, self.sof + (bit as u64 + 1) * cpb);
            if cycle < from {
                q = q.min(from - cycle);
            } else if cycle < to {
                flip = true;
                q = q.min(to - cycle);
            }
        }
        (flip, q)
    }

    /// Advances `n` cycles of a line held at the undisturbed `level`, at
    /// most [`Disturber::steady`]: what `n` calls of `step` would do.
    pub(crate) fn skip(&mut self, n: u64, level: bool) {
        self.recessive_run = if level { self.recessive_run + n } else { 0 };
        self.prev = level;
    }
}

/// Where the core's `tq_cnt` sits among the decoded signals (the layout in [`Bench::new`]).
const TQ_CNT_COLUMN: usize = 2;

/// The core, emulated nodes and the bus.
pub struct Bench {
    cfg: BenchConfig,
    dut: Controller,
    monitor: PinMonitor,
    nodes: Vec<Emulator>,
    bus: Bus,
    disturbers: Vec<Disturber>,
    stuck: Vec<(u64, u64)>,
    script: Vec<(u64, super::frame::Frame)>,
    next: usize,
    last_out: Out,
    /// The last step gave the core a start pulse (the next sample shows it fall).
    started: bool,
    rx_dut: bool,
    cycle: u64,
    end: Option<u64>,
    max_cycles: u64,
    idle_cycles: u64,
    cpb: u64,
    overloads: u32,
    rx_buf: Vec<bool>,
    tx_buf: Vec<bool>,
    transactions: Vec<Transaction>,
    layout: Layout,
}

impl Bench {
    /// A bench in its reset state.
    pub fn new(cfg: &BenchConfig) -> Result<Self> {
        cfg.check()?;
        let tb = cfg.timebase()?;
        let cc = cfg.controller_config()?;
        let mut places = vec![cfg.dut.place()];
        places.extend(cfg.nodes.iter().map(NodeSettings::place));
        let nodes = cfg.nodes.iter().map(|n| Emulator::new(n, cc, &tb)).collect::<Result<Vec<_>>>()?;
        let names: Vec<&str> = std::iter::once("dut").chain(cfg.nodes.iter().map(|n| n.name.as_str())).collect();
        let disturbers = names.iter().map(|name| Disturber::new(&cfg.faults, name)).collect();
        let stuck = Disturber::stuck_windows(&cfg.faults, &tb);
        let layout = Layout {
            inputs: Controller::input_ports(),
            outputs: Controller::output_ports(),
            line: vec![Port::new("can_rx", 1), Port::new("can_tx", 1), Port::new("bus_tx_nodes", 1)],
            decoded: vec![Port::new("state", 4), Port::new("pos", 7), Port::new("tq_cnt", 5), Port::new("monitor_state", 4)],
        };
        Ok(Bench {
            dut: Controller::new(cc)?,
            monitor: PinMonitor::new(cc)?,
            nodes,
            bus: Bus::new(&places, cfg.ns_per_m, &tb),
            disturbers,
            stuck,
            script: cfg.dut.frames.iter().map(|s| (tb.cycles_nearest_ns(s.at_us * 1e3), s.frame())).collect(),
            next: 0,
            last_out: Out::default(),
            started: false,
            rx_dut: true,
            cycle: 0,
            end: None,
            max_cycles: tb.cycles_nearest_ns(cfg.max_us * 1e3),
            idle_cycles: 0,
            cpb: cc.timing.clocks_per_bit(),
            overloads: 0,
            rx_buf: Vec::new(),
            tx_buf: Vec::new(),
            transactions: Vec::new(),
            layout,
            cfg: cfg.clone(),
        })
    }

    /// The emulated nodes.
    pub fn nodes(&self) -> &[Emulator] {
        &self.nodes
    }

    /// The core's model.
    pub fn dut(&self) -> &Controller {
        &self.dut
    }

    fn rx_at(&mut self, j: usize) -> bool {
        let level = self.undisturbed_rx(j);
        self.disturbers[j].step(level, self.cycle, self.cpb)
    }

    /// Nothing left to send and the core idle: `step` counts such cycles
    /// towards the end of the run.
    fn all_done(&self) -> bool {
        self.next == self.script.len() && !self.last_out.o_tx_busy && self.nodes.iter().all(Emulator::done) && self.dut.state() == State::Idle
    }

    /// Cycles from this one to the one whose step decides the end of the
    /// run (two idle bits, or `max_us`), while nothing changes: the end is
    /// then one bit later.
    fn cycles_to_end_decision(&self) -> u64 {
        let by_idle = if self.all_done() { (2 * self.cpb).saturating_sub(self.idle_cycles).max(1) } else { u64::MAX };
        by_idle.min(self.max_cycles.saturating_sub(self.cycle).max(1))
    }

    fn undisturbed_rx(&self, j: usize) -> bool {
        undisturbed_rx(&self.bus, &self.stuck, j, self.cycle)
    }

    fn steady_rx(&self, j: usize) -> Option<(bool, u64)> {
        steady_rx(&self.bus, &self.stuck, &self.disturbers[j], j, self.cycle, self.cpb)
    }

    fn outcome(&mut self, outcome: &'static str, out: &Out) {
        let f = &self.monitor.frame;
        let n = super::frame::data_len(f.seen.dlc, f.seen.rtr);
        self.transactions.push(Transaction {
            index: self.transactions.len(),
            outcome,
            sof_cycle: f.sof_cycle,
            cycle: self.cycle,
            arb_lost: f.arb_lost,
            overloads: self.overloads,
            rx_id: out.o_rx_valid.then_some(out.o_rx_id),
            complete: f.complete,
            id: f.seen.id,
            ide: f.seen.ide,
            rtr: f.seen.rtr,
            dlc: f.seen.dlc,
            data: if f.complete { unpack(f.seen.data, n) } else { Vec::new() },
            crc: f.complete.then_some(f.seen.crc),
            ack: f.ack_passed && f.seen.ack,
            errors: f.errors.clone(),
            tec: out.o_tec,
            rec: out.o_rec,
            err_state: out.o_err_state,
        });
        self.overloads = 0;
    }
}

impl Testbench for Bench {
    crate::compiled_here!();

    type Transaction = Transaction;

    fn layout(&self) -> &Layout {
        &self.layout
    }

    fn step(&mut self, sample: Option<&mut Sample>) {
        let mut rx = std::mem::take(&mut self.rx_buf);
        rx.clear();
        for j in 0..=self.nodes.len() {
            let level = self.rx_at(j);
            rx.push(level);
        }
        let mut input = In { i_can_rx: rx[0], i_filter_id: self.cfg.dut.filter_id, i_filter_mask: self.cfg.dut.filter_mask, ..In::default() };
        if let Some((at, f)) = self.script.get(self.next) {
            if self.cycle >= *at && !self.last_out.o_tx_busy {
                input.i_tx_start = true;
                input.i_tx_id = f.id as u16;
                input.i_tx_rtr = f.rtr;
                input.i_tx_dlc = f.dlc;
                input.i_tx_data = pack(&f.data);
                self.next += 1;
            }
        }
        let out = self.dut.step(&input);
        self.started = input.i_tx_start;
        let mut tx = std::mem::take(&mut self.tx_buf);
        tx.clear();
        tx.push(out.o_can_tx);
        for (k, n) in self.nodes.iter_mut().enumerate() {
            tx.push(n.step(rx[k + 1]));
        }
        let nodes_tx = tx[1..].iter().all(|&t| t);
        self.bus.push(&tx);
        self.tx_buf = tx;
        // The listen-only receiver at the core's pin.
        self.monitor.step(rx[0], self.cycle, true);
        self.monitor.frame.arb_lost |= out.o_arb_lost;
        self.overloads += out.o_overload as u32;
        for (flag, name) in [
            (out.o_tx_done, "tx_done"),
            (out.o_rx_valid, "rx_valid"),
            (out.o_err_bit, "err_bit"),
            (out.o_err_stuff, "err_stuff"),
            (out.o_err_crc, "err_crc"),
            (out.o_err_form, "err_form"),
            (out.o_err_ack, "err_ack"),
        ] {
            if flag {
                self.outcome(name, &out);
            }
        }
        self.rx_dut = rx[0];
        let rx0 = rx[0];
        self.rx_buf = rx;
        self.last_out = out;
        self.cycle += 1;
        let quiet = self.next == self.script.len() && !out.o_tx_busy && self.nodes.iter().all(Emulator::done) && self.dut.state() == State::Idle;
        self.idle_cycles = if quiet { self.idle_cycles + 1 } else { 0 };
        if self.end.is_none() && (self.idle_cycles >= 2 * self.cpb || self.cycle >= self.max_cycles) {
            self.end = Some(self.cycle + self.cpb);
        }
        let Some(sample) = sample else { return };
        input.write_values(&mut sample.inputs);
        out.write_values(&mut sample.outputs);
        sample.line.copy_from_slice(&[rx0 as u64, out.o_can_tx as u64, nodes_tx as u64]);
        sample.decoded.copy_from_slice(&[self.dut.state() as u64, self.dut.pos() as u64 & 0x7F, self.dut.clock().tq_cnt as u64, self.monitor.controller().state() as u64]);
    }

    /// Quiet while no line and no controller can change: each node's
    /// receive level (the bus through its delay lines, the stuck windows
    /// and its flip windows) holds ([`Bus::steady`], [`Disturber::steady`]),
    /// and the core, the listen-only monitor and every node only count
    /// their bit clocks ([`Controller::quiet`], [`Emulator::quiet`]): in
    /// bus idle for as long as that lasts, in a frame up to the next sample
    /// point or bit end of any of them. No scripted frame, flip or stuck
    /// window ahead before then, the core's last input no start pulse and
    /// its receive level the one the last sample shows. The core's `tq_cnt`
    /// counts on through it ([`Testbench::counters`]; see the module docs).
    fn quiet_cycles(&self) -> u64 {
        let c = self.cycle;
        // Cycle 0 has no sample before it to repeat.
        if c == 0 || self.started {
            return 0;
        }
        let mut q = u64::MAX;
        let Some((rx, steady)) = self.steady_rx(0) else { return 0 };
        if rx != self.rx_dut {
            return 0;
        }
        q = q.min(steady).min(self.dut.quiet(rx)).min(self.monitor.controller().quiet(rx));
        for (k, node) in self.nodes.iter().enumerate() {
            if q == 0 {
                return 0;
            }
            let Some((rx, steady)) = self.steady_rx(k + 1) else { return 0 };
            q = q.min(steady).min(node.quiet(rx));
        }
        q = match self.end {
            Some(e) => q.min(e - c),
            // No further than where `skip` decides the end (as `step` would).
            None => q.min(self.cycles_to_end_decision()),
        };
        match self.script.get(self.next) {
            // One already due waits for the core's buffer, which frees only on a sample point.
            Some((at, _)) if *at <= c && self.last_out.o_tx_busy => {}
            Some((at, _)) => q = q.min(at.saturating_sub(c)),
            None => {}
        }
        q
    }

    fn skip(&mut self, n: u64) {
        if n == 0 {
            return;
        }
        for j in 0..self.disturbers.len() {
            let level = self.undisturbed_rx(j);
            self.disturbers[j].skip(n, level);
        }
        self.dut.skip(n);
        self.monitor.skip(n);
        for node in &mut self.nodes {
            node.skip(n);
        }
        self.bus.skip(n);
        // The end as `step` decides it, its conditions being the same on every skipped cycle.
        let c = self.cycle;
        if self.end.is_none() {
            let s = self.cycles_to_end_decision();
            if s <= n {
                self.end = Some(c + s + self.cpb);
            }
        }
        self.idle_cycles = if self.all_done() { self.idle_cycles + n } else { 0 };
        self.cycle += n;
    }

    /// The core's `tq_cnt` counts through a quiet stretch.
    fn counters(&self) -> &'static [usize] {
        &[TQ_CNT_COLUMN]
    }

    fn finished(&self) -> bool {
        self.end.is_some_and(|e| self.cycle >= e)
    }

    fn cycle(&self) -> u64 {
        self.cycle
    }

    fn into_transactions(self) -> Vec<Transaction> {
        self.transactions
    }
}
