//! The SSI master's timing rules (seed 001, SAR58K24 manual, SSI (2):
//! "T_cs > 4µs; 100kHz < f_clk < 250kHz; T_m > 500µs"), in the shape of
//! [`crate::rules`].
//!
//! A read is what the encoder takes for one: it begins with a falling clock
//! edge while the encoder is idle (the clock high, its monoflop run out) and
//! ends when the clock has not changed for the monoflop time `T_m` (the
//! encoder's meaning, [`super::Encoder`]). Within it:
//!
//! ```text
//!  CLK ‾‾‾‾\______/‾‾\__/‾‾\__ ... __/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\____
//!          |<T_cs>|<--->|  period: rising to rising edge
//!                                   |<-- at least T_m ------>| next read
//! ```
//!
//! The clock range is a frequency, so it is held on whole periods (rising
//! edge to rising edge), whatever the duty cycle. A high phase as long as
//! the slowest period or longer (no clock of a legal read has one: its low
//! phase takes a part of the period) is the master's pause: the falling
//! edge after it starts a new read, which the encoder takes for one only
//! after `T_m`.
//!
//! The watcher (and the emulator) expects the clock idle high before the
//! first read: until the clock has been seen high, nothing is a read, so a
//! master holding reset (its clock at 0) from time 0 draws no report.

use std::sync::OnceLock;

use crate::rules::{self, Bound, Line, Rule, Settable, Step, Transaction, Unit};

const SECTION: &str = "seed 001 SAR58K24 manual, SSI (2)";

/// The least first low phase.
pub static T_CS: Rule = Rule {
    protocol: "ssi",
    name: "T_cs",
    section: SECTION,
    seed_words: "T_cs > 4µs",
    quantity: "first low phase",
    bound: Bound::AtLeast(4.0, Unit::Us),
    measured: "the storing falling edge of a read to its first rising edge",
    reading: "read inclusively (the house's 12-bit seed master at 250 kHz on 50 MHz has T_cs of exactly 4 us, 200 cycles); a configuration may set another, as the seed says \"T_cs f_clk T_m varies according to the actual situation and products\"",
    settable: Some(Settable { lo: 0.1, hi: 1e6 }),
    label: OnceLock::new(),
};

/// The clock range.
pub static CLOCK: Rule = Rule {
    protocol: "ssi",
    name: "f_clk",
    section: SECTION,
    seed_words: "100kHz < f_clk < 250kHz",
    quantity: "clock",
    bound: Bound::Within(100.0, 250.0, Unit::KHz),
    measured: "every clock period of a read, rising edge to rising edge (4 to 10 us)",
    reading: "read inclusively, as the master model does (its default clock is 250 kHz); a configuration may set another range (a reader faster than the seed's encoder on purpose), as the seed says \"T_cs f_clk T_m varies according to the actual situation and products\"",
    settable: Some(Settable { lo: 1.0, hi: 10_000.0 }),
    label: OnceLock::new(),
};

/// A new read only after the monoflop.
pub static T_M: Rule = Rule {
    protocol: "ssi",
    name: "T_m",
    section: SECTION,
    seed_words: "T_m > 500µs",
    quantity: "clock high before a new read",
    bound: Bound::AtLeast(500.0, Unit::Us),
    measured: "the last clock edge of a read to the falling edge that starts the next, when that high phase is at least the slowest clock period (10 us)",
    reading: "the bound is the encoder's monoflop time (`encoder.monoflop_us`, the seed's 500 us by default), a device property: the seed says \"T_cs f_clk T_m varies according to the actual situation and products\"",
    settable: None,
    label: OnceLock::new(),
};

/// The SSI rules, in the order of the seed.
pub static RULES: &[&Rule] = &[&T_CS, &CLOCK, &T_M];

/// The bounds in force, ps.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Limits {
    /// Least first low phase ([`T_CS`]).
    pub t_cs: u64,
    /// Least clock period, the fastest clock ([`CLOCK`]).
    pub period_min: u64,
    /// Greatest clock period, the slowest clock ([`CLOCK`]).
    pub period_max: u64,
    /// The encoder's monoflop time ([`T_M`]).
    pub t_m: u64,
}

