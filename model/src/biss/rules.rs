//! The BiSS-C master's timing rules (seed 001, SAR58K24 manual, BiSS-C, "The
//! maximum transmission timing is as follows": "TMAS: The allowed clock
//! cycle is >100ns; TMASH: High level duration >25ns; TMASL: Low level
//! duration >25ns; Tbusy: Minimum data output delay X2TMAS; Timeout: Biss
//! timeout 16µs"), in the shape of [`crate::rules`].
//!
//! A frame is what the slave takes for one: it begins with a falling MA
//! edge while the slave is idle and ends when MA has not changed for the
//! slave's timeout (the seed's meaning; the slave then takes the CDM bit from
//! the MA level and goes idle). Within it:
//!
//! ```text
//!  MA  ‾‾‾\_/‾\_/‾\_/‾\_ ... _/‾\_/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_/‾
//!         |<->|       TMAS: rising to rising edge
//!          |>| TMASL  |<>| TMASH
//!  SLO ‾‾‾‾‾‾‾\____ ... __/S\_data..CRC_/‾‾\____________/‾‾‾‾
//!             ack          start                  |<- timeout ->| next frame
//! ```
//!
//! `Tbusy` binds the slave, not the master ([`super::seed_timing`]).
//!
//! A frame restarted before the slave's timeout is, for the slave, the same
//! frame clocked on, and on the pins it is the same as a master clocking
//! past the CRC (which the seed does not forbid): the watcher cannot tell
//! them apart and reports neither. What it reports is what the pins show:
//! an MA high phase of 25 ns or less before the restart (`TMASH`), and a
//! frame started while SLO is still low at the master (`timeout`: the
//! slave's timeout not yet over as the master can see it, after a line
//! delay, or a slave still busy).

use std::sync::OnceLock;

use crate::rules::{self, Bound, Line, Rule, Settable, Step, Transaction, Unit};

const SECTION: &str = "seed 001 SAR58K24 manual, BiSS-C timing";

/// The least MA period.
pub static TMAS: Rule = Rule {
    protocol: "biss",
    name: "TMAS",
    section: SECTION,
    seed_words: "TMAS: The allowed clock cycle is >100ns",
    quantity: "MA period",
    bound: Bound::AtLeast(100.0, Unit::Ns),
    measured: "every MA period within a frame, rising edge to rising edge",
    reading: "read as MA up to 10 MHz, as the master model and protocols.md do (\"MA clock > 100 ns period (up to 10 MHz)\"): a period of exactly 100 ns meets it",
    settable: Some(Settable { lo: 100.0, hi: 1e6 }),
    label: OnceLock::new(),
};

/// The least MA high phase.
pub static TMASH: Rule = Rule {
    protocol: "biss",
    name: "TMASH",
    section: SECTION,
    seed_words: "TMASH: High level duration >25ns",
    quantity: "MA high",
    bound: Bound::MoreThan(25.0, Unit::Ns),
    measured: "every MA high phase within a frame, rising edge to falling edge",
    reading: "",
    settable: Some(Settable { lo: 25.0, hi: 1e6 }),
    label: OnceLock::new(),
};

/// The least MA low phase.
pub static TMASL: Rule = Rule {
    protocol: "biss",
    name: "TMASL",
    section: SECTION,
    seed_words: "TMASL: Low level duration >25ns",
    quantity: "MA low",
    bound: Bound::MoreThan(25.0, Unit::Ns),
    measured: "every MA low phase within a frame, the first (frame start to the latching edge) included, falling edge to rising edge",
    reading: "",
    settable: Some(Settable { lo: 25.0, hi: 1e6 }),
    label: OnceLock::new(),
};

/// A new frame only after the slave's timeout.
pub static TIMEOUT: Rule = Rule {
    protocol: "biss",
    name: "timeout",
    section: SECTION,
    seed_words: "Timeout: Biss timeout 16µs",
    quantity: "MA unchanged before a new frame",
    bound: Bound::AtLeast(16.0, Unit::Us),
    measured: "a frame ends when MA has not changed for the slave's timeout (a falling edge before that is a clock of the same frame); the falling edge that starts the next frame must find SLO high at the master (the slave's timeout over, as the master sees it)",
    reading: "the bound is the slaves' own timeout (`[[slaves]] timeout_us`, the seed's 16 µs by default), a device property: `monitor.timeout_us` may name it for a monitor without slaves",
    settable: None,
    label: OnceLock::new(),
};

