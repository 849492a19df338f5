//! What the SAR58K24 and Modbus RTU monitors share: the host's side of a
//! half-duplex RS-485 pair carrying asynchronous characters (start 0, 8 data
//! LSB first, an optional parity bit, stop 1), watched at the host's
//! transceiver (driver input D, its enable DE, receiver output R), and the
//! line recorded for the decoder (`model::uart::line`, shared with `tbgen
//! decode sar|modbus`).
//!
//! Timing rules of the host's requests (each with one monitor cycle of
//! tolerance; the rule names are the protocol's, [`Rules`]):
//!
//! * character: every edge of a request character on the bit grid from its
//!   start edge, within `tolerance × (time since the start edge)` (the baud
//!   rate tolerance); the parity bit right; the stop bit high at its middle
//!   and a full bit long; DE not released inside a character;
//! * gap: the silence between two characters of one request (from the
//!   previous stop bit's middle, where a receiver has seen the character
//!   end, to the next start edge) at most `max_gap_ps`;
//! * silence: a request begins only `min_silence_ps` after the last
//!   character on the line, either direction, counted from the end of its
//!   stop bit (half a bit after its middle, at the configured baud): the
//!   silence on the line the Modbus serial-line specification asks for;
//! * release: DE off within `release_ps` of the request's last stop bit
//!   (reported when it falls);
//! * answer: never both drivers on (R low for a quarter bit or more while
//!   the host drives a 1: an echoing receiver lags the driver), never
//!   DE switched on inside a character of the device;
//! * wait: after a request (or trigger) that the device answers, the next
//!   request only once an answer character has begun or `timeout_ps` has
//!   passed since the request ended.

use model::uart::Parity;
use model::wire::Signal;

use super::Base;

/// The rule names of one protocol, as its seed states them (or the project's reading).
#[derive(Debug, Clone, Copy)]
pub struct Rules {
    /// Off-grid edge, bad parity bit, low or short stop bit, DE released in a character.
    pub character: &'static str,
    /// Silence inside a request.
    pub gap: &'static str,
    /// Too little silence before a request.
    pub silence: &'static str,
    /// DE still on after the request.
    pub release: &'static str,
    /// The host drove while the device answered.
    pub answer: &'static str,
    /// The next request before the answer or the timeout.
    pub wait: &'static str,
}

/// The limits, ps (`f64`: exact at any baud rate).
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// One bit.
    pub bit_ps: f64,
    /// The character format.
    pub parity: Parity,
    /// Drift allowed per ps since the character's start edge (0.02 = 2 %).
    pub tolerance: f64,
    /// Longest silence between two characters of a request (stop-bit middle to start edge).
    pub max_gap_ps: f64,
    /// Least silence before a request (0: not checked).
    pub min_silence_ps: f64,
    /// Longest time from the last stop bit's end to DE off.
    pub release_ps: f64,
    /// The host's answer timeout: the least wait for an answer that does not come.
    pub timeout_ps: f64,
}

/// One request as the host's driver sent it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Request {
    /// The first start edge, ps.
    pub start_ps: u64,
    /// The characters (sampled mid-bit), in order.
    pub bytes: Vec<u8>,
}

/// The watcher's state.
#[derive(Debug, Clone)]
pub struct Watch {
    limits: Limits,
    rules: Rules,
    de: bool,
    drive: bool,
    /// The character in progress: its start edge.
    ch: Option<u64>,
    bits: u32,
    value: u8,
    stop_checked: bool,
    parity_checked: bool,
    resync: bool,
    lost: bool,
    last_edge: u64,
    /// The request in progress (DE on, at least one character).
    request: Option<Request>,
    /// The last host character's stop-bit middle and end.
    last_stop_mid: Option<f64>,
    last_end: Option<f64>,
    gap_reported: bool,
    /// The device's character in progress (its start edge) and the last one's stop-bit middle.
    rx: bool,
    dev_char: Option<u64>,
    dev_stop_mid: Option<f64>,
    both: bool,
    both_since: Option<u64>,
    /// A request (or trigger) waiting for its answer: when it ended.
    awaiting: Option<u64>,
}

impl Watch {
    /// A watcher with `limits`, reporting under `rules`.
    pub fn new(limits: Limits, rules: Rules) -> Self {
        Watch {
            limits,
            rules,
            de: false,
            drive: true,
            ch: None,
            bits: 0,
            value: 0,
            stop_checked: false,
            parity_checked: false,
            resync: false,
            lost: false,
            last_edge: 0,
            request: None,
            last_stop_mid: None,
            last_end: None,
            gap_reported: false,
            rx: true,
            dev_char: None,
            dev_stop_mid: None,
            both: false,
            both_since: None,
            awaiting: None,
        }
    }

