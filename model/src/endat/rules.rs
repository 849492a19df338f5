//! The EnDat master's timing rules (seed 004, HEIDENHAIN EnDat 2.2, D297403:
//! 2.1.1 and 2.1.2 the clock with and without delay compensation and the
//! delay measurement, 2.3 the send block, 2.3.2 the timing table, appendix
//! A2 4.2.1 the wait after an error), in the shape of [`crate::rules`].
//!
//! The watcher sees what a probe at the master's pins sees: the clock, the
//! master's data driver (level `D` and enable `DE`) and the encoder's level
//! at the master's receiver (`R`); the line at the master is `D` while `DE`
//! is on, else `R`. A transfer begins with a falling clock edge that does
//! not continue the one before ([`Burst::continues_at`]: the clock high for
//! more than twice the high phase `R1..F2` ends a transfer), `F_k` its
//! falling edges and `R_k` the rising edge after `F_k`:
//!
//! ```text
//!  clk  ‾‾‾\______/‾‾\__/‾‾\__/‾‾ ... ‾\__/‾‾\__/‾‾ ... _/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\___
//!          F1 t_ST R1 F2  R2  F3       F8  R8                               F1 (next)
//!  DE   ____________/‾‾‾‾ M2..M0 /M2../M0 ‾\____________________________________________
//!  line ‾‾‾‾‾‾‾‾‾‾‾‾ mode bits (the master) ‾\__ low .. /S F1 F2 pos CRC \__ t_m __/‾ t_R ‾
//!          every phase >= 1/(2 f_c,max), every period F_k..F_(k+1) <= 1/100 kHz,
//!          each phase within 10 % of its period of the other (on-off ratio)
//! ```
//!
//! The mode word is the line at `R2..R7` (the encoder takes each bit with the
//! rising edge); a type 2.1 parameter command (`frame_kind` `Param21`) keeps
//! the master driving through its 29-bit block, to `R37` instead of `R8`. A
//! transfer is over at the next one's first falling edge, or once the clock
//! has been high 10 µs (seed 2.3.2's longest high phase `t_HI`) past a point
//! where a falling edge would no longer continue it; its last clock edge is
//! what the recovery times count from. A transfer had no start bit (an error,
//! appendix A2) when the line at the master, low after `R_off`, did not rise
//! before its last clock edge, or when the clock stopped before `R_off`.
//!
//! With delay compensation, a `000111` transfer clocked below
//! [`Limits::meas_below_khz`] is a frame of the delay measurement (2.1.2).
//!
//! Before the clock has been seen high (a master holding reset from time
//! 0), nothing is checked: neither the clock nor the driver enable.

use std::sync::OnceLock;

use super::decode::Burst;
use super::{frame_kind, Command, FrameKind, BLOCK_BITS};
use crate::rules::{self, Bound, Line, Rule, Settable, Step, Unit};

const TABLE: &str = "seed 004 EnDat 2.2, 2.3.2";

/// The fastest clock: the shorter phase `t_min` of every period.
pub static F_C: Rule = Rule {
    protocol: "endat",
    name: "f_c",
    section: "seed 004 EnDat 2.2, 2.1.1, 2.1.2 and 2.3.2",
    seed_words: "the maximum possible clock pulse frequency is 2 MHz ... With deviating duty cycle f_c = 1/(2t_min) (2.1.1, without delay compensation); This makes a maximum clock pulse frequency of 8 MHz possible (2.1.2, with delay compensation); Frequency f_c 100 kHz 2 MHz 8 MHz (2.3.2)",
    quantity: "f_c = 1/(2 t_min) without delay compensation <= 2000 kHz, with it",
    bound: Bound::AtMost(8000.0, Unit::KHz),
    measured: "every clock phase within a transfer, edge to edge, at least 1/(2 f_c,max): 250 ns without delay compensation, 62.5 ns with it",
    reading: "the seed's deviating duty cycle: the shorter phase sets the clock, so an asymmetric clock is legal while its shorter phase is at least half the fastest period; a configuration may set the fastest clock lower (a longer cable) or, with delay compensation, up to the 16 MHz of special applications (\"The clock pulse frequency of 8 to 16 MHz is intended for special applications\")",
    settable: Some(Settable {
        lo: 100.0,
        hi: 16_000.0,
    }),
    label: OnceLock::new(),
};

