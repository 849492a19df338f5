//! The CAN master's rules, in the shape of [`crate::rules`]: what a master's
//! transceiver pins (TXD as it drives it, RXD the wired-AND bus at its
//! receiver) must show, held by one watcher that the CAN and CANopen
//! emulators and monitors of `cosim` all feed.
//!
//! # Sources
//!
//! The seeds do not restate CAN. Seed 001 §3.4 puts the SAR58K24 on a CAN
//! transceiver (SN65HVD230) at 250 kbit/s by default; seed 003 §1.3 lists
//! "CAN Specification Version 2.0 A, Robert Bosch GmbH" among its references
//! and §5.5 gives the gateway's rates (10 kbit/s to 1 Mbit/s). The rules
//! here cite that document, the Bosch CAN Specification 2.0 (September
//! 1991), by part and section as its own contents page numbers them (read
//! from a public scan of it); ISO 11898-1, which restates it, is not cited,
//! for no clause of it could be checked. Where a rule's words are the
//! house's reading and not the specification's, [`Rule::reading`] says so.
//!
//! # What is watched
//!
//! Frames are read off RXD by the decode core of `tbgen decode can`
//! ([`super::decode`]). A frame is the master's when its TXD was dominant at
//! the SOF's sample point and equal to the bus at every sample point of the
//! arbitration field (it did not lose arbitration). On every frame and on
//! the line between them:
//!
//! * [`STUFF`]: no six equal bits in a frame the master transmits, SOF to
//!   the CRC sequence's last bit (unless they are its error flag);
//! * [`CRC`]: the CRC sequence of a frame the master transmits is the one
//!   its bits give;
//! * [`FORM`]: TXD recessive in the CRC delimiter, the ACK delimiter and
//!   EOF of every intact frame, and in the ACK slot of the master's own;
//! * [`INTERMISSION`]: the master's SOF only after 11 recessive bits on the
//!   bus (ACK delimiter and EOF, or error delimiter, then 3 of
//!   intermission), less the propagation segment (the bus's last edge may
//!   come late by the round trip) and the oscillator tolerance;
//! * [`BIT_TIME`]: every TXD edge of the master's frame on the bit grid of
//!   its SOF at the configured bit rate, within `tolerance × time since the
//!   SOF` plus one SJW (and one more per resynchronising edge another node
//!   drove while the master sent recessive);
//! * [`DOMINANT`]: TXD never dominant longer than an error flag (6 bits)
//!   with the oscillator tolerance.
//!
//! A frame with a bit-time breach is not also judged for stuffing, CRC and
//! form (its bits were sampled off the master's grid). Frames are final
//! (judged, handed back) once the bus has been idle for 10.5 bits after
//! them. Each limit is applied to the times of the sampled edges with no
//! slack of a sampling cycle ([`crate::rules::resolution_notes`] says when
//! the clock is too coarse for the SJW).
//!
//! Nothing is watched until TXD and RXD have both been seen recessive: a
//! master in reset (TXD unknown, read dominant) from time 0 draws no report.

use std::sync::OnceLock;

use super::decode::{self, Decoded};
use super::BitTiming;
use crate::rules::{Bound, Breach, Rule, Settable};
use crate::wire::Signal;
use crate::ConfigError;

/// Six equal bits in the master's frame.
pub static STUFF: Rule = Rule {
    protocol: "can",
    name: "stuffing",
    section: "Bosch CAN Specification 2.0 part A §5 and part B §7.1",
    seed_words: "A STUFF ERROR has to be detected at the bit time of the 6th consecutive equal bit level in a message field that should be coded by the method of bit stuffing",
    quantity: "after five equal bits from SOF to the CRC sequence's end, one of the other level",
    bound: Bound::Form,
    measured: "the bus at each sample point of a frame the master transmits (its TXD dominant at SOF and equal to the bus through arbitration), SOF to the last CRC bit; six dominant bits followed by seven recessive TXD bits are the master's error flag, not a missing stuff bit",
    reading: "the words are part B §7.1's (error detection), seen in a scan; part A §5 (coding, the stuffing rule itself) is cited by its title in the contents, its text not seen",
    settable: None,
    label: OnceLock::new(),
};