    fn fb(&self) -> f64 {
        self.limits.parity.frame_bits() as f64
    }

    fn at(&self, start: u64, bits: f64) -> u64 {
        start + (bits * self.limits.bit_ps).round() as u64
    }

    /// The host's request (or trigger) that `end_ps` ended waits for an answer from now on.
    pub fn expect_answer(&mut self, end_ps: u64) {
        self.awaiting = Some(end_ps);
    }

    /// A device character is on the line now (or was until its stop bit's middle).
    pub fn device_busy(&self, now: u64) -> bool {
        self.dev_char.is_some_and(|d| now < self.at(d, self.fb()))
    }

    /// The wait rule, for a request or trigger beginning at `now` (`what` names it).
    pub fn check_wait(&mut self, base: &mut Base, now: u64, what: &str) {
        if let Some(end) = self.awaiting {
            let waited = now.saturating_sub(end) as f64;
            if waited + (base.period_ps as f64) < self.limits.timeout_ps {
                base.violation(
                    now,
                    self.rules.wait,
                    format!("{what} {:.1} us after the previous request ended, with no answer begun; the host waits for the answer or its timeout of {:.1} us", waited / 1e6, self.limits.timeout_ps / 1e6),
                );
            }
            self.awaiting = None;
        }
    }

    /// A character-timing violation: the character is abandoned, and
    /// neither the gap to the next character nor the release after it is
    /// measured (their reference is lost with it).
    fn lose(&mut self) {
        self.lost = true;
        self.ch = None;
        self.resync = true;
        self.last_end = None;
    }

