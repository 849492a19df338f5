//! The CAN monitor: the master's transceiver pins, TXD as it drives it and
//! RXD (the wired-AND bus level at its receiver).
//!
//! Pins in: bit 0 RXD, bit 1 TXD. Frames are read off RXD by the decode core
//! of `tbgen decode can` ([`model::can::decode`]); a frame is the master's
//! when its TXD was dominant at the SOF's sample point and equal to the bus
//! at every sample point of the stuffed part (it did not lose arbitration).
//! CAN itself is not restated in the seeds (`../shared/protocols.md`: "read
//! its public descriptions"); the rules are ISO 11898-1's (classical CAN)
//! as `docs/timing/can.md` cites them, each measured at the master's pins:
//!
//! * stuffing: in a frame the master transmits, never six equal bits from
//!   SOF to the CRC's last bit (the bus parser's stuff error at a bit the
//!   master drove);
//! * form: the master's TXD recessive in the CRC delimiter, the ACK
//!   delimiter and the seven EOF bits of every intact frame, and in the ACK
//!   slot of its own (a receiver's ACK is dominant there);
//! * intermission: the master's SOF only after 11 recessive bits on the bus
//!   (ACK delimiter and EOF, or error delimiter, then 3 of intermission),
//!   less the propagation segment (the round trip the bus's last edge may
//!   have come late by) and the bit-rate tolerance; a dominant TXD after
//!   fewer than 7.5 recessive bits is a bit inside a frame, not a SOF;
//! * bit time: every TXD edge of a frame the master transmits on the bit
//!   grid of its SOF at the configured bit rate, within `tolerance × time
//!   since the SOF` plus one SJW (and one more per resynchronising edge
//!   another node drove while the master sent recessive) plus two monitor
//!   cycles;
//! * dominant length: TXD never dominant longer than an error flag (6 bits,
//!   `monitor.max_dominant_bits`) plus the tolerance.
//!
//! A frame with a bit-time violation is not also judged for stuffing and
//! form (its bits were sampled off the master's grid). Frames are final
//! (judged, handed to the transcript) once the bus has been idle for 10.5
//! bits after them; the frames of the current window are decoded on demand
//! for `count`/`last_value` when complete.
//!
//! Configuration (a whole scenario file will do): `[can]` `f_sys_mhz`
//! (default: the monitor clock), `timing = { bit_rate_kbps, tq_per_bit,
//! sample_point, sjw }`; `[monitor]` `bit_tolerance_percent` (default the
//! oscillator tolerance the bit timing allows, ISO 11898-1 as derived by
//! Hartwig and Bassemir), `max_dominant_bits` (6).

use serde::Deserialize;
use serde_json::Value;

use model::can::decode::{self, Decoded};
use model::can::BitTiming;
use model::wire::Signal;

use super::{limit, listens_only, proto_table, us, Base};
use crate::config::{self, Error};
use crate::{Emulator, Pins, Result};

/// The rules (ISO 11898-1; the seeds do not restate CAN).
pub const RULE_STUFF: &str = "stuffing (ISO 11898-1 10.5: after five equal bits from SOF to the CRC's end the transmitter inserts one of the other level)";
/// See [`RULE_STUFF`].
pub const RULE_FORM: &str = "form (ISO 11898-1 10.4: CRC delimiter, ACK delimiter and EOF recessive; the transmitter's ACK slot recessive)";
/// See [`RULE_STUFF`].
pub const RULE_INTERMISSION: &str = "intermission (ISO 11898-1 10.4.5: 3 recessive bits after EOF or an error delimiter before a SOF, 11 in all)";
/// See [`RULE_STUFF`].
pub const RULE_BIT_TIME: &str = "bit time (ISO 11898-1 11.3: the transmitter's edges on the nominal bit time of the configured bit rate, within the oscillator tolerance and SJW)";
/// See [`RULE_STUFF`].
pub const RULE_DOMINANT: &str =
    "dominant length (ISO 11898-1 10.4.4: no dominant level longer than an error flag, 6 bits)";