/// The slowest clock.
pub static F_C_MIN: Rule = Rule {
    protocol: "endat",
    name: "f_c min",
    section: "seed 004 EnDat 2.2, 2.1.1 and 2.3.2",
    seed_words: "The minimum possible clock pulse frequency is 100 kHz",
    quantity: "clock",
    bound: Bound::AtLeast(100.0, Unit::KHz),
    measured: "every clock period within a transfer from F2 on, falling edge to falling edge, at most 10 us",
    reading: "",
    settable: Some(Settable {
        lo: 100.0,
        hi: 16_000.0,
    }),
    label: OnceLock::new(),
};

/// The on-off ratio of every period.
pub static ON_OFF: Rule = Rule {
    protocol: "endat",
    name: "on-off ratio",
    section: TABLE,
    seed_words: "On-off ratio error 0% ±10%",
    quantity: "on-off ratio error within 10 %",
    bound: Bound::Form,
    measured: "every clock period within a transfer from F2 on: its high and its low phase differ by at most 10 % of the period (each phase 45 to 55 % of it)",
    reading: "the table is garbled (0 % and ±10 % in its columns); read as the stricter relative reading, each phase within 45 % to 55 % of its period, as the master model and its RTL hold their own clock (docs/timing/endat.md, \"Odd dividers\"); a configuration may set a smaller error (`on_off_percent`)",
    settable: Some(Settable { lo: 0.0, hi: 10.0 }),
    label: OnceLock::new(),
};

/// The first low phase: the encoder's time to switch its send block off.
pub static T_ST: Rule = Rule {
    protocol: "endat",
    name: "t_ST",
    section: "seed 004 EnDat 2.2, 2.3 and 2.3.2 note 8",
    seed_words: "With each transfer and with the first falling clock edge, the send block in the encoder must be deactivated (t_ST, observe the time conditions) (2.3); Recommendation for f_c = 2 ... 8 MHz: t_st = 2 µs specification for f_c = 16 MHz: t_st = 1 µs (linear adaptation in range of 8...16 MHz t_st) (note 8)",
    quantity: "first low phase at f_c = 2 to 8 MHz (1 us at 16 MHz, linear between)",
    bound: Bound::AtLeast(2.0, Unit::Us),
    measured: "F1 to R1 of every transfer whose clock (F2 to F3) is 2 MHz or faster; below 2 MHz the first low phase is held to f_c alone",
    reading: "a least time, the time the encoder has to release the line before the master drives at F2 (docs/timing/endat.md); the seed says \"The 2 µs relate to a cable length of 100 m and can be reduced with a shorter cable\": a configuration may set one t_ST for every clock (`t_st_us`)",
    settable: Some(Settable { lo: 0.0, hi: 1e6 }),
    label: OnceLock::new(),
};

/// The master drives the data line only while the encoder does not.
pub static SEND_BLOCK: Rule = Rule {
    protocol: "endat",
    name: "send block",
    section: "seed 004 EnDat 2.2, 2.3",
    seed_words: "The send block is activated in the subsequent electronics with the second falling edge and the mode word is then transferred. After the mode word, the subsequent electronics deactivates the send block again and switches the encoder on",
    quantity: "the master drives the data line from the second falling clock edge through its mode word, and switches off before the encoder sends",
    bound: Bound::Form,
    measured: "the master's driver enable goes on only from F2 of a transfer and is off again at R8 (R37 after the 29-bit block of a type 2.1 parameter command), where the encoder drives",
    reading: "",
    settable: None,
    label: OnceLock::new(),
};

/// Recovery time I: the encoder holds the line low, then is ready.
pub static T_M: Rule = Rule {
    protocol: "endat",
    name: "t_m",
    section: TABLE,
    seed_words: "Recovery time I For type 2.1 mode commands t_m 10 µs 30 µs; For type 2.2 mode commands 10 µs or 1.25 µs (f_c >= 1 MHz) 30 µs or 3.75 µs (2.3.2); The transfer is terminated after expiry of a certain time (recovery time I) (2.3)",
    quantity: "recovery time I; the next transfer only after the encoder's t_m",
    bound: Bound::Form,
    measured: "the next transfer's first falling edge at least the encoder's t_m after the last clock edge of the one before (type 2.2 commands: `t_m_us`, type 2.1: `t_m21_us`), and not while the line at the master is still low (the encoder holds it low for t_m)",
    reading: "the bound is the encoder's own t_m (`encoder.t_m_us`, 15 us by default, 2 us with `recovery_short`; `encoder.t_m21_us`), a device property within the seed's 10 to 30 us (1.25 to 3.75 us)",
    settable: None,
    label: OnceLock::new(),
};

