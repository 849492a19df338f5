//! The CANopen encoder emulator: the DS 406 encoders of
//! [`model::canopen::EncoderNode`] (the Leine & Linde gateway of seed 003)
//! and the SAR58K24 encoders in their CAN mode ([`model::canopen::sar58k24::SarCan`],
//! seed 001 §3.4) on the wired-AND bus ([`model::can::Bus`]) they share with
//! the master under test.
//!
//! Configuration: the scenario's `[canopen]` table (`bit_rate_kbps`,
//! `tq_per_bit`, `sample_point`, `sjw`, `sync_stages`, `ns_per_m`,
//! `[master]` for the master's place on the cable, `[[encoders]]` with
//! their `[encoders.encoder]`, places, oscillators, power-on and alarm
//! times, `[[sar]]` with their `[sar.encoder]` and places); `f_sys_mhz`, the
//! master's table entries other than its place and `run_us` belong to the
//! master's side. Either kind alone or both on one bus. The service tool
//! node (`[canopen.tool]`) is refused by name: in co-simulation the master
//! under test plays its part. The emulator clock is the nodes' reference clock.
//!
//! Devices are numbered DS 406 encoders first (`[[encoders]]` in order),
//! then the SAR58K24s (`[[sar]]` in order): with one encoder and one
//! SAR58K24 the SAR58K24 is device 1.
//!
//! Pins (`emu_step`): in bit 1 the master's TXD; out bit 0 the bus level at
//! the master's RXD.
//!
//! The master is held to the CAN and CANopen rule books
//! ([`model::can::rules`], [`model::canopen::rules`]) on its TXD and the bus
//! as its RXD shows it, as the CANopen monitor holds it: the same rules,
//! limits ([`limits`]) and words. The devices' own error counts are in the
//! transcript (`encoders[].errors`).
//!
//! Values (`last_value(device + 16 × field)`):
//!
//! | field | DS 406 encoder | SAR58K24 |
//! |---|---|---|
//! | 0 | position (bytes 0..3 little-endian) of its last TPDO1 or TPDO2 | position of its last position answer (to `01` start, `80` click, or sent by itself) |
//! | 1 | frames it sent | frames it sent (over power cycles) |
//! | 2 | NMT state code (0 initialisation, 4 stopped, 5 operational, 127 pre-operational) | node in use |
//! | 3 | bit rate in use, kbit/s | bit rate in use, kbit/s |
//! | 4 | data of the last frame it sent (first byte in bits 63..56, as a controller's `i_tx_data`) | the same |
//! | 5 | identifier of the last frame it sent | the same |
//! | 6 | — | node from the next power-on (`11 <node>` on 0x7E5) |
//! | 7 | — | bit rate from the next power-on, kbit/s (`13 00 <code>` on 0x7E5) |
//!
//! `set_position(device, raw)` moves the disk (raw counts; a SAR58K24
//! answers it less its zero, reversed after `22`); `set_motion(device,
//! toml)` moves it along a [`crate::motion`] profile. `set_status(device,
//! "alarm", on)` raises or clears a DS 406 encoder's position alarm (an
//! emergency frame); `set_status(device, "power", on)` switches a SAR58K24
//! off (its transceiver recessive, deaf) and on again (a power-on: the node
//! and bit rate set on 0x7E5 take effect, configuration mode and any
//! self-sending end; zero and direction are kept). `last_status`: DS 406
//! `operational`; SAR58K24 `config_mode`, `sending`, `reversed`, `powered`.
//! `count` is the position frames device 0 sent.

use std::collections::VecDeque;

use serde::{Deserialize, Serialize};

use model::can::bus::Place;
use model::can::emulator::NodeSettings;
use model::can::frame::Frame;
use model::can::Bus;
use model::canopen::cob::{classify, Service};
use model::canopen::rules::{Limits, Watch};

use crate::can::MasterWatch;
use model::canopen::sar58k24::{SarCan, CONFIG_ID};
use model::canopen::{BenchConfig, Device, DeviceNode, EncoderNode, NodeTiming};
use model::Timebase;

