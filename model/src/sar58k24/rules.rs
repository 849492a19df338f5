//! The SAR58K24 host's rules in its asynchronous serial modes (seed 001,
//! SAR58K24 manual, "Product communication" and 3.1.1 to 3.1.6), in the
//! shape of [`crate::rules`]: the host's bus commands (`BC AA Bx`,
//! `BC AA Cx`) on the shared RS-485 line, its trigger pulse (CLK of the
//! handshake modes) and its CLR pulse.
//!
//! ```text
//!  DE       __/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\__________________________
//!  line     ‾‾‾\_BC_/‾\_AA_/‾\_B1_/‾‾‾‾‾‾‾‾‾\_FF_/\_81_/ ... \_cs_/‾‾
//!                       |<>| command gap   |<- answer ->|
//!                                |<>| release      (no driver on: one driver)
//!  trigger  ‾‾‾‾‾\_______/‾‾‾‾ ... T2 >= 10 us, not inside the frame (T1-T3)
//!  CLR      ‾‾‾‾‾\_______/‾‾‾‾ ... a low pulse zeroes
//! ```
//!
//! The characters' rules are decided by [`crate::uart::watch`] under this
//! book's names; the trigger and CLR pulses here. The emulator and the
//! monitor both feed [`Watch`] and print what it returns.

use std::sync::OnceLock;

use crate::rules::{self, Bound, Breach, Line, Rule, Settable, Unit};
use crate::uart::watch::{self, Book};
use crate::uart::Parity;
use crate::ConfigError;

use super::frames::{parse_command, Command};

/// The seed's words on the character format.
const CHARACTER_WORDS: &str = "Asynchronous serial: one byte is 10 bits, 1 bit start bit 0, 1 bit stop bit 1, 8 bits data bits, no parity check bit, 8 bits data bits are transmitted first low and then high; (parity check or even check can be added according to customer requirements)";
/// The seed's words on the bus commands and their answers.
const COMMAND_WORDS: &str = "the control commands BC AA B1, BC AA B2 and BC AA B3 correspond to the return data FF B1....., FF B2....., FF B3.....";

/// Every edge of a command character on its bit grid.
pub static CHARACTER: Rule = Rule {
    protocol: "sar58k24",
    name: "character",
    section: "seed 001 SAR58K24 manual, Product communication",
    seed_words: CHARACTER_WORDS,
    quantity: "a command character's edge off its bit grid",
    bound: Bound::AtMost(2.0, Unit::Percent),
    measured: "every edge of a command character, from its start edge: off the nearest bit boundary by at most the tolerance times the time since the start edge (and the next start edge no sooner than a character less the tolerance); the parity bit as configured; the stop bit high at its middle; DE not released inside a character",
    reading: "the seed gives no baud rate tolerance: the project's reading, 2 % of the time since the start edge (a receiver sampling mid-bit reads such a character), `monitor.baud_tolerance_percent`",
    settable: Some(Settable { lo: 0.0, hi: 2.0 }),
    label: OnceLock::new(),
};

/// The three characters of a command close together.
pub static GAP: Rule = Rule {
    protocol: "sar58k24",
    name: "command gap",
    section: "seed 001 SAR58K24 manual, 3.1.5, 3.1.6",
    seed_words: "control command : BC AA BX (BX: is the command number. If the customer has no special requirements, each product in the same batch has a unique command number,  And use it as the product address number)",
    quantity: "silence inside a command",
    bound: Bound::AtMost(15.0, Unit::Bits),
    measured: "from a command character's stop-bit middle (where a receiver has seen it end) to the next start edge of the same command (DE held on)",
    reading: "the seed names BC AA Bx one command and gives no gap: the project's reading, at most the encoder's `command_gap_bits` (15) bit times, beyond which the encoder drops the command",
    settable: Some(Settable { lo: 1.0, hi: 1000.0 }),
    label: OnceLock::new(),
};

/// DE released after the command.
pub static RELEASE: Rule = Rule {
    protocol: "sar58k24",
    name: "release",
    section: "seed 001 SAR58K24 manual, 3.1, 3.1.5",
    seed_words: COMMAND_WORDS,
    quantity: "DE held after the command",
    bound: Bound::AtMost(1.0, Unit::Bits),
    measured: "from the end of the command's last stop bit to DE falling",
    reading: "the encoder answers on the same RS-485 pair (MAX485, half duplex), so the host releases it after its command: the project's reading, within one bit time, `monitor.release_bits`",
    settable: Some(Settable { lo: 0.0, hi: 1.0 }),
    label: OnceLock::new(),
};

