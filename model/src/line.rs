//! The cable between master and encoder: one delay line per direction, with
//! optional jitter, and a half-duplex RS-485 pair with driver enables.
//!
//! A cable of length `L` delays each direction by `L × ns_per_m` (5 ns/m by
//! default, the propagation delay of twisted pair with a velocity factor of
//! about 0.67), rounded to the nearest system-clock cycle. Transceiver delays
//! belong to the devices at either end, not to the cable.

use std::collections::VecDeque;

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use serde::{Deserialize, Serialize};

use crate::{ConfigError, Result, Timebase};

/// A cable as a scenario file describes it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct CableConfig {
    /// Length in metres (0 to 1000).
    pub length_m: f64,
    /// One-way propagation delay per metre in nanoseconds.
    pub ns_per_m: f64,
    /// Peak jitter added to each edge, in nanoseconds (uniform in ±jitter).
    pub jitter_ns: f64,
    /// Seed of the jitter's random sequence, so that a scenario replays exactly.
    pub seed: u64,
}

impl Default for CableConfig {
    fn default() -> Self {
        CableConfig {
            length_m: 0.0,
            ns_per_m: 5.0,
            jitter_ns: 0.0,
            seed: 1,
        }
    }
}

impl CableConfig {
    /// Checks the fields; `prefix` is the scenario table the cable sits in.
    pub fn validate(&self, prefix: &str) -> Result<()> {
        if !(0.0..=1000.0).contains(&self.length_m) {
            return Err(ConfigError::invalid(
                format!("{prefix}.length_m"),
                format!("{} m is outside 0 to 1000 m", self.length_m),
                "give the cable length in metres, 0 to 1000",
            ));
        }
        if !(0.0..=50.0).contains(&self.ns_per_m) {
            return Err(ConfigError::invalid(
                format!("{prefix}.ns_per_m"),
                format!("{} ns/m is not a cable propagation delay", self.ns_per_m),
                "use about 5 ns/m for twisted pair",
            ));
        }
        if !(0.0..=10_000.0).contains(&self.jitter_ns) {
            return Err(ConfigError::invalid(
                format!("{prefix}.jitter_ns"),
                format!("{} ns is not a usable jitter", self.jitter_ns),
                "give the peak jitter in ns, 0 for none",
            ));
        }
        Ok(())
    }

    /// One-way delay in system-clock cycles (nearest whole cycle).
    pub fn delay_cycles(&self, tb: &Timebase) -> u64 {
        tb.cycles_nearest_ns(self.length_m * self.ns_per_m)
    }

    /// Peak jitter in system-clock cycles (nearest whole cycle).
    pub fn jitter_cycles(&self, tb: &Timebase) -> u64 {
        tb.cycles_nearest_ns(self.jitter_ns)
    }

    /// The two delay lines of this cable: (master to device, device to master).
    /// The second line's jitter sequence is seeded differently from the first.
    pub fn lines(&self, tb: &Timebase, idle: bool) -> (DelayLine, DelayLine) {
        let (delay, jitter) = (self.delay_cycles(tb), self.jitter_cycles(tb));
        (
            DelayLine::with_jitter(delay, jitter, self.seed, idle),
            DelayLine::with_jitter(delay, jitter, self.seed.wrapping_add(0x9E37_79B9), idle),
        )
    }
}

/// One direction of a cable: a level that enters at cycle `t` leaves at
/// `t + delay` (± jitter). With no delay the output follows the input in the
/// same cycle. Edges never overtake one another: a jittered edge that would
/// arrive at or before the previous one is held until the cycle after it.
#[derive(Debug, Clone)]
pub struct DelayLine {
    delay: u64,
    jitter: u64,
    rng: Pcg64Mcg,
    now: u64,
    last_input: bool,
    output: bool,
    last_due: Option<u64>,
    pending: VecDeque<(u64, bool)>,
}

impl DelayLine {
    /// A line of `delay` cycles without jitter, idle at `idle`.
    pub fn new(delay: u64, idle: bool) -> Self {
        DelayLine::with_jitter(delay, 0, 1, idle)
    }

    /// A line of `delay` cycles whose edges move by up to ±`jitter` cycles.
    pub fn with_jitter(delay: u64, jitter: u64, seed: u64, idle: bool) -> Self {
        DelayLine {
            delay,
            jitter,
            rng: Pcg64Mcg::seed_from_u64(seed),
            now: 0,
            last_input: idle,
            output: idle,
            last_due: None,
            pending: VecDeque::new(),
        }
    }

    /// The nominal delay in cycles.
    pub fn delay(&self) -> u64 {
        self.delay
    }

    /// Advances one cycle: `input` is the level at the sending end now; the
    /// result is the level at the receiving end now.
    #[inline]
    pub fn step(&mut self, input: bool) -> bool {
        // Most cycles carry no edge and have none in flight: inlined into
        // the callers (a half-duplex pair steps four lines every cycle).
        if input == self.last_input && self.pending.is_empty() {
            self.now += 1;
            return self.output;
        }
        self.step_edge(input)
    }

    /// [`DelayLine::step`] with an edge at the input or one in flight.
    fn step_edge(&mut self, input: bool) -> bool {
        if input != self.last_input {
            self.last_input = input;
            let mut due = self.now + self.delay;
            if self.jitter > 0 {
                let j = self.rng.random_range(0..=2 * self.jitter) as i64 - self.jitter as i64;
                due = (due as i64 + j).max(self.now as i64) as u64;
            }
            // Keep edges in order and at least one cycle apart, so none is lost.
            if let Some(last) = self.last_due {
                due = due.max(last + 1);
            }
            self.last_due = Some(due);
            self.pending.push_back((due, input));
        }
        while let Some(&(due, level)) = self.pending.front() {
            if due > self.now {
                break;
            }
            self.output = level;
            self.pending.pop_front();
        }
        self.now += 1;
        self.output
    }

