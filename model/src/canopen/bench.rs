//! The core under test (`canopen_master`) on a CAN bus with DS 406 encoders
//! ([`EncoderNode`]), SAR58K24 CAN-mode encoders ([`DeviceNode`] of
//! [`SarCan`]) and an optional scripted node (a service tool). Implements
//! [`Setup`]/[`Testbench`] for `tbgen` (`[canopen]` of a scenario).
//!
//! ```text
//!  canopen_master (Master: can::Controller + state machine) ── bus (wired-AND, cable delays) ── encoders, SAR58K24s, tool
//!       │ i_can_rx                                                 
//!       └─ listen-only monitor at the same pin: every frame on the bus, for the transcript
//! ```
//!
//! The transcript has one transaction per pulse of the master (`booted`,
//! `config_done`, `sdo_abort`, `node_lost`, `pos_valid`, `pos_timeout`,
//! `emcy_valid`, `sync_sent`), each with the frames that ended at the
//! master's pin since the previous pulse, read as CANopen; frames after the
//! last pulse go with the last transaction.
//!
//! Fast-forward ([`Testbench::quiet_cycles`]): quiet while every receive
//! level holds and no part has anything due, as in the CAN bench: in bus
//! idle and within a frame, up to the next sample point, or bit end that
//! loads a new level, of any controller on the bus; the master's boot, SDO and PDO timeouts and SYNC
//! period ([`super::master::Master::quiet`]), each device's cyclic,
//! heartbeat, guarding or SAR58K24 cycle timer and queued answers
//! ([`super::node::DeviceNode::quiet`]), and the script's start pulses,
//! power-ons, alarms and fault windows. A SYNC gap or a cyclic TPDO period
//! goes in one skip (`docs/timing/canopen.md`). No bit clock is in the
//! samples, so nothing counts on through a skip.

use serde::{Deserialize, Serialize};

use super::encoder::EncoderConfig;
use super::interpret::interpret;
use super::master::{In, Master, MasterConfig, Out, Param};
use super::node::{DeviceNode, EncoderNode, NodeTiming};
use super::sar58k24::{SarCan, SarCanConfig};
use crate::can::bench::{steady_rx, undisturbed_rx, Disturber, Fault, OnBus, PinMonitor};
use crate::can::bus::{Bus, Place};
use crate::can::controller::State as CanState;
use crate::can::emulator::{Emulator, NodeSettings};
use crate::can::frame::{unpack, Frame};
use crate::ports::Port;
use crate::testbench::{self, Setup, Testbench};
use crate::trace::{Layout, Sample};
use crate::{ConfigError, Ports, Result, Timebase};

/// The master (`[canopen.master]`); times in µs become the RTL's cycle counts.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct MasterSettings {
    /// The encoder's node number, 1 to 127 (`NODE`).
    pub node: u8,
    /// SDO downloads, in order, at most 8 (`PARAMk_OBJECT`, `PARAMk_VALUE`).
    pub params: Vec<Param>,
    /// Wait for the boot-up before NMT reset node, µs (`BOOT_TIMEOUT`).
    pub boot_timeout_us: f64,
    /// Wait for an SDO answer before sending again, µs (`SDO_TIMEOUT`).
    pub sdo_timeout_us: f64,
    /// Timeouts tolerated before `o_node_lost` (`RETRIES`).
    pub retries: u32,
    /// No position for this long: `o_pos_timeout`, µs (`PDO_TIMEOUT`).
    pub pdo_timeout_us: f64,
    /// SYNC period, µs; 0: no SYNC (`SYNC_PERIOD`).
    pub sync_period_us: f64,
    /// Position along the cable, metres.
    pub position_m: f64,
    /// Transceiver loop delay, ns.
    pub loop_delay_ns: f64,
    /// `i_start` pulses, µs after reset (restart from WAIT_BOOT).
    pub start_us: Vec<f64>,
}

impl Default for MasterSettings {
    fn default() -> Self {
        MasterSettings {
            node: 1,
            params: Vec::new(),
            boot_timeout_us: 10_000.0,
            sdo_timeout_us: 5_000.0,
            retries: 2,
            pdo_timeout_us: 25_000.0,
            sync_period_us: 0.0,
            position_m: 0.0,
            loop_delay_ns: 150.0,
            start_us: Vec::new(),
        }
    }
}

