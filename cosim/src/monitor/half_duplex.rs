//! What the T-format and ESL monitors share: the host's side of a
//! half-duplex RS-485 pair, watched at its transceiver (the driver's input
//! D, its enable DE, the receiver's output R), and the timing rules of a
//! host that sends 10-bit characters (start 0, 8 data LSB first, stop 1)
//! and then listens:
//!
//! * character timing: every edge of a request field on the bit grid from
//!   the field's start edge, within `tolerance × (time since the start
//!   edge) + jitter + one monitor cycle`; the stop bit high at its middle and
//!   a full bit long; a request's fields back to back (the next start bit
//!   within `max_gap` of the stop bit's end while the driver stays on); the
//!   driver enable not released inside a field;
//! * turnaround: the driver enable off within `release` of the request's
//!   last stop bit; the host's driver never on while the encoder drives its
//!   receiver low while its own driver sends a 1 (both drivers on; a
//!   receiver that echoes the host's driver is low whenever the host sends
//!   a 0, so only a low against a 1 is another driver), and never switched on inside the
//!   encoder's answer (before a bit time of idle line has followed the
//!   answer's last character).
//!
//! A request (its fields as the host's driver sent them) is handed back when
//! the driver enable falls, for the protocol's own checks (field count,
//! request spacing).

use model::wire::Signal;
use serde_json::Value;

use super::Base;
use crate::Pins;

/// The rule names of one protocol, as its seed states them.
#[derive(Debug, Clone, Copy)]
pub struct Rules {
    /// An edge off the bit grid, a low or short stop bit, DE released in a field.
    pub character: &'static str,
    /// A pause between the fields of one request.
    pub gap: &'static str,
    /// DE still on too long after the request.
    pub release: &'static str,
    /// The host drove while the encoder answered.
    pub answer: &'static str,
}

/// The limits, in ps.
#[derive(Debug, Clone, Copy)]
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

/// One request as the host's driver sent it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Request {
    /// The first start edge, ps.
    pub start_ps: u64,
    /// The last stop bit's end (nominal), ps.
    pub end_ps: u64,
    /// The fields' values (sampled mid-bit), in order.
    pub fields: Vec<u8>,
    /// A character-timing violation in it (its fields are not all known).
    pub damaged: bool,
}