    /// How many of the next steps with `input` leave the output as it is
    /// (fast-forward, [`crate::testbench::Testbench::quiet_cycles`]): up to
    /// the next edge in flight, unbounded when none is; 0 when `input` is a
    /// new edge.
    pub fn quiet(&self, input: bool) -> u64 {
        if input != self.last_input {
            return 0;
        }
        match self.pending.front() {
            Some(&(due, _)) => due.saturating_sub(self.now),
            None => u64::MAX,
        }
    }

    /// The level at the receiving end after the last step.
    pub fn output(&self) -> bool {
        self.output
    }

    /// The same as `n` steps with the last input, for `n` up to [`DelayLine::quiet`].
    pub fn skip(&mut self, n: u64) {
        self.now += n;
    }
}

/// What one end of a half-duplex pair drives: its driver enable and the level
/// it would put on the line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Drive {
    /// RS-485 driver enable (DE).
    pub enable: bool,
    /// The level driven while enabled.
    pub level: bool,
}

/// What a receiver at one end of a half-duplex pair sees.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Sensed {
    /// The received level. With no driver on the line it is the fail-safe
    /// idle level; with two it is the level of the nearer driver.
    pub level: bool,
    /// Both drivers are on at this end of the cable in this cycle.
    pub contention: bool,
}

/// A half-duplex RS-485 pair between a master (end A) and a device (end B).
/// Each end's driver state travels to the other end through its own delay
/// line. A receiver sees its own driver at once and the far driver delayed.
#[derive(Debug, Clone)]
pub struct HalfDuplexLine {
    idle: bool,
    a_to_b_enable: DelayLine,
    a_to_b_level: DelayLine,
    b_to_a_enable: DelayLine,
    b_to_a_level: DelayLine,
    contention_cycles: u64,
}

impl HalfDuplexLine {
    /// A pair with `delay` cycles each way whose fail-safe biasing holds
    /// the undriven line at `idle` (high on a correctly terminated RS-485 bus).
    pub fn new(delay: u64, idle: bool) -> Self {
        HalfDuplexLine {
            idle,
            a_to_b_enable: DelayLine::new(delay, false),
            a_to_b_level: DelayLine::new(delay, idle),
            b_to_a_enable: DelayLine::new(delay, false),
            b_to_a_level: DelayLine::new(delay, idle),
            contention_cycles: 0,
        }
    }

    /// Advances one cycle with what each end drives now; returns what the
    /// receivers at A and at B see now.
    pub fn step(&mut self, a: Drive, b: Drive) -> (Sensed, Sensed) {
        let far_a = Drive {
            enable: self.b_to_a_enable.step(b.enable),
            level: self.b_to_a_level.step(b.level),
        };
        let far_b = Drive {
            enable: self.a_to_b_enable.step(a.enable),
            level: self.a_to_b_level.step(a.level),
        };
        let at_a = resolve(a, far_a, self.idle);
        let at_b = resolve(b, far_b, self.idle);
        if at_a.contention || at_b.contention {
            self.contention_cycles += 1;
        }
        (at_a, at_b)
    }

    /// How many of the next steps with drives `a` and `b` leave both
    /// receivers' levels as they are (see [`DelayLine::quiet`]).
    pub fn quiet(&self, a: Drive, b: Drive) -> u64 {
        self.b_to_a_enable
            .quiet(b.enable)
            .min(self.b_to_a_level.quiet(b.level))
            .min(self.a_to_b_enable.quiet(a.enable))
            .min(self.a_to_b_level.quiet(a.level))
    }

    /// The same as `n` steps with drives `a` and `b`, for `n` up to
    /// [`HalfDuplexLine::quiet`]; returns what the receivers see.
    pub fn skip(&mut self, n: u64, a: Drive, b: Drive) -> (Sensed, Sensed) {
        for line in [
            &mut self.b_to_a_enable,
            &mut self.b_to_a_level,
            &mut self.a_to_b_enable,
            &mut self.a_to_b_level,
        ] {
            line.skip(n);
        }
        let (at_a, at_b) = self.sensed(a, b);
        if at_a.contention || at_b.contention {
            self.contention_cycles += n;
        }
        (at_a, at_b)
    }

    /// What the receivers at A and B see now with drives `a` and `b`, the
    /// far ends' levels as they left the lines in the last step.
    pub fn sensed(&self, a: Drive, b: Drive) -> (Sensed, Sensed) {
        let far_a = self.b_at_a();
        let far_b = Drive {
            enable: self.a_to_b_enable.output,
            level: self.a_to_b_level.output,
        };
        (resolve(a, far_a, self.idle), resolve(b, far_b, self.idle))
    }

    /// Cycles in which two drivers were on at either end.
    pub fn contention_cycles(&self) -> u64 {
        self.contention_cycles
    }

    /// B's drive as it arrives at A after the last step: the level and the
    /// enable a transceiver at A would show of the far driver.
    pub fn b_at_a(&self) -> Drive {
        Drive {
            enable: self.b_to_a_enable.output,
            level: self.b_to_a_level.output,
        }
    }
}

fn resolve(near: Drive, far: Drive, idle: bool) -> Sensed {
    match (near.enable, far.enable) {
        (true, true) => Sensed {
            level: near.level,
            contention: true,
        },
        (true, false) => Sensed {
            level: near.level,
            contention: false,
        },
        (false, true) => Sensed {
            level: far.level,
            contention: false,
        },
        (false, false) => Sensed {
            level: idle,
            contention: false,
        },
    }
}