/// Recovery time II: the line high before the next query.
pub static T_R: Rule = Rule {
    protocol: "endat",
    name: "t_R",
    section: "seed 004 EnDat 2.2, 2.3.2 and note 9",
    seed_words: "Recovery time II t_R 500 ns Any; Time before the next query can be received",
    quantity: "line high at the encoder before the next transfer",
    bound: Bound::AtLeast(0.5, Unit::Us),
    measured: "after recovery time I, from the line's rise at the master to the next first falling edge, plus the round trip (cable both ways and the encoder's output delay: the encoder sees the line rise that much earlier and the edge that much later)",
    reading: "",
    settable: Some(Settable { lo: 0.5, hi: 1e6 }),
    label: OnceLock::new(),
};

/// The wait after a transfer without start bit.
pub static T_ERR: Rule = Rule {
    protocol: "endat",
    name: "t_m after an error",
    section: "seed 004 EnDat 2.2, appendix A2 4.2.1",
    seed_words: "After an error handling, the maximum t_m of 30 μs must at least be waited before the next command",
    quantity: "clock high after a transfer without start bit",
    bound: Bound::AtLeast(30.0, Unit::Us),
    measured: "the last clock edge of a transfer without start bit (or one the clock left before R8) to the next first falling edge",
    reading: "",
    settable: Some(Settable { lo: 30.0, hi: 1e6 }),
    label: OnceLock::new(),
};

/// The time between EnDat 2.1 commands.
pub static T_B: Rule = Rule {
    protocol: "endat",
    name: "t_b",
    section: TABLE,
    seed_words: "Time between cycle t_b EnDat 2.1 commands : t_b > 1 ms",
    quantity: "clock high after a type 2.1 command",
    bound: Bound::MoreThan(1000.0, Unit::Us),
    measured: "the last clock edge of a transfer with a type 2.1 mode command to the next first falling edge",
    reading: "",
    settable: Some(Settable { lo: 1000.0, hi: 1e7 }),
    label: OnceLock::new(),
};

/// The clock of the delay measurement.
pub static MEAS_CLOCK: Rule = Rule {
    protocol: "endat",
    name: "measurement clock",
    section: "seed 004 EnDat 2.2, 2.1.2",
    seed_words: "Calculation of the propagation time must be with reduced clock pulse frequency (100 kHz to 200 kHz)",
    quantity: "clock of a delay measurement frame",
    bound: Bound::Within(100.0, 200.0, Unit::KHz),
    measured: "with delay compensation, every phase of a measurement frame (a 000111 transfer clocked below 500 kHz, `meas_frame_below_khz`) within 45 to 55 % of a 100 to 200 kHz period: 2.25 to 5.5 us; one report per frame",
    reading: "the phases, not only the period, as the on-off ratio holds every clock (45 to 55 %)",
    settable: None,
    label: OnceLock::new(),
};

/// How often, and when, the delay is measured.
pub static MEAS_COUNT: Rule = Rule {
    protocol: "endat",
    name: "delay measurement",
    section: "seed 004 EnDat 2.2, 2.1.2",
    seed_words: "must be implemented automatically following each power interruption ... This process should be repeated at least three times",
    quantity: "measured at least three times, automatically after each power interruption, before compensated transfers",
    bound: Bound::Form,
    measured: "with delay compensation, a run of measurement frames has at least three frames, and the first other transfer comes after one",
    reading: "a run's frames are counted up to the first other transfer; the monitor and the emulator see a power interruption only as their own start",
    settable: Some(Settable { lo: 3.0, hi: 1e6 }),
    label: OnceLock::new(),
};

