//! The CANopen master's rules (seed 003, the Leine & Linde DS 406 gateway;
//! seed 001 §3.4, the SAR58K24 CAN mode), in the shape of
//! [`crate::rules`]: the order of the master's frames, read off the bus by
//! the CAN watcher ([`crate::can::rules::Watch`], whose rules a CANopen
//! master is held to as well) and judged one final frame at a time:
//!
//! * [`SDO`]: one request outstanding per node: a request (not an abort)
//!   before the node answered the previous one and before the SDO timeout
//!   after that request's end;
//! * [`NMT`]: a second NMT start of a node (or of all) with no stop,
//!   pre-operational, reset or boot-up of it between;
//! * [`GUARD`]: once the master wrote a guard time (100Ch, or
//!   `monitor.guard_time_ms`) to a node and guards it, each guard request
//!   within the guard time plus `guard_tolerance_percent` plus one frame
//!   (160 bits: the bus may be busy);
//! * [`GUARD_HEARTBEAT`]: no guard request to a node whose producer
//!   heartbeat time (1017h) the master set;
//! * [`SYNC`]: when a period is configured, each SYNC within the period ±
//!   the oscillator tolerance ± one frame;
//! * [`SAR`]: a SAR58K24 command before the answer to the previous one (or
//!   before the answer timeout).
//!
//! A heartbeat consumer sends nothing, so its timing is not visible on the
//! bus; the DS 406 gateway is the heartbeat producer, not the master.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use super::cob::{classify, Service};
use super::sar58k24::CONFIG_ID;
use crate::can::rules::{self as can, Seen};
use crate::rules::{Bound, Breach, Rule};

/// A second SDO request before the answer.
pub static SDO: Rule = Rule {
    protocol: "canopen",
    name: "SDO",
    section: "seed 003 §8 step 5",
    seed_words: "we need to send an SDO request message (ID = 1536 + Gateway address) ... The Gateway will confirm with the SDO response message (ID = 1408 + Gateway address)",
    quantity: "a request on 0x600 + node is confirmed on 0x580 + node; one request outstanding until its answer or the SDO timeout",
    bound: Bound::Form,
    measured: "the SOF of the master's SDO request (8 bytes on 0x600 + node, not an abort) against the end of its previous one to that node, unanswered: at least the SDO timeout (`monitor.sdo_timeout_us`, else `[canopen.master] sdo_timeout_us`) after it",
    reading: "one request outstanding is the house's reading of a confirmed service (the seed shows one request and its confirmation); the timeout is the master's own, the seed states none",
    settable: None,
    label: OnceLock::new(),
};

/// A second NMT start.
pub static NMT: Rule = Rule {
    protocol: "canopen",
    name: "NMT start",
    section: "seed 003 §8 step 6",
    seed_words: "To get the Gateway in operation we need to send an NMT \"start remote node\" message, ID = 0, two data bytes ... The Gateway has now entered the operational state",
    quantity: "one NMT start remote node brings the node to operational; a second with no stop, reset or boot-up between",
    bound: Bound::Form,
    measured: "each NMT start (01 <node>, or 01 00 for all) the master sends, against the starts, stops (02), pre-operational (80), resets (81, 82) and boot-ups (an empty frame on 0x80 + node, or 00 on 0x700 + node) before it",
    reading: "the seed starts a node once; a second start of a started node is read as a master that lost its place",
    settable: None,
    label: OnceLock::new(),
};

/// A guard request late.
pub static GUARD: Rule = Rule {
    protocol: "canopen",
    name: "node guarding",
    section: "seed 003 §2.1 (Nodeguard 1793 - 1919); CiA DS 301",
    seed_words: "Nodeguard 1110 1793 – 1919",
    quantity: "the master guards each node at its guard time 100Ch",
    bound: Bound::Form,
    measured: "the SOF of each guard request (a remote frame on 0x700 + node) to the SOF of the previous one: at most the guard time (100Ch as the master wrote it, or `monitor.guard_time_ms`) x (1 + `guard_tolerance_percent`, 10 %) plus 160 bits",
    reading: "the seed lists the node-guard identifiers only; the guard time object 100Ch and its meaning are CiA DS 301's (cited by seed 003 §1.3, not a seed: no clause of it is cited, none could be checked)",
    settable: None,
    label: OnceLock::new(),
};

