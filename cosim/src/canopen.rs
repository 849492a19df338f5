//! The CANopen encoder emulator: the DS 406 encoders of
//! [`model::canopen::EncoderNode`] (the Leine & Linde gateway of seed 003)
//! on the wired-AND bus ([`model::can::Bus`]) they share with the master
//! under test.
//!
//! Configuration: the scenario's `[canopen]` table (`bit_rate_kbps`,
//! `tq_per_bit`, `sample_point`, `sjw`, `sync_stages`, `ns_per_m`,
//! `[master]` for the master's place on the cable, `[[encoders]]` with
//! their `[encoders.encoder]`, places, oscillators, power-on and alarm
//! times); `f_sys_mhz`, the master's table entries other than its place and
//! `run_us` belong to the master's side. SAR58K24 devices and the tool node
//! are not emulated here yet and are refused by name. The emulator clock is
//! the nodes' reference clock.
//!
//! Pins (`emu_step`): in bit 1 the master's TXD; out bit 0 the bus level at
//! the master's RXD.
//!
//! Values (`last_value(device)`): the position (bytes 0..3 little-endian)
//! of the last TPDO1 or TPDO2 encoder `device` sent; `device + 16`: the
//! number of frames it sent; `device + 32`: its NMT state code (0
//! initialisation, 4 stopped, 5 operational, 127 pre-operational).
//! `set_position(device, raw)` moves the encoder's disk (raw counts).
//! `set_status(device, "alarm", on)` raises or clears its position alarm
//! (an emergency frame). `count` is the TPDOs encoder 0 sent.

use serde::Serialize;

use model::can::bus::Place;
use model::can::frame::Frame;
use model::can::Bus;
use model::canopen::cob::{classify, Service};
use model::canopen::{BenchConfig, EncoderNode};

use crate::check::{Checks, VIOLATION_PENDING};
use crate::config::{self, Error};
use crate::{Emulator, Pins, Result};

/// The fastest CAN bit rate (1 Mbit/s).
pub const MAX_BIT_RATE_KHZ: f64 = 1000.0;

/// A frame as the transcript shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// The encoder.
    pub node: String,
    /// `received` or `sent`.
    pub what: &'static str,
    /// Emulator cycle the node reported it.
    pub cycle: u64,
    /// Identifier.
    pub id: u32,
    /// Data, hex.
    pub data: String,
    /// CANopen meaning.
    pub meaning: String,
}

/// DS 406 encoders on a CAN bus with the master, on the emulator clock.
pub struct CanopenEmulator {
    f_emu_hz: u64,
    names: Vec<String>,
    nodes: Vec<EncoderNode>,
    power_on: Vec<u64>,
    bus: Bus,
    tx: Vec<bool>,
    cycle: u64,
    seen: Vec<(usize, usize, u64)>,
    pdos: Vec<(u64, Option<u64>)>,
    entries: Vec<Entry>,
    checks: Checks,
}

fn is_pdo(f: &Frame) -> bool {
    !f.ide && matches!(classify(f.id as u16), Service::Tpdo1(_) | Service::Tpdo2(_)) && f.data.len() >= 4
}