/// The watcher's state.
#[derive(Debug, Clone)]
pub struct Watch {
    limits: Limits,
    rules: Rules,
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

impl Watch {
    /// A watcher with `limits`, reporting under `rules`.
    pub fn new(limits: Limits, rules: Rules) -> Self {
        Watch {
            limits,
            rules,
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

    /// One monitor cycle at `now`: the host's driver input `tx`, its enable
    /// `de`, its receiver's output `rx`. Returns the request that ended
    /// (the driver enable fell).
    pub fn step(
        &mut self,
        base: &mut Base,
        now: u64,
        tx: bool,
        de: bool,
        rx: bool,
    ) -> Option<Request> {
        let bit = self.limits.bit_ps;
        let cycle = base.period_ps as f64;
        let r = self.rules;
        // The encoder's answer on the host's receiver.
        if rx != self.rx {
            self.rx = rx;
            if !rx && !de && now >= self.rx_char_end {
                // The next start bit is looked for from this one's stop-bit
                // middle on, as a UART receiver does (an encoder off rate
                // sends characters shorter or longer than 10 bits).
                self.rx_char_end = self.at(now, 9.5);
                self.answer_last = now;
                self.answer_until = Some(self.at(now, 11.0));
            }
        }
        // Low at the receiver while the host drives high: another driver.
        // (Only then: a receiver that echoes the host's own driver is low
        // whenever the host sends a 0.)
        let both = de && tx && !rx;
        if both && !self.both {
            base.violation(
                now,
                r.answer,
                "the host's driver was on while the encoder drove the line low (both drivers on)"
                    .to_string(),
            );
        }
        self.both = both;
        if de && !self.de && self.answer_until.is_some_and(|u| now < u) {
            base.violation(now, r.answer, format!("the host switched its driver on {:.2} bits after the start bit of the encoder's last character, inside its answer (a frame set ends when a bit time of idle line follows a character)", (now - self.answer_last) as f64 / bit));
        }
        // The host's request, as its driver puts it on the line.
        let level = tx || !de;
        let mut ended = None;
        if self.lost && ((level && self.drive && now - self.last_edge > bit as u64) || !de) {
            self.lost = false;
        }
        if self.lost {
            // not timed
        } else if let Some(s) = self.field {
            let o = (now - s) as f64;
            let slack = self.limits.tolerance * o + self.limits.jitter_ps + cycle;
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
                    base.violation(
                        now,
                        r.character,
                        "stop bit low at its middle (framing error)".to_string(),
                    );
                    self.lose();
                }
            }
            if self.lost {
                // the stop bit was low
            } else if !de && self.de && !self.stop_checked {
                base.violation(
                    now,
                    r.character,
                    format!("driver enable released {:.2} bits into a field", o / bit),
                );
                self.lose();
            } else if level != self.drive {
                if self.stop_checked {
                    if !level {
                        if o < 10.0 * bit - slack {
                            base.violation(now, r.character, format!("stop bit short: the next start bit {:.3} us after the field's start edge ({:.3} us for 10 bits)", o / 1e6, 10.0 * bit / 1e6));
                        }
                        self.last_end = Some(self.at(s, 10.0));
                        self.start_field(now);
                    } else {
                        self.last_end = Some(self.at(s, 10.0));
                        self.field = None;
                    }
                } else {
                    let n = (o / bit).round();
                    if n < 1.0 || (o - n * bit).abs() > slack {
                        base.violation(now, r.character, format!("an edge {:.1} ns after the field's start edge, {:.2} bits: off the bit grid by more than {} ns", o / 1e3, o / bit, ((slack - cycle) / 1e3).round()));
                        self.lose();
                    }
                }
            } else if self.stop_checked && o >= 10.0 * bit {
                self.last_end = Some(self.at(s, 10.0));
                self.field = None;
            }
        } else if level != self.drive && !level {
            if let (Some(end), Some(_)) = (self.last_end, &self.request) {
                let gap = now.saturating_sub(end) as f64;
                if gap > self.limits.max_gap_ps + self.limits.jitter_ps + cycle {
                    base.violation(now, r.gap, format!("{:.2} bits of idle line between two fields of one request (the driver stayed on); at most {:.2}", gap / bit, self.limits.max_gap_ps / bit));
                }
            }
            self.start_field(now);
        }
        if level != self.drive {
            self.last_edge = now;
        }
        self.drive = level;
        // The end of the request: the driver enable falls.
        if de && self.field.is_none() && !self.release_reported {
            if let Some(end) = self.last_end.filter(|&e| {
                self.request.is_some() && now > e + self.limits.release_ps + base.period_ps
            }) {
                self.release_reported = true;
                base.violation(now, r.release, format!("driver enable still on {:.3} us after the request's last stop bit; at most {:.3} us", (now - end) as f64 / 1e6, self.limits.release_ps as f64 / 1e6));
            }
        }
        if !de && self.de {
            if let Some(mut req) = self.request.take() {
                req.end_ps = self.last_end.unwrap_or(now);
                ended = Some(req);
            }
            self.field = None;
            self.last_end = None;
            self.release_reported = false;
            self.lost = false;
        }
        self.de = de;
        ended
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

/// The line since the exchange not yet decoded: the wire at the host (its
/// driver's level while DE is on, else the receiver's), DE, and what the
/// host's receiver hears (high while DE is on: it is deaf then). An exchange
/// runs from one rise of DE to the next; it is handed to the decoder a few
/// bits after the next rise (a character of the answer may straddle it),
/// and the line before it is then forgotten.
#[derive(Debug, Clone)]
pub struct Exchanges {
    /// The wire at the host.
    pub wire: Signal,
    /// The host's driver enable.
    pub de: Signal,
    /// What the host's receiver hears.
    pub heard: Signal,
    start: Option<u64>,
    next: Option<u64>,
    settle_ps: u64,
    de_now: bool,
}

/// An exchange to decode: DE's rise, its fall (`u64::MAX`: still on), the next rise (`u64::MAX`: none yet).
pub type Window = (u64, u64, u64);

impl Exchanges {
    /// An empty line; an exchange is decoded `settle_ps` after the next one began.
    pub fn new(settle_ps: u64) -> Self {
        Exchanges {
            wire: Signal::named("wire"),
            de: Signal::named("de"),
            heard: Signal::named("heard"),
            start: None,
            next: None,
            settle_ps,
            de_now: false,
        }
    }

    /// One cycle; `decode` gets each exchange as it becomes complete (with
    /// the line still holding it).
    pub fn step(
        &mut self,
        now: u64,
        tx: bool,
        de: bool,
        rx: bool,
        mut decode: impl FnMut(&Exchanges, Window),
    ) {
        if de && !self.de_now {
            if let Some(w) = self.window(false) {
                decode(self, w);
                self.advance();
            }
            if self.start.is_none() {
                self.start = Some(now);
            } else {
                self.next = Some(now);
            }
        }
        self.de_now = de;
        self.wire.push(now, if de { tx } else { rx });
        self.de.push(now, de);
        self.heard.push(now, de || rx);
        if self.next.is_some_and(|n| now >= n + self.settle_ps) {
            if let Some(w) = self.window(false) {
                decode(self, w);
                self.advance();
            }
        }
    }

    /// The exchange complete but not yet decoded (`open`: or else the one in
    /// progress, up to now).
    pub fn window(&self, open: bool) -> Option<Window> {
        let start = self.start?;
        if !open && self.next.is_none() {
            return None;
        }
        let next = self.next.unwrap_or(u64::MAX);
        let fall = self
            .de
            .next_level(start, false)
            .filter(|&f| f < next)
            .unwrap_or(u64::MAX);
        Some((start, fall, next))
    }

    /// Every exchange not yet decoded, the one in progress last.
    pub fn pending(&self) -> Vec<Window> {
        let mut list: Vec<Window> = self.window(true).into_iter().collect();
        if let Some(n) = self.next {
            list.push((
                n,
                self.de.next_level(n, false).unwrap_or(u64::MAX),
                u64::MAX,
            ));
        }
        list
    }

    /// After the complete exchange was decoded: forget the line before the next one.
    pub fn advance(&mut self) {
        if let Some(n) = self.next.take() {
            self.wire.forget_before(n);
            self.de.forget_before(n);
            self.heard.forget_before(n);
            self.start = Some(n);
        }
    }
}

/// A protocol's decoder, one exchange at a time (its transactions as JSON).
pub trait ExchangeDecoder: Clone {
    /// One exchange of `line`; the transaction it closed, if any.
    fn exchange(&mut self, line: &Exchanges, window: Window) -> Option<Value>;
    /// The transaction still open.
    fn finish(&mut self) -> Option<Value>;
}

/// The host's side of the pair as a monitor sees it: the timing watch, the
/// line not yet decoded and the decoder; what the T-format and ESL monitors
/// share but their own request checks.
pub struct Side<D> {
    /// Clock, violations, decoded transactions.
    pub base: Base,
    watch: Watch,
    line: Exchanges,
    decoder: D,
}

impl<D: ExchangeDecoder> Side<D> {
    /// A side at `base`'s clock with `limits` and `rules`; an exchange is
    /// decoded 12 bits after the next one began.
    pub fn new(base: Base, limits: Limits, rules: Rules, decoder: D) -> Self {
        let settle = (12.0 * limits.bit_ps).round() as u64;
        Side {
            base,
            watch: Watch::new(limits, rules),
            line: Exchanges::new(settle),
            decoder,
        }
    }

    /// One monitor cycle (pins: bit 0 R, bit 1 D, bit 2 DE); the request that ended, if any.
    pub fn step(&mut self, pins: Pins) -> Option<Request> {
        let now = self.base.now_ps();
        let (rx, tx, de) = (pins.0 & 1 != 0, pins.0 & 2 != 0, pins.0 & 4 != 0);
        let (decoder, done) = (&mut self.decoder, &mut self.base.done);
        self.line.step(now, tx, de, rx, |line, w| {
            done.extend(decoder.exchange(line, w))
        });
        self.watch.step(&mut self.base, now, tx, de, rx)
    }

    /// The transactions not yet in `base.done` (the decoder's state is not changed).
    pub fn pending(&self) -> Vec<Value> {
        let mut d = self.decoder.clone();
        let mut out: Vec<Value> = self
            .line
            .pending()
            .into_iter()
            .filter_map(|w| d.exchange(&self.line, w))
            .collect();
        out.extend(d.finish());
        out
    }

    /// The last transaction (the one in progress included).
    pub fn last(&self) -> Option<Value> {
        self.pending()
            .pop()
            .or_else(|| self.base.done.last().cloned())
    }

    /// Transactions seen so far (the one in progress included).
    pub fn count(&self) -> u64 {
        (self.base.done.len() + self.pending().len()) as u64
    }

    /// The transcript.
    pub fn transcript(&self, protocol: &str) -> Value {
        self.base
            .transcript(protocol, &["rx", "tx", "tx_en"], self.pending())
    }
}