use crate::check::{Checks, VIOLATION_PENDING};
use crate::config::{self, Error};
use crate::motion::Motions;
use crate::{Emulator, Pins, Result};

/// The CANopen rules' limits a configuration may set (`[monitor]`, every
/// field optional): the CAN ones and the CANopen ones.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct MonitorTable {
    bit_tolerance_percent: Option<f64>,
    max_dominant_bits: Option<f64>,
    sdo_timeout_us: Option<f64>,
    sync_period_us: Option<f64>,
    guard_time_ms: Option<f64>,
    guard_tolerance_percent: Option<f64>,
    sar_answer_timeout_us: Option<f64>,
}

/// The limits the emulator and the CANopen monitor hold the master to: its
/// bit timing (`[canopen]` `f_sys_mhz`, default `f_hz`, `bit_rate_kbps`,
/// `tq_per_bit`, `sample_point`, `sjw`), `[canopen.master]`
/// `sdo_timeout_us` and `sync_period_us`, the devices on the bus, and
/// `[monitor]`: the CAN fields of [`crate::can::CanLimits`] and
/// `sdo_timeout_us`, `sync_period_us`, `guard_time_ms`,
/// `guard_tolerance_percent` (10), `sar_answer_timeout_us` (10 000).
pub fn limits(text: &str, origin: &str, f_hz: u64) -> Result<Limits> {
    use crate::monitor::limit;
    let whole = crate::monitor::proto_table(text, origin, "canopen")?;
    let mon: MonitorTable = config::decode_in(&whole, "monitor", origin)?;
    let mut device = crate::monitor::can::model_table(&whole, f_hz);
    device.remove("tool");
    device.remove("faults");
    let bench: BenchConfig = config::decode(device, origin)?;
    let master = bench
        .master_config()
        .map_err(|e| Error::config(origin, e))?;
    let can = crate::can::CanLimits {
        bit_tolerance_percent: mon.bit_tolerance_percent,
        max_dominant_bits: mon.max_dominant_bits,
    }
    .limits(&master.can.timing, bench.f_sys_mhz * 1e6, origin)?;
    let ps = |us: f64| (us * 1e6).round() as u64;
    let [sdo, sync, guard_tol, sar] = [
        (
            "monitor.sdo_timeout_us",
            mon.sdo_timeout_us.unwrap_or(bench.master.sdo_timeout_us),
            "give the master's SDO timeout in µs",
        ),
        (
            "monitor.sync_period_us",
            mon.sync_period_us.unwrap_or(bench.master.sync_period_us),
            "give the master's SYNC period in µs (0: not checked)",
        ),
        (
            "monitor.guard_tolerance_percent",
            mon.guard_tolerance_percent.unwrap_or(10.0),
            "give the guard period's tolerance in %",
        ),
        (
            "monitor.sar_answer_timeout_us",
            mon.sar_answer_timeout_us.unwrap_or(10_000.0),
            "give the time after which a SAR58K24 command counts as unanswered, in µs",
        ),
    ]
    .map(|(path, v, fix)| limit(origin, path, v, fix));
    let (sdo, sync, guard_tol, sar) = (sdo?, sync?, guard_tol?, sar?);
    let guard_ms = match mon.guard_time_ms {
        Some(g) => Some(limit(
            origin,
            "monitor.guard_time_ms",
            g,
            "give the guard time in ms (0: guarding off)",
        )?),
        None => None,
    };
    Ok(Limits {
        can,
        sdo_timeout_ps: ps(sdo),
        sync_period_ps: ps(sync),
        guard_ms,
        guard_tolerance: guard_tol / 100.0,
        sar_timeout_ps: ps(sar),
        sar_bases: bench.sar.iter().map(|s| s.encoder.answer_base).collect(),
        ds406: bench
            .encoders
            .iter()
            .map(|e| e.encoder.node_switch)
            .collect(),
    })
}

