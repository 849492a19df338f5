//! The Modbus RTU master's rules (seed 001, SAR58K24 manual, 3.1.7, and the
//! Modbus over serial line rules it relies on for t1.5 and t3.5, as
//! `protocols.md` reads them), in the shape of [`crate::rules`].
//!
//! ```text
//!  DE    __/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_____________________________/‾‾‾
//!  line  ‾‾‾‾\_01_/\_03_/ .. \_CRC_/‾‾‾‾‾‾‾‾‾‾‾‾\_01_/ .. \_CRC_/‾‾‾‾‾‾‾‾\_01
//!               |<>| t1.5            |<>| release  |<- answer ->|<-t3.5->|
//! ```
//!
//! t1.5 and t3.5 are 1.5 and 3.5 character times, fixed at 750 µs and
//! 1750 µs above 19200 baud ([`super::frames::t15_seconds`],
//! [`super::frames::t35_seconds`]). t1.5 is measured from a stop bit's
//! middle, where a receiver has seen the character end; t3.5 from the end
//! of the last stop bit on the line, as the master model counts it
//! ([`crate::uart::stop_rest_clocks`]). The characters' rules are decided
//! by [`crate::uart::watch`] under this book's names; the CRC and the
//! answer wait here. The emulator and the monitor both feed [`Watch`] and
//! print what it returns.

use std::sync::OnceLock;

use crate::rules::{Bound, Breach, Rule, Settable, Unit};
use crate::uart::watch::{self, Book};
use crate::uart::Parity;
use crate::ConfigError;

use super::frames::{self, BROADCAST};

const SECTION: &str = "seed 001 SAR58K24 manual, 3.1.7";
/// The seed's words on the request.
const REQUEST_WORDS: &str = "The command format of the host is the slave address, function code, starting address, number of bytes and CRC code.";

/// Every edge of a request character on its bit grid.
pub static CHARACTER: Rule = Rule {
    protocol: "modbus",
    name: "character",
    section: SECTION,
    seed_words: "(1) Modbus communication protocol (RTU mode). (3) Factory default Settings: ① No parity bit ② Port rate 19200bps",
    quantity: "a request character's edge off its bit grid",
    bound: Bound::AtMost(2.0, Unit::Percent),
    measured: "every edge of a request character, from its start edge: off the nearest bit boundary by at most the tolerance times the time since the start edge (and the next start edge no sooner than a character less the tolerance); the parity bit as configured; the stop bit high at its middle; DE not released inside a character",
    reading: "the seed gives no baud rate tolerance: the project's reading, 2 % of the time since the start edge (a sender's share beside a receiver's own), `monitor.baud_tolerance_percent`",
    settable: Some(Settable { lo: 0.0, hi: 2.0 }),
    label: OnceLock::new(),
};

/// The longest silence inside a request.
pub static T15: Rule = Rule {
    protocol: "modbus",
    name: "t1.5",
    section: "seed 001 SAR58K24 manual, 3.1.7; Modbus over serial line 2.5.1.1",
    seed_words: "(1) Modbus communication protocol (RTU mode).",
    quantity: "silence inside a request",
    bound: Bound::AtMost(1.5, Unit::Chars),
    measured: "from a request character's stop-bit middle (where a receiver has seen it end) to the next start edge of the same request (DE held on); 750 us above 19200 baud",
    reading: "RTU mode's frame as the Modbus serial-line rules state it (protocols.md): a frame is a continuous stream, a silence over t1.5 inside it makes the devices discard it",
    settable: None,
    label: OnceLock::new(),
};

/// The least silence before a request.
pub static T35: Rule = Rule {
    protocol: "modbus",
    name: "t3.5",
    section: SECTION,
    seed_words: "Each frame contains at least 3.5 bytes of time interval between its start and end.",
    quantity: "silence before a request",
    bound: Bound::AtLeast(3.5, Unit::Chars),
    measured: "from the end of the last stop bit on the line, either direction, to the request's first start edge; 1750 us above 19200 baud",
    reading: "the silent interval between frames of the Modbus serial-line rules (protocols.md: \"3.5-character gap between frames\"), counted from the end of the stop bit as the master model does",
    settable: None,
    label: OnceLock::new(),
};

/// DE released after the request.
pub static RELEASE: Rule = Rule {
    protocol: "modbus",
    name: "release",
    section: SECTION,
    seed_words: REQUEST_WORDS,
    quantity: "DE held after the request",
    bound: Bound::AtMost(1.0, Unit::Bits),
    measured: "from the end of the request's last stop bit to DE falling",
    reading: "the device answers on the same RS-485 pair, so the master releases it after its request: the project's reading, within one bit time, `monitor.release_bits`",
    settable: Some(Settable { lo: 0.0, hi: 1.0 }),
    label: OnceLock::new(),
};