/// The EnDat rules, in the order of the seed.
pub static RULES: &[&Rule] = &[
    &F_C,
    &F_C_MIN,
    &ON_OFF,
    &T_ST,
    &SEND_BLOCK,
    &T_M,
    &T_R,
    &T_ERR,
    &T_B,
    &MEAS_CLOCK,
    &MEAS_COUNT,
];

/// How long after a transfer's last clock edge it is over, if no transfer
/// starts before, ps: seed 2.3.2's longest high phase `t_HI` (10 µs); the
/// round trip of any cable is shorter, so every bit the encoder sent has
/// crossed back by then.
pub const SETTLE_PS: u64 = 10_000_000;

/// The bounds in force, ps.
#[derive(Debug, Clone, PartialEq)]
pub struct Limits {
    /// The master compensates the line delay (2.1.2): the fastest clock and
    /// the delay measurement rules follow from it.
    pub delay_comp: bool,
    /// The fastest clock, kHz ([`F_C`]).
    pub max_clock_khz: f64,
    /// The least clock phase, `1 / (2 f_c,max)` ([`F_C`]).
    pub phase_min: u64,
    /// The greatest period, `1 / f_c,min` ([`F_C_MIN`]).
    pub period_max: u64,
    /// The greatest on-off ratio error, a fraction of the period ([`ON_OFF`]).
    pub on_off: f64,
    /// A t_ST set for every clock, else the seed's by the clock ([`T_ST`]).
    pub t_st: Option<u64>,
    /// The encoder's recovery time I after type 2.2 commands ([`T_M`]).
    pub t_m22: u64,
    /// The same after type 2.1 commands ([`T_M`]).
    pub t_m21: u64,
    /// Recovery time II ([`T_R`]).
    pub t_r: u64,
    /// The round trip: cable both ways and the encoder's output delay ([`T_R`]).
    pub round_trip: u64,
    /// The wait after a transfer without start bit ([`T_ERR`]).
    pub t_err: u64,
    /// The time between type 2.1 commands, exclusive ([`T_B`]).
    pub t_b: u64,
    /// The clock below which a `000111` transfer is a measurement frame, kHz.
    pub meas_below_khz: f64,
    /// The least and greatest phase of a measurement frame ([`MEAS_CLOCK`]).
    pub meas_phase: (u64, u64),
    /// The least frames of a delay measurement ([`MEAS_COUNT`]).
    pub meas_frames_min: u32,
}

/// The value of a bound in its unit.
fn value(b: Bound) -> f64 {
    match b {
        Bound::MoreThan(v, _) | Bound::AtLeast(v, _) | Bound::AtMost(v, _) => v,
        Bound::Within(lo, _, _) => lo,
        Bound::Form => 0.0,
    }
}

impl Limits {
    /// The seed's bounds for a master with or without delay compensation,
    /// an encoder whose recovery time I is `t_m22_us` (type 2.2) and
    /// `t_m21_us` (type 2.1), and a round trip of `round_trip_ns`.
    pub fn seed(delay_comp: bool, t_m22_us: f64, t_m21_us: f64, round_trip_ns: f64) -> Self {
        let Bound::Within(meas_lo, meas_hi, khz) = MEAS_CLOCK.bound else {
            unreachable!("the measurement clock is a range")
        };
        // Each phase of a measurement frame: 45 to 55 % of a 100 to 200 kHz
        // period (the on-off ratio's 10 %).
        let on_off = 0.10;
        let max_clock_khz = if delay_comp { value(F_C.bound) } else { 2000.0 };
        Limits {
            delay_comp,
            max_clock_khz,
            phase_min: Unit::KHz.ps(2.0 * max_clock_khz),
            period_max: Unit::KHz.ps(value(F_C_MIN.bound)),
            on_off,
            t_st: None,
            t_m22: Unit::Us.ps(t_m22_us),
            t_m21: Unit::Us.ps(t_m21_us),
            t_r: Unit::Us.ps(value(T_R.bound)),
            round_trip: Unit::Ns.ps(round_trip_ns),
            t_err: Unit::Us.ps(value(T_ERR.bound)),
            t_b: Unit::Us.ps(value(T_B.bound)),
            meas_below_khz: 500.0,
            meas_phase: (
                (khz.ps(meas_hi) as f64 * (0.5 - on_off / 2.0)).round() as u64,
                (khz.ps(meas_lo) as f64 * (0.5 + on_off / 2.0)).round() as u64,
            ),
            meas_frames_min: 3,
        }
    }