/// One DS 406 encoder on the bus (`[[canopen.encoders]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct EncoderSettings {
    /// Name in the transcript.
    pub name: String,
    /// Position along the cable, metres.
    pub position_m: f64,
    /// Transceiver loop delay, ns.
    pub loop_delay_ns: f64,
    /// Oscillator offset, ppm.
    pub ppm: f64,
    /// Power-on, µs after the master's reset (its boot-up follows 11 recessive bits later).
    pub power_on_us: f64,
    /// An alarm (position error) raised at this time, µs: an emergency frame.
    pub alarm_at_us: Option<f64>,
    /// The encoder (`[canopen.encoders.encoder]`).
    pub encoder: EncoderConfig,
}

impl Default for EncoderSettings {
    fn default() -> Self {
        EncoderSettings {
            name: "encoder".into(),
            position_m: 10.0,
            loop_delay_ns: 150.0,
            ppm: 0.0,
            power_on_us: 0.0,
            alarm_at_us: None,
            encoder: EncoderConfig::default(),
        }
    }
}

impl EncoderSettings {
    fn node_settings(&self) -> NodeSettings {
        NodeSettings {
            name: self.name.clone(),
            position_m: self.position_m,
            loop_delay_ns: self.loop_delay_ns,
            ppm: self.ppm,
            ack: true,
            frames: Vec::new(),
        }
    }
}

/// One SAR58K24 in its CAN mode on the bus (`[[canopen.sar]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SarSettings {
    /// Name in the transcript.
    pub name: String,
    /// Position along the cable, metres.
    pub position_m: f64,
    /// Transceiver loop delay, ns.
    pub loop_delay_ns: f64,
    /// The encoder (`[canopen.sar.encoder]`).
    pub encoder: SarCanConfig,
}

impl Default for SarSettings {
    fn default() -> Self {
        SarSettings {
            name: "sar58k24".into(),
            position_m: 10.0,
            loop_delay_ns: 150.0,
            encoder: SarCanConfig::default(),
        }
    }
}

/// Everything a scenario says about a CANopen set-up (`[canopen]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BenchConfig {
    /// System clock, MHz.
    pub f_sys_mhz: f64,
    /// The master's bit rate, kbit/s (10, 20, 50, 125, 250, 500, 800 or 1000).
    pub bit_rate_kbps: u32,
    /// Time quanta per bit wanted (each node takes the next that divides f_sys).
    pub tq_per_bit: u32,
    /// Sample point, fraction of the bit.
    pub sample_point: f64,
    /// Synchronisation jump width, quanta.
    pub sjw: u32,
    /// Flops of each `i_can_rx` synchroniser (2 or 3).
    pub sync_stages: u32,
    /// Cable propagation delay, ns/m.
    pub ns_per_m: f64,
    /// The master.
    pub master: MasterSettings,
    /// DS 406 encoders.
    pub encoders: Vec<EncoderSettings>,
    /// SAR58K24 encoders in CAN mode.
    pub sar: Vec<SarSettings>,
    /// A scripted node (a service tool sending the frames it lists, at the master's bit rate).
    pub tool: Option<NodeSettings>,
    /// Bus faults (`[[canopen.faults]]`, as `[[can.faults]]`: a bit read
    /// inverted by `master`, `tool` or a named encoder, or the bus stuck dominant).
    pub faults: Vec<Fault>,
    /// Run at least this long, µs; the run ends once the bus is idle after it.
    pub run_us: f64,
}

impl Default for BenchConfig {
    fn default() -> Self {
        BenchConfig {
            f_sys_mhz: 40.0,
            bit_rate_kbps: 250,
            tq_per_bit: 16,
            sample_point: 0.875,
            sjw: 1,
            sync_stages: 2,
            ns_per_m: 5.0,
            master: MasterSettings::default(),
            encoders: Vec::new(),
            sar: Vec::new(),
            tool: None,
            faults: Vec::new(),
            run_us: 50_000.0,
        }
    }
}

impl BenchConfig {
    /// The bit timing rules of every node.
    pub fn node_timing(&self) -> NodeTiming {
        NodeTiming {
            tq_per_bit: self.tq_per_bit,
            sample_point: self.sample_point,
            sjw: self.sjw,
            sync_stages: self.sync_stages,
        }
    }

