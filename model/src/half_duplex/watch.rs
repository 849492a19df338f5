//! The rule watcher of a half-duplex request/answer host (ESL, T-format),
//! below both the emulator and the monitor: fed the host's transceiver pins
//! one sample at a time (its driver's input D, its enable DE, its
//! receiver's output R), it decides the rules the two protocols share and
//! hands each request back for the protocol's own ([`crate::esl::rules`],
//! [`crate::tformat::rules`], which name the rules).
//!
//! * character timing: every edge of a request field on the bit grid from
//!   the field's start edge, within `tolerance × (time since the start
//!   edge) + jitter`; the stop bit high at its middle and a full bit long;
//!   the driver enable not released inside a field;
//! * a request's fields back to back: the next start bit within `max_gap`
//!   (plus the jitter) of the stop bit's end while the driver stays on;
//! * release: the driver enable off within `release` of the request's last
//!   stop bit (measured to the sample that shows it off);
//! * answer: the host's driver never on while the encoder drives its
//!   receiver low while its own driver sends a 1 (a receiver that echoes the
//!   host's own driver is low whenever the host sends a 0, so only a low
//!   against a 1 is another driver), and never switched on inside the
//!   encoder's answer (before a bit time of idle line has followed the
//!   answer's last character).
//!
//! Lengths are measured between sampled edges in ps with no slack of a
//! sampling cycle. Nothing is timed until the host's line has been idle
//! (high, or the driver off) for a character ([`IDLE_BITS`]): a host
//! holding its driver on and low in reset from time 0 draws no report, nor
//! one whose enable is unknown (read as off).

use crate::rules::{ps_at, Breach, Rule, Unit};
use crate::ConfigError;

/// The rules a protocol reports the shared checks under.
#[derive(Debug, Clone, Copy)]
pub struct Rules {
    /// An edge off the bit grid, a low or short stop bit, DE released in a field.
    pub character: &'static Rule,
    /// A pause between the fields of one request.
    pub gap: &'static Rule,
    /// DE still on too long after the request.
    pub release: &'static Rule,
    /// The host drove while the encoder answered.
    pub answer: &'static Rule,
}

/// The limits, in ps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// One bit.
    pub bit_ps: f64,
    /// Drift allowed per ps since the field's start edge.
    pub tolerance: f64,
    /// Jitter allowed on every edge, ps.
    pub jitter_ps: f64,
    /// Longest idle line between two fields of a request (from the stop bit's end).
    pub max_gap_ps: f64,
    /// Longest time from the last stop bit's end to the driver enable's fall.
    pub release_ps: u64,
}

impl Limits {
    /// The release set to `us` (field `field`), within `rule`'s range.
    pub fn set_release(
        &mut self,
        rule: &'static Rule,
        field: &str,
        us: f64,
    ) -> Result<(), ConfigError> {
        self.release_ps = Unit::Us.ps(rule.setting(field, us)?);
        Ok(())
    }

    /// The longest pause between a request's characters set to `bits` bits.
    pub fn set_gap_bits(&mut self, bits: f64) {
        self.max_gap_ps = bits * self.bit_ps;
    }
}

/// A protocol's checks of each whole request (its field count, the spacing
/// of requests).
pub trait Requests: Clone + std::fmt::Debug {
    /// The checks of one request the host sent; breaches into `out`.
    fn request(&mut self, r: &Request, out: &mut Vec<Breach>);
}

/// A protocol's watcher: the shared checks of every sample and the
/// protocol's of every request.
#[derive(Debug, Clone)]
pub struct Host<P> {
    line: Watch,
    requests: P,
}

impl<P: Requests> Host<P> {
    /// A watcher with `limits`, the shared checks reported under `rules`.
    pub fn with(limits: Limits, rules: Rules, requests: P) -> Self {
        Host {
            line: Watch::new(limits, rules),
            requests,
        }
    }

    /// One sample at `t_ps`: the host's driver input `tx`, its enable
    /// `de`, its receiver's output `rx`.
    pub fn sample(&mut self, t_ps: u64, tx: bool, de: bool, rx: bool) -> Vec<Breach> {
        let seen = self.line.sample(t_ps, tx, de, rx);
        let mut out = seen.breaches;
        if let Some(r) = seen.request {
            self.requests.request(&r, &mut out);
        }
        out
    }

    /// Sample `n` of a clock of `f_hz` as an emulator sees the host: its
    /// driver's input `tx` and enable `de`, and the encoder's driver at the
    /// host's end (`Some(level)` while it drives), which the host's
    /// receiver hears ([`heard`]) as a monitor at the host's pins does.
    pub fn sample_n(
        &mut self,
        n: u64,
        f_hz: u64,
        tx: bool,
        de: bool,
        encoder: Option<bool>,
    ) -> Vec<Breach> {
        self.sample(ps_at(n, f_hz), tx, de, heard(tx, de, encoder))
    }
}