/// A wrong CRC sequence in the master's frame.
pub static CRC: Rule = Rule {
    protocol: "can",
    name: "CRC",
    section: "Bosch CAN Specification 2.0 part B §7.1",
    seed_words: "The receivers calculate the CRC in the same way as the transmitter. A CRC ERROR has to be detected, if the calculated result is not the same as that received in the CRC sequence",
    quantity: "the CRC sequence of the master's frame is the CRC-15 of its bits",
    bound: Bound::Form,
    measured: "the CRC-15 of the destuffed bits read off the bus (SOF to the data field's end) against the CRC sequence read, in a frame the master transmits",
    reading: "",
    settable: None,
    label: OnceLock::new(),
};

/// A dominant TXD in a fixed-form field.
pub static FORM: Rule = Rule {
    protocol: "can",
    name: "form",
    section: "Bosch CAN Specification 2.0 part B §7.1",
    seed_words: "A FORM ERROR has to be detected when a fixed-form bit field contains one or more illegal bits",
    quantity: "CRC delimiter, ACK delimiter and EOF recessive; the transmitter's ACK slot recessive",
    bound: Bound::Form,
    measured: "TXD at the sample points of the CRC delimiter, ACK delimiter and 7 EOF bits of every intact frame, and of the ACK slot of the master's own",
    reading: "the master's own ACK slot is the house's reading: the specification has the transmitter send it recessive (a receiver overwrites it), so a dominant TXD there is a transmitter acknowledging itself",
    settable: None,
    label: OnceLock::new(),
};

/// The master's SOF before 3 bits of intermission.
pub static INTERMISSION: Rule = Rule {
    protocol: "can",
    name: "intermission",
    section: "Bosch CAN Specification 2.0 part A §3.1.5",
    seed_words: "INTERMISSION consists of three 'recessive' bits. During INTERMISSION no station is allowed to start transmission of a DATA FRAME or REMOTE FRAME",
    quantity: "3 recessive bits after EOF or an error delimiter before a SOF, 11 in all",
    bound: Bound::Form,
    measured: "the master's SOF (TXD falling after 7.5 or more recessive bits on the bus) to the bus's last rising edge: at least 11 bits x (1 - tolerance) less the propagation segment",
    reading: "11 bits (ACK delimiter and 7 EOF, or the last 8 error delimiter bits, then 3) with the oscillator tolerance and PROP_SEG taken off: the master times its bits from its own sample points, which may lag the bus's edge by the round trip; a TXD fall after fewer than 7.5 recessive bits is a bit inside a frame, not a SOF",
    settable: None,
    label: OnceLock::new(),
};

/// A TXD edge off the master's bit grid.
pub static BIT_TIME: Rule = Rule {
    protocol: "can",
    name: "bit time",
    section: "Bosch CAN Specification 2.0 part A §8 and part B §9",
    seed_words: "NOMINAL BIT TIME = 1 / NOMINAL BIT RATE ... SYNC_SEG: an edge is expected to lie within this segment; part B §9: A maximum oscillator tolerance of 1.58% is given",
    quantity: "the transmitter's edges on the nominal bit time of the configured bit rate, within the oscillator tolerance and SJW",
    bound: Bound::Form,
    measured: "each TXD edge of a frame the master transmits, from its SOF: off the nearest whole bit by at most tolerance x its time since the SOF plus one SJW, and one SJW more for each falling edge another node drove on the bus while the master sent recessive",
    reading: "the tolerance is `monitor.bit_tolerance_percent`, by default the oscillator tolerance the timing allows (min(PHASE_SEG1, PHASE_SEG2) / (2 (13 NTQ - PHASE_SEG2)) and SJW / (20 NTQ), as Hartwich and Bassemir, \"The Configuration of the CAN Bit Timing\", Bosch, 1999, derive them); a configuration may set 0 to 1.58 % (part B §9)",
    settable: Some(Settable { lo: 0.0, hi: 1.58 }),
    label: OnceLock::new(),
};

/// TXD dominant longer than an error flag.
pub static DOMINANT: Rule = Rule {
    protocol: "can",
    name: "dominant length",
    section: "Bosch CAN Specification 2.0 part A §3.1.3",
    seed_words: "The ACTIVE ERROR FLAG consists of six consecutive 'dominant' bits ... The total length of this sequence varies between a minimum of six and a maximum of twelve bits",
    quantity: "no dominant TXD longer than an error flag, 6 bits",
    bound: Bound::Form,
    measured: "every dominant stretch of TXD, falling edge to rising edge (or to now while it lasts): at most `monitor.max_dominant_bits` (6) bits x (1 + tolerance)",
    reading: "a node sends at most five equal bits in a frame and six in an error or overload flag; a configuration may set 6 to 12 bits (the longest dominant sequence the superposed flags of all nodes show on the bus)",
    settable: Some(Settable { lo: 6.0, hi: 12.0 }),
    label: OnceLock::new(),
};