    /// The master's configuration (the Verilog parameters).
    pub fn master_config(&self) -> Result<MasterConfig> {
        let tb = self.timebase()?;
        if !super::encoder::BIT_RATES_KBPS.contains(&self.bit_rate_kbps) {
            return Err(ConfigError::invalid("bit_rate_kbps", format!("{}", self.bit_rate_kbps), "give one of the gateway's rates: 10, 20, 50, 125, 250, 500, 800, 1000 kbit/s (seed 003 §5.5)"));
        }
        if !(8..=25).contains(&self.tq_per_bit) {
            return Err(ConfigError::invalid(
                "tq_per_bit",
                format!("{}", self.tq_per_bit),
                "give 8 to 25 quanta per bit (Bosch CAN 2.0 part A §8)",
            ));
        }
        if !(0.5..0.95).contains(&self.sample_point) {
            return Err(ConfigError::invalid(
                "sample_point",
                format!("{}", self.sample_point),
                "give a sample point between 0.5 and 0.95",
            ));
        }
        let m = &self.master;
        let cycles = |field: &str, us: f64, zero_ok: bool| -> Result<u64> {
            if !(us.is_finite() && us >= 0.0 && (zero_ok || us > 0.0)) {
                return Err(ConfigError::invalid(
                    format!("master.{field}"),
                    format!("{us}"),
                    "give a time in µs above 0",
                ));
            }
            Ok(tb.cycles_nearest_ns(us * 1e3))
        };
        let c = MasterConfig {
            can: self.node_timing().controller(&tb, self.bit_rate_kbps)?,
            node: m.node,
            params: m.params.clone(),
            boot_timeout: cycles("boot_timeout_us", m.boot_timeout_us, false)?,
            sdo_timeout: cycles("sdo_timeout_us", m.sdo_timeout_us, false)?,
            retries: m.retries,
            pdo_timeout: cycles("pdo_timeout_us", m.pdo_timeout_us, false)?,
            sync_period: cycles("sync_period_us", m.sync_period_us, true)?,
        };
        c.validate()?;
        Ok(c)
    }

    /// The nodes in bus order: `master`, the encoders, the SAR58K24s, `tool`.
    fn node_names(&self) -> Vec<&str> {
        let mut v = vec!["master"];
        v.extend(self.encoders.iter().map(|e| e.name.as_str()));
        v.extend(self.sar.iter().map(|s| s.name.as_str()));
        if self.tool.is_some() {
            v.push("tool");
        }
        v
    }

