//! The rule book: every timing limit a seed states for a master, written
//! once, and the edge watchers that decide a breach. The emulators and the
//! monitors of `cosim` both feed a protocol's watcher and print what it
//! returns, so the same break draws the same rule name and text on both
//! sides, and no rule is decided in two places.
//!
//! # The shape every protocol follows
//!
//! A protocol's rules live in `model/src/<proto>/rules.rs` (see
//! [`crate::biss::rules`], [`crate::ssi::rules`]) and hold four things:
//!
//! 1. **One `pub static` [`Rule`] per limit the seed states**, named once by
//!    the seed's symbol (`TMASH`, `T_cs`) and section, with the seed's own
//!    words, the [`Bound`] enforced (value, unit, comparison), how it is
//!    measured on the edges, and the range a configuration may set it to
//!    ([`Rule::settable`]).
//! 2. **`RULES`**, the protocol's list of them, in the order of the seed; the
//!    catalogue [`all`] joins the lists (the rule probe suite and
//!    `docs/rules.md` walk it).
//! 3. **`Limits`**: the bounds in force, in picoseconds, made from a
//!    configuration by [`Rule::setting`], which refuses a bound outside the
//!    seed's range with that range.
//! 4. **`Watch`**: the edge watcher. It is fed one sample at a time, the time
//!    in picoseconds ([`ps_at`]) and the pin levels as the master's end of the
//!    line shows them, and returns [`Breach`] values. It knows nothing of the
//!    sampling clock but its period, for [`resolution_notes`].
//!
//! A limit is the seed's bound applied to the length measured between two
//! sampled edges, with no slack of a sampling cycle: a high phase of 25 ns
//! measured at 200 MHz breaks `TMASH > 25 ns`. Where the sampling clock is
//! too coarse for a limit (fewer than two periods within it), the caller says
//! so once, before the first sample ([`resolution_notes`]).
//!
//! Every watcher starts unaware of the line: nothing is checked until the
//! line clock has been seen at its idle level, so a master that holds reset
//! (its clock at 0, or X read as 0) from time 0 draws no report.

use std::fmt;
use std::sync::OnceLock;

use crate::time::PS_PER_S;
use crate::ConfigError;

/// The unit a seed states a limit in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    /// Nanoseconds.
    Ns,
    /// Microseconds.
    Us,
    /// Milliseconds.
    Ms,
    /// Kilohertz (a clock frequency, measured as its period).
    KHz,
    /// Megahertz (a clock frequency, measured as its period).
    MHz,
    /// Percent of a measured length (a tolerance): a ratio, with no length
    /// of its own; the protocol's `Limits` apply it.
    Percent,
    /// Bit times at the configured baud rate: the protocol's `Limits`
    /// scale it, [`Unit::ps`] cannot.
    Bits,
    /// Character times (start, data, parity, stop) at the configured baud
    /// rate: the protocol's `Limits` scale it, [`Unit::ps`] cannot.
    Chars,
}

impl Unit {
    /// The unit as written in reports and docs.
    pub fn symbol(self) -> &'static str {
        match self {
            Unit::Ns => "ns",
            Unit::Us => "us",
            Unit::Ms => "ms",
            Unit::KHz => "kHz",
            Unit::MHz => "MHz",
            Unit::Percent => "%",
            Unit::Bits => "bits",
            Unit::Chars => "characters",
        }
    }

    /// `value` in this unit as picoseconds (a frequency as its period; a
    /// ratio or a count of bits or characters, which need the baud rate: 0).
    pub fn ps(self, value: f64) -> u64 {
        let ps = match self {
            Unit::Ns => value * 1e3,
            Unit::Us => value * 1e6,
            Unit::Ms => value * 1e9,
            Unit::KHz => PS_PER_S as f64 / (value * 1e3),
            Unit::MHz => PS_PER_S as f64 / (value * 1e6),
            Unit::Percent | Unit::Bits | Unit::Chars => 0.0,
        };
        ps.round().max(0.0) as u64
    }
}

/// How a measured length is held to a bound.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Bound {
    /// The length must exceed the value (the seed's `>`).
    MoreThan(f64, Unit),
    /// The length must reach the value (the seed's `>` where the house
    /// reads it inclusively: [`Rule::reading`] says why).
    AtLeast(f64, Unit),
    /// The length must not exceed the value (the seed's `<=`, "at most").
    AtMost(f64, Unit),
    /// A clock frequency from the first value to the second, both
    /// included, measured as its period.
    Within(f64, f64, Unit),
    /// A rule of a frame's form or of the order of transactions, with no
    /// figure: what the seed asks, in the rule's `seed_words`.
    Form,
}

