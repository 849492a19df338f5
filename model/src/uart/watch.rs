//! The host's asynchronous characters on a half-duplex RS-485 pair, as the
//! SAR58K24 and Modbus RTU rule books judge them: one watcher, fed one
//! sample at a time by the emulator and by the monitor alike, that decides
//! every rule of a host's requests and returns [`Breach`]es under the rule
//! names of the protocol's book ([`Book`]). The protocols' watchers
//! ([`crate::sar58k24::rules`], [`crate::modbus::rules`]) wrap it with
//! their own rules (trigger, CLR, CRC).
//!
//! The host's transceiver as it is sampled: its driver input `tx`, its
//! driver enable `de`, its receiver output `rx`. A request is the
//! characters the host drives between DE rising and DE falling.
//!
//! ```text
//!  DE   __/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_______________
//!  line ‾‾‾‾\_S_d0.._d7_P_/‾stop‾\_S_ ... ‾stop‾|‾‾‾‾‾\_device_ ..
//!           |<- grid ->|      |<->| gap   |<>| release
//!  last char on the line ..stop|<------ silence ------>|\_ next request
//! ```
//!
//! Each limit is applied to the lengths between sampled edges as measured,
//! with no slack of a sampling cycle:
//!
//! * character: an edge of a request character `o` ps after its start edge
//!   is off the bit grid by at most `tolerance × o`; the parity bit right;
//!   the stop bit high at its middle and a full bit long (the next start
//!   edge no sooner than `frame bits × bit × (1 − tolerance)`); DE not
//!   released inside a character;
//! * gap: from a stop bit's middle (where a receiver has seen the character
//!   end) to the next start edge of the same request, at most `max_gap_ps`;
//! * silence: from the end of the last stop bit on the line, either
//!   direction (the stop bit's middle and half a bit, as
//!   [`super::stop_rest_clocks`] counts), to a request's first start edge,
//!   at least `min_silence_ps`;
//! * release: DE off at most `release_ps` after the end of the request's
//!   last stop bit;
//! * answer: never both drivers on (the receiver low for a quarter bit or
//!   more while the host drives a 1: an echoing receiver lags its driver),
//!   never DE switched on inside a character of the device;
//! * wait: after a request the device answers, the next request only once
//!   an answer character has begun or `timeout_ps` has passed.
//!
//! The line is idle (high) before time 0, as the fail-safe bias holds an
//! undriven pair: a host in reset from time 0 leaves DE off (X or Z on it
//! reads as not driving) and draws no report, and a host that drives a
//! start bit at time 0 sends a character. After a character breach the
//! request is broken: its other characters are not judged again until DE
//! falls.

use crate::rules::{self, Breach, Rule};

use super::Parity;

/// The rules of one protocol's book the watcher reports under.
#[derive(Debug, Clone, Copy)]
pub struct Book {
    /// Off-grid edge, bad parity bit, low or short stop bit, DE released in a character.
    pub character: &'static Rule,
    /// Silence inside a request.
    pub gap: &'static Rule,
    /// Too little silence before a request (`None`: not a rule of the protocol).
    pub silence: Option<&'static Rule>,
    /// DE still on after the request.
    pub release: &'static Rule,
    /// The host drove while the device answered.
    pub answer: &'static Rule,
    /// The next request before the answer or the timeout.
    pub wait: &'static Rule,
}

/// The limits in force, ps (the bit grid in `f64`: exact at any baud rate).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// One bit.
    pub bit_ps: f64,
    /// The character format.
    pub parity: Parity,
    /// Drift allowed per ps since the character's start edge (0.02 = 2 %).
    pub tolerance: f64,
    /// Longest silence between two characters of a request (stop-bit middle to start edge).
    pub max_gap_ps: u64,
    /// Least silence before a request, from the end of the last stop bit.
    pub min_silence_ps: u64,
    /// Longest time from the last stop bit's end to DE off.
    pub release_ps: u64,
    /// The host's answer timeout: the least wait for an answer that does not come.
    pub timeout_ps: u64,
}

impl Limits {
    /// Bits of one character.
    pub fn frame_bits(&self) -> f64 {
        self.parity.frame_bits() as f64
    }

    /// The least lengths of `book`'s rules, for [`rules::resolution_notes`]:
    /// the character's tolerance one bit after its start edge, the shortest
    /// it is held to.
    pub fn least(&self, book: &Book) -> Vec<(&'static Rule, u64)> {
        let mut v = vec![
            (
                book.character,
                (self.tolerance * self.bit_ps).round() as u64,
            ),
            (book.gap, self.max_gap_ps),
        ];
        if let Some(s) = book.silence {
            v.push((s, self.min_silence_ps));
        }
        v.push((book.release, self.release_ps));
        v
    }
}