/// The fastest CAN bit rate (1 Mbit/s).
pub const MAX_BIT_RATE_KHZ: f64 = 1000.0;

/// A frame as the transcript shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// The device (its name).
    pub node: String,
    /// `received` or `sent`.
    pub what: &'static str,
    /// Emulator cycle the node reported it.
    pub cycle: u64,
    /// Identifier.
    pub id: u32,
    /// Data, hex.
    pub data: String,
    /// CANopen meaning (DS 406), or the SAR58K24 command or answer.
    pub meaning: String,
    /// The position a SAR58K24 position answer carries.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub position: Option<u64>,
}

/// A SAR58K24 that remembers, for every frame it produced, whether it
/// carries a position: its answers to `01` and `80` and the frames it sends
/// by itself do; the acknowledgements (`20 00`, `22 00`, `31 00`, `11 00`,
/// `13 00`) do not, even where their bytes equal a position's.
#[derive(Debug, Clone)]
struct Recorded {
    sar: SarCan,
    produced: VecDeque<(Frame, Option<u64>)>,
}

impl Recorded {
    fn position_of(&self, f: &Frame) -> u64 {
        let n = self.sar.config().bits.div_ceil(8).max(2) as usize;
        f.data
            .iter()
            .take(n)
            .rev()
            .fold(0u64, |v, &b| v << 8 | b as u64)
    }

    fn record(&mut self, frames: &[Frame], positions: bool) {
        for f in frames {
            let p = positions.then(|| self.position_of(f));
            self.produced.push_back((f.clone(), p));
        }
    }

    /// What a frame the node sent carried (its entry in the produced list).
    fn sent(&mut self, f: &Frame) -> Option<u64> {
        while let Some((g, p)) = self.produced.pop_front() {
            if &g == f {
                return p;
            }
        }
        None
    }
}

impl Device for Recorded {
    fn power_on(&mut self, now_ns: u64) -> Vec<Frame> {
        let out = self.sar.power_on(now_ns);
        self.record(&out, false);
        out
    }
    fn on_frame(&mut self, f: &Frame, now_ns: u64) -> Vec<Frame> {
        let own = !f.ide && !f.rtr && f.id == 0x200 + self.sar.node() as u32;
        let positions = own && matches!(f.data.first(), Some(0x01 | 0x80));
        let out = self.sar.on_frame(f, now_ns);
        self.record(&out, positions);
        out
    }
    fn poll(&mut self, now_ns: u64) -> Vec<Frame> {
        let out = self.sar.poll(now_ns);
        self.record(&out, true);
        out
    }
    fn next_due_ns(&self) -> Option<u64> {
        self.sar.next_due_ns()
    }
    fn bit_rate_kbps(&self) -> u32 {
        self.sar.bit_rate_kbps()
    }
    fn response_delay_us(&self) -> f64 {
        self.sar.response_delay_us()
    }
}