    fn check(&self) -> Result<()> {
        self.master_config()?;
        if !(0.0..=50.0).contains(&self.ns_per_m) {
            return Err(ConfigError::invalid(
                "ns_per_m",
                format!("{}", self.ns_per_m),
                "give the cable delay in ns/m (5 for twisted pair)",
            ));
        }
        Place {
            position_m: self.master.position_m,
            loop_delay_ns: self.master.loop_delay_ns,
        }
        .validate("master")?;
        for (k, e) in self.encoders.iter().enumerate() {
            let f = format!("encoders[{k}]");
            e.encoder.validate(&format!("{f}.encoder"))?;
            e.node_settings().validate(&f)?;
            if !(e.power_on_us >= 0.0 && e.power_on_us < self.run_us) {
                return Err(ConfigError::invalid(
                    format!("{f}.power_on_us"),
                    format!("{}", e.power_on_us),
                    "give a power-on time from 0 to run_us",
                ));
            }
            if let Some(a) = e.alarm_at_us {
                if !(a > e.power_on_us && a < self.run_us) {
                    return Err(ConfigError::invalid(
                        format!("{f}.alarm_at_us"),
                        format!("{a}"),
                        "give a time after power_on_us and before run_us",
                    ));
                }
            }
        }
        for (k, s) in self.sar.iter().enumerate() {
            s.encoder.validate(&format!("sar[{k}].encoder"))?;
            Place {
                position_m: s.position_m,
                loop_delay_ns: s.loop_delay_ns,
            }
            .validate(&format!("sar[{k}]"))?;
        }
        if let Some(t) = &self.tool {
            t.validate("tool")?;
            for (k, s) in t.frames.iter().enumerate() {
                s.frame().validate(&format!("tool.frames[{k}]"))?;
            }
        }
        let names: Vec<&str> = self.node_names();
        Fault::validate_all(
            &self.faults,
            &names,
            "name `master`, `tool` or an encoder of [[canopen.encoders]] or [[canopen.sar]]",
        )?;
        for (k, &t) in self.master.start_us.iter().enumerate() {
            if !(t >= 0.0 && t < self.run_us) {
                return Err(ConfigError::invalid(
                    format!("master.start_us[{k}]"),
                    format!("{t}"),
                    "give a time from 0 to run_us",
                ));
            }
        }
        if !(1.0..=10_000_000.0).contains(&self.run_us) {
            return Err(ConfigError::invalid(
                "run_us",
                format!("{}", self.run_us),
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
        const OBJECT: [&str; 8] = [
            "PARAM0_OBJECT",
            "PARAM1_OBJECT",
            "PARAM2_OBJECT",
            "PARAM3_OBJECT",
            "PARAM4_OBJECT",
            "PARAM5_OBJECT",
            "PARAM6_OBJECT",
            "PARAM7_OBJECT",
        ];
        const VALUE: [&str; 8] = [
            "PARAM0_VALUE",
            "PARAM1_VALUE",
            "PARAM2_VALUE",
            "PARAM3_VALUE",
            "PARAM4_VALUE",
            "PARAM5_VALUE",
            "PARAM6_VALUE",
            "PARAM7_VALUE",
        ];
        let c = self.master_config()?;
        let t = c.can.timing;
        let mut p = vec![
            ("BRP", t.brp as u64),
            ("PROP_SEG", t.prop_seg as u64),
            ("PHASE_SEG1", t.phase_seg1 as u64),
            ("PHASE_SEG2", t.phase_seg2 as u64),
            ("SJW", t.sjw as u64),
            ("SYNC_STAGES", c.can.sync_stages as u64),
            ("NODE", c.node as u64),
            ("N_PARAMS", c.params.len() as u64),
        ];
        for (k, q) in c.params.iter().enumerate() {
            p.push((OBJECT[k], q.object_word() as u64));
            p.push((VALUE[k], q.value as u64));
        }
        p.extend([
            ("BOOT_TIMEOUT", c.boot_timeout),
            ("SDO_TIMEOUT", c.sdo_timeout),
            ("RETRIES", c.retries as u64),
            ("PDO_TIMEOUT", c.pdo_timeout),
            ("SYNC_PERIOD", c.sync_period),
        ]);
        Ok(p)
    }

    fn bench(&self) -> Result<Bench> {
        Bench::new(self)
    }
}

/// One frame on the bus as the listen-only receiver at the master's pin read it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BusFrame {
    /// Cycle of its SOF.
    pub sof_cycle: u64,
    /// Identifier.
    pub id: u32,
    /// DLC.
    pub dlc: u8,
    /// Data bytes.
    pub data: Vec<u8>,
    /// CRC sequence.
    pub crc: u16,
    /// ACK slot dominant.
    pub ack: bool,
    /// The frame reached its CRC delimiter without an error.
    pub complete: bool,
    /// Errors the receiver detected in it.
    pub errors: Vec<&'static str>,
    /// CANopen meaning (`model::canopen::interpret`).
    pub meaning: String,
}

/// One pulse of the master, with the frames since the previous one.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Transaction {
    /// 0-based.
    pub index: usize,
    /// `booted`, `config_done`, `sdo_abort`, `node_lost`, `pos_valid`, `pos_timeout`, `emcy_valid` or `sync_sent`.
    pub outcome: &'static str,
    /// First cycle: the first frame's SOF, or the cycle of the pulse.
    pub start_cycle: u64,
    /// Cycle of the pulse.
    pub cycle: u64,
    /// Master state after the pulse (`o_state`).
    pub state: u8,
    /// `o_position` (with `pos_valid`).
    pub position: Option<u32>,
    /// `o_abort_code`, `o_abort_index`, `o_abort_sub` (with `sdo_abort`).
    pub abort: Option<(u32, u16, u8)>,
    /// `o_emcy_code`, `o_emcy_reg` (with `emcy_valid`).
    pub emcy: Option<(u16, u8)>,
    /// Frames that ended at the master's pin since the previous transaction.
    pub frames: Vec<BusFrame>,
}

impl testbench::Transaction for Transaction {
    fn span(&self) -> (u64, u64) {
        (self.start_cycle, self.cycle)
    }
}

/// The master, the nodes and the bus.
pub struct Bench {
    master: Master,
    monitor: PinMonitor,
    encoders: Vec<(EncoderNode, u64, Option<u64>)>,
    sars: Vec<DeviceNode<SarCan>>,
    tool: Option<Emulator>,
    bus: Bus,
    disturbers: Vec<Disturber>,
    stuck: Vec<(u64, u64)>,
    starts: Vec<u64>,
    cycle: u64,
    run_cycles: u64,
    end: Option<u64>,
    cpb: u64,
    pending: Vec<BusFrame>,
    rx_buf: Vec<bool>,
    tx_buf: Vec<bool>,
    transactions: Vec<Transaction>,
    layout: Layout,
}

impl Bench {
    /// Node `j`'s receive level this cycle and for how long it holds ([`steady_rx`]).
    fn steady_rx(&self, j: usize) -> Option<(bool, u64)> {
        steady_rx(
            &self.bus,
            &self.stuck,
            &self.disturbers[j],
            j,
            self.cycle,
            self.cpb,
        )
    }