    /// The fastest clock set to `khz` (from `field`): within [`F_C`]'s
    /// range, and without delay compensation at most the seed's 2 MHz.
    pub fn set_max_clock(&mut self, field: &str, khz: f64) -> Result<(), crate::ConfigError> {
        let khz = F_C.setting(field, khz)?;
        if !self.delay_comp && khz > 2000.0 {
            return Err(crate::ConfigError::invalid(
                field,
                format!("{khz} kHz is outside the seed's range without delay compensation"),
                format!(
                    "give 100 to 2000 kHz, or set delay_comp ({}: \"{}\")",
                    F_C.section, F_C.seed_words
                ),
            ));
        }
        self.max_clock_khz = khz;
        self.phase_min = Unit::KHz.ps(2.0 * khz);
        Ok(())
    }

    /// The least first low phase of a transfer whose period is `period` ps
    /// (none below 2 MHz: the phase rule alone).
    pub fn t_st_at(&self, period: u64) -> Option<u64> {
        if let Some(t) = self.t_st {
            return Some(t);
        }
        let khz = 1e9 / period.max(1) as f64;
        let two_us = Unit::Us.ps(value(T_ST.bound));
        match khz {
            k if k < 2000.0 => None,
            k if k <= 8000.0 => Some(two_us),
            // Note 8: 2 us at 8 MHz to 1 us at 16 MHz, linear; 1 us beyond.
            k => {
                let us = 2.0 - (k.min(16_000.0) - 8000.0) / 8000.0;
                Some(Unit::Us.ps(us))
            }
        }
    }

    /// The least lengths, for [`rules::resolution_notes`].
    pub fn least(&self) -> Vec<(&'static Rule, u64)> {
        let mut l = vec![(&F_C, self.phase_min), (&F_C_MIN, self.period_max)];
        if self.on_off > 0.0 {
            let fastest = 2 * self.phase_min;
            l.push((&ON_OFF, (self.on_off * fastest as f64).round() as u64));
        }
        let fastest_period = 2 * self.phase_min;
        if let Some(t) = self.t_st_at(fastest_period) {
            l.push((&T_ST, t));
        }
        l.extend([
            (&T_M, self.t_m22.min(self.t_m21)),
            (&T_R, self.t_r),
            (&T_ERR, self.t_err),
            (&T_B, self.t_b),
        ]);
        if self.delay_comp {
            l.push((&MEAS_CLOCK, self.meas_phase.0));
        }
        l
    }
}

/// The transfer in progress.
#[derive(Debug, Clone)]
struct Transfer {
    burst: Burst,
    /// The line at `R2..R7`.
    mode_bits: Vec<bool>,
    /// The first low of the line at the master (not driving) from `R_off` on.
    low: Option<u64>,
    /// The first rise after it: the start bit.
    start_bit: Option<u64>,
}

impl Transfer {
    fn mode(&self) -> Option<u8> {
        (self.mode_bits.len() == 6)
            .then(|| self.mode_bits.iter().fold(0u8, |a, &x| (a << 1) | x as u8))
    }

    /// The rising edge after which the encoder drives: `R8`, `R37` after a
    /// type 2.1 parameter command's block.
    fn r_off(&self) -> usize {
        if self.mode().map(frame_kind) == Some(FrameKind::Param21) {
            8 + BLOCK_BITS as usize
        } else {
            8
        }
    }

    fn last_edge(&self) -> u64 {
        let b = &self.burst;
        let start = b.falls[0];
        b.rises
            .last()
            .copied()
            .unwrap_or(start)
            .max(b.falls.last().copied().unwrap_or(start))
    }
}

/// What the next transfer's start is held against: the last one.
#[derive(Debug, Clone)]
struct Previous {
    last_edge: u64,
    mode: Option<u8>,
    error: bool,
}