/// What a SAR58K24 frame means (the transcript's `meaning`): `sent` by
/// the device (an answer) or received (a command, or another node's frame).
fn sar_meaning(f: &Frame, sent: bool, node: u8, position: Option<u64>) -> String {
    let b = |i: usize| f.data.get(i).copied().unwrap_or(0);
    match (sent, f.id == CONFIG_ID, b(0)) {
        (true, _, _) if position.is_some() => format!(
            "SAR58K24 node {node:#04x}: position {}",
            position.unwrap_or(0)
        ),
        (true, true, c) => format!("SAR58K24 configuration: {c:02X} 00 success"),
        (true, false, 0x20) => "SAR58K24 answer: zeroed (20 00)".into(),
        (true, false, c @ (0x22 | 0x23)) => format!("SAR58K24 answer: direction ({c:02X} 00)"),
        (true, false, 0x31) => "SAR58K24 answer: timed send started or stopped (31 00)".into(),
        (true, false, _) => "SAR58K24 answer".into(),
        (false, true, 0x04) => "SAR58K24 configuration: enter configuration mode (04 01)".into(),
        (false, true, 0x11) => format!(
            "SAR58K24 configuration: node {:#04x} from the next power-on",
            b(1)
        ),
        (false, true, 0x13) => format!(
            "SAR58K24 configuration: bit rate code {:02X} from the next power-on",
            b(2)
        ),
        (false, true, _) => "SAR58K24 configuration channel: unknown command".into(),
        (false, false, c) if f.id == 0x200 + node as u32 && !f.ide => match c {
            0x01 => format!("SAR58K24 command to node {:#04x}: start", b(1)),
            0x80 => format!(
                "SAR58K24 command to node {:#04x}: click (one position)",
                b(1)
            ),
            0x20 => format!("SAR58K24 command to node {:#04x}: zero", b(1)),
            0x22 | 0x23 => format!(
                "SAR58K24 command to node {:#04x}: direction ({c:02X})",
                b(1)
            ),
            0x31 => format!(
                "SAR58K24 command to node {:#04x}: timed send {} times a second, or stop",
                b(1),
                b(2)
            ),
            _ => format!("SAR58K24 command to node {:#04x}: unknown ({c:02X})", b(1)),
        },
        (false, false, _) => model::canopen::interpret::interpret(f).text,
    }
}

/// A SAR58K24 on the bus and its power.
struct SarSlot {
    node: DeviceNode<Recorded>,
    settings: NodeSettings,
    powered: bool,
    /// Frames sent before the last power-on (the node's list restarts).
    sent_before: u64,
}

enum Slot {
    Ds406 {
        node: Box<EncoderNode>,
        power_on: u64,
    },
    Sar(Box<SarSlot>),
}

/// DS 406 encoders and SAR58K24s on a CAN bus with the master, on the emulator clock.
pub struct CanopenEmulator {
    f_emu_hz: u64,
    tb: Timebase,
    timing: NodeTiming,
    names: Vec<String>,
    slots: Vec<Slot>,
    motions: Motions,
    bus: Bus,
    tx: Vec<bool>,
    cycle: u64,
    seen: Vec<(usize, usize)>,
    positions: Vec<(u64, Option<u64>)>,
    last_sent: Vec<Option<Frame>>,
    entries: Vec<Entry>,
    checks: Checks,
    watch: MasterWatch<Watch>,
}

fn is_pdo(f: &Frame) -> bool {
    !f.ide
        && matches!(classify(f.id as u16), Service::Tpdo1(_) | Service::Tpdo2(_))
        && f.data.len() >= 4
}

/// The COB-IDs of DS 301 node `n` (NMT error control, EMCY, the four PDO pairs, SDO).
fn cob_ids(n: u8) -> impl Iterator<Item = u32> {
    [
        0x080u32, 0x180, 0x200, 0x280, 0x300, 0x380, 0x400, 0x480, 0x500, 0x580, 0x600, 0x700,
    ]
    .into_iter()
    .map(move |f| f + n as u32)
}