    /// A bench in its reset state.
    pub fn new(cfg: &BenchConfig) -> Result<Self> {
        cfg.check()?;
        let tb = cfg.timebase()?;
        let mc = cfg.master_config()?;
        let timing = cfg.node_timing();
        let mut places = vec![Place {
            position_m: cfg.master.position_m,
            loop_delay_ns: cfg.master.loop_delay_ns,
        }];
        let mut encoders = Vec::new();
        for e in &cfg.encoders {
            places.push(e.node_settings().place());
            let node = EncoderNode::new(&e.encoder, &e.node_settings(), timing, &tb)?;
            encoders.push((
                node,
                tb.cycles_nearest_ns(e.power_on_us * 1e3),
                e.alarm_at_us.map(|a| tb.cycles_nearest_ns(a * 1e3)),
            ));
        }
        let mut sars = Vec::new();
        for s in &cfg.sar {
            let settings = NodeSettings {
                name: s.name.clone(),
                position_m: s.position_m,
                loop_delay_ns: s.loop_delay_ns,
                ppm: 0.0,
                ack: true,
                frames: Vec::new(),
            };
            places.push(settings.place());
            sars.push(DeviceNode::with(
                SarCan::new(&s.encoder)?,
                &settings,
                timing,
                &tb,
            )?);
        }
        let tool = match &cfg.tool {
            Some(t) => {
                places.push(t.place());
                Some(Emulator::new(t, mc.can, &tb)?)
            }
            None => None,
        };
        let layout = Layout {
            inputs: Master::input_ports(),
            outputs: Master::output_ports(),
            line: vec![
                Port::new("can_rx", 1),
                Port::new("can_tx", 1),
                Port::new("bus_tx_nodes", 1),
            ],
            decoded: vec![
                Port::new("state", 3),
                Port::new("param", 4),
                Port::new("tries", 8),
                Port::new("can_state", 4),
                Port::new("monitor_state", 4),
            ],
        };
        Ok(Bench {
            cpb: mc.can.timing.clocks_per_bit(),
            master: Master::new(&mc)?,
            monitor: PinMonitor::new(mc.can)?,
            encoders,
            sars,
            tool,
            bus: Bus::new(&places, cfg.ns_per_m, &tb),
            disturbers: cfg
                .node_names()
                .iter()
                .map(|n| Disturber::new(&cfg.faults, n))
                .collect(),
            stuck: Disturber::stuck_windows(&cfg.faults, &tb),
            starts: cfg
                .master
                .start_us
                .iter()
                .map(|&t| tb.cycles_nearest_ns(t * 1e3))
                .collect(),
            cycle: 0,
            run_cycles: tb.cycles_nearest_ns(cfg.run_us * 1e3),
            end: None,
            pending: Vec::new(),
            rx_buf: Vec::new(),
            tx_buf: Vec::new(),
            transactions: Vec::new(),
            layout,
        })
    }

    /// The master's model.
    pub fn master(&self) -> &Master {
        &self.master
    }

    /// The DS 406 encoders.
    pub fn encoders(&self) -> impl Iterator<Item = &EncoderNode> {
        self.encoders.iter().map(|(e, _, _)| e)
    }