/// The CAN rules, in the order of a frame.
pub static RULES: &[&Rule] = &[&STUFF, &CRC, &FORM, &INTERMISSION, &BIT_TIME, &DOMINANT];

/// The limits in force, ps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// One nominal bit.
    pub bit_ps: f64,
    /// Sample point, fraction of the bit.
    pub sample_point: f64,
    /// SJW.
    pub sjw_ps: f64,
    /// Propagation segment.
    pub prop_ps: f64,
    /// Drift allowed, a fraction ([`BIT_TIME`]).
    pub tolerance: f64,
    /// Longest dominant TXD, bits ([`DOMINANT`]).
    pub max_dominant_bits: f64,
}

impl Limits {
    /// The limits of bit timing `t` at `f_sys_hz`; a tolerance in % and a
    /// longest dominant TXD in bits, each with the field it came from,
    /// replace the defaults, within the rules' ranges.
    pub fn new(
        t: &BitTiming,
        f_sys_hz: f64,
        tolerance_percent: Option<(&str, f64)>,
        dominant_bits: Option<(&str, f64)>,
    ) -> Result<Limits, ConfigError> {
        let tq = t.brp as f64 * 1e12 / f_sys_hz;
        let tol = match tolerance_percent {
            Some((field, v)) => BIT_TIME.setting(field, v)?,
            None => 100.0 * t.oscillator_tolerance(),
        };
        let dom = match dominant_bits {
            Some((field, v)) => DOMINANT.setting(field, v)?,
            None => 6.0,
        };
        Ok(Limits {
            bit_ps: tq * t.ntq() as f64,
            sample_point: t.sample_point(),
            sjw_ps: tq * t.sjw as f64,
            prop_ps: tq * t.prop_seg as f64,
            tolerance: tol / 100.0,
            max_dominant_bits: dom,
        })
    }

    /// The least lengths, for [`crate::rules::resolution_notes`]: an edge is
    /// held to the grid within one SJW.
    pub fn least(&self) -> Vec<(&'static Rule, u64)> {
        vec![(&BIT_TIME, self.sjw_ps.round() as u64)]
    }

    fn bits(&self, b: f64) -> u64 {
        (b * self.bit_ps).round() as u64
    }
}

/// A frame the watcher judged.
#[derive(Debug, Clone)]
pub struct Seen {
    /// The decoded frame.
    pub frame: Decoded,
    /// The master transmitted it.
    pub by_master: bool,
    /// Its end (last bit read), ps.
    pub end_ps: u64,
}

/// What one sample showed: the rules broken, the frames that became final.
#[derive(Debug, Clone, Default)]
pub struct Sampled {
    /// Rules broken.
    pub breaches: Vec<Breach>,
    /// Frames that became final (the bus idle after them), in order.
    pub frames: Vec<Seen>,
}

/// The CAN edge watcher: the master's TXD and the bus at its RXD.
#[derive(Debug, Clone)]
pub struct Watch {
    limits: Limits,
    aware: bool,
    rx: Signal,
    tx: Signal,
    rx_level: bool,
    rx_rise: u64,
    tx_level: bool,
    tx_fall: u64,
    dominant_reported: bool,
    /// The window holds line not yet decoded.
    open: bool,
}

impl Watch {
    /// A watcher holding the master to `limits`.
    pub fn new(limits: Limits) -> Self {
        Watch {
            limits,
            aware: false,
            rx: Signal::named("rx"),
            tx: Signal::named("tx"),
            rx_level: true,
            rx_rise: 0,
            tx_level: true,
            tx_fall: 0,
            dominant_reported: false,
            open: false,
        }
    }

    /// The limits in force.
    pub fn limits(&self) -> &Limits {
        &self.limits
    }

