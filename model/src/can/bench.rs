//! The core under test (`can_controller`, node `dut`) on a CAN bus with
//! emulated nodes, a script of frames for the core to send, and faults on
//! the receive lines. Implements [`Setup`]/[`Testbench`] for `tbgen`.
//!
//! The transcript has one transaction per frame on the bus as a
//! listen-only receiver at the core's `i_can_rx` pin decodes it (the view
//! sigrok's `can` decoder has of the `can_rx` line), with the core's pulses
//! during that frame.
//!
//! Fast-forward ([`Testbench::quiet_cycles`], `docs/timing/can.md`): the
//! bench's parts (the core, the listen-only monitor at its pin, each
//! emulated node, each receive line) have events of their own. A line's
//! level may change when a change on its way through the bus arrives or a
//! stuck or flip window opens or closes; a controller does more than count
//! its bit clock at its sample points, at a bit end that loads a new level,
//! where an edge leaves its synchroniser and while a pulse stands
//! ([`Controller::quiet_crossing`]). A run that records nothing
//! ([`Testbench::run_to_end_compiled`]) steps each part only on its own
//! events ([`Bench::step_due`]) and skips the cycles between the earliest
//! of them, every part left behind catching up when it next steps; a
//! recording run steps every part every cycle. The samples' `tq_cnt` (the
//! core's quantum count) is the one value that runs on through a skip
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
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
        TimingSettings {
            bit_rate_kbps: 250.0,
            tq_per_bit: 16,
            sample_point: 0.875,
            sjw: 1,
        }
    }
}

/// The core under test (`[can.dut]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
        DutSettings {
            position_m: 0.0,
            loop_delay_ns: 150.0,
            filter_id: 0,
            filter_mask: 0,
            frames: Vec::new(),
        }
    }
}

impl DutSettings {
    /// Where the core sits.
    pub fn place(&self) -> Place {
        Place {
            position_m: self.position_m,
            loop_delay_ns: self.loop_delay_ns,
        }
    }
}

/// A disturbance of receive lines (`[[can.faults]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
                    return Err(ConfigError::invalid(
                        format!("faults[{k}].targets"),
                        format!("no node `{t}`"),
                        hint,
                    ));
                }
            }
            if f.kind == FaultKind::StuckDominant && !(f.width_us > 0.0 && f.at_us >= 0.0) {
                return Err(ConfigError::invalid(
                    format!("faults[{k}].width_us"),
                    format!("{}", f.width_us),
                    "give a stuck line a positive width_us and at_us ≥ 0",
                ));
            }
            if f.kind == FaultKind::Flip && (f.bit > 200 || f.count == 0) {
                return Err(ConfigError::invalid(
                    format!("faults[{k}].bit"),
                    format!("bit {} count {}", f.bit, f.count),
                    "give a bit from 0 to 200 and count ≥ 1",
                ));
            }
        }
        Ok(())
    }
}

/// Kinds of [`Fault`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FaultKind {
    /// One bit read inverted at the targets.
    Flip,
    /// The bus reads dominant everywhere.
    StuckDominant,
}