/// The monitor's own table (`[monitor]`), every field optional; the CANopen
/// monitor adds its own fields, which the CAN part ignores.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CanLimits {
    /// Bit-rate tolerance of the master's edges, % (default: the oscillator tolerance of the timing).
    pub bit_tolerance_percent: Option<f64>,
    /// Longest dominant TXD, bits.
    pub max_dominant_bits: Option<f64>,
}

/// The timing the watch holds the master to, ps.
#[derive(Debug, Clone, Copy)]
pub struct Timing {
    /// One nominal bit.
    pub bit_ps: f64,
    /// Sample point, fraction of the bit.
    pub sample_point: f64,
    /// SJW.
    pub sjw_ps: f64,
    /// Propagation segment.
    pub prop_ps: f64,
    /// Drift allowed per ps.
    pub tolerance: f64,
    /// Longest dominant TXD, bits.
    pub max_dominant_bits: f64,
}

impl Timing {
    /// The timing of `t` at `f_sys_hz`, with the `[monitor]` limits.
    pub fn new(t: &BitTiming, f_sys_hz: f64, limits: &CanLimits, origin: &str) -> Result<Timing> {
        let tq = t.brp as f64 * 1e12 / f_sys_hz;
        let tol = limits
            .bit_tolerance_percent
            .unwrap_or(100.0 * t.oscillator_tolerance());
        if !(0.0..=10.0).contains(&tol) {
            return Err(Error::field(
                origin,
                "monitor.bit_tolerance_percent",
                format!("{tol}"),
                "give 0 to 10 %",
            ));
        }
        let dom = limit(
            origin,
            "monitor.max_dominant_bits",
            limits.max_dominant_bits.unwrap_or(6.0),
            "give the longest dominant level in bits (an error flag: 6)",
        )?;
        Ok(Timing {
            bit_ps: tq * t.ntq() as f64,
            sample_point: t.sample_point(),
            sjw_ps: tq * t.sjw as f64,
            prop_ps: tq * t.prop_seg as f64,
            tolerance: tol / 100.0,
            max_dominant_bits: dom,
        })
    }
}

/// A frame the watch judged.
#[derive(Debug, Clone)]
pub struct Seen {
    /// The decoded frame.
    pub frame: Decoded,
    /// The master transmitted it.
    pub by_master: bool,
    /// Its end (last bit read), ps.
    pub end_ps: u64,
}

impl Seen {
    /// The frame as the transcript shows it: `tbgen decode can`'s fields and `sender`.
    pub fn json(&self) -> Value {
        let mut v = serde_json::to_value(&self.frame).unwrap_or(Value::Null);
        v["sender"] = Value::from(if self.by_master { "master" } else { "bus" });
        v
    }
}

/// The CAN part every CAN-based monitor shares: the pins, the streaming
/// rules (intermission, dominant length) and the frame rules (stuffing,
/// form, bit time) on each decoded frame.
pub struct CanWatch {
    /// Clock, violations, decoded frames (JSON).
    pub base: Base,
    t: Timing,
    rx: Signal,
    tx: Signal,
    rx_level: bool,
    rx_rise: u64,
    tx_level: bool,
    tx_fall: u64,
    dominant_reported: bool,
    /// The window holds line not yet decoded.
    open: bool,
    /// The last final frame.
    last: Option<Seen>,
    /// Intact frames and frames the master sent, final ones.
    intact: u64,
    sent: u64,
    /// A frame as the transcript shows it.
    describe: fn(&Seen) -> Value,
}

impl CanWatch {
    /// A watch at `base`'s clock holding the master to `t`; `describe` gives a frame's transcript entry.
    pub fn new(base: Base, t: Timing, describe: fn(&Seen) -> Value) -> Self {
        CanWatch {
            base,
            t,
            rx: Signal::named("rx"),
            tx: Signal::named("tx"),
            rx_level: true,
            rx_rise: 0,
            tx_level: true,
            tx_fall: 0,
            dominant_reported: false,
            open: false,
            last: None,
            intact: 0,
            sent: 0,
            describe,
        }
    }