impl Bound {
    /// The unit of the bound (`None`: a rule of form).
    pub fn unit(self) -> Option<Unit> {
        match self {
            Bound::MoreThan(_, u)
            | Bound::AtLeast(_, u)
            | Bound::AtMost(_, u)
            | Bound::Within(_, _, u) => Some(u),
            Bound::Form => None,
        }
    }
}

impl fmt::Display for Bound {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Bound::MoreThan(v, u) => write!(f, "> {v} {}", u.symbol()),
            Bound::AtLeast(v, u) => write!(f, ">= {v} {}", u.symbol()),
            Bound::AtMost(v, u) => write!(f, "<= {v} {}", u.symbol()),
            Bound::Within(lo, hi, u) => write!(f, "{lo} to {hi} {}", u.symbol()),
            Bound::Form => write!(f, "form"),
        }
    }
}

/// The range a configuration may set a rule's bound to, in the bound's
/// unit, both ends included: the seed's, so that a configuration cannot
/// loosen a limit the seed states.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settable {
    /// The least value.
    pub lo: f64,
    /// The greatest value.
    pub hi: f64,
}

/// One timing limit a seed states for the master.
#[derive(Debug)]
pub struct Rule {
    /// The protocol (`biss`, `ssi`), as `cosim::open` names it.
    pub protocol: &'static str,
    /// The seed's symbol, the rule's one name (`TMASH`).
    pub name: &'static str,
    /// The seed and its section (`seed 001 SAR58K24 manual, BiSS-C timing`).
    pub section: &'static str,
    /// The seed's own words.
    pub seed_words: &'static str,
    /// What is measured, as a report names it (`MA high`).
    pub quantity: &'static str,
    /// The bound enforced.
    pub bound: Bound,
    /// How it is measured on the edges.
    pub measured: &'static str,
    /// Where the bound departs from the seed's literal words, why.
    pub reading: &'static str,
    /// The range a configuration may set the bound to (`None`: fixed).
    pub settable: Option<Settable>,
    /// The report's rule text, made once from the fields above.
    pub label: OnceLock<&'static str>,
}

impl Rule {
    /// The rule as reports print it: name, section and bound,
    /// `TMASH (seed 001 SAR58K24 manual, BiSS-C timing: MA high > 25 ns)`
    /// (a rule of form: its quantity alone).
    pub fn label(&'static self) -> &'static str {
        self.label.get_or_init(|| {
            let what = match self.bound {
                Bound::Form => self.quantity.to_string(),
                b => format!("{} {b}", self.quantity),
            };
            Box::leak(format!("{} ({}: {what})", self.name, self.section).into_boxed_str())
        })
    }

    /// A configured bound `value` (in the rule's unit, from `field`),
    /// refused outside [`Rule::settable`] with the seed's range.
    pub fn setting(&'static self, field: &str, value: f64) -> Result<f64, ConfigError> {
        let unit = self.bound.unit().map_or("", Unit::symbol);
        let Some(range) = self.settable else {
            return Err(ConfigError::invalid(
                field,
                format!("{value} {unit}"),
                format!(
                    "{} is the seed's fixed limit; leave the field out",
                    self.label()
                ),
            ));
        };
        if value.is_finite() && value >= range.lo && value <= range.hi {
            Ok(value)
        } else {
            Err(ConfigError::invalid(
                field,
                format!("{value} {unit} is outside the seed's range"),
                format!(
                    "give {} to {} {unit} ({}: \"{}\")",
                    range.lo, range.hi, self.section, self.seed_words
                ),
            ))
        }
    }

    /// A breach of this rule at `at_ps`.
    pub fn breach(&'static self, at_ps: u64, detail: String) -> Breach {
        Breach {
            rule: self,
            at_ps,
            detail,
        }
    }
}

/// One broken rule: where and what was measured.
#[derive(Debug, Clone)]
pub struct Breach {
    /// The rule.
    pub rule: &'static Rule,
    /// The time of the edge that broke it, ps from the start.
    pub at_ps: u64,
    /// What was measured, against the limit in force.
    pub detail: String,
}

/// What one sample showed a watcher.
#[derive(Debug, Clone, Default)]
pub struct Step {
    /// Rules broken at this sample.
    pub breaches: Vec<Breach>,
    /// A transaction (frame, read) began at this sample: a monitor hands
    /// the line before it to its decoder.
    pub started: bool,
}

/// A transaction (frame, read) as a watcher follows it.
#[derive(Debug, Clone, Default)]
pub struct Transaction {
    /// Its last rising clock edge, ps.
    pub last_rise: Option<u64>,
}

/// Every rule of every protocol, protocol by protocol in listing order
/// (each descriptor's [`crate::protocol::Protocol::rules`]).
pub fn all() -> Vec<&'static Rule> {
    crate::protocol::PROTOCOLS
        .iter()
        .flat_map(|p| p.rules.iter().copied())
        .collect()
}