/// Guarding a node that produces heartbeats.
pub static GUARD_HEARTBEAT: Rule = Rule {
    protocol: "canopen",
    name: "guarding with heartbeat",
    section: "seed 003 §2.1; CiA DS 301",
    seed_words: "Nodeguard 1110 1793 – 1919",
    quantity: "one error control service per node; a node with a producer heartbeat time 1017h is not guarded",
    bound: Bound::Form,
    measured: "a guard request (a remote frame on 0x700 + node) after the master wrote a producer heartbeat time other than 0 to the node (1017h), with no boot-up of it between",
    reading: "DS 301 (not a seed; no clause cited, none checked) gives a node one error control service, guarding or heartbeat; the gateway then ignores the guard request",
    settable: None,
    label: OnceLock::new(),
};

/// A SYNC off its period.
pub static SYNC: Rule = Rule {
    protocol: "canopen",
    name: "SYNC period",
    section: "seed 003 §2.1 (SYNC 128)",
    seed_words: "SYNC 0001 128 0",
    quantity: "the master's configured SYNC period, `sync_period_us`; the seeds state none",
    bound: Bound::Form,
    measured: "the SOF of each SYNC (an empty frame on 0x80) to the SOF of the previous one, when a period is configured (`monitor.sync_period_us`, else `[canopen.master] sync_period_us`): within the period ± (period x the CAN oscillator tolerance + 160 bits)",
    reading: "the seed gives the SYNC identifier only; the period is the master's configuration, held within the oscillator tolerance and one frame the bus may be busy with",
    settable: None,
    label: OnceLock::new(),
};

/// A SAR58K24 command before the answer.
pub static SAR: Rule = Rule {
    protocol: "canopen",
    name: "SAR58K24 command",
    section: "seed 001 §3.4 (3)",
    seed_words: "transmit by radio : 2NN 80 NN 0 0 0 0 0 0 Click the NN encoder / reply : 1NN Low octaves Eight high notes ...",
    quantity: "each command is answered; the next command to the node after the answer or the answer timeout",
    bound: Bound::Form,
    measured: "the SOF of a command on 0x200 + NN (not an RPDO of a DS 406 node) or an 11/13 on 0x7E5 against the end of the previous one, unanswered (on the answer base + NN, or 0x7E5): at least `monitor.sar_answer_timeout_us` (10 000) after it",
    reading: "the seed gives each command with its reply and no spacing; one command outstanding is the house's reading",
    settable: None,
    label: OnceLock::new(),
};

/// The CANopen rules, in the order of a session.
pub static RULES: &[&Rule] = &[&SDO, &NMT, &GUARD, &GUARD_HEARTBEAT, &SYNC, &SAR];

/// The limits in force.
#[derive(Debug, Clone, PartialEq)]
pub struct Limits {
    /// The CAN rules' limits.
    pub can: can::Limits,
    /// The master's SDO timeout, ps.
    pub sdo_timeout_ps: u64,
    /// The SYNC period, ps (0: not checked).
    pub sync_period_ps: u64,
    /// A guard time for every node, ms (`None`: as the master writes 100Ch).
    pub guard_ms: Option<f64>,
    /// The guard period's tolerance, a fraction.
    pub guard_tolerance: f64,
    /// The time after which a SAR58K24 command counts as unanswered, ps.
    pub sar_timeout_ps: u64,
    /// The SAR58K24s' answer bases (none: no SAR58K24 on the bus).
    pub sar_bases: Vec<u16>,
    /// The DS 406 nodes (their 0x200 + node is an RPDO, not a command).
    pub ds406: Vec<u8>,
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

/// The CANopen watcher: the CAN watcher and the order of the master's frames.
#[derive(Debug, Clone)]
pub struct Watch {
    can: can::Watch,
    limits: Limits,
    nodes: BTreeMap<u8, Node>,
    all_started: bool,
    config_cmd: Option<u64>,
    last_sync: Option<u64>,
}

fn le32(d: &[u8]) -> u64 {
    d.iter()
        .take(4)
        .enumerate()
        .fold(0, |a, (k, &b)| a | (b as u64) << (8 * k))
}

impl Watch {
    /// A watcher holding the master to `limits`.
    pub fn new(limits: Limits) -> Self {
        Watch {
            can: can::Watch::new(limits.can),
            limits,
            nodes: BTreeMap::new(),
            all_started: false,
            config_cmd: None,
            last_sync: None,
        }
    }

    /// The CAN watcher inside.
    pub fn can(&self) -> &can::Watch {
        &self.can
    }