    /// One sample at `t_ps`: the bus at the master's receiver (`rx`) and its
    /// TXD (`tx`), high recessive.
    pub fn sample(&mut self, t_ps: u64, rx: bool, tx: bool) -> Sampled {
        let mut out = Sampled::default();
        if !self.aware {
            // A master in reset: nothing is a frame or a flag until both
            // pins have been seen recessive (the bus idle since ever).
            if !(rx && tx) {
                return out;
            }
            self.aware = true;
        }
        let lim = self.limits;
        let (rx_was, rise_was) = (self.rx_level, self.rx_rise);
        // Bus idle for 10.5 bits: the frames of the window are final.
        if rx && tx && self.rx_level && self.open && t_ps - self.rx_rise >= lim.bits(10.5) {
            out.frames = self.flush(t_ps, &mut out.breaches);
        }
        if rx != self.rx_level {
            self.rx_level = rx;
            if rx {
                self.rx_rise = t_ps;
            }
        }
        if !rx || !tx {
            self.open = true;
        }
        let most = lim.max_dominant_bits * lim.bit_ps * (1.0 + lim.tolerance);
        if tx != self.tx_level {
            self.tx_level = tx;
            if !tx {
                self.tx_fall = t_ps;
                self.dominant_reported = false;
                // A SOF of the master: the bus recessive at its receiver for
                // 7.5 bits or more (the bus before this sample: RXD follows
                // TXD by the loop delay, or at once).
                let idle = t_ps - rise_was;
                if rx_was && idle >= lim.bits(7.5) {
                    let least = 11.0 * lim.bit_ps * (1.0 - lim.tolerance) - lim.prop_ps;
                    if (idle as f64) < least {
                        out.breaches.push(INTERMISSION.breach(t_ps, format!("the master's SOF {:.2} bits after the bus's last dominant bit; 11 recessive bits (ACK delimiter and EOF, or error delimiter, and 3 of intermission) come first, at least {:.2} with the tolerance and PROP_SEG", idle as f64 / lim.bit_ps, least / lim.bit_ps)));
                    }
                }
            } else if !self.dominant_reported && (t_ps - self.tx_fall) as f64 > most {
                // The dominant stretch just ended, measured edge to edge.
                out.breaches.push(self.dominant(t_ps));
            }
        }
        if !tx && !self.dominant_reported && (t_ps - self.tx_fall) as f64 > most {
            out.breaches.push(self.dominant(t_ps));
        }
        self.rx.push(t_ps, rx);
        self.tx.push(t_ps, tx);
        out
    }

    fn dominant(&mut self, t_ps: u64) -> Breach {
        self.dominant_reported = true;
        DOMINANT.breach(
            t_ps,
            format!(
                "TXD dominant for more than {:.2} bits ({:.3} us) from {:.3} us",
                self.limits.max_dominant_bits,
                crate::rules::us(t_ps - self.tx_fall),
                crate::rules::us(self.tx_fall)
            ),
        )
    }

    /// The frames of the window complete by `now` (decoded, not judged).
    fn decoded(&self, now: u64) -> Vec<Decoded> {
        let bit = self.limits.bit_ps.round() as u64;
        decode::frames(&self.rx, bit, self.limits.sample_point)
            .into_iter()
            .filter(|d| d.sof_ps + d.bits as u64 * bit <= now)
            .collect()
    }

    /// Judges the window's frames and forgets its line.
    fn flush(&mut self, now: u64, breaches: &mut Vec<Breach>) -> Vec<Seen> {
        let seen = self
            .decoded(now)
            .into_iter()
            .map(|d| self.judge(d, breaches))
            .collect();
        self.rx.forget_before(now);
        self.tx.forget_before(now);
        self.open = false;
        seen
    }

    /// The frames of the window complete by `now`, judged (their
    /// breaches dropped: they are reported when the frames are final).
    pub fn pending(&self, now: u64) -> Vec<Seen> {
        let mut dropped = Vec::new();
        self.decoded(now)
            .into_iter()
            .map(|d| self.judge(d, &mut dropped))
            .collect()
    }

    /// The sample point of wire bit `k` of a frame whose SOF is at `sof`.
    fn at(&self, sof: u64, k: usize) -> u64 {
        sof + ((k as f64 + self.limits.sample_point) * self.limits.bit_ps) as u64
    }