/// The time in ps of sample `n` of a clock of `f_hz`: `n × 10^12 / f`,
/// rounded, with no error carried from sample to sample.
pub fn ps_at(n: u64, f_hz: u64) -> u64 {
    let f = f_hz.max(1) as u128;
    ((n as u128 * PS_PER_S as u128 + f / 2) / f) as u64
}

/// A length in ps as nanoseconds, for reports.
pub fn ns(ps: u64) -> f64 {
    ps as f64 / 1e3
}

/// A length in ps as microseconds, for reports.
pub fn us(ps: u64) -> f64 {
    ps as f64 / 1e6
}

/// `len` breaks a least length `min` (`strict`: the seed's `>`, so equal
/// breaks too).
pub fn short(len: u64, min: u64, strict: bool) -> bool {
    if strict {
        len <= min
    } else {
        len < min
    }
}

/// What a sampling clock of `f_hz` cannot resolve among `limits` (a rule
/// and the least length in force, ps): a limit needs two sampling periods
/// within it, so that a phase one period from it is measured on the right
/// side. One sentence per limit, naming the clock it needs.
pub fn resolution_notes(f_hz: u64, limits: &[(&'static Rule, u64)]) -> Vec<String> {
    let period = PS_PER_S as f64 / f_hz.max(1) as f64;
    limits
        .iter()
        .filter(|(_, ps)| 2.0 * period > *ps as f64)
        .map(|(rule, ps)| {
            let needs = (2.0 * PS_PER_S as f64 / *ps as f64).ceil() as u64;
            format!(
                "{}: a sampling clock of {f_hz} Hz ({:.3} ns a sample) cannot resolve a limit of {:.3} ns; it needs at least {needs} Hz (two samples within the limit)",
                rule.label(),
                period / 1e3,
                ns(*ps)
            )
        })
        .collect()
}

/// The line clock as a watcher follows it: its last level and edge, and
/// whether it has been seen at its idle level yet (before that, nothing is
/// an edge: a master in reset may hold it anywhere).
#[derive(Debug, Clone, Default)]
pub struct Line {
    seen_idle: bool,
    level: bool,
    last_edge_ps: u64,
}

/// An edge of the line clock, with the length of the phase it ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Edge {
    /// The new level.
    pub rose: bool,
    /// The length of the phase that ended, ps.
    pub phase_ps: u64,
}

impl Line {
    /// The line before its first sample; `idle` is the clock's idle level.
    pub fn new() -> Self {
        Line::default()
    }

    /// One sample at `t_ps`: the edge it shows, if any. Before the clock is
    /// first seen at `idle`, no sample is an edge.
    pub fn sample(&mut self, t_ps: u64, level: bool, idle: bool) -> Option<Edge> {
        if !self.seen_idle {
            if level == idle {
                self.seen_idle = true;
                self.level = level;
                self.last_edge_ps = t_ps;
            }
            return None;
        }
        if level == self.level {
            return None;
        }
        let edge = Edge {
            rose: level,
            phase_ps: t_ps - self.last_edge_ps,
        };
        self.level = level;
        self.last_edge_ps = t_ps;
        Some(edge)
    }

    /// The clock has been seen at its idle level.
    pub fn seen_idle(&self) -> bool {
        self.seen_idle
    }

    /// The time of the last edge (or of the first idle sample), ps.
    pub fn last_edge_ps(&self) -> u64 {
        self.last_edge_ps
    }

    /// The level now.
    pub fn level(&self) -> bool {
        self.level
    }
}
