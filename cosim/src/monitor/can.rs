//! The CAN monitor: the master's transceiver pins, TXD as it drives it and
//! RXD (the wired-AND bus level at its receiver).
//!
//! Pins in: bit 0 RXD, bit 1 TXD. Frames are read off RXD by the decode core
//! of `tbgen decode can` ([`model::can::decode`]); a frame is the master's
//! when its TXD was dominant at the SOF's sample point and equal to the bus
//! at every sample point of the arbitration field (it did not lose
//! arbitration). CAN itself is not restated in the seeds (seed 003 §1.3
//! cites the Bosch CAN Specification 2.0, which the rules quote).
//!
//! The master is held to the CAN rule book ([`model::can::rules`]:
//! stuffing, CRC, form, intermission, bit time, dominant length), decided
//! by its watcher, which the CAN emulator feeds too: the same break draws
//! the same rule and words from both. Frames are final (judged, handed to
//! the transcript) once the bus has been idle for 10.5 bits after them; the
//! frames of the current window are decoded on demand for
//! `count`/`last_value` when complete.
//!
//! Configuration (a whole scenario file will do): `[can]` `f_sys_mhz`
//! (default: the monitor clock), `timing = { bit_rate_kbps, tq_per_bit,
//! sample_point, sjw }`; `[monitor]` (`[can.monitor]` in a scenario file)
//! `bit_tolerance_percent` (default the
//! oscillator tolerance the bit timing allows; 0 to 1.58 %) and
//! `max_dominant_bits` (6; 6 to 12), read by [`crate::can::limits`].

use serde_json::Value;

use model::can::rules::{self, Sampled, Seen};

use super::{listens_only, Base};
use crate::config::{self, Error};
use crate::{Emulator, Pins, Result};

/// A frame as the transcript shows it: `tbgen decode can`'s fields and `sender`.
pub fn json(s: &Seen) -> Value {
    let mut v = serde_json::to_value(&s.frame).unwrap_or(Value::Null);
    v["sender"] = Value::from(if s.by_master { "master" } else { "bus" });
    v
}

/// A rule book's watcher of a CAN master's pins: the CAN rules, and what a
/// higher layer adds on the frames.
pub trait Rules {
    /// One sample at `t_ps` of the bus at the master's RXD and its TXD.
    fn sample(&mut self, t_ps: u64, rx: bool, tx: bool) -> Sampled;
    /// The CAN watcher (the frames of its window).
    fn can(&self) -> &rules::Watch;
}

impl Rules for rules::Watch {
    fn sample(&mut self, t_ps: u64, rx: bool, tx: bool) -> Sampled {
        rules::Watch::sample(self, t_ps, rx, tx)
    }
    fn can(&self) -> &rules::Watch {
        self
    }
}

/// The CAN part every CAN-based monitor shares: the pins fed to a rule
/// book's watcher, what it reports, and the frames it hands back.
pub struct CanWatch<R: Rules> {
    /// Clock, violations, decoded frames (JSON).
    pub base: Base,
    rules: R,
    /// The last final frame.
    last: Option<Seen>,
    /// Intact frames and frames the master sent, final ones.
    intact: u64,
    sent: u64,
    /// A frame as the transcript shows it.
    describe: fn(&Seen) -> Value,
}

impl<R: Rules> CanWatch<R> {
    /// A watch at `base`'s clock feeding `rules`; `describe` gives a frame's transcript entry.
    pub fn new(mut base: Base, rules: R, describe: fn(&Seen) -> Value) -> Self {
        for note in model::rules::resolution_notes(base.f_mon_hz, &rules.can().limits().least()) {
            base.checks.note(note);
        }
        CanWatch {
            base,
            rules,
            last: None,
            intact: 0,
            sent: 0,
            describe,
        }
    }

    /// The limits of the CAN rules.
    pub fn limits(&self) -> &rules::Limits {
        self.rules.can().limits()
    }

    /// One monitor cycle; the frames that became final (bus idle after them), in order.
    pub fn step(&mut self, pins: Pins) -> Vec<Seen> {
        let now = self.base.exact_ps();
        let out = self.rules.sample(now, pins.0 & 1 != 0, pins.0 & 2 != 0);
        for b in &out.breaches {
            self.base.breach(b);
        }
        for s in &out.frames {
            self.base.done.push((self.describe)(s));
            self.intact += s.frame.error.is_none() as u64;
            self.sent += s.by_master as u64;
        }
        if let Some(s) = out.frames.last() {
            self.last = Some(s.clone());
        }
        out.frames
    }

    /// The frames of the window complete by now, judged (their breaches
    /// are reported when they are final).
    pub fn pending(&self) -> Vec<Seen> {
        self.rules.can().pending(self.base.exact_ps())
    }

