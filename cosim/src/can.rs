//! The CAN bus emulator: one or more [`model::can::Emulator`] nodes and the
//! wired-AND bus ([`model::can::Bus`]) they share with the master under test.
//!
//! Configuration: the scenario's `[can]` table (`timing`, `ns_per_m`,
//! `[dut]` for the master's place on the cable, `[[nodes]]` with their own
//! places, oscillators, ACK and scripted frames); `f_sys_mhz` and the
//! `dut.frames` script belong to the master's side and are ignored. The
//! bench's `[[faults]]` (bit flips, a stuck bus) are not emulated yet and are
//! refused by name. The emulator clock is the nodes' reference clock (the
//! bit timing is made of its cycles, as the model's nodes are).
//!
//! Pins (`emu_step`): in bit 1 the master's TXD; out bit 0 the bus level at
//! the master's RXD (wired-AND of every node's TXD, each after its delay).
//!
//! The master is held to the CAN rule book ([`model::can::rules`]) on its
//! TXD and the bus as its RXD shows it (its TXD and this emulator's last
//! answer, wired-AND), as the CAN monitor holds it: the same rules, the
//! same limits (`[monitor]` `bit_tolerance_percent`, `max_dominant_bits`,
//! read by [`limits`]), the same words. The nodes' own error counts are in
//! the transcript (`nodes[].errors`).
//!
//! At run time `schedule_fault` also scripts frames: `[[send]]` tables
//! `{ node = 0, id = 0x123, dlc = 2, data = [1, 2] }` (with `ide`, `rtr`)
//! are queued and loaded into that node's controller as soon as it is free.
//!
//! Values (`last_value(device)`): `device = node + 16 × field`, field 0 the
//! data of the last frame the node received (first byte in bits 63..56, as
//! `i_tx_data`), 1 its identifier, 2 its DLC, 3 frames the node sent.
//! Statuses: `ide`, `rtr` of that frame. `count` is the frames node 0
//! received.

use serde::{Deserialize, Serialize};

use model::can::bus::Place;
use model::can::emulator::Scripted;
use model::can::frame::Frame;
use model::can::rules::{Limits, Watch};

use crate::monitor::can::Rules;
use model::can::{BenchConfig, BitTiming, Bus, Emulator as Node};

use crate::check::{Checks, VIOLATION_PENDING};
use crate::config::{self, Error};
use crate::{Emulator, Pins, Result};

/// The fastest CAN bit rate (1 Mbit/s).
pub const MAX_BIT_RATE_KHZ: f64 = 1000.0;

/// The CAN rules' limits a configuration may set (`[monitor]`, every field
/// optional); the CANopen monitor's table adds its own fields.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CanLimits {
    /// Bit-rate tolerance of the master's edges, % (default: the oscillator tolerance of the timing).
    pub bit_tolerance_percent: Option<f64>,
    /// Longest dominant TXD, bits.
    pub max_dominant_bits: Option<f64>,
}

impl CanLimits {
    /// The rule book's limits for the master's bit timing `t` at `f_sys_hz`.
    pub fn limits(&self, t: &BitTiming, f_sys_hz: f64, origin: &str) -> Result<Limits> {
        Limits::new(
            t,
            f_sys_hz,
            self.bit_tolerance_percent
                .map(|v| ("monitor.bit_tolerance_percent", v)),
            self.max_dominant_bits
                .map(|v| ("monitor.max_dominant_bits", v)),
        )
        .map_err(|e| Error::config(origin, e))
    }
}

/// The limits the emulator and the CAN monitor hold the master to: its bit
/// timing (`[can]` `f_sys_mhz`, default `f_hz`, and `timing`) and the
/// `[monitor]` fields of [`CanLimits`].
pub fn limits(text: &str, origin: &str, f_hz: u64) -> Result<Limits> {
    let whole = crate::monitor::proto_table(text, origin, "can")?;
    let given: CanLimits = config::decode_in(&whole, "monitor", origin)?;
    let mut device = crate::monitor::can::model_table(&whole, f_hz);
    for key in ["nodes", "dut", "faults"] {
        device.remove(key);
    }
    let bench: BenchConfig = config::decode(device, origin)?;
    let timing = bench.bit_timing().map_err(|e| Error::config(origin, e))?;
    given.limits(&timing, bench.f_sys_mhz * 1e6, origin)
}

/// A rule book's watcher fed from an emulator's side of the line: the
/// master's TXD and the bus as the master's RXD shows it (its TXD and the
/// emulator's last answer, wired-AND), as a monitor beside it sees them.
pub struct MasterWatch<R: Rules> {
    rules: R,
    answered: bool,
}