/// One driver on the line at a time.
pub static ANSWER: Rule = Rule {
    protocol: "sar58k24",
    name: "one driver",
    section: "seed 001 SAR58K24 manual, 3.1, 3.1.5",
    seed_words: "chip--MAX485 ESA (250kbps) or MAX13443EESA (10Mbps)",
    quantity: "the host drives while the encoder answers",
    bound: Bound::Form,
    measured: "the host's receiver low for a quarter bit or more while it drives a 1, or DE switched on inside a character of the encoder",
    reading: "a half-duplex transceiver: one driver on the pair at a time",
    settable: None,
    label: OnceLock::new(),
};

/// One answer per command or trigger, waited for.
pub static WAIT: Rule = Rule {
    protocol: "sar58k24",
    name: "answer wait",
    section: "seed 001 SAR58K24 manual, 3.1.3, 3.1.5",
    seed_words: COMMAND_WORDS,
    quantity: "the next command or trigger before the answer or the host's timeout",
    bound: Bound::Form,
    measured: "after a read command (a zeroing command the encoder answers, `answer_zeroing`) or a trigger, the next command's first start edge or trigger's falling edge once an answer character has begun or the host's timeout has passed since the command ended (DE fell) or the trigger fell",
    reading: "the seed gives no timeout: the host's own, `[host] timeout_us` (5000 us)",
    settable: None,
    label: OnceLock::new(),
};

/// The trigger pulse's least low time.
pub static T2: Rule = Rule {
    protocol: "sar58k24",
    name: "T2",
    section: "seed 001 SAR58K24 manual, 3.1.3",
    seed_words:
        "The falling edge of the external pulse signal triggers the encoder to work  T2 >= 10us",
    quantity: "trigger low",
    bound: Bound::AtLeast(10.0, Unit::Us),
    measured: "every trigger (CLK) low phase, falling edge to rising edge",
    reading: "",
    settable: Some(Settable { lo: 10.0, hi: 1e6 }),
    label: OnceLock::new(),
};

/// No trigger while the frame is on the line.
pub static TRIGGER_BUSY: Rule = Rule {
    protocol: "sar58k24",
    name: "T1-T3",
    section: "seed 001 SAR58K24 manual, 3.1.3",
    seed_words: "T1-T3: Data transmission time",
    quantity: "a trigger inside the encoder's frame",
    bound: Bound::Form,
    measured: "a trigger's falling edge while a character of the encoder's frame is on the line at the host (its start edge to the end of its stop bit)",
    reading: "",
    settable: None,
    label: OnceLock::new(),
};

/// The CLR pulse's least low time.
pub static CLR: Rule = Rule {
    protocol: "sar58k24",
    name: "CLR",
    section: "seed 001 SAR58K24 manual, 3.1.2, 3.1.4",
    seed_words: "The CLR pin is usually at 3.3V and the signal falls on the pulse  V_L < 0.5V  product reset.",
    quantity: "CLR low",
    bound: Bound::AtLeast(10.0, Unit::Us),
    measured: "every CLR low phase, falling edge to rising edge",
    reading: "the seed gives only the level: the project's reading, a pulse as long as T2, the encoder's `clr_min_low_us` (10 us)",
    settable: Some(Settable { lo: 1.0, hi: 1e6 }),
    label: OnceLock::new(),
};

/// The SAR58K24 rules, in the order of the seed.
pub static RULES: &[&Rule] = &[
    &CHARACTER,
    &GAP,
    &RELEASE,
    &ANSWER,
    &WAIT,
    &T2,
    &TRIGGER_BUSY,
    &CLR,
];

/// The book the character watcher reports under (no silence rule: the
/// manual asks for none before a command).
pub const BOOK: Book = Book {
    character: &CHARACTER,
    gap: &GAP,
    silence: None,
    release: &RELEASE,
    answer: &ANSWER,
    wait: &WAIT,
};