    /// The timing.
    pub fn timing(&self) -> &Timing {
        &self.t
    }

    fn bits(&self, b: f64) -> u64 {
        (b * self.t.bit_ps).round() as u64
    }

    /// One monitor cycle; the frames that became final (bus idle after them), in order.
    pub fn step(&mut self, pins: Pins) -> Vec<Seen> {
        let now = self.base.now_ps();
        let (rx, tx) = (pins.0 & 1 != 0, pins.0 & 2 != 0);
        let cycle = self.base.period_ps;
        let mut out = Vec::new();
        let (rx_was, rise_was) = (self.rx_level, self.rx_rise);
        // Bus idle for 10.5 bits: the frames of the window are final.
        if rx && tx && self.rx_level && self.open && now - self.rx_rise >= self.bits(10.5) {
            out = self.flush(now);
        }
        if rx != self.rx_level {
            self.rx_level = rx;
            if rx {
                self.rx_rise = now;
            }
        }
        if !rx || !tx {
            self.open = true;
        }
        if tx != self.tx_level {
            self.tx_level = tx;
            if !tx {
                self.tx_fall = now;
                self.dominant_reported = false;
                // A SOF of the master: the bus recessive at its receiver for 7.5 bits or more.
                // (The bus before this cycle: RXD follows TXD by the loop delay, or at once.)
                let idle = now - rise_was;
                if rx_was && idle >= self.bits(7.5) {
                    let least = 11.0 * self.t.bit_ps * (1.0 - self.t.tolerance)
                        - self.t.prop_ps
                        - 2.0 * cycle as f64;
                    if (idle as f64) < least {
                        self.base.violation(now, RULE_INTERMISSION, format!("the master's SOF {:.2} bits after the bus's last dominant bit; 11 recessive bits (ACK delimiter and EOF, or error delimiter, and 3 of intermission) come first", idle as f64 / self.t.bit_ps));
                    }
                }
            }
        }
        if !tx && !self.dominant_reported {
            let held = (now - self.tx_fall) as f64;
            if held
                > self.t.max_dominant_bits * self.t.bit_ps * (1.0 + self.t.tolerance)
                    + 2.0 * cycle as f64
            {
                self.dominant_reported = true;
                self.base.violation(
                    now,
                    RULE_DOMINANT,
                    format!(
                        "TXD dominant for more than {:.2} bits ({:.3} us) from {:.3} us",
                        self.t.max_dominant_bits,
                        us(now - self.tx_fall),
                        us(self.tx_fall)
                    ),
                );
            }
        }
        self.rx.push(now, rx);
        self.tx.push(now, tx);
        out
    }

    /// The frames of the window complete by `now` (decoded, not judged).
    fn decoded(&self, now: u64) -> Vec<Decoded> {
        let bit = self.t.bit_ps.round() as u64;
        decode::frames(&self.rx, bit, self.t.sample_point)
            .into_iter()
            .filter(|d| d.sof_ps + d.bits as u64 * bit <= now)
            .collect()
    }

    /// Judges the window's frames and forgets its line.
    fn flush(&mut self, now: u64) -> Vec<Seen> {
        let frames = self.decoded(now);
        let seen: Vec<Seen> = frames.into_iter().map(|d| self.judge(d)).collect();
        for s in &seen {
            self.base.done.push((self.describe)(s));
            self.intact += s.frame.error.is_none() as u64;
            self.sent += s.by_master as u64;
        }
        if let Some(s) = seen.last() {
            self.last = Some(s.clone());
        }
        self.rx.forget_before(now);
        self.tx.forget_before(now);
        self.open = false;
        seen
    }

    /// The sample point of wire bit `k` of a frame whose SOF is at `sof`.
    fn at(&self, sof: u64, k: usize) -> u64 {
        sof + ((k as f64 + self.t.sample_point) * self.t.bit_ps) as u64
    }