/// One request as the host's driver sent it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Request {
    /// The first start edge, ps.
    pub start_ps: u64,
    /// The last stop bit's end (nominal: its field's start edge and 10 bits), ps.
    pub end_ps: u64,
    /// The fields' values (sampled mid-bit), in order.
    pub fields: Vec<u8>,
    /// A character-timing violation in it (its fields are not all known).
    pub damaged: bool,
}

/// What one sample showed.
#[derive(Debug, Clone, Default)]
pub struct Seen {
    /// Rules broken at this sample.
    pub breaches: Vec<Breach>,
    /// The request that ended (the driver enable fell).
    pub request: Option<Request>,
}

/// The watcher's state.
#[derive(Debug, Clone)]
pub struct Watch {
    limits: Limits,
    rules: Rules,
    seen_idle: bool,
    idle_since: Option<u64>,
    de: bool,
    drive: bool,
    field: Option<u64>,
    bits: u32,
    value: u8,
    stop_checked: bool,
    request: Option<Request>,
    last_end: Option<u64>,
    release_reported: bool,
    rx: bool,
    rx_char_end: u64,
    answer_until: Option<u64>,
    answer_last: u64,
    both: bool,
    /// After a character-timing violation: edges are not timed until the
    /// line has been high for more than a bit or the driver is off.
    lost: bool,
    last_edge: u64,
}

/// Bits of idle line (high, or the driver off) before the watcher times
/// the host's first request: a character, so that a host that starts
/// watching mid-character (or holds its line low in reset) is not timed
/// from an edge inside it (seed 002 7.1 and seed 000 Figure 1: a request
/// starts at "the first logic 0 after the idle").
pub const IDLE_BITS: f64 = 10.0;

/// Bits from the start bit of an answer's character to the end of the
/// answer when no start bit follows: the character and a bit of idle line.
pub const ANSWER_END_BITS: f64 = 11.0;

/// What a receiver at the host hears: the encoder while its driver is on
/// at the host's end (`encoder`), else the host's own driver while it is
/// on, else the fail-safe bias of an idle pair (high).
pub fn heard(tx: bool, de: bool, encoder: Option<bool>) -> bool {
    encoder.unwrap_or(!de || tx)
}

impl Watch {
    /// A watcher with `limits`, reporting under `rules`.
    pub fn new(limits: Limits, rules: Rules) -> Self {
        Watch {
            limits,
            rules,
            seen_idle: false,
            idle_since: None,
            de: false,
            drive: true,
            field: None,
            bits: 0,
            value: 0,
            stop_checked: false,
            request: None,
            last_end: None,
            release_reported: false,
            rx: true,
            rx_char_end: 0,
            answer_until: None,
            answer_last: 0,
            both: false,
            lost: false,
            last_edge: 0,
        }
    }

    /// The limits in force.
    pub fn limits(&self) -> &Limits {
        &self.limits
    }

    /// A character-timing violation: the field is abandoned.
    fn lose(&mut self) {
        self.lost = true;
        self.field = None;
        if let Some(r) = &mut self.request {
            r.damaged = true;
        }
    }

    fn at(&self, start: u64, bits: f64) -> u64 {
        start + (bits * self.limits.bit_ps).round() as u64
    }