/// The host's configured bounds, each with the field it came from (the
/// values in the rules' units).
#[derive(Debug, Clone)]
pub struct Settings<'a> {
    /// Baud rate.
    pub baud: f64,
    /// Character format.
    pub parity: Parity,
    /// [`CHARACTER`], %.
    pub tolerance_percent: (&'a str, f64),
    /// [`GAP`], bit times.
    pub command_gap_bits: (&'a str, f64),
    /// [`RELEASE`], bit times.
    pub release_bits: (&'a str, f64),
    /// [`WAIT`]: the host's answer timeout, µs.
    pub timeout_us: f64,
    /// [`T2`], µs.
    pub t2_us: (&'a str, f64),
    /// [`CLR`], µs.
    pub clr_us: (&'a str, f64),
    /// A trigger is answered (the handshake modes).
    pub handshake: bool,
    /// A zeroing command is answered.
    pub answer_zeroing: bool,
}

/// The bounds in force, ps.
#[derive(Debug, Clone, PartialEq)]
pub struct Limits {
    /// The characters' limits.
    pub uart: watch::Limits,
    /// Least trigger low ([`T2`]).
    pub t2: u64,
    /// Least CLR low ([`CLR`]).
    pub clr: u64,
    /// A trigger is answered.
    pub handshake: bool,
    /// A zeroing command is answered.
    pub answer_zeroing: bool,
}

impl Limits {
    /// The limits of `s`, each bound refused outside its rule's range.
    pub fn new(s: &Settings) -> Result<Self, ConfigError> {
        let bit_ps = 1e12 / s.baud;
        let bits = |b: f64| (b * bit_ps).round() as u64;
        Ok(Limits {
            uart: watch::Limits {
                bit_ps,
                parity: s.parity,
                tolerance: CHARACTER.setting(s.tolerance_percent.0, s.tolerance_percent.1)? / 100.0,
                max_gap_ps: bits(GAP.setting(s.command_gap_bits.0, s.command_gap_bits.1)?),
                min_silence_ps: 0,
                release_ps: bits(RELEASE.setting(s.release_bits.0, s.release_bits.1)?),
                timeout_ps: Unit::Us.ps(s.timeout_us),
            },
            t2: Unit::Us.ps(T2.setting(s.t2_us.0, s.t2_us.1)?),
            clr: Unit::Us.ps(CLR.setting(s.clr_us.0, s.clr_us.1)?),
            handshake: s.handshake,
            answer_zeroing: s.answer_zeroing,
        })
    }

    /// The least lengths, for [`rules::resolution_notes`].
    pub fn least(&self) -> Vec<(&'static Rule, u64)> {
        let mut v = self.uart.least(&BOOK);
        v.push((&T2, self.t2));
        v.push((&CLR, self.clr));
        v
    }
}

/// The host's pins as the watcher samples them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HostPins {
    /// The host's receiver output (the line at the host).
    pub rx: bool,
    /// Its driver input.
    pub tx: bool,
    /// Its driver enable.
    pub de: bool,
    /// The trigger (CLK), idle high.
    pub trigger: bool,
    /// CLR, idle high.
    pub clr: bool,
}

/// The SAR58K24 watcher: the characters ([`watch::Watch`]), the trigger and CLR.
#[derive(Debug, Clone)]
pub struct Watch {
    chars: watch::Watch,
    trigger: Line,
    clr: Line,
    t2: u64,
    clr_min: u64,
    handshake: bool,
    answer_zeroing: bool,
}

impl Watch {
    /// A watcher holding the host to `limits`.
    pub fn new(limits: Limits) -> Self {
        Watch {
            chars: watch::Watch::new(limits.uart, BOOK),
            trigger: Line::new(),
            clr: Line::new(),
            t2: limits.t2,
            clr_min: limits.clr,
            handshake: limits.handshake,
            answer_zeroing: limits.answer_zeroing,
        }
    }

    /// One sample at `t_ps`.
    pub fn sample(&mut self, t_ps: u64, p: HostPins) -> Vec<Breach> {
        let seen = self.chars.sample(t_ps, p.tx, p.de, p.rx);
        let mut out = seen.breaches;
        if let Some(r) = seen.ended.filter(|r| !r.broken) {
            let answered = match parse_command(&r.bytes) {
                Some(Command::Read(_)) => true,
                Some(Command::Zero(_)) => self.answer_zeroing,
                None => false,
            };
            if answered {
                self.chars.expect_answer(t_ps);
            }
        }
        if let Some(e) = self.trigger.sample(t_ps, p.trigger, true) {
            if e.rose {
                out.extend(short_pulse(&T2, "trigger", t_ps, e.phase_ps, self.t2));
            } else {
                if self.chars.device_busy(t_ps) {
                    out.push(TRIGGER_BUSY.breach(
                        t_ps,
                        "a trigger's falling edge while the encoder sends a character of its frame"
                            .to_string(),
                    ));
                }
                out.extend(self.chars.check_wait(t_ps, "a trigger"));
                if self.handshake {
                    self.chars.expect_answer(t_ps);
                }
            }
        }
        if let Some(e) = self.clr.sample(t_ps, p.clr, true) {
            if e.rose {
                out.extend(short_pulse(&CLR, "CLR", t_ps, e.phase_ps, self.clr_min));
            }
        }
        out
    }
}

/// A low pulse of `low` ps on `name` against its least `min` ps.
fn short_pulse(rule: &'static Rule, name: &str, t_ps: u64, low: u64, min: u64) -> Option<Breach> {
    rules::short(low, min, false).then(|| {
        rule.breach(
            t_ps,
            format!(
                "{name} low for {:.3} us; at least {:.3} us",
                rules::us(low),
                rules::us(min)
            ),
        )
    })
}