    /// The last frame complete (pending or final).
    pub fn last(&self) -> Option<Seen> {
        self.pending().pop().or_else(|| self.last.clone())
    }

    /// Frames decoded so far (complete ones), intact frames, frames the master sent.
    pub fn counts(&self) -> (u64, u64, u64) {
        let p = self.pending();
        let intact = p.iter().filter(|s| s.frame.error.is_none()).count() as u64;
        let sent = p.iter().filter(|s| s.by_master).count() as u64;
        (
            self.base.done.len() as u64 + p.len() as u64,
            self.intact + intact,
            self.sent + sent,
        )
    }

    /// `last_value(field)` of the CAN monitors: 0 the last frame's data
    /// (first byte in bits 63..56, as `i_tx_data`), 1 its identifier, 2 its
    /// DLC, 3 intact frames so far, 4 frames the master sent.
    pub fn value(&self, field: usize) -> Option<u64> {
        let (_, intact, sent) = self.counts();
        match field {
            0 => Some(self.last()?.frame.frame().packed()),
            1 => Some(self.last()?.frame.id as u64),
            2 => Some(self.last()?.frame.dlc as u64),
            3 => Some(intact),
            4 => Some(sent),
            _ => None,
        }
    }

    /// `last_status(name)`: `rtr`, `ide`, `ack`, `error` (damaged), `master` (the master sent it) of the last frame.
    pub fn status(&self, kind: &str, name: &str) -> Result<bool> {
        let s = self
            .last()
            .ok_or_else(|| Error::Usage(format!("{kind}: no frame decoded yet")))?;
        match name {
            "rtr" => Ok(s.frame.rtr),
            "ide" => Ok(s.frame.ide),
            "ack" => Ok(s.frame.ack),
            "error" => Ok(s.frame.error.is_some()),
            "master" => Ok(s.by_master),
            other => Err(Error::Usage(format!("{kind}: no status `{other}`; give \"rtr\", \"ide\", \"ack\", \"error\" or \"master\""))),
        }
    }
}

/// The `[<proto>]` table without the tables the model's configuration does not know, and `f_sys_mhz` (default: the monitor clock).
pub fn model_table(whole: &toml::Table, f_mon_hz: u64) -> toml::Table {
    let mut t = whole.clone();
    for key in ["monitor", "emulator", "name", "description"] {
        t.remove(key);
    }
    t.entry("f_sys_mhz")
        .or_insert(toml::Value::Float(f_mon_hz as f64 / 1e6));
    t
}

/// A CAN monitor.
pub struct CanMonitor {
    watch: CanWatch<rules::Watch>,
}

impl CanMonitor {
    /// A monitor from TOML text (`origin` names it in errors) at `f_mon_hz`.
    pub fn from_toml(text: &str, origin: &str, f_mon_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "can")?;
        config::emulator_clock(
            f_mon_hz,
            &tables.emulator,
            crate::can::MAX_BIT_RATE_KHZ,
            "the CAN monitor",
            origin,
        )?;
        let limits = crate::can::limits(text, origin, f_mon_hz)?;
        Ok(CanMonitor {
            watch: CanWatch::new(Base::new(f_mon_hz), rules::Watch::new(limits), json),
        })
    }
}

impl Emulator for CanMonitor {
    fn kind(&self) -> &'static str {
        "can_monitor"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        self.watch.step(pins);
        self.watch.base.step_out()
    }

    fn set_position(&mut self, _: usize, _: u64) -> Result<()> {
        Err(listens_only("can_monitor", "position to set"))
    }

    fn set_status(&mut self, _: usize, _: &str, _: bool) -> Result<()> {
        Err(listens_only("can_monitor", "status to set"))
    }

    fn schedule_fault(&mut self, _: &str) -> Result<()> {
        Err(listens_only(
            "can_monitor",
            "frames to send or faults to schedule",
        ))
    }

    /// Frames seen so far (complete ones, damaged ones included).
    fn count(&self) -> u64 {
        self.watch.counts().0
    }

    /// `field`: 0 data, 1 identifier, 2 DLC of the last frame; 3 intact frames, 4 the master's frames.
    fn last_value(&self, field: usize) -> Option<u64> {
        self.watch.value(field)
    }

    fn last_status(&self, _: usize, name: &str) -> Result<bool> {
        self.watch.status("can_monitor", name)
    }

    fn transcript(&self) -> Value {
        let pending = self.watch.pending().iter().map(json).collect();
        self.watch.base.transcript("can", &["rx", "tx"], pending)
    }

    fn checks(&mut self) -> &mut crate::check::Checks {
        &mut self.watch.base.checks
    }
}
