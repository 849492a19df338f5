//! The CANopen monitor: the CAN monitor's pins and rules ([`super::can`])
//! and, on the frames it decodes, CANopen DS 301 / DS 406 (seed 003, the
//! Leine & Linde gateway) and the SAR58K24 CAN mode (seed 001 §3.4), each
//! frame read by `model::canopen::interpret` as `tbgen decode canopen`
//! reads it. The master's frames (see [`super::can`]) are held to:
//!
//! * SDO: one request outstanding per node (seed 003 §8 step 5: a request
//!   on 0x600 + node is confirmed on 0x580 + node; DS 301's SDO is a
//!   confirmed service): a request (not an abort) before the node answered
//!   the previous one and before `sdo_timeout_us` after its end
//!   (`[canopen.master] sdo_timeout_us`, `monitor.sdo_timeout_us`);
//! * NMT start: `01 <node>` (seed 003 §8 step 6) once; a second start of a
//!   node (or of all, `01 00`) with no stop, pre-operational, reset or
//!   boot-up of that node between is a master that lost its place;
//! * node guarding (DS 301; the seed lists the node-guard object only): once
//!   the master wrote a guard time (100Ch, or `monitor.guard_time_ms`) to a
//!   node and guards it (remote frames on 0x700 + node), each guard request
//!   within the guard time plus `guard_tolerance_percent` (10) plus one
//!   frame (160 bits: the bus may be busy); guarding a node the master gave
//!   a producer heartbeat time (1017h ≠ 0) is reported too (DS 301: one
//!   error control service per node; the gateway then ignores the request);
//! * SYNC period: when a period is configured (`[canopen.master]
//!   sync_period_us`, `monitor.sync_period_us`; the seed states none), each
//!   SYNC (0x80) within the period ± the bit-rate tolerance ± one frame;
//! * SAR58K24 commands (seed 001 §3.4 (3): each command is a request and its
//!   reply; the seed gives no spacing): a command on 0x200 + NN (not an RPDO
//!   of a DS 406 node) before the answer on `answer_base` + NN to the
//!   previous one, and an `11`/`13` on 0x7E5 before the 0x7E5 answer to the
//!   previous one, unless `sar_answer_timeout_us` (10 000) has passed.
//!
//! A heartbeat consumer sends nothing, so its timing is not visible on the
//! bus; the DS 406 gateway is the heartbeat producer, not the master.
//!
//! Configuration: the scenario's `[canopen]` table (`f_sys_mhz`,
//! `bit_rate_kbps`, `tq_per_bit`, `sample_point`, `sjw`, `[master]`,
//! `[[encoders]]`, `[[sar]]`), `[monitor]` with the CAN monitor's fields
//! and `sdo_timeout_us`, `sync_period_us`, `guard_time_ms`,
//! `guard_tolerance_percent`, `sar_answer_timeout_us`.

use std::collections::BTreeMap;

use serde::Deserialize;
use serde_json::Value;

use model::canopen::cob::{classify, Service};
use model::canopen::sar58k24::CONFIG_ID;

use super::can::{model_table, CanLimits, CanWatch, Seen, Timing};
use super::{limit, listens_only, proto_table, us, Base};
use crate::config::{self, Error};
use crate::{Emulator, Pins, Result};

/// The rules, as the seeds (and DS 301 where they are silent) state them.
pub const RULE_SDO: &str = "SDO (seed 003 §8 step 5: a request on 0x600 + node is confirmed on 0x580 + node; one request outstanding until its answer or the SDO timeout)";
/// See [`RULE_SDO`].
pub const RULE_NMT: &str = "NMT start (seed 003 §8 step 6: one NMT start remote node brings the node to operational; a second with no stop, reset or boot-up between)";
/// See [`RULE_SDO`].
pub const RULE_GUARD: &str = "node guarding (DS 301: the master guards each node at its guard time 100Ch; seed 003 §2.1 node guard 0x700 + node)";
/// See [`RULE_SDO`].
pub const RULE_GUARD_HEARTBEAT: &str = "node guarding (DS 301: one error control service per node; a node with a producer heartbeat time 1017h is not guarded)";
/// See [`RULE_SDO`].
pub const RULE_SYNC: &str =
    "SYNC period (the master's configured SYNC period, `sync_period_us`; the seeds state none)";
/// See [`RULE_SDO`].
pub const RULE_SAR: &str = "SAR58K24 command (seed 001 §3.4 (3): each command is answered; the next command to the node after the answer or the answer timeout)";

/// The monitor's own table (`[monitor]`), every field optional.
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