/// One driver on the line at a time.
pub static ANSWER: Rule = Rule {
    protocol: "modbus",
    name: "one driver",
    section: SECTION,
    seed_words: "The data format of the slave response is the slave address, function code, data area and CRC code.",
    quantity: "the master drives while a device answers",
    bound: Bound::Form,
    measured: "the master's receiver low for a quarter bit or more while it drives a 1, or DE switched on inside a character of a device",
    reading: "half-duplex RS-485: one driver on the pair at a time",
    settable: None,
    label: OnceLock::new(),
};

/// The answer waited for.
pub static TIMEOUT: Rule = Rule {
    protocol: "modbus",
    name: "response timeout",
    section: SECTION,
    seed_words: "The data format of the slave response is the slave address, function code, data area and CRC code.",
    quantity: "the next request before the answer or the master's timeout",
    bound: Bound::Form,
    measured: "after a request to one station (not the broadcast address 0) that the devices keep, the next request's first start edge once an answer character has begun or the master's timeout has passed since DE fell",
    reading: "the seed gives no timeout: the master's own, `[master] timeout_us` (5000 us)",
    settable: None,
    label: OnceLock::new(),
};

/// The request's CRC.
pub static CRC: Rule = Rule {
    protocol: "modbus",
    name: "CRC",
    section: SECTION,
    seed_words: "The CRC code is two bytes, with the low bits first.",
    quantity: "a request's CRC-16",
    bound: Bound::Form,
    measured: "every request whose characters met their rules (DE on to DE off) ends with the CRC-16 of its bytes, low byte first",
    reading: "",
    settable: None,
    label: OnceLock::new(),
};

/// The Modbus RTU rules, in the order of the seed.
pub static RULES: &[&Rule] = &[&CHARACTER, &T15, &T35, &RELEASE, &ANSWER, &TIMEOUT, &CRC];

/// The book the character watcher reports under.
pub const BOOK: Book = Book {
    character: &CHARACTER,
    gap: &T15,
    silence: Some(&T35),
    release: &RELEASE,
    answer: &ANSWER,
    wait: &TIMEOUT,
};

/// The master's configured bounds, each with the field it came from.
#[derive(Debug, Clone)]
pub struct Settings<'a> {
    /// Baud rate.
    pub baud: f64,
    /// Character format.
    pub parity: Parity,
    /// [`CHARACTER`], %.
    pub tolerance_percent: (&'a str, f64),
    /// [`RELEASE`], bit times.
    pub release_bits: (&'a str, f64),
    /// [`TIMEOUT`]: the master's answer timeout, µs.
    pub timeout_us: f64,
}

/// The bounds in force, ps.
#[derive(Debug, Clone, PartialEq)]
pub struct Limits {
    /// The characters' limits (t1.5 the longest gap, t3.5 the least silence).
    pub uart: watch::Limits,
}

impl Limits {
    /// The limits of `s`, each bound refused outside its rule's range.
    pub fn new(s: &Settings) -> Result<Self, ConfigError> {
        let bit_ps = 1e12 / s.baud;
        let fb = s.parity.frame_bits();
        let ps = |seconds: f64| (seconds * 1e12).round() as u64;
        Ok(Limits {
            uart: watch::Limits {
                bit_ps,
                parity: s.parity,
                tolerance: CHARACTER.setting(s.tolerance_percent.0, s.tolerance_percent.1)? / 100.0,
                max_gap_ps: ps(frames::t15_seconds(s.baud, fb)),
                min_silence_ps: ps(frames::t35_seconds(s.baud, fb)),
                release_ps: (RELEASE.setting(s.release_bits.0, s.release_bits.1)? * bit_ps).round()
                    as u64,
                timeout_ps: Unit::Us.ps(s.timeout_us),
            },
        })
    }

    /// The least lengths, for [`crate::rules::resolution_notes`].
    pub fn least(&self) -> Vec<(&'static Rule, u64)> {
        self.uart.least(&BOOK)
    }
}

/// The Modbus watcher: the characters ([`watch::Watch`]), the CRC, the wait.
#[derive(Debug, Clone)]
pub struct Watch {
    chars: watch::Watch,
}

impl Watch {
    /// A watcher holding the master to `limits`.
    pub fn new(limits: Limits) -> Self {
        Watch {
            chars: watch::Watch::new(limits.uart, BOOK),
        }
    }

    /// One sample at `t_ps`: the master's receiver output `rx`, its driver
    /// input `tx` and enable `de`.
    pub fn sample(&mut self, t_ps: u64, rx: bool, tx: bool, de: bool) -> Vec<Breach> {
        let seen = self.chars.sample(t_ps, tx, de, rx);
        let mut out = seen.breaches;
        if let Some(r) = seen.ended.filter(|r| !r.broken) {
            if !frames::crc_ok(&r.bytes) {
                out.push(CRC.breach(
                    t_ps,
                    format!(
                        "a request of {} bytes whose CRC does not check ({})",
                        r.bytes.len(),
                        r.bytes
                            .iter()
                            .map(|b| format!("{b:02X}"))
                            .collect::<Vec<_>>()
                            .join(" ")
                    ),
                ));
            } else if r.bytes[0] != BROADCAST {
                self.chars.expect_answer(t_ps);
            }
        }
        out
    }
}