    /// Who sent `d`, and the frame rules on the master's TXD.
    fn judge(&mut self, d: Decoded) -> Seen {
        let bit = self.t.bit_ps;
        let end_ps = d.sof_ps + (d.bits as f64 * bit) as u64;
        let stuffed = match &d.error {
            None => d.bits.saturating_sub(10),
            Some(_) => d.bits.saturating_sub(1),
        };
        let sof = d.sof_ps;
        // TXD is read on the master's own bit grid: a frame the master
        // starts reaches its RXD late by the loop delay (its transceiver, the
        // bus, a testbench's registers), and with few clock cycles after the
        // sample point (10 quanta at BRP 1, 80 %: two) TXD read at RXD's
        // sample point would already show the next bit.
        let lead = self.lead(sof);
        let tx_at = |w: &CanWatch, k: usize| w.tx.level_at(w.at(sof, k) - lead);
        let rx_at = |w: &CanWatch, k: usize| w.rx.level_at(w.at(sof, k));
        // Arbitration is lost only in the arbitration field (wire bits, stuff bits included).
        let arbitration = if d.error.is_none() {
            let a = model::can::frame::arbitration_end(d.ide) as usize;
            a + a / 4 + 1
        } else {
            40
        };
        let by_master = !tx_at(self, 0)
            && (0..stuffed.min(arbitration).max(1)).all(|k| !tx_at(self, k) || rx_at(self, k));
        let seen = Seen {
            frame: d,
            by_master,
            end_ps,
        };
        if by_master && !self.grid(&seen, stuffed) {
            return seen;
        }
        let d = seen.frame.clone();
        let mut form: Vec<(usize, &str)> = Vec::new();
        match d.error.as_deref() {
            None => {
                let n = d.bits;
                form.push((n - 10, "CRC delimiter"));
                if by_master {
                    form.push((n - 9, "ACK slot of its own frame"));
                }
                form.push((n - 8, "ACK delimiter"));
                form.extend((n - 7..n).map(|k| (k, "EOF")));
            }
            Some("form") => form.push((d.bits - 1, "CRC delimiter, ACK delimiter or EOF")),
            Some("stuff") if by_master && !self.error_flag(sof, lead, d.bits - 1) => {
                let k = d.bits - 1;
                let t = self.at(d.sof_ps, k);
                let level = rx_at(self, k);
                self.base.violation(t, RULE_STUFF, format!("six equal bits in the master's frame ending at wire bit {k} ({} {:.3} us after its SOF)", if level { "recessive" } else { "dominant" }, us(t - d.sof_ps)));
            }
            _ => {}
        }
        if let Some(&(k, what)) = form.iter().find(|&&(k, _)| !tx_at(self, k)) {
            let t = self.at(d.sof_ps, k);
            self.base.violation(
                t,
                RULE_FORM,
                format!(
                    "TXD dominant in the {what} (wire bit {k}) of a frame {} sent",
                    if by_master {
                        "the master"
                    } else {
                        "another node"
                    }
                ),
            );
        }
        seen
    }

    /// How far the master's TXD leads the bus at its receiver in the frame
    /// whose SOF RXD shows at `sof`: from TXD's SOF when the master started
    /// it (TXD fell at most a bit before), else 0 (a receiver's TXD, the ACK
    /// slot alone, follows RXD).
    fn lead(&self, sof: u64) -> u64 {
        let bit = self.t.bit_ps as u64;
        self.tx
            .edges()
            .iter()
            .rev()
            .find(|&&(t, l)| !l && t <= sof)
            .map_or(0, |&(t, _)| if sof - t < bit { sof - t } else { 0 })
    }