/// One request as the host's driver sent it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Request {
    /// The first start edge, ps.
    pub start_ps: u64,
    /// The characters (sampled mid-bit), in order.
    pub bytes: Vec<u8>,
    /// A rule of the request's characters was broken (its bytes may be
    /// incomplete).
    pub broken: bool,
}

/// What one sample showed.
#[derive(Debug, Clone, Default)]
pub struct Seen {
    /// Rules broken at this sample.
    pub breaches: Vec<Breach>,
    /// The request DE's fall ended at this sample.
    pub ended: Option<Request>,
}

/// The watcher.
#[derive(Debug, Clone)]
pub struct Watch {
    limits: Limits,
    book: Book,
    de: bool,
    /// A character breach was reported since DE last fell: the request is
    /// broken, and what follows in it is not judged again.
    char_reported: bool,
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
    /// The last host character's stop-bit middle and end, ps.
    last_stop_mid: Option<f64>,
    last_end: Option<f64>,
    gap_reported: bool,
    /// The device's character in progress (its start edge) and the last one's stop-bit middle.
    rx: bool,
    dev_char: Option<u64>,
    dev_stop_mid: Option<f64>,
    /// Both drivers were reported on since DE last rose (once a request).
    both: bool,
    both_since: Option<u64>,
    /// A request (or trigger) waiting for its answer: when it ended.
    awaiting: Option<u64>,
}