    /// Who sent `d`, and the frame rules on the master's TXD.
    fn judge(&self, d: Decoded, breaches: &mut Vec<Breach>) -> Seen {
        let bit = self.limits.bit_ps;
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
        let tx_at = |k: usize| self.tx.level_at(self.at(sof, k) - lead);
        let rx_at = |k: usize| self.rx.level_at(self.at(sof, k));
        // Arbitration is lost only in the arbitration field (wire bits, stuff bits included).
        let arbitration = if d.error.is_none() {
            let a = super::frame::arbitration_end(d.ide) as usize;
            a + a / 4 + 1
        } else {
            40
        };
        let by_master =
            !tx_at(0) && (0..stuffed.min(arbitration).max(1)).all(|k| !tx_at(k) || rx_at(k));
        let seen = Seen {
            frame: d,
            by_master,
            end_ps,
        };
        if by_master && !self.grid(&seen, stuffed, breaches) {
            return seen;
        }
        let d = &seen.frame;
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
            Some("stuff")
                if by_master
                    && !self.error_flag(sof, lead, d.bits - 1)
                    && !self.overlong(self.at(sof, d.bits - 1) - lead) =>
            {
                let k = d.bits - 1;
                let t = self.at(sof, k);
                breaches.push(STUFF.breach(
                    t,
                    format!(
                        "six equal bits in the master's frame ending at wire bit {k} ({} {:.3} us after its SOF)",
                        if rx_at(k) { "recessive" } else { "dominant" },
                        crate::rules::us(t - sof)
                    ),
                ));
            }
            Some("crc") if by_master => {
                let k = d.bits - 1;
                breaches.push(CRC.breach(
                    self.at(sof, k),
                    format!("the CRC sequence of the master's frame, ending at wire bit {k}, is not the CRC-15 of its bits"),
                ));
            }
            _ => {}
        }
        if let Some(&(k, what)) = form.iter().find(|&&(k, _)| !tx_at(k)) {
            breaches.push(FORM.breach(
                self.at(sof, k),
                format!(
                    "TXD dominant in the {what} (wire bit {k}) of a frame {} sent",
                    if by_master {
                        "the master"
                    } else {
                        "another node"
                    }
                ),
            ));
        }
        seen
    }

    /// How far the master's TXD leads the bus at its receiver in the frame
    /// whose SOF RXD shows at `sof`: from TXD's SOF when the master started
    /// it (TXD fell at most a bit before), else 0 (a receiver's TXD, the ACK
    /// slot alone, follows RXD).
    fn lead(&self, sof: u64) -> u64 {
        let bit = self.limits.bit_ps as u64;
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

    /// TXD dominant at `t` in a stretch longer than an error flag: the
    /// [`DOMINANT`] rule's (six dominant bits in it are not also a missing
    /// stuff bit).
    fn overlong(&self, t: u64) -> bool {
        let edges = self.tx.edges();
        let Some(&(fall, _)) = edges.iter().rev().find(|&&(e, l)| !l && e <= t) else {
            return false;
        };
        let rise = edges
            .iter()
            .find(|&&(e, l)| l && e > fall)
            .map_or(u64::MAX, |&(e, _)| e);
        let lim = &self.limits;
        rise > t
            && (rise - fall) as f64 > lim.max_dominant_bits * lim.bit_ps * (1.0 + lim.tolerance)
    }

    /// The bit-time rule on the master's TXD edges from its SOF through
    /// wire bit `through`; false when an edge is off the grid.
    fn grid(&self, s: &Seen, through: usize, breaches: &mut Vec<Breach>) -> bool {
        let lim = &self.limits;
        let bit = lim.bit_ps;
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
        for &(t, _) in edges.iter().filter(|&&(t, _)| t > sof && t < last) {
            let resyncs = rx_edges
                .iter()
                .filter(|&&(r, l)| !l && r > sof && r < t && self.tx.level_at(r))
                .count() as f64;
            let o = (t - sof) as f64;
            let n = (o / bit).round();
            let slack = lim.tolerance * o + lim.sjw_ps * (1.0 + resyncs);
            if n < 1.0 || (o - n * bit).abs() > slack {
                breaches.push(BIT_TIME.breach(t, format!("a TXD edge {:.3} us after the master's SOF, {:.3} bits of {:.3} us: off the bit grid by {:.0} ns, more than {:.0} ns", o / 1e6, o / bit, bit / 1e6, (o - n * bit).abs() / 1e3, slack / 1e3)));
                return false;
            }
        }
        true
    }
}