    /// One sample at `now` ps: the host's driver input `tx`, its enable
    /// `de`, its receiver's output `rx`.
    pub fn sample(&mut self, now: u64, tx: bool, de: bool, rx: bool) -> Seen {
        let mut seen = Seen::default();
        let level = tx || !de;
        if !self.seen_idle {
            // A host in reset, or one that began mid-character: nothing is
            // an edge until its line has been idle a character long.
            let since = *self.idle_since.get_or_insert(now);
            if ((now - since) as f64) < IDLE_BITS * self.limits.bit_ps {
                if !level {
                    self.idle_since = None;
                }
                return seen;
            }
            self.seen_idle = true;
            self.last_edge = since;
        }
        let bit = self.limits.bit_ps;
        let r = self.rules;
        let out = &mut seen.breaches;
        // The encoder's answer on the host's receiver.
        if rx != self.rx {
            self.rx = rx;
            if !rx && !de && now >= self.rx_char_end {
                // The next start bit is looked for from this one's stop-bit
                // middle on, as a UART receiver does (an encoder off rate
                // sends characters shorter or longer than 10 bits).
                self.rx_char_end = self.at(now, 9.5);
                self.answer_last = now;
                self.answer_until = Some(self.at(now, ANSWER_END_BITS));
            }
        }
        // Low at the receiver while the host drives high: another driver.
        let both = de && tx && !rx;
        if both && !self.both {
            out.push(r.answer.breach(
                now,
                "the host's driver was on while the encoder drove the line low (both drivers on)"
                    .to_string(),
            ));
        }
        self.both = both;
        if de && !self.de && self.answer_until.is_some_and(|u| now < u) {
            let after = (now - self.answer_last) as f64;
            out.push(r.answer.breach(now, format!("the host switched its driver on {:.2} bits ({:.1} ns) after the start bit of the encoder's last character, inside its answer (it ends when a bit time of idle line follows a character: {ANSWER_END_BITS} bits, {:.1} ns)", after / bit, after / 1e3, ANSWER_END_BITS * bit / 1e3)));
        }
        // The host's request, as its driver puts it on the line.
        if self.lost && ((level && self.drive && now - self.last_edge > bit as u64) || !de) {
            self.lost = false;
        }
        if self.lost {
            // not timed
        } else if let Some(s) = self.field {
            self.in_field(now, s, level, de, out);
        } else if level != self.drive && !level {
            if let (Some(end), Some(_)) = (self.last_end, &self.request) {
                let gap = now.saturating_sub(end) as f64;
                let most = self.limits.max_gap_ps + self.limits.jitter_ps;
                if gap > most {
                    out.push(r.gap.breach(now, format!("{:.2} bits ({:.1} ns) of idle line between two fields of one request (the driver stayed on); at most {:.2} bits ({:.1} ns)", gap / bit, gap / 1e3, most / bit, most / 1e3)));
                }
            }
            self.start_field(now);
        }
        if level != self.drive {
            self.last_edge = now;
        }
        self.drive = level;
        // Release: the enable on at the sample before is measured to this one.
        if self.de && !self.release_reported && (self.field.is_none() || !de) {
            if let Some(end) = self.last_end.filter(|_| self.request.is_some()) {
                let len = now.saturating_sub(end);
                if len > self.limits.release_ps {
                    self.release_reported = true;
                    out.push(r.release.breach(now, format!("driver enable on {:.3} us after the request's last stop bit; at most {:.3} us", len as f64 / 1e6, self.limits.release_ps as f64 / 1e6)));
                }
            }
        }
        if !de && self.de {
            if let Some(mut req) = self.request.take() {
                req.end_ps = self.last_end.unwrap_or(now);
                seen.request = Some(req);
            }
            self.field = None;
            self.last_end = None;
            self.release_reported = false;
            self.lost = false;
        }
        self.de = de;
        seen
    }

    /// One sample inside the field that began at `s`.
    fn in_field(&mut self, now: u64, s: u64, level: bool, de: bool, out: &mut Vec<Breach>) {
        let bit = self.limits.bit_ps;
        let r = self.rules;
        let o = (now - s) as f64;
        let slack = self.limits.tolerance * o + self.limits.jitter_ps;
        while self.bits < 8 && now >= self.at(s, self.bits as f64 + 1.5) {
            if level {
                self.value |= 1 << self.bits;
            }
            self.bits += 1;
        }
        if !self.stop_checked && now >= self.at(s, 9.5) {
            self.stop_checked = true;
            self.request
                .get_or_insert(Request {
                    start_ps: s,
                    end_ps: 0,
                    fields: Vec::new(),
                    damaged: false,
                })
                .fields
                .push(self.value);
            if !level {
                out.push(r.character.breach(
                    now,
                    "stop bit low at its middle (framing error)".to_string(),
                ));
                self.lose();
                return;
            }
        }
        if !de && self.de && !self.stop_checked {
            out.push(r.character.breach(
                now,
                format!("driver enable released {:.2} bits into a field", o / bit),
            ));
            self.lose();
        } else if level != self.drive {
            if self.stop_checked {
                self.last_end = Some(self.at(s, 10.0));
                if level {
                    self.field = None;
                    return;
                }
                if o < 10.0 * bit - slack {
                    out.push(r.character.breach(now, format!("stop bit short: the next start bit {:.1} ns after the field's start edge ({:.1} ns for 10 bits, {:.1} ns allowed)", o / 1e3, 10.0 * bit / 1e3, slack / 1e3)));
                }
                self.start_field(now);
            } else {
                let n = (o / bit).round();
                let off = o - n * bit;
                if n < 1.0 || off.abs() > slack {
                    out.push(r.character.breach(now, format!("an edge {:.1} ns after the field's start edge, {:.2} bits: {:+.1} ns off the bit grid, {:.1} ns allowed", o / 1e3, o / bit, off / 1e3, slack / 1e3)));
                    self.lose();
                }
            }
        } else if self.stop_checked && o >= 10.0 * bit {
            self.last_end = Some(self.at(s, 10.0));
            self.field = None;
        }
    }

    fn start_field(&mut self, now: u64) {
        self.field = Some(now);
        self.bits = 0;
        self.value = 0;
        self.stop_checked = false;
        self.release_reported = false;
        if self.request.is_none() {
            self.request = Some(Request {
                start_ps: now,
                end_ps: 0,
                fields: Vec::new(),
                damaged: false,
            });
        }
    }
}