impl CanopenEmulator {
    /// An emulator from TOML text (`origin` names it in errors) at `f_emu_hz`.
    pub fn from_toml(text: &str, origin: &str, f_emu_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "canopen")?;
        let tb = config::emulator_clock(f_emu_hz, &tables.emulator, MAX_BIT_RATE_KHZ, "CANopen", origin)?;
        let mut device = tables.device;
        device.insert("f_sys_mhz".into(), toml::Value::Float(f_emu_hz as f64 / 1e6));
        let bench: BenchConfig = config::decode(device, origin)?;
        if !bench.sar.is_empty() || bench.tool.is_some() {
            return Err(Error::field(origin, "sar", "SAR58K24 devices and the tool node are not emulated in co-simulation yet", "remove [[canopen.sar]] and [canopen.tool] (the vector bench runs them)"));
        }
        if bench.encoders.is_empty() {
            return Err(Error::field(origin, "encoders", "no [[canopen.encoders]]", "give at least one encoder (name = \"encoder\", [canopen.encoders.encoder] node_switch = 1)"));
        }
        model::Setup::validate(&bench).map_err(|e| Error::config(origin, e))?;
        let mut places = vec![Place { position_m: bench.master.position_m, loop_delay_ns: bench.master.loop_delay_ns }];
        let mut nodes = Vec::new();
        let mut power_on = Vec::new();
        for e in &bench.encoders {
            let s = model::can::emulator::NodeSettings { name: e.name.clone(), position_m: e.position_m, loop_delay_ns: e.loop_delay_ns, ppm: e.ppm, ack: true, frames: Vec::new() };
            places.push(s.place());
            nodes.push(EncoderNode::new(&e.encoder, &s, bench.node_timing(), &tb).map_err(|e| Error::config(origin, e))?);
            power_on.push(tb.cycles_nearest_ns(e.power_on_us * 1e3));
        }
        let n = nodes.len();
        Ok(CanopenEmulator {
            f_emu_hz,
            names: bench.encoders.iter().map(|e| e.name.clone()).collect(),
            nodes,
            power_on,
            bus: Bus::new(&places, bench.ns_per_m, &tb),
            tx: vec![true; n + 1],
            cycle: 0,
            seen: vec![(0, 0, 0); n],
            pdos: vec![(0, None); n],
            entries: Vec::new(),
            checks: Checks::new(tb.period_ps()),
        })
    }

    /// Frames the encoders sent and received so far, in order.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    fn node_mut(&mut self, device: usize) -> Result<&mut EncoderNode> {
        let n = self.nodes.len();
        self.nodes.get_mut(device).ok_or_else(|| Error::Usage(format!("the CANopen emulator has {n} encoder(s), not encoder {device}")))
    }
}

fn entry(node: &str, what: &'static str, cycle: u64, f: &Frame) -> Entry {
    Entry { node: node.to_string(), what, cycle, id: f.id, data: crate::sar58k24::hex(&f.data), meaning: model::canopen::interpret::interpret(f).text }
}