    fn close_frame(&mut self, f: OnBus) {
        if !f.active {
            return;
        }
        let n = crate::can::frame::data_len(f.seen.dlc, f.seen.rtr);
        let data = if f.complete {
            unpack(f.seen.data, n)
        } else {
            Vec::new()
        };
        let frame = Frame {
            id: f.seen.id,
            ide: f.seen.ide,
            rtr: f.seen.rtr,
            dlc: f.seen.dlc,
            data: data.clone(),
        };
        self.pending.push(BusFrame {
            sof_cycle: f.sof_cycle,
            id: f.seen.id,
            dlc: f.seen.dlc,
            meaning: if f.complete && f.errors.is_empty() {
                interpret(&frame).text
            } else {
                "damaged frame".into()
            },
            data,
            crc: f.seen.crc,
            ack: f.ack_passed && f.seen.ack,
            complete: f.complete,
            errors: f.errors,
        });
    }

    fn outcome(&mut self, outcome: &'static str, o: &Out) {
        let frames = std::mem::take(&mut self.pending);
        self.transactions.push(Transaction {
            index: self.transactions.len(),
            outcome,
            start_cycle: frames.first().map_or(self.cycle, |f| f.sof_cycle),
            cycle: self.cycle,
            state: o.o_state,
            position: (outcome == "pos_valid").then_some(o.o_position),
            abort: (outcome == "sdo_abort").then_some((
                o.o_abort_code,
                o.o_abort_index,
                o.o_abort_sub,
            )),
            emcy: (outcome == "emcy_valid").then_some((o.o_emcy_code, o.o_emcy_reg)),
            frames,
        });
    }
}

impl Testbench for Bench {
    crate::compiled_here!();

    type Transaction = Transaction;

    fn layout(&self) -> &Layout {
        &self.layout
    }

    fn step(&mut self, sample: Option<&mut Sample>) {
        let nodes = 1 + self.encoders.len() + self.sars.len() + self.tool.is_some() as usize;
        let mut rx = std::mem::take(&mut self.rx_buf);
        rx.clear();
        let stuck = self
            .stuck
            .iter()
            .any(|&(a, b)| (a..b).contains(&self.cycle));
        for j in 0..nodes {
            let level = self.bus.rx(j) && !stuck;
            rx.push(self.disturbers[j].step(level, self.cycle, self.cpb));
        }
        let input = In {
            i_start: self.starts.contains(&self.cycle),
            i_can_rx: rx[0],
        };
        let out = self.master.step(&input);
        let mut tx = std::mem::take(&mut self.tx_buf);
        tx.clear();
        tx.push(out.o_can_tx);
        let mut j = 1;
        for (e, power_on, alarm) in self.encoders.iter_mut() {
            if self.cycle < *power_on {
                tx.push(true);
            } else {
                if Some(self.cycle) == *alarm {
                    let now = e.time_ns();
                    let f = e.encoder_mut().set_alarm(true, now);
                    e.send(f);
                }
                tx.push(e.step(rx[j]));
            }
            j += 1;
        }
        for s in self.sars.iter_mut() {
            tx.push(s.step(rx[j]));
            j += 1;
        }
        if let Some(t) = self.tool.as_mut() {
            tx.push(t.step(rx[j]));
        }
        let nodes_tx = tx[1..].iter().all(|&t| t);
        self.bus.push(&tx);
        self.tx_buf = tx;
        // The listen-only receiver at the master's pin.
        let (m, before, now, replaced) = self.monitor.step(rx[0], self.cycle, false);
        if let Some(f) = replaced {
            self.close_frame(f);
        }
        // A frame ends where a receiver takes it (the cycle the master's
        // controller pulses o_rx_valid for it), or at an error.
        if m.o_rx_valid || (now == CanState::ErrFlag && before != CanState::ErrFlag) {
            let mut f = std::mem::take(&mut self.monitor.frame);
            if f.active && !f.complete {
                f.seen = self.monitor.controller().seen();
            }
            self.close_frame(f);
        }
        for (flag, name) in [
            (out.o_booted, "booted"),
            (out.o_config_done, "config_done"),
            (out.o_sdo_abort, "sdo_abort"),
            (out.o_node_lost, "node_lost"),
            (out.o_pos_valid, "pos_valid"),
            (out.o_pos_timeout, "pos_timeout"),
            (out.o_emcy_valid, "emcy_valid"),
            (out.o_sync_sent, "sync_sent"),
        ] {
            if flag {
                self.outcome(name, &out);
            }
        }
        let rx0 = rx[0];
        self.rx_buf = rx;
        self.cycle += 1;
        if self.end.is_none()
            && self.cycle >= self.run_cycles
            && !self.monitor.frame.active
            && matches!(now, CanState::Idle | CanState::Integrate | CanState::BusOff)
        {
            self.end = Some(self.cycle + self.cpb);
        }
        if self.end.is_none() && self.cycle >= 2 * self.run_cycles {
            self.end = Some(self.cycle);
        }
        let Some(sample) = sample else { return };
        input.write_values(&mut sample.inputs);
        out.write_values(&mut sample.outputs);
        sample
            .line
            .copy_from_slice(&[rx0 as u64, out.o_can_tx as u64, nodes_tx as u64]);
        sample.decoded.copy_from_slice(&[
            self.master.state() as u64,
            self.master.param_index() as u64 & 0xF,
            self.master.tries() as u64 & 0xFF,
            self.master.controller().state() as u64,
            self.monitor.controller().state() as u64,
        ]);
    }