    /// One sample at `t_ps` (as [`can::Watch::sample`]): the CAN rules, then
    /// the CANopen rules on each frame that became final.
    pub fn sample(&mut self, t_ps: u64, rx: bool, tx: bool) -> can::Sampled {
        let mut out = self.can.sample(t_ps, rx, tx);
        for s in &out.frames {
            self.on_frame(s, &mut out.breaches);
        }
        out
    }

    fn bits(&self, b: f64) -> u64 {
        (b * self.limits.can.bit_ps) as u64
    }

    /// The CANopen rules on one final frame.
    fn on_frame(&mut self, s: &Seen, found: &mut Vec<Breach>) {
        let f = &s.frame;
        if f.error.is_some() || f.ide {
            return;
        }
        let (sof, end, d) = (f.sof_ps, s.end_ps, f.data.as_slice());
        let frame_time = self.bits(160.0);
        let us = crate::rules::us;
        let service = classify(f.id as u16);
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
            for &b in &self.limits.sar_bases {
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
                let timeout = self.limits.sdo_timeout_ps;
                let node = self.nodes.entry(n).or_default();
                let abort = d[0] >> 5 == 4;
                if let Some(prev) = node.sdo.filter(|&p| !abort && sof < p + timeout) {
                    found.push(SDO.breach(sof, format!("SDO request to node {n} {:.3} us after the end of the previous one, which node {n} has not answered; the SDO timeout is {:.3} us", us(sof - prev), us(timeout))));
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
                        let (who, was) = if n == 0 {
                            ("all nodes".to_string(), "a node was".to_string())
                        } else {
                            (format!("node {n}"), format!("node {n} was"))
                        };
                        found.push(NMT.breach(
                            sof,
                            format!("NMT start ({who}) while {was} already started by the master"),
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
                let (default, tol) = (self.limits.guard_ms, self.limits.guard_tolerance);
                let node = self.nodes.entry(n).or_default();
                if node.heartbeat {
                    found.push(GUARD_HEARTBEAT.breach(sof, format!("a guard request to node {n}, whose producer heartbeat time the master set (1017h)")));
                }
                let guard = default.or(node.guard_ms).unwrap_or(0.0);
                if let Some(prev) = node.last_guard.filter(|_| guard > 0.0) {
                    let most = (guard * 1e9 * (1.0 + tol)) as u64 + frame_time;
                    if sof - prev > most {
                        found.push(GUARD.breach(sof, format!("guard request to node {n} {:.3} ms after the previous one; the guard time is {guard} ms, at most {:.3} ms with the tolerance and one frame", (sof - prev) as f64 / 1e9, most as f64 / 1e9)));
                    }
                }
                node.last_guard = Some(sof);
            }
            Service::Sync if d.is_empty() && !f.rtr && self.limits.sync_period_ps > 0 => {
                let period = self.limits.sync_period_ps;
                if let Some(prev) = self.last_sync {
                    let gap = sof - prev;
                    let tol = (period as f64 * self.limits.can.tolerance) as u64 + frame_time;
                    if gap + tol < period || gap > period + tol {
                        found.push(SYNC.breach(
                            sof,
                            format!(
                                "SYNC {:.3} us after the previous one; the period is {:.3} us, within {:.3} us",
                                us(gap),
                                us(period),
                                us(tol)
                            ),
                        ));
                    }
                }
                self.last_sync = Some(sof);
            }
            _ => {}
        }
        if !self.limits.sar_bases.is_empty() && !f.rtr {
            let timeout = self.limits.sar_timeout_ps;
            if f.id == CONFIG_ID && matches!(d.first(), Some(0x11 | 0x13)) {
                if let Some(prev) = self.config_cmd.filter(|&p| sof < p + timeout) {
                    found.push(SAR.breach(sof, format!("configuration command {:02X} on 0x7E5 {:.3} us after the previous one, not answered yet", d[0], us(sof - prev))));
                }
                self.config_cmd = Some(end);
            }
            let nn = f.id.wrapping_sub(0x200);
            if (1..=0x7F).contains(&nn) && !self.limits.ds406.contains(&(nn as u8)) {
                let node = self.nodes.entry(nn as u8).or_default();
                if let Some(prev) = node.sar.filter(|&p| sof < p + timeout) {
                    found.push(SAR.breach(sof, format!("command {:02X} to SAR58K24 node {nn:#04x} {:.3} us after the previous one, not answered yet", d.first().copied().unwrap_or(0), us(sof - prev))));
                }
                node.sar = Some(end);
            }
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
}