/// One node's state as the master's frames left it.
#[derive(Debug, Clone, Default)]
struct Node {
    /// End of the SDO request not yet answered.
    sdo: Option<u64>,
    started: bool,
    guard_ms: Option<f64>,
    heartbeat: bool,
    last_guard: Option<u64>,
    /// End of the SAR58K24 command not yet answered.
    sar: Option<u64>,
}

/// A CANopen monitor.
pub struct CanopenMonitor {
    watch: CanWatch,
    nodes: BTreeMap<u8, Node>,
    all_started: bool,
    sdo_timeout: u64,
    sync_period: u64,
    guard_ms: Option<f64>,
    guard_tol: f64,
    sar_timeout: u64,
    /// SAR58K24 answer bases; DS 406 nodes (their 0x200 + node is an RPDO).
    sar_bases: Vec<u16>,
    ds406: Vec<u8>,
    config_cmd: Option<u64>,
    last_sync: Option<u64>,
    last_position: Option<u64>,
}

fn le32(d: &[u8]) -> u64 {
    d.iter()
        .take(4)
        .enumerate()
        .fold(0, |a, (k, &b)| a | (b as u64) << (8 * k))
}

impl CanopenMonitor {
    /// A monitor from TOML text (`origin` names it in errors) at `f_mon_hz`.
    pub fn from_toml(text: &str, origin: &str, f_mon_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "canopen")?;
        config::emulator_clock(
            f_mon_hz,
            &tables.emulator,
            crate::canopen::MAX_BIT_RATE_KHZ,
            "the CANopen monitor",
            origin,
        )?;
        let whole = proto_table(text, origin, "canopen")?;
        let mon: MonitorTable = config::decode_in(&whole, "monitor", origin)?;
        let mut device = model_table(&whole, f_mon_hz);
        device.remove("tool");
        device.remove("faults");
        let bench: model::canopen::BenchConfig = config::decode(device, origin)?;
        let master = bench
            .master_config()
            .map_err(|e| Error::config(origin, e))?;
        let limits = CanLimits {
            bit_tolerance_percent: mon.bit_tolerance_percent,
            max_dominant_bits: mon.max_dominant_bits,
        };
        let t = Timing::new(&master.can.timing, bench.f_sys_mhz * 1e6, &limits, origin)?;
        let ps = |us: f64| (us * 1e6).round() as u64;
        let sdo = limit(
            origin,
            "monitor.sdo_timeout_us",
            mon.sdo_timeout_us.unwrap_or(bench.master.sdo_timeout_us),
            "give the master's SDO timeout in µs",
        )?;
        let sync = limit(
            origin,
            "monitor.sync_period_us",
            mon.sync_period_us.unwrap_or(bench.master.sync_period_us),
            "give the master's SYNC period in µs (0: not checked)",
        )?;
        let guard_tol = limit(
            origin,
            "monitor.guard_tolerance_percent",
            mon.guard_tolerance_percent.unwrap_or(10.0),
            "give the guard period's tolerance in %",
        )?;
        let guard_ms = match mon.guard_time_ms {
            Some(g) => Some(limit(
                origin,
                "monitor.guard_time_ms",
                g,
                "give the guard time in ms (0: guarding off)",
            )?),
            None => None,
        };
        let sar = limit(
            origin,
            "monitor.sar_answer_timeout_us",
            mon.sar_answer_timeout_us.unwrap_or(10_000.0),
            "give the time after which a SAR58K24 command counts as unanswered, in µs",
        )?;
        Ok(CanopenMonitor {
            watch: CanWatch::new(Base::new(f_mon_hz), t, CanopenMonitor::json),
            nodes: BTreeMap::new(),
            all_started: false,
            sdo_timeout: ps(sdo),
            sync_period: ps(sync),
            guard_ms,
            guard_tol: guard_tol / 100.0,
            sar_timeout: ps(sar),
            sar_bases: bench.sar.iter().map(|s| s.encoder.answer_base).collect(),
            ds406: bench
                .encoders
                .iter()
                .map(|e| e.encoder.node_switch)
                .collect(),
            config_cmd: None,
            last_sync: None,
            last_position: None,
        })
    }

    fn bits(&self, b: f64) -> u64 {
        (b * self.watch.timing().bit_ps) as u64
    }

    /// The CANopen rules on one final frame.
    fn on_frame(&mut self, s: &Seen) {
        let f = &s.frame;
        if f.error.is_some() || f.ide {
            return;
        }
        let (sof, end, d) = (f.sof_ps, s.end_ps, f.data.clone());
        let slack = self.bits(1.0) + 2 * self.watch.base.period_ps;
        let frame_time = self.bits(160.0);
        let mut found: Vec<(u64, &'static str, String)> = Vec::new();
        let service = classify(f.id as u16);
        if matches!(service, Service::Tpdo1(_) | Service::Tpdo2(_)) && d.len() >= 4 && !s.by_master
        {
            self.last_position = Some(le32(&d));
        }
        if !s.by_master {
            match service {
                Service::SdoTx(n) => self.nodes.entry(n).or_default().sdo = None,
                Service::NmtErr(n) if d == [0] => self.booted(n),
                Service::Emcy(n) if d.is_empty() && !f.rtr => self.booted(n),
                _ => {}
            }
            if f.id == CONFIG_ID {
                self.config_cmd = None;
            }
            for &b in &self.sar_bases {
                if let Some(n) = (f.id as u16)
                    .checked_sub(b)
                    .filter(|&n| (1..=0x7F).contains(&n))
                {
                    self.nodes.entry(n as u8).or_default().sar = None;
                }
            }
            return;
        }
        // The master's frame.
        match service {
            Service::SdoRx(n) if !f.rtr && d.len() == 8 => {
                let node = self.nodes.entry(n).or_default();
                let abort = d[0] >> 5 == 4;
                if let Some(prev) = node
                    .sdo
                    .filter(|&p| !abort && sof < p + self.sdo_timeout - slack.min(self.sdo_timeout))
                {
                    found.push((sof, RULE_SDO, format!("SDO request to node {n} {:.3} us after the end of the previous one, which node {n} has not answered; the SDO timeout is {:.3} us", us(sof - prev), us(self.sdo_timeout))));
                }
                node.sdo = (!abort).then_some(end);
                // Expedited downloads of the guard time and the producer heartbeat time.
                if d[0] & 0xE3 == 0x23 || d[0] == 0x22 {
                    let (index, subi) = (u16::from_le_bytes([d[1], d[2]]), d[3]);
                    let v = le32(&d[4..])
                        & if d[0] & 1 != 0 {
                            0xFFFF_FFFF >> (8 * ((d[0] >> 2) & 3))
                        } else {
                            0xFFFF_FFFF
                        };
                    match (index, subi) {
                        (0x100C, 0) => node.guard_ms = Some(v as f64),
                        (0x1017, 0) => node.heartbeat = v != 0,
                        _ => {}
                    }
                }
            }
            Service::Nmt if d.len() >= 2 && !f.rtr => {
                let (cmd, n) = (d[0], d[1]);
                if cmd == 0x01 {
                    let again = self.all_started
                        || if n == 0 {
                            self.nodes.values().any(|x| x.started)
                        } else {
                            self.nodes.get(&n).is_some_and(|x| x.started)
                        };
                    if again {
                        found.push((
                            sof,
                            RULE_NMT,
                            format!(
                                "NMT start ({}) while {} already started by the master",
                                if n == 0 {
                                    "all nodes".into()
                                } else {
                                    format!("node {n}")
                                },
                                if n == 0 {
                                    "a node was".to_string()
                                } else {
                                    format!("node {n} was")
                                }
                            ),
                        ));
                    }
                    if n == 0 {
                        self.all_started = true;
                    } else {
                        self.nodes.entry(n).or_default().started = true;
                    }
                } else if matches!(cmd, 0x02 | 0x80 | 0x81 | 0x82) {
                    if n == 0 {
                        self.all_started = false;
                        self.nodes.values_mut().for_each(|x| x.started = false);
                    } else {
                        self.nodes.entry(n).or_default().started = false;
                    }
                }
            }
            Service::NmtErr(n) if f.rtr => {
                let default = self.guard_ms;
                let node = self.nodes.entry(n).or_default();
                if node.heartbeat {
                    found.push((sof, RULE_GUARD_HEARTBEAT, format!("a guard request to node {n}, whose producer heartbeat time the master set (1017h)")));
                }
                let guard = default.or(node.guard_ms).unwrap_or(0.0);
                if let Some(prev) = node.last_guard.filter(|_| guard > 0.0) {
                    let most = (guard * 1e9 * (1.0 + self.guard_tol)) as u64 + frame_time;
                    if sof - prev > most {
                        found.push((sof, RULE_GUARD, format!("guard request to node {n} {:.3} ms after the previous one; the guard time is {guard} ms", (sof - prev) as f64 / 1e9)));
                    }
                }
                node.last_guard = Some(sof);
            }
            Service::Sync if d.is_empty() && !f.rtr && self.sync_period > 0 => {
                if let Some(prev) = self.last_sync {
                    let gap = sof - prev;
                    let tol = (self.sync_period as f64 * self.watch.timing().tolerance) as u64
                        + frame_time
                        + slack;
                    if gap + tol < self.sync_period || gap > self.sync_period + tol {
                        found.push((
                            sof,
                            RULE_SYNC,
                            format!(
                                "SYNC {:.3} us after the previous one; the period is {:.3} us",
                                us(gap),
                                us(self.sync_period)
                            ),
                        ));
                    }
                }
                self.last_sync = Some(sof);
            }
            _ => {}
        }
        if !self.sar_bases.is_empty() && !f.rtr {
            if f.id == CONFIG_ID && matches!(d.first(), Some(0x11 | 0x13)) {
                if let Some(prev) = self.config_cmd.filter(|&p| sof < p + self.sar_timeout) {
                    found.push((sof, RULE_SAR, format!("configuration command {:02X} on 0x7E5 {:.3} us after the previous one, not answered yet", d[0], us(sof - prev))));
                }
                self.config_cmd = Some(end);
            }
            let nn = f.id.wrapping_sub(0x200);
            if (1..=0x7F).contains(&nn) && !self.ds406.contains(&(nn as u8)) {
                let node = self.nodes.entry(nn as u8).or_default();
                if let Some(prev) = node.sar.filter(|&p| sof < p + self.sar_timeout) {
                    found.push((sof, RULE_SAR, format!("command {:02X} to SAR58K24 node {nn:#04x} {:.3} us after the previous one, not answered yet", d.first().copied().unwrap_or(0), us(sof - prev))));
                }
                node.sar = Some(end);
            }
        }
        for (t, rule, detail) in found {
            self.watch.base.violation(t, rule, detail);
        }
    }

    fn booted(&mut self, n: u8) {
        let node = self.nodes.entry(n).or_default();
        node.started = false;
        node.sdo = None;
        node.last_guard = None;
        node.heartbeat = false;
        node.guard_ms = None;
        self.all_started = false;
    }

    fn json(s: &Seen) -> Value {
        let mut v = s.json();
        if s.frame.error.is_none() {
            let m = model::canopen::interpret::interpret(&s.frame.frame());
            v["service"] = serde_json::to_value(m.service).unwrap_or(Value::Null);
            v["meaning"] = Value::from(m.text);
        } else {
            v["service"] = Value::Null;
            v["meaning"] = Value::from(format!(
                "damaged frame ({})",
                s.frame.error.as_deref().unwrap_or("")
            ));
        }
        v
    }
}