impl<R: Rules> MasterWatch<R> {
    /// A watcher feeding `rules`; the resolution notes of its limits go to
    /// `checks` (the emulator clock `f_hz`).
    pub fn new(rules: R, f_hz: u64, checks: &mut Checks) -> Self {
        for note in model::rules::resolution_notes(f_hz, &rules.can().limits().least()) {
            checks.note(note);
        }
        MasterWatch {
            rules,
            answered: true,
        }
    }

    /// Emulator cycle `cycle` at `f_hz`: the master's TXD `tx`; what the
    /// rules find goes to `checks`.
    pub fn step(&mut self, cycle: u64, f_hz: u64, tx: bool, checks: &mut Checks) {
        let t = model::rules::ps_at(cycle, f_hz);
        for b in self.rules.sample(t, tx && self.answered, tx).breaches {
            checks.breach(cycle, &b);
        }
    }

    /// The bus level this cycle answers at the master's RXD.
    pub fn answer(&mut self, rx: bool) {
        self.answered = rx;
    }
}

/// A frame scripted at run time.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct Send {
    node: usize,
    id: u32,
    #[serde(default)]
    ide: bool,
    #[serde(default)]
    rtr: bool,
    #[serde(default)]
    dlc: u8,
    #[serde(default)]
    data: Vec<u8>,
}

#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct SendTables {
    send: Vec<Send>,
}

/// A frame as the transcript shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// The node.
    pub node: String,
    /// `received` or `sent`.
    pub what: &'static str,
    /// Emulator cycle the node reported it.
    pub cycle: u64,
    /// Identifier.
    pub id: u32,
    /// Extended.
    pub ide: bool,
    /// Remote.
    pub rtr: bool,
    /// DLC.
    pub dlc: u8,
    /// Data, hex.
    pub data: String,
}

fn entry(node: &str, what: &'static str, cycle: u64, f: &Frame) -> Entry {
    Entry {
        node: node.to_string(),
        what,
        cycle,
        id: f.id,
        ide: f.ide,
        rtr: f.rtr,
        dlc: f.dlc,
        data: model::bits::hex(&f.data),
    }
}

/// Nodes on a CAN bus with the master, on the emulator clock.
pub struct CanEmulator {
    f_emu_hz: u64,
    names: Vec<String>,
    nodes: Vec<Node>,
    pending: Vec<Vec<Frame>>,
    bus: Bus,
    tx: Vec<bool>,
    cycle: u64,
    seen: Vec<(usize, usize)>,
    entries: Vec<Entry>,
    checks: Checks,
    watch: MasterWatch<Watch>,
}

impl CanEmulator {
    /// An emulator from TOML text (`origin` names it in errors) at `f_emu_hz`.
    pub fn from_toml(text: &str, origin: &str, f_emu_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "can")?;
        let tb =
            config::emulator_clock(f_emu_hz, &tables.emulator, MAX_BIT_RATE_KHZ, "CAN", origin)?;
        let mut device = tables.device;
        device.insert(
            "f_sys_mhz".into(),
            toml::Value::Float(f_emu_hz as f64 / 1e6),
        );
        let bench: BenchConfig = config::decode(device, origin)?;
        if !bench.faults.is_empty() {
            return Err(Error::field(
                origin,
                "faults",
                "bit flips and a stuck bus are not emulated in co-simulation yet",
                "remove [[can.faults]] (the vector bench runs them), or script a node's frames",
            ));
        }
        if bench.nodes.is_empty() {
            return Err(Error::field(
                origin,
                "nodes",
                "no [[can.nodes]]",
                "give at least one emulated node (name = \"a\")",
            ));
        }
        let cfg = bench
            .controller_config()
            .map_err(|e| Error::config(origin, e))?;
        let mut places: Vec<Place> = vec![bench.dut.place()];
        let mut nodes = Vec::new();
        for (k, n) in bench.nodes.iter().enumerate() {
            n.validate(&format!("nodes[{k}]"))
                .map_err(|e| Error::config(origin, e))?;
            places.push(n.place());
            nodes.push(Node::new(n, cfg, &tb).map_err(|e| Error::config(origin, e))?);
        }
        let n = nodes.len();
        let mut checks = Checks::new(tb.period_ps());
        let watch = MasterWatch::new(
            Watch::new(limits(text, origin, f_emu_hz)?),
            f_emu_hz,
            &mut checks,
        );
        Ok(CanEmulator {
            f_emu_hz,
            names: bench.nodes.iter().map(|n| n.name.clone()).collect(),
            nodes,
            pending: vec![Vec::new(); n],
            bus: Bus::new(&places, bench.ns_per_m, &tb),
            tx: vec![true; n + 1],
            cycle: 0,
            seen: vec![(0, 0); n],
            entries: Vec::new(),
            checks,
            watch,
        })
    }

    /// Frames the nodes sent and received so far, in order.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    fn node(&self, node: usize) -> Result<&Node> {
        self.nodes.get(node).ok_or_else(|| {
            Error::Usage(format!(
                "the CAN emulator has {} node(s), not node {node}",
                self.nodes.len()
            ))
        })
    }
}