    /// Six dominant bits ending at wire bit `k` that are the master's error
    /// flag (TXD then recessive for 7 bits: an error delimiter), not a
    /// missing stuff bit.
    fn error_flag(&self, sof: u64, lead: u64, k: usize) -> bool {
        let tx = |j: usize| self.tx.level_at(self.at(sof, j) - lead);
        !self.rx.level_at(self.at(sof, k))
            && (k + 1..=k + 7)
                .find(|&j| tx(j))
                .is_some_and(|j| (j..j + 7).all(tx))
    }

    /// The bit-time rule on the master's TXD edges from its SOF through
    /// wire bit `through`; false when an edge is off the grid.
    fn grid(&mut self, s: &Seen, through: usize) -> bool {
        let bit = self.t.bit_ps;
        let sof_rx = s.frame.sof_ps;
        let edges = self.tx.edges();
        let Some(&(sof, _)) = edges
            .iter()
            .rev()
            .find(|&&(t, l)| !l && t <= sof_rx + bit as u64 && t + 2 * bit as u64 >= sof_rx)
        else {
            return true;
        };
        // Through the CRC's last bit; a damaged frame (read off the master's
        // grid, perhaps) to the end of the master's transmission: TXD then
        // recessive for 7 bits.
        let mut last = sof + ((through as f64 + 1.0) * bit) as u64;
        if s.frame.error.is_some() {
            let after: Vec<(u64, bool)> = edges.iter().copied().filter(|&(t, _)| t > sof).collect();
            last = after
                .iter()
                .enumerate()
                .find(|&(i, &(t, l))| {
                    l && after
                        .get(i + 1)
                        .is_none_or(|&(u, _)| (u - t) as f64 >= 7.0 * bit)
                })
                .map_or(last, |(_, &(t, _))| t + 1)
                .max(last);
        }
        let rx_edges = self.rx.edges();
        let cycle = 2.0 * self.base.period_ps as f64;
        for &(t, _) in edges.iter().filter(|&&(t, _)| t > sof && t < last) {
            let resyncs = rx_edges
                .iter()
                .filter(|&&(r, l)| !l && r > sof && r < t && self.tx.level_at(r))
                .count() as f64;
            let o = (t - sof) as f64;
            let n = (o / bit).round();
            let slack = self.t.tolerance * o + self.t.sjw_ps * (1.0 + resyncs) + cycle;
            if n < 1.0 || (o - n * bit).abs() > slack {
                self.base.violation(t, RULE_BIT_TIME, format!("a TXD edge {:.3} us after the master's SOF, {:.3} bits of {:.3} us: off the bit grid by more than {:.0} ns", o / 1e6, o / bit, bit / 1e6, slack / 1e3));
                return false;
            }
        }
        true
    }

    /// The frames of the window complete by now, judged on a copy (the violations of the copy are dropped).
    pub fn pending(&self) -> Vec<Seen> {
        let now = self.base.now_ps();
        let mut copy = CanWatch::new(Base::new(self.base.f_mon_hz), self.t, self.describe);
        copy.rx = self.rx.clone();
        copy.tx = self.tx.clone();
        copy.base.cycle = self.base.cycle;
        self.decoded(now)
            .into_iter()
            .map(|d| copy.judge(d))
            .collect()
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
    watch: CanWatch,
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
        let whole = proto_table(text, origin, "can")?;
        let limits: CanLimits = config::decode_in(&whole, "monitor", origin)?;
        let mut device = model_table(&whole, f_mon_hz);
        device.remove("nodes");
        device.remove("dut");
        device.remove("faults");
        let bench: model::can::BenchConfig = config::decode(device, origin)?;
        let timing = bench.bit_timing().map_err(|e| Error::config(origin, e))?;
        let t = Timing::new(&timing, bench.f_sys_mhz * 1e6, &limits, origin)?;
        Ok(CanMonitor {
            watch: CanWatch::new(Base::new(f_mon_hz), t, Seen::json),
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
        let pending = self.watch.pending().iter().map(Seen::json).collect();
        self.watch.base.transcript("can", &["rx", "tx"], pending)
    }

    fn checks(&mut self) -> &mut crate::check::Checks {
        &mut self.watch.base.checks
    }
}