impl Emulator for CanopenMonitor {
    fn kind(&self) -> &'static str {
        "canopen_monitor"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        for s in self.watch.step(pins) {
            self.on_frame(&s);
        }
        self.watch.base.step_out()
    }

    fn set_position(&mut self, _: usize, _: u64) -> Result<()> {
        Err(listens_only("canopen_monitor", "position to set"))
    }

    fn set_status(&mut self, _: usize, _: &str, _: bool) -> Result<()> {
        Err(listens_only("canopen_monitor", "status to set"))
    }

    fn schedule_fault(&mut self, _: &str) -> Result<()> {
        Err(listens_only(
            "canopen_monitor",
            "frames to send or faults to schedule",
        ))
    }

    /// Frames seen so far (complete ones, damaged ones included).
    fn count(&self) -> u64 {
        self.watch.counts().0
    }

    /// `field`: 0 data, 1 identifier, 2 DLC of the last frame; 3 intact
    /// frames, 4 the master's frames; 5 the position (bytes 0..3 little
    /// endian) of the last TPDO1/TPDO2 another node sent.
    fn last_value(&self, field: usize) -> Option<u64> {
        if field == 5 {
            let pending = self.watch.pending().into_iter().rev().find(|s| {
                !s.by_master
                    && s.frame.error.is_none()
                    && !s.frame.ide
                    && matches!(
                        classify(s.frame.id as u16),
                        Service::Tpdo1(_) | Service::Tpdo2(_)
                    )
                    && s.frame.data.len() >= 4
            });
            return pending.map(|s| le32(&s.frame.data)).or(self.last_position);
        }
        self.watch.value(field)
    }

    fn last_status(&self, _: usize, name: &str) -> Result<bool> {
        self.watch.status("canopen_monitor", name)
    }

    fn transcript(&self) -> Value {
        let pending = self
            .watch
            .pending()
            .iter()
            .map(CanopenMonitor::json)
            .collect();
        self.watch
            .base
            .transcript("canopen", &["rx", "tx"], pending)
    }

    fn checks(&mut self) -> &mut crate::check::Checks {
        &mut self.watch.base.checks
    }
}