impl Watch {
    /// A watcher holding the host to `limits`, reporting under `book`.
    pub fn new(limits: Limits, book: Book) -> Self {
        Watch {
            limits,
            book,
            de: false,
            char_reported: false,
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

    /// The limits in force.
    pub fn limits(&self) -> &Limits {
        &self.limits
    }

    fn at(&self, start: u64, bits: f64) -> u64 {
        start + (bits * self.limits.bit_ps).round() as u64
    }

    /// The host's request (or trigger) that `end_ps` ended waits for an answer from now on.
    pub fn expect_answer(&mut self, end_ps: u64) {
        self.awaiting = Some(end_ps);
    }

    /// A device character is on the line at `now` (until the end of its stop bit).
    pub fn device_busy(&self, now: u64) -> bool {
        self.dev_char
            .is_some_and(|d| now < self.at(d, self.limits.frame_bits()))
    }

    /// The wait rule, for a request or trigger beginning at `now` (`what` names it).
    pub fn check_wait(&mut self, now: u64, what: &str) -> Option<Breach> {
        let end = self.awaiting.take()?;
        let waited = now.saturating_sub(end);
        (waited < self.limits.timeout_ps).then(|| {
            self.book.wait.breach(
                now,
                format!(
                    "{what} {:.1} us after the previous request ended, with no answer begun; the host waits for the answer or its timeout of {:.1} us",
                    rules::us(waited),
                    rules::us(self.limits.timeout_ps)
                ),
            )
        })
    }

    /// A character-timing breach: the character is abandoned, and neither
    /// the gap to the next character nor the release after it is measured
    /// (their reference is lost with it).
    fn lose(&mut self) {
        self.lost = true;
        self.ch = None;
        self.resync = true;
        self.last_end = None;
        if let Some(r) = self.request.as_mut() {
            r.broken = true;
        }
    }

    fn character(&mut self, out: &mut Vec<Breach>, now: u64, detail: String) {
        if !std::mem::replace(&mut self.char_reported, true) {
            out.push(self.book.character.breach(now, detail));
        }
        if let Some(r) = self.request.as_mut() {
            r.broken = true;
        }
    }

    /// One sample at `now`, ps: the host's driver input `tx`, its enable
    /// `de`, its receiver's output `rx`.
    pub fn sample(&mut self, now: u64, tx: bool, de: bool, rx: bool) -> Seen {
        let mut out = Vec::new();
        let bit = self.limits.bit_ps;
        let fb = self.limits.frame_bits();
        let tol = self.limits.tolerance;
        let level = tx || !de;
        // The device's characters at the host's receiver: a falling edge
        // from the last one's stop-bit middle on starts the next (a device
        // a little fast starts it before the nominal end of the last).
        if rx != self.rx {
            self.rx = rx;
            if !rx && !de && self.dev_char.is_none_or(|d| now >= self.at(d, fb - 0.5)) {
                self.dev_char = Some(now);
                self.dev_stop_mid = Some(now as f64 + (fb - 0.5) * bit);
                self.awaiting = None;
            }
        }
        // Low at the receiver while the host drives a 1 for a quarter bit or
        // more: another driver (a receiver that echoes the host's own driver
        // lags it by a few cycles at each edge).
        if de && tx && !rx {
            let since = *self.both_since.get_or_insert(now);
            if !self.both && (now - since) as f64 >= bit / 4.0 {
                self.both = true;
                out.push(self.book.answer.breach(
                    since,
                    "the host's driver was on while the device drove the line low (both drivers on)"
                        .to_string(),
                ));
            }
        } else {
            self.both_since = None;
        }
        if de && !self.de && self.device_busy(now) {
            let d = self.dev_char.unwrap_or(now);
            out.push(self.book.answer.breach(
                now,
                format!(
                    "the host switched its driver on {:.2} bits into a character of the device",
                    (now - d) as f64 / bit
                ),
            ));
        }
        // The host's characters, as its driver puts them on the line.
        if self.lost && ((level && (now - self.last_edge) as f64 > bit) || !de) {
            self.lost = false;
        }
        if self.lost {
            // not timed until the line is idle again
        } else if let Some(s) = self.ch {
            let o = (now - s) as f64;
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
                    let detail = format!(
                        "parity bit wrong for 0x{:02X} ({:?} parity)",
                        self.value, self.limits.parity
                    );
                    self.character(&mut out, now, detail);
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
                        broken: false,
                    })
                    .bytes
                    .push(v);
                if !level {
                    self.character(
                        &mut out,
                        now,
                        "stop bit low at its middle (framing error)".to_string(),
                    );
                    self.lose();
                }
            }
            if self.lost {
                // the stop bit was low
            } else if !de && self.de && !self.stop_checked {
                self.character(
                    &mut out,
                    now,
                    format!(
                        "driver enable released {:.2} bits into a character",
                        o / bit
                    ),
                );
                self.lose();
            } else if level != self.drive {
                if self.stop_checked {
                    if !level {
                        if o < fb * bit * (1.0 - tol) {
                            let detail = format!("stop bit short: the next start bit {:.3} us after the character's start edge ({:.3} us for {fb} bits, less {:.1} %)", o / 1e6, fb * bit / 1e6, tol * 100.0);
                            self.character(&mut out, now, detail);
                        }
                        self.start_char(&mut out, now);
                    } else {
                        self.ch = None;
                    }
                } else {
                    let n = (o / bit).round();
                    if n < 1.0 || (o - n * bit).abs() > tol * o {
                        let detail = format!("an edge {:.2} bits after the character's start edge: off the bit grid by more than {:.1} % of the time since it (baud rate tolerance)", o / bit, tol * 100.0);
                        self.character(&mut out, now, detail);
                        self.lose();
                    }
                }
            } else if self.stop_checked && o >= fb * bit {
                self.ch = None;
            }
        } else if level != self.drive && !level {
            self.start_char(&mut out, now);
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
                let held = now as f64 - end;
                if self.request.is_some() && held > self.limits.release_ps as f64 {
                    out.push(self.book.release.breach(
                        now,
                        format!(
                            "driver enable released {:.3} us after the request's last stop bit; at most {:.3} us",
                            held / 1e6,
                            rules::us(self.limits.release_ps)
                        ),
                    ));
                }
            }
            ended = self.request.take();
            self.ch = None;
            self.char_reported = false;
            self.both = false;
        }
        self.de = de;
        Seen {
            breaches: out,
            ended,
        }
    }

    fn start_char(&mut self, out: &mut Vec<Breach>, now: u64) {
        if self.request.is_none() {
            // The silence before a request, from the end of the last
            // character on the line (either direction).
            let last = [self.last_stop_mid, self.dev_stop_mid]
                .into_iter()
                .flatten()
                .reduce(f64::max);
            if let (Some(rule), Some(mid)) = (self.book.silence, last) {
                let quiet = now as f64 - (mid + self.limits.bit_ps / 2.0);
                if quiet < self.limits.min_silence_ps as f64 {
                    out.push(rule.breach(
                        now,
                        format!(
                            "a request began {:.3} us after the last character on the line (from the end of its stop bit); at least {:.3} us",
                            quiet / 1e6,
                            rules::us(self.limits.min_silence_ps)
                        ),
                    ));
                }
            }
            out.extend(self.check_wait(now, "a request"));
            self.resync = false;
        } else if let Some(m) = self
            .last_stop_mid
            .filter(|_| !std::mem::take(&mut self.resync))
        {
            let gap = now as f64 - m;
            if gap > self.limits.max_gap_ps as f64 && !self.gap_reported {
                self.gap_reported = true;
                out.push(self.book.gap.breach(
                    now,
                    format!(
                        "{:.3} us of silence between two characters of one request (from the stop bit's middle); at most {:.3} us",
                        gap / 1e6,
                        rules::us(self.limits.max_gap_ps)
                    ),
                ));
                if let Some(r) = self.request.as_mut() {
                    r.broken = true;
                }
            }
        }
        self.ch = Some(now);
        self.bits = 0;
        self.value = 0;
        self.stop_checked = false;
        self.parity_checked = false;
    }
}