/// The EnDat edge watcher: the clock, the master's data driver (level and
/// enable) and the encoder's level at the master's receiver.
#[derive(Debug, Clone)]
pub struct Watch {
    limits: Limits,
    clk: Line,
    cur: Option<Transfer>,
    prev: Option<Previous>,
    finished: Option<Burst>,
    de: bool,
    line: bool,
    /// The last rise of the line while the master did not drive.
    line_rise: Option<u64>,
    meas_run: u32,
    measured: bool,
    unmeasured_reported: bool,
}

/// One sample of the pins at the master.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pins {
    /// The clock.
    pub clk: bool,
    /// The master's data driver's level.
    pub d: bool,
    /// The master's data driver's enable.
    pub de: bool,
    /// The encoder's level at the master's receiver (high while nobody drives).
    pub r: bool,
}

impl Watch {
    /// A watcher holding the master to `limits`.
    pub fn new(limits: Limits) -> Self {
        Watch {
            limits,
            clk: Line::new(),
            cur: None,
            prev: None,
            finished: None,
            de: false,
            line: true,
            line_rise: None,
            meas_run: 0,
            measured: false,
            unmeasured_reported: false,
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

    /// The clock edges of the transfer in progress.
    pub fn burst(&self) -> Option<&Burst> {
        self.cur.as_ref().map(|t| &t.burst)
    }

    /// The transfer this sample ended, if one (a monitor decodes it).
    pub fn take_finished(&mut self) -> Option<Burst> {
        self.finished.take()
    }

    /// One sample of the pins at the master at `t_ps`.
    pub fn sample(&mut self, t_ps: u64, p: Pins) -> Step {
        let mut step = Step::default();
        let line = if p.de { p.d } else { p.r };
        let edge = self.clk.sample(t_ps, p.clk, true);
        if !self.clk.seen_idle() {
            return step;
        }
        let over = self.cur.as_ref().is_some_and(|c| {
            let b = &c.burst;
            p.clk
                && edge.is_none()
                && b.falls.len() >= 2
                && !b.continues_at(t_ps)
                && b.rises.last().is_some_and(|&r| t_ps - r > SETTLE_PS)
        });
        if over {
            self.finish(&mut step);
        }
        self.follow_line(t_ps, p.de, line);
        // The line of this sample: a transfer started as the line rises has a t_R of 0.
        let line_low = !p.de && !line;
        self.line = line;
        match edge {
            Some(e) if e.rose && self.cur.is_some() => {
                self.check_edge(t_ps, true, &mut step);
                if let Some(c) = self.cur.as_mut() {
                    c.burst.rises.push(t_ps);
                    let k = c.burst.rises.len();
                    if (2..=7).contains(&k) {
                        c.mode_bits.push(line);
                    }
                    if k == c.r_off() && !p.de && !line && c.low.is_none() {
                        c.low = Some(t_ps);
                    }
                }
            }
            Some(e) if e.rose => {}
            Some(_) => {
                if self
                    .cur
                    .as_ref()
                    .is_some_and(|c| c.burst.continues_at(t_ps))
                {
                    self.check_edge(t_ps, false, &mut step);
                    if let Some(c) = self.cur.as_mut() {
                        c.burst.falls.push(t_ps);
                    }
                } else {
                    if self.cur.is_some() {
                        self.finish(&mut step);
                    }
                    self.check_start(t_ps, line_low, &mut step);
                    step.started = true;
                    self.cur = Some(Transfer {
                        burst: Burst {
                            falls: vec![t_ps],
                            rises: Vec::new(),
                        },
                        mode_bits: Vec::new(),
                        low: None,
                        start_bit: None,
                    });
                }
            }
            None => {}
        }
        if p.de && !self.de && self.cur.as_ref().is_none_or(|c| c.burst.falls.len() < 2) {
            let when = if self.cur.is_some() {
                "between the first and the second falling clock edge (t_ST)"
            } else {
                "outside a transfer"
            };
            step.breaches.push(SEND_BLOCK.breach(
                t_ps,
                format!("the master switched its data driver on {when}"),
            ));
        }
        self.de = p.de;
        step
    }

    /// The line at the master: its rises while the master does not drive
    /// (recovery time II), and the encoder's low and start bit after `R_off`.
    fn follow_line(&mut self, t_ps: u64, de: bool, line: bool) {
        if !de && line && !self.line {
            self.line_rise = Some(t_ps);
        }
        let Some(c) = self.cur.as_mut() else { return };
        if c.burst.rises.len() < c.r_off() || de {
            return;
        }
        match (c.low, c.start_bit) {
            (None, _) if !line => c.low = Some(t_ps),
            (Some(_), None) if line => c.start_bit = Some(t_ps),
            _ => {}
        }
    }

    fn is_measurement(&self, c: &Transfer) -> bool {
        let khz = c.burst.period().map_or(0.0, |p| 1e9 / p.max(1) as f64);
        self.limits.delay_comp
            && c.mode() == Some(Command::Pos21.code())
            && khz < self.limits.meas_below_khz
    }

    /// The transfer in progress is over: its measurement rules, and what
    /// the next one's start is held against.
    fn finish(&mut self, step: &mut Step) {
        let Some(c) = self.cur.take() else { return };
        let last_edge = c.last_edge();
        let start = c.burst.falls[0];
        let error = c.burst.rises.len() < c.r_off()
            || c.start_bit.is_none_or(|s| s > last_edge)
            || c.low.is_none();
        if self.is_measurement(&c) {
            self.meas_run += 1;
            let (lo, hi) = self.limits.meas_phase;
            let mut edges: Vec<(u64, bool)> = c
                .burst
                .falls
                .iter()
                .map(|&t| (t, false))
                .chain(c.burst.rises.iter().map(|&t| (t, true)))
                .collect();
            edges.sort_unstable();
            let bad: Vec<(u64, u64, bool)> = edges
                .windows(2)
                .map(|w| (w[1].0, w[1].0 - w[0].0, w[1].1))
                .filter(|&(_, len, _)| len < lo || len > hi)
                .collect();
            if let Some(&(t, len, rose)) = bad.first() {
                let phase = if rose { "low" } else { "high" };
                step.breaches.push(MEAS_CLOCK.breach(
                    t,
                    format!(
                        "delay measurement frame at {:.3} us: clock {phase} for {:.3} us ({} phase(s) of this frame outside {:.3} to {:.3} us)",
                        rules::us(start),
                        rules::us(len),
                        bad.len(),
                        rules::us(lo),
                        rules::us(hi)
                    ),
                ));
            }
        } else {
            self.end_of_measurement(start, step);
        }
        self.prev = Some(Previous {
            last_edge,
            mode: c.mode(),
            error,
        });
        self.finished = Some(c.burst);
    }

    /// A transfer that is no measurement frame, starting at `start`: a run
    /// of measurement frames before it must have had enough frames, and
    /// with delay compensation there must have been one.
    fn end_of_measurement(&mut self, start: u64, step: &mut Step) {
        if self.meas_run > 0 {
            if self.meas_run < self.limits.meas_frames_min {
                step.breaches.push(MEAS_COUNT.breach(
                    start,
                    format!(
                        "a delay measurement of {} frame(s) before the transfer at {:.3} us; at least {}",
                        self.meas_run,
                        rules::us(start),
                        self.limits.meas_frames_min
                    ),
                ));
            }
            self.measured = true;
            self.meas_run = 0;
        } else if self.limits.delay_comp && !self.measured && !self.unmeasured_reported {
            self.unmeasured_reported = true;
            step.breaches.push(MEAS_COUNT.breach(
                start,
                format!(
                    "transfer at {:.3} us with delay compensation and no delay measurement before it (000111 frames at 100 to 200 kHz)",
                    rules::us(start)
                ),
            ));
        }
    }

    /// A new transfer's first falling edge at `now`: the waits after the
    /// previous one (one report: the first wait it breaks).
    fn check_start(&mut self, now: u64, line_low: bool, step: &mut Step) {
        let lim = &self.limits;
        let Some(p) = self.prev.clone() else {
            if line_low {
                step.breaches.push(T_M.breach(now, line_low_text()));
            }
            return;
        };
        let gap = now - p.last_edge;
        let is21 = p
            .mode
            .and_then(Command::from_code)
            .is_some_and(|c| !c.is_type22());
        let t_m = if is21 { lim.t_m21 } else { lim.t_m22 };
        let b = if is21 && rules::short(gap, lim.t_b, true) {
            T_B.breach(
                now,
                format!(
                    "next transfer {:.3} us after the last clock edge of a type 2.1 command ({:06b}); t_b is more than {:.3} us",
                    rules::us(gap),
                    p.mode.unwrap_or(0),
                    rules::us(lim.t_b)
                ),
            )
        } else if p.error && gap < lim.t_err {
            T_ERR.breach(
                now,
                format!(
                    "next transfer {:.3} us after the last clock edge of a transfer without start bit; wait at least {:.3} us",
                    rules::us(gap),
                    rules::us(lim.t_err)
                ),
            )
        } else if gap < t_m {
            T_M.breach(
                now,
                format!(
                    "next transfer {:.3} us after the last clock edge of the previous one; the encoder's t_m is {:.3} us",
                    rules::us(gap),
                    rules::us(t_m)
                ),
            )
        } else if line_low {
            T_M.breach(now, line_low_text())
        } else if let Some(rise) = self.line_rise.filter(|&r| r > p.last_edge) {
            let high = now - rise + lim.round_trip;
            if high >= lim.t_r {
                return;
            }
            T_R.breach(
                now,
                format!(
                    "the line rose at the master {:.3} us before the first falling edge ({:.3} us at the encoder with the round trip of {:.3} us); t_R is {:.3} us",
                    rules::us(now - rise),
                    rules::us(high),
                    rules::us(lim.round_trip),
                    rules::us(lim.t_r)
                ),
            )
        } else {
            return;
        };
        step.breaches.push(b);
    }

    /// The phase rules at a clock edge of the transfer in progress (`rose`:
    /// a rising edge at `now`).
    fn check_edge(&mut self, now: u64, rose: bool, step: &mut Step) {
        let Some(c) = &self.cur else { return };
        let lim = &self.limits;
        let b = &c.burst;
        let (nf, nr) = (b.falls.len(), b.rises.len());
        let len = if rose {
            now - b.falls[nf - 1]
        } else {
            now - b.rises[nr - 1]
        };
        let phase = if rose { "low" } else { "high" };
        if len < lim.phase_min {
            step.breaches.push(F_C.breach(
                now,
                format!(
                    "clock {phase} for {:.3} us within a transfer (at {:.0} kHz at most: {:.3} us)",
                    rules::us(len),
                    lim.max_clock_khz,
                    rules::us(lim.phase_min)
                ),
            ));
        }
        if !rose && nf >= 2 {
            let period = now - b.falls[nf - 1];
            let low = b.rises[nr - 1] - b.falls[nf - 1];
            if period > lim.period_max {
                step.breaches.push(F_C_MIN.breach(
                    now,
                    format!(
                        "clock period {:.3} us within a transfer (at least {:.0} kHz: {:.3} us at most)",
                        rules::us(period),
                        1e9 / lim.period_max as f64,
                        rules::us(lim.period_max)
                    ),
                ));
            }
            if len.abs_diff(low) as f64 > lim.on_off * period as f64 {
                step.breaches.push(ON_OFF.breach(
                    now,
                    format!(
                        "clock high {:.3} us and low {:.3} us in a period of {:.3} us (at most {:.0} % of it apart)",
                        rules::us(len),
                        rules::us(low),
                        rules::us(period),
                        lim.on_off * 100.0
                    ),
                ));
            }
            if nf == 2 {
                // F3: the clock is known, so is t_ST of its first low phase.
                let first = b.rises[0] - b.falls[0];
                if let Some(need) = lim.t_st_at(period).filter(|&n| first < n) {
                    step.breaches.push(T_ST.breach(
                        b.rises[0],
                        format!(
                            "first low phase {:.3} us at a {:.0} kHz clock; t_ST is {:.3} us",
                            rules::us(first),
                            1e9 / period.max(1) as f64,
                            rules::us(need)
                        ),
                    ));
                }
            }
        }
        if rose && nr + 1 == c.r_off() && self.de {
            step.breaches.push(SEND_BLOCK.breach(
                now,
                format!(
                    "the master's data driver still on at R{} (mode {:06b}), where the encoder drives",
                    nr + 1,
                    c.mode().unwrap_or(0)
                ),
            ));
        }
    }
}

fn line_low_text() -> String {
    "first falling clock edge while the data line at the master was still low (the encoder's recovery time I, or a line not idle)".to_string()
}