impl CanopenEmulator {
    /// An emulator from TOML text (`origin` names it in errors) at `f_emu_hz`.
    pub fn from_toml(text: &str, origin: &str, f_emu_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "canopen")?;
        let tb = config::emulator_clock(
            f_emu_hz,
            &tables.emulator,
            MAX_BIT_RATE_KHZ,
            "CANopen",
            origin,
        )?;
        let mut device = tables.device;
        device.insert(
            "f_sys_mhz".into(),
            toml::Value::Float(f_emu_hz as f64 / 1e6),
        );
        let bench: BenchConfig = config::decode(device, origin)?;
        if bench.tool.is_some() {
            return Err(Error::field(origin, "tool", "the service tool node is not emulated in co-simulation: the master under test plays its part", "remove [canopen.tool] (the vector bench runs it) and send its frames from your master"));
        }
        if bench.encoders.is_empty() && bench.sar.is_empty() {
            return Err(Error::field(origin, "encoders", "no [[canopen.encoders]] and no [[canopen.sar]]", "give at least one device: a DS 406 encoder (name = \"encoder\", [canopen.encoders.encoder] node_switch = 1) or a SAR58K24 ([[canopen.sar]] with [canopen.sar.encoder] node = 0x20)"));
        }
        model::Setup::validate(&bench).map_err(|e| Error::config(origin, e))?;
        let timing = bench.node_timing();
        let mut places = vec![Place {
            position_m: bench.master.position_m,
            loop_delay_ns: bench.master.loop_delay_ns,
        }];
        let mut slots = Vec::new();
        let mut names = Vec::new();
        let mut ids: Vec<(u32, String)> = Vec::new();
        for (k, e) in bench.encoders.iter().enumerate() {
            let s = NodeSettings {
                name: e.name.clone(),
                position_m: e.position_m,
                loop_delay_ns: e.loop_delay_ns,
                ppm: e.ppm,
                ack: true,
                frames: Vec::new(),
            };
            places.push(s.place());
            let node = EncoderNode::new(&e.encoder, &s, timing, &tb)
                .map_err(|e| Error::config(origin, e))?;
            ids.extend(cob_ids(node.encoder().node()).map(|id| {
                (
                    id,
                    format!("encoders[{k}] (DS 406 node {})", node.encoder().node()),
                )
            }));
            slots.push(Slot::Ds406 {
                node: Box::new(node),
                power_on: tb.cycles_nearest_ns(e.power_on_us * 1e3),
            });
            names.push(e.name.clone());
        }
        for (k, s) in bench.sar.iter().enumerate() {
            let field = format!("sar[{k}]");
            let c = &s.encoder;
            if c.bit_rate_kbps != bench.bit_rate_kbps {
                return Err(Error::field(
                    origin,
                    format!("{field}.encoder.bit_rate_kbps"),
                    format!("{} kbit/s, but the bus (bit_rate_kbps) runs at {} kbit/s", c.bit_rate_kbps, bench.bit_rate_kbps),
                    "give the SAR58K24 the bus's bit rate (it would hear nobody at another); change it at run time on 0x7E5 (13 00 <code>) and a power cycle",
                ));
            }
            for (id, what) in [
                (0x200 + c.node as u32, "command"),
                (c.answer_base as u32 + c.node as u32, "answer"),
            ] {
                if let Some((_, other)) = ids.iter().find(|(i, _)| *i == id) {
                    return Err(Error::field(
                        origin,
                        format!("{field}.encoder.node"),
                        format!("{:#04x}: its {what} identifier {id:#05x} is also used by {other}", c.node),
                        "give every device on the bus its own node (a SAR58K24 uses 0x200 + node and its answer base + node)",
                    ));
                }
            }
            ids.push((
                0x200 + c.node as u32,
                format!("{field} (SAR58K24 node {:#04x})", c.node),
            ));
            ids.push((
                c.answer_base as u32 + c.node as u32,
                format!("{field} (SAR58K24 node {:#04x})", c.node),
            ));
            let settings = NodeSettings {
                name: s.name.clone(),
                position_m: s.position_m,
                loop_delay_ns: s.loop_delay_ns,
                ppm: 0.0,
                ack: true,
                frames: Vec::new(),
            };
            places.push(settings.place());
            let sar = SarCan::new(c).map_err(|e| Error::config(origin, e))?;
            let node = DeviceNode::with(
                Recorded {
                    sar,
                    produced: VecDeque::new(),
                },
                &settings,
                timing,
                &tb,
            )
            .map_err(|e| Error::config(origin, e))?;
            slots.push(Slot::Sar(Box::new(SarSlot {
                node,
                settings,
                powered: true,
                sent_before: 0,
            })));
            names.push(s.name.clone());
        }
        let n = slots.len();
        let mut checks = Checks::new(tb.period_ps());
        let watch = MasterWatch::new(
            Watch::new(limits(text, origin, f_emu_hz)?),
            f_emu_hz,
            &mut checks,
        );
        Ok(CanopenEmulator {
            f_emu_hz,
            tb,
            timing,
            names,
            slots,
            motions: Motions::default(),
            bus: Bus::new(&places, bench.ns_per_m, &tb),
            tx: vec![true; n + 1],
            cycle: 0,
            seen: vec![(0, 0); n],
            positions: vec![(0, None); n],
            last_sent: vec![None; n],
            entries: Vec::new(),
            checks,
            watch,
        })
    }

    /// Frames the devices sent and received so far, in order.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    fn slot_mut(&mut self, device: usize) -> Result<&mut Slot> {
        let n = self.slots.len();
        self.slots.get_mut(device).ok_or_else(|| Error::Usage(format!("the CANopen emulator has {n} device(s) (DS 406 encoders first, then SAR58K24s), not device {device}")))
    }

    /// The resolution of device `device` as a bit count (motion profiles wrap there).
    fn bits(&self, device: usize) -> Result<u32> {
        match self.slots.get(device) {
            Some(Slot::Sar(s)) => Ok(s.node.encoder().sar.config().bits),
            Some(Slot::Ds406 { node, .. }) => {
                let top = node.encoder().config().kind.total_resolution();
                if top.is_power_of_two() {
                    Ok(top.trailing_zeros())
                } else {
                    Err(Error::Usage(format!("device {device}: a motion profile wraps at a power of two; this encoder has {top} counts (set positions instead)")))
                }
            }
            None => Err(Error::Usage(format!(
                "the CANopen emulator has {} device(s), not device {device}",
                self.slots.len()
            ))),
        }
    }

    fn move_disk(&mut self, device: usize, raw: u64) {
        match &mut self.slots[device] {
            Slot::Ds406 { node, .. } => {
                let now = node.time_ns();
                node.encoder_mut().set_raw(raw, now);
            }
            Slot::Sar(s) => {
                let now = s.node.time_ns();
                s.node.encoder_mut().sar.set_raw(raw, now);
            }
        }
    }
}