/// Everything a scenario says about a CAN set-up (`[can]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
            return Err(ConfigError::invalid(
                "timing.sample_point",
                format!("{}", t.sample_point),
                "give a sample point between 0.5 and 0.95",
            ));
        }
        if !(10.0..=1000.0).contains(&t.bit_rate_kbps) {
            return Err(ConfigError::invalid(
                "timing.bit_rate_kbps",
                format!("{}", t.bit_rate_kbps),
                "give 10 to 1000 kbit/s",
            ));
        }
        BitTiming::for_rate(
            self.timebase()?.f_sys_hz(),
            t.bit_rate_kbps * 1e3,
            t.tq_per_bit,
            t.sample_point,
            t.sjw,
        )
    }

    /// The core's configuration (the Verilog parameters).
    pub fn controller_config(&self) -> Result<ControllerConfig> {
        let c = ControllerConfig {
            timing: self.bit_timing()?,
            sync_stages: self.sync_stages,
        };
        c.validate()?;
        Ok(c)
    }

    fn check(&self) -> Result<()> {
        self.controller_config()?;
        if !(0.0..=50.0).contains(&self.ns_per_m) {
            return Err(ConfigError::invalid(
                "ns_per_m",
                format!("{}", self.ns_per_m),
                "give the cable delay in ns/m (5 for twisted pair)",
            ));
        }
        self.dut.place().validate("dut")?;
        for (k, s) in self.dut.frames.iter().enumerate() {
            s.frame().validate(&format!("dut.frames[{k}]"))?;
            // The emulated nodes' rule (`Node::validate`), for the core's script.
            if !(0.0..1e8).contains(&s.at_us) {
                return Err(ConfigError::invalid(
                    format!("dut.frames[{k}].at_us"),
                    format!("{}", s.at_us),
                    "give a time ≥ 0 µs",
                ));
            }
            if s.ide {
                return Err(ConfigError::invalid(
                    format!("dut.frames[{k}].ide"),
                    "the core sends standard frames only",
                    "send extended frames from an emulated node",
                ));
            }
        }
        if self.dut.filter_id >= 1 << 29 || self.dut.filter_mask >= 1 << 29 {
            return Err(ConfigError::invalid(
                "dut.filter_id",
                "wider than 29 bits",
                "give 29-bit filter_id and filter_mask",
            ));
        }
        for (k, n) in self.nodes.iter().enumerate() {
            n.validate(&format!("nodes[{k}]"))?;
            if n.name == "dut" || self.nodes[..k].iter().any(|m| m.name == n.name) {
                return Err(ConfigError::invalid(
                    format!("nodes[{k}].name"),
                    format!("`{}` is taken", n.name),
                    "give each node its own name (not `dut`)",
                ));
            }
        }
        let names: Vec<&str> = std::iter::once("dut")
            .chain(self.nodes.iter().map(|n| n.name.as_str()))
            .collect();
        Fault::validate_all(
            &self.faults,
            &names,
            "name `dut` or a node of [[can.nodes]]",
        )?;
        if !(1.0..=1e7).contains(&self.max_us) {
            return Err(ConfigError::invalid(
                "max_us",
                format!("{}", self.max_us),
                "give 1 to 10 000 000 µs",
            ));
        }
        Ok(())
    }
}