impl Emulator for CanopenEmulator {
    fn kind(&self) -> &'static str {
        "canopen"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let rx_master = self.bus.rx(0);
        self.tx[0] = pins.0 & 2 != 0;
        for (i, node) in self.nodes.iter_mut().enumerate() {
            if self.cycle < self.power_on[i] {
                self.tx[i + 1] = true;
                continue;
            }
            self.tx[i + 1] = node.step(self.bus.rx(i + 1));
            let (r, s, e) = self.seen[i];
            // A reset at a new bit rate (5000h) rebuilds the node's controller and its list of frames sent.
            let s = if s > node.sent().len() { 0 } else { s };
            for (_, f) in &node.received()[r..] {
                self.entries.push(entry(&self.names[i], "received", self.cycle, f));
            }
            for f in &node.sent()[s..] {
                self.entries.push(entry(&self.names[i], "sent", self.cycle, f));
                if is_pdo(f) {
                    let p = u32::from_le_bytes([f.data[0], f.data[1], f.data[2], f.data[3]]) as u64;
                    self.pdos[i] = (self.pdos[i].0 + 1, Some(p));
                }
            }
            let errors = node.can().errors();
            if errors > e {
                self.checks.push(self.cycle, "CAN frame coding (ISO 11898-1: bit, stuff, CRC, form and ACK rules)", format!("encoder `{}` detected an error ({errors} so far)", self.names[i]));
            }
            self.seen[i] = (node.received().len(), node.sent().len(), errors);
        }
        self.bus.push(&self.tx);
        self.cycle += 1;
        let flag = if self.checks.pending() { VIOLATION_PENDING } else { 0 };
        Pins(rx_master as u32 | flag)
    }

    fn set_position(&mut self, device: usize, position: u64) -> Result<()> {
        let node = self.node_mut(device)?;
        let top = node.encoder().config().kind.total_resolution();
        if position >= top {
            return Err(Error::Usage(format!("encoder {device}: raw position {position} is beyond its {top} counts")));
        }
        let now = node.time_ns();
        node.encoder_mut().set_raw(position, now);
        Ok(())
    }

    fn set_status(&mut self, device: usize, name: &str, value: bool) -> Result<()> {
        if name != "alarm" {
            return Err(Error::Usage(format!("a CANopen encoder has the status `alarm` (position error, an emergency frame), not `{name}`")));
        }
        let node = self.node_mut(device)?;
        let now = node.time_ns();
        let frames = node.encoder_mut().set_alarm(value, now);
        node.send(frames);
        Ok(())
    }

    fn schedule_fault(&mut self, _toml: &str) -> Result<()> {
        Err(Error::Usage("the CANopen emulator has no faults to schedule yet: move the disk (set_position) or raise an alarm (set_status \"alarm\")".into()))
    }

    fn count(&self) -> u64 {
        self.pdos.first().map_or(0, |p| p.0)
    }

    fn last_value(&self, device: usize) -> Option<u64> {
        let node = self.nodes.get(device % 16)?;
        match device / 16 {
            0 => self.pdos[device % 16].1,
            1 => Some(node.sent().len() as u64),
            2 => Some(node.encoder().state() as u64),
            _ => None,
        }
    }

    fn last_status(&self, device: usize, name: &str) -> Result<bool> {
        let node = self.nodes.get(device).ok_or_else(|| Error::Usage(format!("no encoder {device}")))?;
        match name {
            "operational" => Ok(node.encoder().state() == model::canopen::cob::NmtState::Operational),
            other => Err(Error::Usage(format!("a CANopen encoder reports `operational`, not `{other}`"))),
        }
    }

    fn transcript(&self) -> serde_json::Value {
        let nodes: Vec<serde_json::Value> = self
            .nodes
            .iter()
            .zip(&self.names)
            .map(|(n, name)| serde_json::json!({ "name": name, "node": n.encoder().node(), "sent": n.sent().len(), "received": n.received().len(), "errors": n.can().errors() }))
            .collect();
        serde_json::json!({ "protocol": "canopen", "f_emu_hz": self.f_emu_hz, "encoders": nodes, "frames": self.entries, "violations": self.checks.all() })
    }

    fn checks(&mut self) -> &mut Checks {
        &mut self.checks
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ONE: &str = "[canopen]\nbit_rate_kbps = 1000\ntq_per_bit = 8\nsample_point = 0.75\n\
        [[canopen.encoders]]\nname = \"enc\"\nposition_m = 10\n[canopen.encoders.encoder]\nnode_switch = 5\nbit_rate_switch = 7\nraw_position = 321\n";

    /// A recessive master: the encoder's boot-up (0x85, no data) reaches the
    /// master's RXD; nobody acknowledges it, so it stays the only frame sent.
    #[test]
    fn the_boot_up_reaches_the_master() {
        let mut emu = CanopenEmulator::from_toml(ONE, "one.toml", 8_000_000).unwrap();
        let mut dominant = 0;
        for _ in 0..2000 {
            dominant += (emu.step(Pins(2)).0 & 1 == 0) as u32;
        }
        assert!(dominant > 5);
        assert_eq!(emu.count(), 0);
        assert_eq!(emu.last_value(32), Some(127), "pre-operational after its boot-up");
    }

    #[test]
    fn positions_and_bad_configurations() {
        let mut emu = CanopenEmulator::from_toml(ONE, "one.toml", 8_000_000).unwrap();
        emu.set_position(0, 1000).unwrap();
        assert!(emu.set_position(0, 1 << 25).is_err());
        assert!(emu.set_position(3, 1).is_err());
        assert!(emu.set_status(0, "busy", true).is_err());
        let err = CanopenEmulator::from_toml("[canopen]\n", "c.toml", 8_000_000).err().unwrap().to_string();
        assert!(err.starts_with("c.toml: ") && err.contains("encoders"), "{err}");
    }
}