    /// Quiet while no line and no node can change, on an idle bus and in
    /// a frame alike (as in the CAN bench): each node's receive level holds
    /// (the bus through its delay lines, the stuck and flip windows:
    /// [`steady_rx`]) and the master, the listen-only monitor and every
    /// powered node are quiet at that level ([`Master::quiet`],
    /// [`DeviceNode::quiet`], [`Emulator::quiet`]: in a frame, short of
    /// their next sample point, or bit end that loads a new level; their
    /// timers and queued frames not due). No start pulse, power-on or alarm
    /// ahead before then, and
    /// the run's end not decided within it (see the module docs).
    fn quiet_cycles(&self) -> u64 {
        let c = self.cycle;
        let Some((rx, steady)) = self.steady_rx(0) else {
            return 0;
        };
        let mut q = self
            .master
            .quiet(rx)
            .min(self.monitor.controller().quiet(rx));
        if q == 0 {
            return 0;
        }
        q = q.min(steady);
        q = match self.end {
            Some(e) => q.min(e - c),
            None => q.min(self.run_cycles.saturating_sub(c + 1)),
        };
        for &s in &self.starts {
            // The cycle after a start shows its pulse falling.
            if s + 1 == c {
                return 0;
            }
            if s >= c {
                q = q.min(s - c);
            }
        }
        // The nodes in bus order, as `step` reads their receive levels.
        let mut j = 1;
        for (e, power_on, alarm) in &self.encoders {
            let Some((rx, steady)) = self.steady_rx(j) else {
                return 0;
            };
            q = q.min(steady);
            if c < *power_on {
                q = q.min(power_on - c);
            } else {
                q = q.min(e.quiet(rx));
            }
            if let Some(a) = *alarm {
                if a >= c {
                    q = q.min(a - c);
                }
            }
            j += 1;
        }
        for s in &self.sars {
            let Some((rx, steady)) = self.steady_rx(j) else {
                return 0;
            };
            q = q.min(steady).min(s.quiet(rx));
            j += 1;
        }
        if let Some(t) = &self.tool {
            let Some((rx, steady)) = self.steady_rx(j) else {
                return 0;
            };
            q = q.min(steady).min(t.quiet(rx));
        }
        q
    }

    fn skip(&mut self, n: u64) {
        for j in 0..self.disturbers.len() {
            let level = undisturbed_rx(&self.bus, &self.stuck, j, self.cycle);
            self.disturbers[j].skip(n, level);
        }
        self.master.skip(n);
        self.monitor.skip(n);
        for (e, power_on, _) in &mut self.encoders {
            // Off until its power-on (a quiet stretch ends there): not stepped, not skipped.
            if self.cycle >= *power_on {
                e.skip(n);
            }
        }
        for s in &mut self.sars {
            s.skip(n);
        }
        if let Some(t) = self.tool.as_mut() {
            t.skip(n);
        }
        self.bus.skip(n);
        self.cycle += n;
    }

    fn finished(&self) -> bool {
        self.end.is_some_and(|e| self.cycle >= e)
    }

    fn cycle(&self) -> u64 {
        self.cycle
    }

    fn into_transactions(mut self) -> Vec<Transaction> {
        let f = std::mem::take(&mut self.monitor.frame);
        self.close_frame(f);
        let rest = std::mem::take(&mut self.pending);
        if let Some(last) = self.transactions.last_mut() {
            last.frames.extend(rest);
        }
        self.transactions
    }
}