impl Emulator for CanEmulator {
    fn kind(&self) -> &'static str {
        "can"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let rx_master = self.bus.rx(0);
        self.tx[0] = pins.0 & 2 != 0;
        self.watch
            .step(self.cycle, self.f_emu_hz, self.tx[0], &mut self.checks);
        self.watch.answer(rx_master);
        for (i, node) in self.nodes.iter_mut().enumerate() {
            if let Some(f) = self.pending[i].first() {
                if node.load(f) {
                    self.pending[i].remove(0);
                }
            }
            self.tx[i + 1] = node.step(self.bus.rx(i + 1));
            let (r, s) = self.seen[i];
            for f in &node.received()[r..] {
                self.entries
                    .push(entry(&self.names[i], "received", self.cycle, f));
            }
            for f in &node.sent()[s..] {
                self.entries
                    .push(entry(&self.names[i], "sent", self.cycle, f));
            }
            self.seen[i] = (node.received().len(), node.sent().len());
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

    fn set_position(&mut self, _device: usize, _position: u64) -> Result<()> {
        Err(Error::Usage(
            "a CAN node has no position: script its frames ([[nodes]] frames, or schedule_fault with [[send]] tables)".into(),
        ))
    }

    fn set_status(&mut self, _device: usize, name: &str, _value: bool) -> Result<()> {
        Err(Error::Usage(format!(
            "a CAN node has no status to set (`{name}`): its ACK is nodes[i].ack"
        )))
    }

    fn schedule_fault(&mut self, toml: &str) -> Result<()> {
        let tables = config::tables(toml, "send", "can")?;
        let s: SendTables = config::decode(tables.device, "send")?;
        for (k, f) in s.send.iter().enumerate() {
            self.node(f.node).map_err(|e| {
                Error::field(
                    "send",
                    format!("send[{k}].node"),
                    e.to_string(),
                    "give a node index of [[can.nodes]]",
                )
            })?;
            let frame = Scripted {
                at_us: 0.0,
                id: f.id,
                ide: f.ide,
                rtr: f.rtr,
                dlc: f.dlc,
                data: f.data.clone(),
            }
            .frame();
            frame
                .validate(&format!("send[{k}]"))
                .map_err(|e| Error::config("send", e))?;
            self.pending[f.node].push(frame);
        }
        Ok(())
    }

    fn count(&self) -> u64 {
        self.nodes.first().map_or(0, |n| n.received().len() as u64)
    }

    fn last_value(&self, device: usize) -> Option<u64> {
        let node = self.nodes.get(device % 16)?;
        let last = node.received().last();
        match device / 16 {
            0 => last.map(|f| f.packed()),
            1 => last.map(|f| f.id as u64),
            2 => last.map(|f| f.dlc as u64),
            3 => Some(node.sent().len() as u64),
            _ => None,
        }
    }

    fn last_status(&self, device: usize, name: &str) -> Result<bool> {
        let last = self.node(device)?.received().last();
        match name {
            "ide" => Ok(last.is_some_and(|f| f.ide)),
            "rtr" => Ok(last.is_some_and(|f| f.rtr)),
            other => Err(Error::Usage(format!(
                "a CAN node reports `ide` and `rtr` of the last frame it received, not `{other}`"
            ))),
        }
    }

    fn transcript(&self) -> serde_json::Value {
        let nodes: Vec<serde_json::Value> = self
            .nodes
            .iter()
            .zip(&self.names)
            .map(|(n, name)| {
                serde_json::json!({
                    "name": name,
                    "sent": n.sent().len(),
                    "received": n.received().len(),
                    "errors": n.errors(),
                    "arbitrations_lost": n.arbitrations_lost(),
                })
            })
            .collect();
        serde_json::json!({
            "protocol": "can",
            "f_emu_hz": self.f_emu_hz,
            "nodes": nodes,
            "frames": self.entries,
            "violations": self.checks.all(),
        })
    }

    fn checks(&mut self) -> &mut Checks {
        &mut self.checks
    }
}