    /// One monitor cycle at `now`: the host's driver input `tx`, its enable
    /// `de`, its receiver's output `rx`. Returns the request that ended (DE fell).
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
        let fb = self.fb();
        let r = self.rules;
        // The device's characters at the host's receiver.
        if rx != self.rx {
            self.rx = rx;
            if !rx
                && !de
                && !self.device_busy(now)
                && self.dev_char.is_none_or(|d| now >= self.at(d, fb - 0.5))
            {
                self.dev_char = Some(now);
                self.dev_stop_mid = Some(now as f64 + (fb - 0.5) * bit);
                self.awaiting = None;
            }
        }
        // Low at the receiver while the host drives a 1 for a quarter bit or
        // more: another driver (a receiver that echoes the host's own driver,
        // or a resolved line level, lags it by a few cycles at each edge).
        if de && tx && !rx {
            let since = *self.both_since.get_or_insert(now);
            if !self.both && (now - since) as f64 >= bit / 4.0 {
                self.both = true;
                base.violation(since, r.answer, "the host's driver was on while the device drove the line low (both drivers on)".to_string());
            }
        } else {
            self.both_since = None;
            self.both = false;
        }
        if de && !self.de && self.device_busy(now) {
            let d = self.dev_char.unwrap_or(now);
            base.violation(
                now,
                r.answer,
                format!(
                    "the host switched its driver on {:.2} bits into a character of the device",
                    (now - d) as f64 / bit
                ),
            );
        }
        // The host's characters, as its driver puts them on the line.
        let level = tx || !de;
        if self.lost && ((level && now - self.last_edge > bit as u64) || !de) {
            self.lost = false;
        }
        if self.lost {
            // not timed until the line is idle again
        } else if let Some(s) = self.ch {
            let o = (now - s) as f64;
            let slack = self.limits.tolerance * o + cycle;
            while self.bits < 8 && now >= self.at(s, self.bits as f64 + 1.5) {
                if level {
                    self.value |= 1 << self.bits;
                }
                self.bits += 1;
            }
            if self.limits.parity != Parity::None
                && self.bits == 8
                && !self.parity_checked
                && now >= self.at(s, 9.5)
            {
                self.parity_checked = true;
                if level != self.limits.parity.bit(self.value) {
                    base.violation(
                        now,
                        r.character,
                        format!(
                            "parity bit wrong for 0x{:02X} ({:?} parity)",
                            self.value, self.limits.parity
                        ),
                    );
                }
            }
            if !self.stop_checked && now >= self.at(s, fb - 0.5) {
                self.stop_checked = true;
                self.last_stop_mid = Some(s as f64 + (fb - 0.5) * bit);
                self.last_end = Some(s as f64 + fb * bit);
                self.gap_reported = false;
                let v = self.value;
                self.request
                    .get_or_insert(Request {
                        start_ps: s,
                        bytes: Vec::new(),
                    })
                    .bytes
                    .push(v);
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
                    format!(
                        "driver enable released {:.2} bits into a character",
                        o / bit
                    ),
                );
                self.lose();
            } else if level != self.drive {
                if self.stop_checked {
                    if !level {
                        if o < fb * bit - slack {
                            base.violation(now, r.character, format!("stop bit short: the next start bit {:.3} us after the character's start edge ({:.3} us for {fb} bits)", o / 1e6, fb * bit / 1e6));
                        }
                        self.start_char(base, now);
                    } else {
                        self.ch = None;
                    }
                } else {
                    let n = (o / bit).round();
                    if n < 1.0 || (o - n * bit).abs() > slack {
                        base.violation(now, r.character, format!("an edge {:.2} bits after the character's start edge: off the bit grid by more than {:.1} % of the time since it (baud rate tolerance)", o / bit, self.limits.tolerance * 100.0));
                        self.lose();
                    }
                }
            } else if self.stop_checked && o >= fb * bit {
                self.ch = None;
            }
        } else if level != self.drive && !level {
            self.start_char(base, now);
        }
        if level != self.drive {
            self.last_edge = now;
        }
        self.drive = level;
        // DE held after the request is reported when it falls: while it
        // is on, a next character may still come (then a long silence is a
        // gap), and a device answering into it is two drivers on.
        let mut ended = None;
        if !de && self.de {
            if let Some(end) = self.last_end {
                if self.request.is_some() && now as f64 > end + self.limits.release_ps + cycle {
                    base.violation(now, r.release, format!("driver enable released {:.1} us after the request's last stop bit; at most {:.1} us", (now as f64 - end) / 1e6, self.limits.release_ps / 1e6));
                }
            }
            ended = self.request.take();
            self.ch = None;
        }
        self.de = de;
        ended
    }

    fn start_char(&mut self, base: &mut Base, now: u64) {
        let first = self.request.is_none();
        if first {
            // The silence before a request, from the last character on the line (either direction).
            let last = [self.last_stop_mid, self.dev_stop_mid]
                .into_iter()
                .flatten()
                .fold(None, |a: Option<f64>, b| Some(a.map_or(b, |a| a.max(b))));
            if let Some(l) = last.filter(|_| self.limits.min_silence_ps > 0.0) {
                let quiet = now as f64 - (l + self.limits.bit_ps / 2.0);
                if quiet + (base.period_ps as f64) < self.limits.min_silence_ps {
                    base.violation(now, self.rules.silence, format!("a request began {:.1} us after the last character on the line (from the end of its stop bit); at least {:.1} us", quiet / 1e6, self.limits.min_silence_ps / 1e6));
                }
            }
            self.check_wait(base, now, "a request");
            self.resync = false;
        } else if let Some(m) = self
            .last_stop_mid
            .filter(|_| !std::mem::take(&mut self.resync))
        {
            let gap = now as f64 - m;
            if gap > self.limits.max_gap_ps + base.period_ps as f64 && !self.gap_reported {
                self.gap_reported = true;
                base.violation(now, self.rules.gap, format!("{:.1} us of silence between two characters of one request (from the stop bit's middle); at most {:.1} us", gap / 1e6, self.limits.max_gap_ps / 1e6));
            }
        }
        self.ch = Some(now);
        self.bits = 0;
        self.value = 0;
        self.stop_checked = false;
        self.parity_checked = false;
    }
}

/// The line as the decoder reads it: the wire at the host (D while DE is
/// on, else R) and DE, from the last cut on.
#[derive(Debug, Clone)]
pub struct Line {
    /// The wire.
    pub wire: Signal,
    /// The host's driver enable.
    pub de: Signal,
    /// Where the piece not yet decoded begins, ps.
    pub from: u64,
}

impl Line {
    /// An empty line, idle high, DE off.
    pub fn new() -> Self {
        let mut de = Signal::named("tx_en");
        de.push(0, false);
        Line {
            wire: Signal::named("line"),
            de,
            from: 0,
        }
    }

    /// One monitor cycle.
    pub fn step(&mut self, now: u64, tx: bool, de: bool, rx: bool) {
        self.wire.push(now, if de { tx } else { rx });
        self.de.push(now, de);
    }

    /// Forgets the line before `t_ps` (the next piece begins there).
    pub fn cut(&mut self, t_ps: u64) {
        self.wire.forget_before(t_ps);
        self.de.forget_before(t_ps);
        self.from = t_ps;
    }
}

impl Default for Line {
    fn default() -> Self {
        Line::new()
    }
}

/// The pins of a UART monitor: bit 0 R, bit 1 D, bit 2 DE.
pub fn pins(p: crate::Pins) -> (bool, bool, bool) {
    (p.0 & 1 != 0, p.0 & 2 != 0, p.0 & 4 != 0)
}