impl Emulator for CanopenEmulator {
    fn kind(&self) -> &'static str {
        "canopen"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let rx_master = self.bus.rx(0);
        self.tx[0] = pins.0 & 2 != 0;
        self.watch
            .step(self.cycle, self.f_emu_hz, self.tx[0], &mut self.checks);
        self.watch.answer(rx_master);
        if self.motions.any() {
            for i in 0..self.slots.len() {
                if let Ok(bits) = self.bits(i) {
                    if let Some(p) = self.motions.position_on(i, self.cycle, &self.tb, bits) {
                        self.move_disk(i, p);
                    }
                }
            }
        }
        for i in 0..self.slots.len() {
            let rx = self.bus.rx(i + 1);
            let (r, s) = self.seen[i];
            let name = &self.names[i];
            let level = match &mut self.slots[i] {
                Slot::Ds406 { node, power_on } => {
                    if self.cycle < *power_on {
                        self.tx[i + 1] = true;
                        continue;
                    }
                    let level = node.step(rx);
                    // A reset at a new bit rate (5000h) rebuilds the node's controller and its list of frames sent.
                    let s = if s > node.sent().len() { 0 } else { s };
                    for (_, f) in &node.received()[r..] {
                        self.entries.push(entry(
                            name,
                            "received",
                            self.cycle,
                            f,
                            model::canopen::interpret::interpret(f).text,
                            None,
                        ));
                    }
                    for f in &node.sent()[s..] {
                        self.entries.push(entry(
                            name,
                            "sent",
                            self.cycle,
                            f,
                            model::canopen::interpret::interpret(f).text,
                            None,
                        ));
                        if is_pdo(f) {
                            let p = u32::from_le_bytes([f.data[0], f.data[1], f.data[2], f.data[3]])
                                as u64;
                            self.positions[i] = (self.positions[i].0 + 1, Some(p));
                        }
                        self.last_sent[i] = Some(f.clone());
                    }
                    self.seen[i] = (node.received().len(), node.sent().len());
                    level
                }
                Slot::Sar(slot) => {
                    if !slot.powered {
                        self.tx[i + 1] = true;
                        continue;
                    }
                    let level = slot.node.step(rx);
                    let node_no = slot.node.encoder().sar.node();
                    for (_, f) in &slot.node.received()[r..] {
                        self.entries.push(entry(
                            name,
                            "received",
                            self.cycle,
                            f,
                            sar_meaning(f, false, node_no, None),
                            None,
                        ));
                    }
                    let sent: Vec<Frame> = slot.node.sent()[s..].to_vec();
                    for f in sent {
                        let p = slot.node.encoder_mut().sent(&f);
                        self.entries.push(entry(
                            name,
                            "sent",
                            self.cycle,
                            &f,
                            sar_meaning(&f, true, node_no, p),
                            p,
                        ));
                        if p.is_some() {
                            self.positions[i] = (self.positions[i].0 + 1, p);
                        }
                        self.last_sent[i] = Some(f);
                    }
                    self.seen[i] = (slot.node.received().len(), slot.node.sent().len());
                    level
                }
            };
            self.tx[i + 1] = level;
        }
        self.bus.push(&self.tx);
        self.cycle += 1;
        let flag = if self.checks.pending() {
            VIOLATION_PENDING
        } else {
            0
        };
        Pins(rx_master as u32 | flag)
    }

    fn set_position(&mut self, device: usize, position: u64) -> Result<()> {
        let top = match self.slot_mut(device)? {
            Slot::Ds406 { node, .. } => node.encoder().config().kind.total_resolution(),
            Slot::Sar(s) => 1u64 << s.node.encoder().sar.config().bits,
        };
        if position >= top {
            return Err(Error::Usage(format!("device {device}: raw position {position} is beyond its {top} counts; give a position below {top}")));
        }
        self.motions.stop(device);
        self.move_disk(device, position);
        Ok(())
    }

    fn set_motion(&mut self, device: usize, toml: &str) -> Result<()> {
        self.bits(device)?;
        self.motions.set(device, toml, self.cycle)
    }

    fn set_status(&mut self, device: usize, name: &str, value: bool) -> Result<()> {
        let (tb, timing) = (self.tb, self.timing);
        let seen = self.seen.get_mut(device);
        let n = self.slots.len();
        let slot = self.slots.get_mut(device).ok_or_else(|| Error::Usage(format!("the CANopen emulator has {n} device(s) (DS 406 encoders first, then SAR58K24s), not device {device}")))?;
        match (slot, name) {
            (Slot::Ds406 { node, .. }, "alarm") => {
                let now = node.time_ns();
                let frames = node.encoder_mut().set_alarm(value, now);
                node.send(frames);
                Ok(())
            }
            (Slot::Ds406 { .. }, other) => Err(Error::Usage(format!("a CANopen DS 406 encoder has the status `alarm` (position error, an emergency frame), not `{other}`"))),
            (Slot::Sar(s), "power") => {
                if value && !s.powered {
                    // Power-on: a new controller (it integrates 11 recessive bits first) at the rate set on 0x7E5.
                    let sar = s.node.encoder().sar.clone();
                    let node = DeviceNode::with(Recorded { sar, produced: VecDeque::new() }, &s.settings, timing, &tb).map_err(|e| Error::Usage(format!("device {device}: power-on: {e}")))?;
                    s.sent_before += s.node.sent().len() as u64;
                    s.node = node;
                    if let Some(seen) = seen {
                        *seen = (0, 0);
                    }
                }
                s.powered = value;
                Ok(())
            }
            (Slot::Sar(_), other) => Err(Error::Usage(format!("a SAR58K24 in CAN mode has the status `power` (off and on again: the node and bit rate set on 0x7E5 take effect), not `{other}`; its answers carry no status bits"))),
        }
    }

    fn schedule_fault(&mut self, _toml: &str) -> Result<()> {
        Err(Error::Usage("the CANopen emulator has no faults to schedule yet: move the disk (set_position, set_motion), raise an alarm (set_status \"alarm\") or cycle a SAR58K24's power (set_status \"power\")".into()))
    }

    fn count(&self) -> u64 {
        self.positions.first().map_or(0, |p| p.0)
    }

    fn last_value(&self, device: usize) -> Option<u64> {
        let (d, field) = (device % 16, device / 16);
        let slot = self.slots.get(d)?;
        let last = self.last_sent[d].as_ref();
        match (slot, field) {
            (_, 0) => self.positions[d].1,
            (Slot::Ds406 { node, .. }, 1) => Some(node.sent().len() as u64),
            (Slot::Sar(s), 1) => Some(s.sent_before + s.node.sent().len() as u64),
            (Slot::Ds406 { node, .. }, 2) => Some(node.encoder().state() as u64),
            (Slot::Sar(s), 2) => Some(s.node.encoder().sar.node() as u64),
            (Slot::Ds406 { node, .. }, 3) => Some(node.encoder().bit_rate_kbps() as u64),
            (Slot::Sar(s), 3) => Some(s.node.encoder().bit_rate_kbps() as u64),
            (_, 4) => last.map(|f| f.packed()),
            (_, 5) => last.map(|f| f.id as u64),
            (Slot::Sar(s), 6) => Some(s.node.encoder().sar.pending().0 as u64),
            (Slot::Sar(s), 7) => Some(s.node.encoder().sar.pending().1 as u64),
            _ => None,
        }
    }

    fn last_status(&self, device: usize, name: &str) -> Result<bool> {
        let slot = self
            .slots
            .get(device)
            .ok_or_else(|| Error::Usage(format!("no device {device}")))?;
        match (slot, name) {
            (Slot::Ds406 { node, .. }, "operational") => Ok(node.encoder().state() == model::canopen::cob::NmtState::Operational),
            (Slot::Ds406 { .. }, other) => Err(Error::Usage(format!("a CANopen encoder reports `operational`, not `{other}`"))),
            (Slot::Sar(s), "config_mode") => Ok(s.node.encoder().sar.config_mode()),
            (Slot::Sar(s), "sending") => Ok(s.node.encoder().sar.sending()),
            (Slot::Sar(s), "reversed") => Ok(s.node.encoder().sar.reversed()),
            (Slot::Sar(s), "powered") => Ok(s.powered),
            (Slot::Sar(_), other) => Err(Error::Usage(format!("a SAR58K24 reports `config_mode`, `sending`, `reversed` and `powered`, not `{other}`"))),
        }
    }

    fn transcript(&self) -> serde_json::Value {
        let devices: Vec<serde_json::Value> = self
            .slots
            .iter()
            .zip(&self.names)
            .map(|(slot, name)| match slot {
                Slot::Ds406 { node: n, .. } => serde_json::json!({ "name": name, "kind": "ds406", "node": n.encoder().node(), "sent": n.sent().len(), "received": n.received().len(), "errors": n.can().errors() }),
                Slot::Sar(s) => serde_json::json!({ "name": name, "kind": "sar58k24", "node": s.node.encoder().sar.node(), "bit_rate_kbps": s.node.encoder().bit_rate_kbps(), "sent": s.sent_before + s.node.sent().len() as u64, "received": s.node.received().len(), "errors": s.node.can().errors() }),
            })
            .collect();
        serde_json::json!({ "protocol": "canopen", "f_emu_hz": self.f_emu_hz, "encoders": devices, "frames": self.entries, "violations": self.checks.all() })
    }

    fn checks(&mut self) -> &mut Checks {
        &mut self.checks
    }
}

fn entry(
    node: &str,
    what: &'static str,
    cycle: u64,
    f: &Frame,
    meaning: String,
    position: Option<u64>,
) -> Entry {
    Entry {
        node: node.to_string(),
        what,
        cycle,
        id: f.id,
        data: model::bits::hex(&f.data),
        meaning,
        position,
    }
}