impl Setup for BenchConfig {
    type Bench = Bench;
    const PROTOCOL: &'static crate::protocol::Protocol = &super::descriptor::PROTOCOL;

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
        Ok(PinMonitor {
            monitor,
            frame: OnBus::default(),
        })
    }

    /// The receiver.
    pub(crate) fn controller(&self) -> &Controller {
        &self.monitor
    }

    /// Advances `n` cycles of an idle receiver ([`Controller::quiet`]).
    pub(crate) fn skip(&mut self, n: u64) {
        self.monitor.skip(n);
    }

    /// Advances `n` cycles with `rx` held ([`Controller::skip_crossing`]).
    pub(crate) fn skip_crossing(&mut self, n: u64, rx: bool) {
        self.monitor.skip_crossing(n, rx);
    }

    /// One cycle at `rx` (cycle `cycle`): a SOF begins a new frame (the one
    /// it replaces is returned), the CRC delimiter completes it, the end of
    /// the ACK slot records the acknowledgement, and the receiver's errors
    /// (with `overload`, its overload flags too) go with the frame while it
    /// is active. Returns the receiver's outputs, its state before and after,
    /// and the replaced frame.
    pub(crate) fn step(
        &mut self,
        rx: bool,
        cycle: u64,
        overload: bool,
    ) -> (Out, State, State, Option<OnBus>) {
        let before = self.monitor.state();
        let m = self.monitor.step(&In {
            i_can_rx: rx,
            ..In::default()
        });
        let now = self.monitor.state();
        let mut replaced = None;
        if now == State::Frame && before != State::Frame && self.monitor.pos() <= 1 {
            replaced = Some(std::mem::replace(
                &mut self.frame,
                OnBus {
                    sof_cycle: cycle,
                    active: true,
                    ..OnBus::default()
                },
            ));
        }
        if now == State::CrcDelim && before == State::Frame {
            self.frame.complete = true;
            self.frame.seen = self.monitor.seen();
        }
        if before == State::AckSlot && now != State::AckSlot {
            self.frame.ack_passed = true;
            self.frame.seen.ack = self.monitor.seen().ack;
        }
        for (flag, name) in [
            (m.o_err_bit, "bit"),
            (m.o_err_stuff, "stuff"),
            (m.o_err_crc, "crc"),
            (m.o_err_form, "form"),
            (m.o_err_ack, "ack"),
            (m.o_overload && overload, "overload"),
        ] {
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
            flips: faults
                .iter()
                .filter(|f| {
                    f.kind == FaultKind::Flip
                        && (f.targets.is_empty() || f.targets.iter().any(|t| t == name))
                })
                .map(|f| (f.frame, f.count, f.bit))
                .collect(),
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
                // A fault at or beyond the end of time is one that never comes.
                (
                    a,
                    a.saturating_add(tb.cycles_nearest_ns(f.width_us * 1e3).max(1)),
                )
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
        let flip = self
            .flips
            .iter()
            .any(|&(f, n, bit)| k >= f && k < f + n && off / cpb == bit as u64);
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
pub(crate) fn steady_rx(
    bus: &Bus,
    stuck: &[(u64, u64)],
    disturber: &Disturber,
    j: usize,
    cycle: u64,
    cpb: u64,
) -> Option<(bool, u64)> {
    let (undisturbed, q) = undisturbed_steady(bus, stuck, j, cycle);
    let (level, flips) = disturber.steady(undisturbed, cycle, cpb)?;
    Some((level, q.min(flips)))
}

/// Node `j`'s receive level at `cycle` before its flips
/// ([`undisturbed_rx`]), and for how many cycles from `cycle` on it holds
/// while every node keeps its transmit level: until a change on its way
/// through the bus arrives, or a stuck window opens or closes.
pub(crate) fn undisturbed_steady(
    bus: &Bus,
    stuck: &[(u64, u64)],
    j: usize,
    cycle: u64,
) -> (bool, u64) {
    let (mut level, mut q) = bus.rx_steady(j);
    for &(a, b) in stuck {
        if cycle < a {
            q = q.min(a - cycle);
        } else if cycle < b {
            q = q.min(b - cycle);
            level = false;
        }
    }
    (level, q)
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
            let (from, to) = (
                self.sof + bit as u64 * cpb,
                self.sof + (bit as u64 + 1) * cpb,
            );
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

    /// Advances `n` cycles of a line that kept the undisturbed level the
    /// last `step` read: a line the CAN bench did not read in them.
    pub(crate) fn hold(&mut self, n: u64) {
        self.skip(n, self.prev);
    }
}

/// Where the core's `tq_cnt` sits among the decoded signals (the layout in [`Bench::new`]).
const TQ_CNT_COLUMN: usize = 2;

/// The parts of the bench that run on their own events, by index: the
/// core, the listen-only monitor at its pin, then the emulated nodes.
const DUT: usize = 0;
/// The monitor's part index.
const MONITOR: usize = 1;
/// Node `k`'s part index is `NODES + k`.
const NODES: usize = 2;

/// The receive line part `p` reads: the core's pin (line 0) for the core
/// and the monitor, node `k`'s RXD (line `k + 1`) for node `k`.
fn line_of(p: usize) -> usize {
    p.saturating_sub(1)
}

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
    cycle: u64,
    end: Option<u64>,
    max_cycles: u64,
    idle_cycles: u64,
    cpb: u64,
    overloads: u32,
    /// Per line, the level it had on the cycle it was last read.
    rx: Vec<bool>,
    /// Per node (the core first), the TXD level it last sent.
    tx: Vec<bool>,
    /// Per part, the next cycle it has yet to run (see [`Bench::quiet_cycles`]).
    part_at: Vec<u64>,
    /// Per part, the first cycle it must be stepped on while its line holds
    /// `part_rx`.
    part_due: Vec<u64>,
    /// Per part, the level of its line its due cycle was reckoned with.
    part_rx: Vec<bool>,
    /// Per line, the next cycle its disturber has yet to run.
    line_at: Vec<u64>,
    /// Per line, the first cycle its level may change.
    line_due: Vec<u64>,
    /// Per line, that level before its flips (until `line_due`).
    line_level: Vec<bool>,
    /// Per part, stepped by the step under way (kept to save allocating).
    part_runs: Vec<bool>,
    /// Per line, read by the step under way (likewise).
    line_read: Vec<bool>,
    /// The earliest of `part_due` and `line_due`.
    next_event: u64,
    /// `part_due`, `line_due` and `next_event` are reckoned for this cycle
    /// (after a step of every part they are not until asked).
    scheduled: bool,
    /// The transmitters whose level the step under way changes (likewise).
    tx_changed: Vec<usize>,
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
        let nodes = cfg
            .nodes
            .iter()
            .map(|n| Emulator::new(n, cc, &tb))
            .collect::<Result<Vec<_>>>()?;
        let names: Vec<&str> = std::iter::once("dut")
            .chain(cfg.nodes.iter().map(|n| n.name.as_str()))
            .collect();
        let disturbers = names
            .iter()
            .map(|name| Disturber::new(&cfg.faults, name))
            .collect();
        let stuck = Disturber::stuck_windows(&cfg.faults, &tb);
        let layout = Layout {
            inputs: Controller::input_ports(),
            outputs: Controller::output_ports(),
            line: vec![
                Port::new("can_rx", 1),
                Port::new("can_tx", 1),
                Port::new("bus_tx_nodes", 1),
            ],
            decoded: vec![
                Port::new("state", 4),
                Port::new("pos", 7),
                Port::new("tq_cnt", 5),
                Port::new("monitor_state", 4),
            ],
        };
        let (lines, parts) = (cfg.nodes.len() + 1, cfg.nodes.len() + NODES);
        Ok(Bench {
            dut: Controller::new(cc)?,
            monitor: PinMonitor::new(cc)?,
            nodes,
            bus: Bus::new(&places, cfg.ns_per_m, &tb),
            disturbers,
            stuck,
            script: cfg
                .dut
                .frames
                .iter()
                .map(|s| (tb.cycles_nearest_ns(s.at_us * 1e3), s.frame()))
                .collect(),
            next: 0,
            last_out: Out::default(),
            started: false,
            cycle: 0,
            end: None,
            max_cycles: tb.cycles_nearest_ns(cfg.max_us * 1e3),
            idle_cycles: 0,
            cpb: cc.timing.clocks_per_bit(),
            overloads: 0,
            rx: vec![true; lines],
            tx: vec![true; lines],
            part_at: vec![0; parts],
            part_due: vec![0; parts],
            part_rx: vec![true; parts],
            line_at: vec![0; lines],
            line_due: vec![0; lines],
            line_level: vec![true; lines],
            part_runs: vec![false; parts],
            line_read: vec![false; lines],
            next_event: 0,
            scheduled: true,
            tx_changed: Vec::new(),
            transactions: Vec::new(),
            layout,
            cfg: cfg.clone(),
        })
    }

    /// The emulated nodes, each as of its last event (see [`Bench::catch_up`]).
    pub fn nodes(&self) -> &[Emulator] {
        &self.nodes
    }

    /// The core's model, as of its last event (see [`Bench::catch_up`]).
    pub fn dut(&self) -> &Controller {
        &self.dut
    }

    /// The listen-only receiver at the core's pin, as of its last event.
    pub fn monitor(&self) -> &Controller {
        self.monitor.controller()
    }

    /// Brings every part to the current cycle. A fast-forwarded run
    /// ([`Testbench::quiet_cycles`]) steps each part only on its own events
    /// and leaves it behind in between, where it would only have counted
    /// its bit clock; this counts those clocks up, as stepping would have.
    pub fn catch_up(&mut self) {
        for p in 0..self.part_at.len() {
            self.catch_up_part(p);
        }
        for j in 0..self.line_at.len() {
            self.disturbers[j].hold(self.cycle - self.line_at[j]);
            self.line_at[j] = self.cycle;
        }
        self.bus.skip(self.cycle - self.bus.cycle());
    }

    /// Part `p` counts up the cycles since it last ran, its line having
    /// held the level its due cycle was reckoned with (`part_rx`).
    #[inline]
    fn catch_up_part(&mut self, p: usize) {
        if self.part_at[p] != self.cycle {
            self.catch_up_part_from(p);
        }
    }

    fn catch_up_part_from(&mut self, p: usize) {
        let (n, rx) = (self.cycle - self.part_at[p], self.part_rx[p]);
        match p {
            DUT => self.dut.skip_crossing(n, rx),
            MONITOR => self.monitor.skip_crossing(n, rx),
            _ => self.nodes[p - NODES].skip_crossing(n, rx),
        }
        self.part_at[p] = self.cycle;
    }

    /// Reads line `j` this cycle: its disturber counts up the cycles since
    /// it last ran, then steps on the line's level now.
    fn read_line(&mut self, j: usize) -> bool {
        let c = self.cycle;
        if self.line_at[j] != c {
            self.disturbers[j].hold(c - self.line_at[j]);
        }
        self.line_at[j] = c + 1;
        // Before its next event (reckoned: not after steps of every part)
        // the line keeps the level it had.
        let level = if self.scheduled && c < self.line_due[j] {
            self.line_level[j]
        } else {
            undisturbed_rx(&self.bus, &self.stuck, j, c)
        };
        self.rx[j] = self.disturbers[j].step(level, c, self.cpb);
        self.rx[j]
    }

    /// Nothing left to send and the core idle: `step` counts such cycles
    /// towards the end of the run.
    fn all_done(&self) -> bool {
        self.next == self.script.len()
            && !self.last_out.o_tx_busy
            && self.nodes.iter().all(Emulator::done)
            && self.dut.state() == State::Idle
    }

    /// Cycles from this one to the one whose step decides the end of the
    /// run (two idle bits, or `max_us`), while nothing changes: the end is
    /// then one bit later.
    fn cycles_to_end_decision(&self) -> u64 {
        let by_idle = if self.all_done() {
            (2 * self.cpb).saturating_sub(self.idle_cycles).max(1)
        } else {
            u64::MAX
        };
        by_idle.min(self.max_cycles.saturating_sub(self.cycle).max(1))
    }

    /// Part `p`'s first cycle to be stepped on, counted from this one,
    /// given its line's level `rx` from now on
    /// ([`Controller::quiet_crossing`], [`Emulator::quiet_crossing`]); for
    /// the core also its start pulse falling and its next scripted frame.
    fn part_quiet(&self, p: usize, rx: bool) -> u64 {
        match p {
            DUT => {
                if self.started {
                    return 0;
                }
                let q = self.dut.quiet_crossing(rx);
                match self.script.get(self.next) {
                    // One already due waits for the core's buffer, which frees only on a sample point.
                    Some((at, _)) if !self.last_out.o_tx_busy => {
                        q.min(at.saturating_sub(self.cycle))
                    }
                    _ => q,
                }
            }
            MONITOR => self.monitor.controller().quiet_crossing(rx),
            _ => self.nodes[p - NODES].quiet_crossing(rx),
        }
    }

    /// After a step, the next events of what it touched: each line read
    /// (`read`) holds from the next cycle on for as long as
    /// [`undisturbed_steady`] and [`Disturber::steady`] say, if it keeps
    /// the level it had, else it is read again then; a change sent this
    /// cycle (`changed`, by transmitter) may reach each line after that
    /// pair's delay; each part stepped is due at its next event, its line
    /// holding the level it just read.
    fn schedule(&mut self, read: &[bool], changed: &[usize]) {
        let next = self.cycle;
        for (j, _) in read.iter().enumerate().filter(|&(_, &r)| r) {
            (self.line_level[j], self.line_due[j]) = self.line_event(j);
        }
        for &i in changed {
            for (j, due) in self.line_due.iter_mut().enumerate() {
                *due = (*due).min(next - 1 + self.bus.delay(i, j) as u64);
            }
        }
        for p in 0..self.part_at.len() {
            if self.part_at[p] == next {
                self.part_rx[p] = self.rx[line_of(p)];
                self.part_due[p] = self.part_event(p);
            }
        }
        self.next_event = self
            .part_due
            .iter()
            .chain(&self.line_due)
            .copied()
            .min()
            .unwrap_or(next);
        self.scheduled = true;
    }

    /// Line `j`, read on the cycle before this one: its level before its
    /// flips from this cycle on, and the first cycle from this one its
    /// level may differ from the one it was read at.
    fn line_event(&self, j: usize) -> (bool, u64) {
        let next = self.cycle;
        let (undisturbed, steady) = undisturbed_steady(&self.bus, &self.stuck, j, next);
        let due = match self.disturbers[j].steady(undisturbed, next, self.cpb) {
            Some((level, q)) if level == self.rx[j] => next.saturating_add(q.min(steady)),
            _ => next,
        };
        (undisturbed, due)
    }

    /// Part `p`, stepped on the cycle before this one (or caught up to
    /// this one): the first cycle of its next event while its line holds
    /// the level it last read.
    fn part_event(&self, p: usize) -> u64 {
        self.cycle
            .saturating_add(self.part_quiet(p, self.rx[line_of(p)]))
    }

    /// After steps of every part (which leave the next events unreckoned:
    /// recording runs never ask), reckons them all.
    fn reschedule(&mut self) {
        if !self.scheduled {
            let mut read = std::mem::take(&mut self.line_read);
            read.fill(true);
            self.schedule(&read, &[]);
            self.line_read = read;
        }
    }

    /// One cycle of a run that records nothing, in which only the parts
    /// whose event this cycle is step ([`Bench::quiet_cycles`]), each
    /// first counting up the cycles it was left behind: what `step(None)`
    /// does, but for the state of the parts left behind (their bit
    /// clocks and synchronisers, until they next step or
    /// [`Bench::catch_up`]). [`Testbench::run_to_end_compiled`] runs on it.
    pub fn step_due(&mut self) {
        self.reschedule();
        self.advance(false, None);
    }

    /// Reads this cycle's lines and says which parts step (`read`, `runs`:
    /// per line, per part). With `all`, every one. Otherwise the lines
    /// whose level may change and those of the parts due; a part whose
    /// line now reads another level than the one its due cycle was
    /// reckoned with is reckoned again (the level may only be entering its
    /// synchroniser); then the parts due step.
    fn read_lines(&mut self, all: bool, read: &mut [bool], runs: &mut [bool]) {
        let c = self.cycle;
        if all {
            read.fill(true);
            runs.fill(true);
            for j in 0..read.len() {
                self.read_line(j);
            }
            return;
        }
        for (j, r) in read.iter_mut().enumerate() {
            let parts_due = if j == 0 {
                self.part_due[DUT].min(self.part_due[MONITOR])
            } else {
                self.part_due[NODES + j - 1]
            };
            *r = c >= self.line_due[j].min(parts_due);
        }
        for (p, r) in runs.iter_mut().enumerate() {
            let j = line_of(p);
            if read[j] && (p == DUT || p >= NODES) {
                self.read_line(j);
            }
            if read[j] && self.part_due[p] > c && self.rx[j] != self.part_rx[p] {
                self.catch_up_part(p);
                self.part_rx[p] = self.rx[j];
                self.part_due[p] = self.part_event(p);
            }
            *r = c >= self.part_due[p];
        }
    }

    /// One cycle: every part stepped (`all`), or only those due.
    fn advance(&mut self, all: bool, sample: Option<&mut Sample>) {
        let c = self.cycle;
        if self.bus.cycle() != c {
            self.bus.skip(c - self.bus.cycle());
        }
        let mut read = std::mem::take(&mut self.line_read);
        let mut runs = std::mem::take(&mut self.part_runs);
        self.read_lines(all, &mut read, &mut runs);
        let rx0 = self.rx[0];
        let mut input = In {
            i_can_rx: rx0,
            i_filter_id: self.cfg.dut.filter_id,
            i_filter_mask: self.cfg.dut.filter_mask,
            ..In::default()
        };
        let out = if runs[DUT] {
            self.catch_up_part(DUT);
            if let Some((at, f)) = self.script.get(self.next) {
                if c >= *at && !self.last_out.o_tx_busy {
                    input.i_tx_start = true;
                    input.i_tx_id = f.id as u16;
                    input.i_tx_rtr = f.rtr;
                    input.i_tx_dlc = f.dlc;
                    input.i_tx_data = pack(&f.data);
                    self.next += 1;
                }
            }
            self.part_at[DUT] = c + 1;
            self.dut.step(&input)
        } else {
            // A core left behind only counts its bit clock: no pulse, the same outputs.
            self.last_out
        };
        self.started = input.i_tx_start;
        // The transmitters whose level changes this cycle (0: the core, k + 1: node k).
        let mut changed = std::mem::take(&mut self.tx_changed);
        changed.clear();
        if out.o_can_tx != self.tx[0] {
            changed.push(0);
        }
        self.tx[0] = out.o_can_tx;
        for k in 0..self.nodes.len() {
            if runs[NODES + k] {
                self.catch_up_part(NODES + k);
                self.part_at[NODES + k] = c + 1;
                let t = self.nodes[k].step(self.rx[k + 1]);
                if t != self.tx[k + 1] {
                    changed.push(k + 1);
                }
                self.tx[k + 1] = t;
            }
        }
        let nodes_tx = self.tx[1..].iter().all(|&t| t);
        self.bus.push(&self.tx);
        // The listen-only receiver at the core's pin.
        if runs[MONITOR] {
            self.catch_up_part(MONITOR);
            self.part_at[MONITOR] = c + 1;
            self.monitor.step(rx0, c, true);
        }
        self.monitor.frame.arb_lost |= out.o_arb_lost;
        self.overloads += out.o_overload as u32;
        if out.o_tx_done
            || out.o_rx_valid
            || out.o_err_bit
            || out.o_err_stuff
            || out.o_err_crc
            || out.o_err_form
            || out.o_err_ack
        {
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
        }
        self.last_out = out;
        self.cycle += 1;
        let quiet = self.next == self.script.len()
            && !out.o_tx_busy
            && self.nodes.iter().all(Emulator::done)
            && self.dut.state() == State::Idle;
        self.idle_cycles = if quiet { self.idle_cycles + 1 } else { 0 };
        if self.end.is_none() && (self.idle_cycles >= 2 * self.cpb || self.cycle >= self.max_cycles)
        {
            self.end = Some(self.cycle + self.cpb);
        }
        if all {
            // Every part stepped and every line read: reckoned when asked.
            self.scheduled = false;
        } else {
            self.schedule(&read, &changed);
        }
        self.part_runs = runs;
        self.line_read = read;
        self.tx_changed = changed;
        let Some(sample) = sample else { return };
        input.write_values(&mut sample.inputs);
        out.write_values(&mut sample.outputs);
        sample
            .line
            .copy_from_slice(&[rx0 as u64, out.o_can_tx as u64, nodes_tx as u64]);
        sample.decoded.copy_from_slice(&[
            self.dut.state() as u64,
            self.dut.pos() as u64 & 0x7F,
            self.dut.clock().tq_cnt as u64,
            self.monitor.controller().state() as u64,
        ]);
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
            data: if f.complete {
                unpack(f.seen.data, n)
            } else {
                Vec::new()
            },
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
    /// [`run_to_end`](crate::testbench::run_to_end) with
    /// [`Bench::step_due`] for its steps.
    fn run_to_end_compiled(self) -> crate::testbench::Run<Transaction> {
        let mut bench = self;
        while !bench.finished() {
            match bench.quiet_cycles() {
                0 => bench.step_due(),
                n => bench.skip(n),
            }
        }
        crate::testbench::Run {
            cycles: bench.cycle,
            transactions: bench.transactions,
        }
    }
    fn run_every_cycle_compiled(self) -> crate::testbench::Run<Transaction> {
        crate::testbench::run_every_cycle(self)
    }
    fn lockstep_compiled(
        self,
        name: &str,
        stepped: Self,
    ) -> crate::testbench::Lockstep<Transaction> {
        crate::testbench::lockstep(name, self, stepped)
    }

    type Transaction = Transaction;

    fn layout(&self) -> &Layout {
        &self.layout
    }

    /// One cycle, every part stepped ([`Bench::step_due`] steps only the
    /// parts whose event it is).
    fn step(&mut self, sample: Option<&mut Sample>) {
        self.advance(true, sample);
    }

    /// Quiet up to the earliest next event of any part (and where `step`
    /// decides the run's end). Each part keeps the first cycle of its
    /// next event: the core, the monitor and each node when they would do
    /// more than count their bit clocks ([`Controller::quiet_crossing`],
    /// [`Emulator::quiet_crossing`]: a sample point, a bit end that loads a
    /// new level, a pulse ending, an edge leaving the synchroniser, a
    /// scripted frame, the core's start pulse falling), reckoned with the
    /// level their line had when they last stepped; each line when its
    /// level may change (a change on its way through the bus's delay lines
    /// arriving, a stuck or flip window opening or closing:
    /// [`Bus::rx_steady`], `Disturber::steady`). After a step, the parts
    /// it stepped and the lines it read are reckoned again. The core's
    /// `tq_cnt` counts on through a quiet stretch ([`Testbench::counters`];
    /// see the module docs).
    fn quiet_cycles(&self) -> u64 {
        let c = self.cycle;
        let next_event = if self.scheduled {
            self.next_event
        } else {
            // After a step of every part: each line was read, each part stepped.
            let lines = (0..self.line_due.len()).map(|j| self.line_event(j).1);
            lines
                .chain((0..self.part_due.len()).map(|p| self.part_event(p)))
                .min()
                .unwrap_or(c)
        };
        let due = match self.end {
            Some(e) => next_event.min(e),
            // No further than where `skip` decides the end (as `step` would).
            None => next_event.min(c.saturating_add(self.cycles_to_end_decision())),
        };
        due.saturating_sub(c)
    }

    /// Advances the bench's own count only: every part catches up when it
    /// next steps (or on [`Bench::catch_up`]).
    fn skip(&mut self, n: u64) {
        if n == 0 {
            return;
        }
        self.reschedule();
        // The end as `step` decides it, its conditions being the same on every skipped cycle.
        let c = self.cycle;
        if self.end.is_none() {
            let s = self.cycles_to_end_decision();
            if s <= n {
                self.end = Some(c + s + self.cpb);
            }
        }
        self.idle_cycles = if self.all_done() {
            self.idle_cycles + n
        } else {
            0
        };
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