/// The BiSS-C rules, in the order of the seed.
pub static RULES: &[&Rule] = &[&TMAS, &TMASH, &TMASL, &TIMEOUT];

/// The bounds in force, ps.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Limits {
    /// Least MA period ([`TMAS`]).
    pub tmas: u64,
    /// Least MA high phase, exclusive ([`TMASH`]).
    pub tmash: u64,
    /// Least MA low phase, exclusive ([`TMASL`]).
    pub tmasl: u64,
    /// The slaves' longest timeout ([`TIMEOUT`]).
    pub timeout: u64,
}

impl Limits {
    /// The seed's bounds for a chain whose slaves time out after `timeout_us`.
    pub fn seed(timeout_us: f64) -> Self {
        let ps = |r: &Rule| match r.bound {
            Bound::MoreThan(v, u) | Bound::AtLeast(v, u) => u.ps(v),
            Bound::AtMost(..) | Bound::Within(..) | Bound::Form => 0,
        };
        Limits {
            tmas: ps(&TMAS),
            tmash: ps(&TMASH),
            tmasl: ps(&TMASL),
            timeout: Unit::Us.ps(timeout_us),
        }
    }

    /// The least lengths, for [`rules::resolution_notes`].
    pub fn least(&self) -> Vec<(&'static Rule, u64)> {
        vec![
            (&TMAS, self.tmas),
            (&TMASH, self.tmash),
            (&TMASL, self.tmasl),
            (&TIMEOUT, self.timeout),
        ]
    }
}

/// The BiSS-C edge watcher: MA as the master drives it, SLO at the master.
#[derive(Debug, Clone)]
pub struct Watch {
    limits: Limits,
    ma: Line,
    frame: Option<Transaction>,
}

impl Watch {
    /// A watcher holding the master to `limits`.
    pub fn new(limits: Limits) -> Self {
        Watch {
            limits,
            ma: Line::new(),
            frame: None,
        }
    }

    /// The bounds in force.
    pub fn limits(&self) -> &Limits {
        &self.limits
    }

    /// MA has been seen idle high (before that, the master is taken to be
    /// in reset and the slaves see MA idle).
    pub fn seen_idle(&self) -> bool {
        self.ma.seen_idle()
    }

    /// A frame is in progress (the slave has not timed out).
    pub fn in_frame(&self) -> bool {
        self.frame.is_some()
    }

    /// One sample at `t_ps`: MA at the master, SLO at the master's receiver.
    pub fn sample(&mut self, t_ps: u64, ma: bool, slo: bool) -> Step {
        let mut step = Step::default();
        let lim = &self.limits;
        let Some(edge) = self.ma.sample(t_ps, ma, true) else {
            if self.frame.is_some() && t_ps - self.ma.last_edge_ps() >= lim.timeout {
                self.frame = None;
            }
            return step;
        };
        let Some(f) = self.frame.as_mut() else {
            if !edge.rose {
                step.started = true;
                self.frame = Some(Transaction::default());
                if !slo {
                    step.breaches.push(TIMEOUT.breach(
                        t_ps,
                        format!(
                            "frame started {:.3} us after the last MA edge with SLO still low at the master (the slave's timeout, {:.3} us, not over as the master sees it)",
                            rules::us(edge.phase_ps),
                            rules::us(lim.timeout)
                        ),
                    ));
                }
            }
            return step;
        };
        let len = edge.phase_ps;
        if edge.rose {
            if rules::short(len, lim.tmasl, true) {
                step.breaches.push(TMASL.breach(
                    t_ps,
                    format!(
                        "MA low for {:.1} ns within a frame (limit: more than {:.1} ns)",
                        rules::ns(len),
                        rules::ns(lim.tmasl)
                    ),
                ));
            }
            if let Some(r) = f.last_rise {
                if rules::short(t_ps - r, lim.tmas, false) {
                    step.breaches.push(TMAS.breach(
                        t_ps,
                        format!(
                            "MA period {:.1} ns within a frame (limit: at least {:.1} ns)",
                            rules::ns(t_ps - r),
                            rules::ns(lim.tmas)
                        ),
                    ));
                }
            }
            f.last_rise = Some(t_ps);
        } else if rules::short(len, lim.tmash, true) {
            step.breaches.push(TMASH.breach(
                t_ps,
                format!(
                    "MA high for {:.1} ns within a frame (limit: more than {:.1} ns)",
                    rules::ns(len),
                    rules::ns(lim.tmash)
                ),
            ));
        }
        step
    }
}