impl Limits {
    /// The seed's bounds for an encoder whose monoflop time is `t_m_us`.
    pub fn seed(t_m_us: f64) -> Self {
        let (Bound::AtLeast(t_cs, u), Bound::Within(lo, hi, f)) = (T_CS.bound, CLOCK.bound) else {
            unreachable!("T_cs is a least time and the clock a range")
        };
        Limits {
            t_cs: u.ps(t_cs),
            period_min: f.ps(hi),
            period_max: f.ps(lo),
            t_m: Unit::Us.ps(t_m_us),
        }
    }

    /// The clock range set to `min_khz` to `max_khz` (fields `fields`),
    /// each within [`CLOCK`]'s settable range.
    pub fn set_clock(
        &mut self,
        fields: [&str; 2],
        min_khz: f64,
        max_khz: f64,
    ) -> Result<(), crate::ConfigError> {
        let lo = CLOCK.setting(fields[0], min_khz)?;
        let hi = CLOCK.setting(fields[1], max_khz)?;
        if lo > hi {
            return Err(crate::ConfigError::invalid(
                fields[0],
                format!("{lo} kHz above {} = {hi} kHz", fields[1]),
                "give min_clock_khz <= max_clock_khz (seed: 100 and 250)",
            ));
        }
        self.period_min = Unit::KHz.ps(hi);
        self.period_max = Unit::KHz.ps(lo);
        Ok(())
    }

    /// The least lengths, for [`rules::resolution_notes`].
    pub fn least(&self) -> Vec<(&'static Rule, u64)> {
        vec![
            (&T_CS, self.t_cs),
            (&CLOCK, self.period_min),
            (&T_M, self.t_m),
        ]
    }
}

/// The SSI edge watcher: the clock as the master drives it.
#[derive(Debug, Clone)]
pub struct Watch {
    limits: Limits,
    clk: Line,
    read: Option<Transaction>,
}

impl Watch {
    /// A watcher holding the master to `limits`.
    pub fn new(limits: Limits) -> Self {
        Watch {
            limits,
            clk: Line::new(),
            read: None,
        }
    }

    /// The bounds in force.
    pub fn limits(&self) -> &Limits {
        &self.limits
    }

    /// The clock has been seen idle high (before that, the master is taken
    /// to be in reset and the encoder sees its clock idle).
    pub fn seen_idle(&self) -> bool {
        self.clk.seen_idle()
    }

    /// One sample of the master's clock at `t_ps`.
    pub fn sample(&mut self, t_ps: u64, clk: bool) -> Step {
        let mut step = Step::default();
        let lim = &self.limits;
        let Some(edge) = self.clk.sample(t_ps, clk, true) else {
            if self.read.is_some() && t_ps - self.clk.last_edge_ps() >= lim.t_m {
                self.read = None;
            }
            return step;
        };
        let len = edge.phase_ps;
        match self.read.as_mut() {
            None if !edge.rose => {
                step.started = true;
                self.read = Some(Transaction::default());
            }
            None => {}
            Some(_) if !edge.rose && len >= lim.period_max => {
                step.breaches.push(T_M.breach(
                    t_ps,
                    format!(
                        "read started {:.3} us after the last clock edge of the previous read; the encoder's T_m is {:.3} us",
                        rules::us(len),
                        rules::us(lim.t_m)
                    ),
                ));
                step.started = true;
                self.read = Some(Transaction::default());
            }
            Some(_) if !edge.rose => {}
            Some(r) => {
                match r.last_rise {
                    None if rules::short(len, lim.t_cs, false) => {
                        step.breaches.push(T_CS.breach(
                            t_ps,
                            format!(
                                "first low phase {:.3} us (limit: at least {:.3} us)",
                                rules::us(len),
                                rules::us(lim.t_cs)
                            ),
                        ));
                    }
                    None => {}
                    Some(prev) => {
                        let period = t_ps - prev;
                        if period < lim.period_min || period > lim.period_max {
                            step.breaches.push(CLOCK.breach(
                                t_ps,
                                format!(
                                    "clock period {:.3} us ({:.1} kHz) within a read (limit: {:.3} to {:.3} us)",
                                    rules::us(period),
                                    1e9 / period as f64,
                                    rules::us(lim.period_min),
                                    rules::us(lim.period_max)
                                ),
                            ));
                        }
                    }
                }
                r.last_rise = Some(t_ps);
            }
        }
        step
    }
}
