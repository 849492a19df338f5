//! Motion profiles: the position an emulated encoder latches as a function
//! of the emulator's time, one place for every protocol.
//!
//! A profile is a `[motion]` table of the emulator's TOML, or the text a
//! testbench gives `set_motion(device, toml)` at run time:
//!
//! ```toml
//! [motion]
//! kind = "constant"          # start + counts_per_ms x t
//! start = 1000
//! counts_per_ms = 250.5      # negative: backwards
//! ```
//!
//! `kind = "steps"`: `start`, `step` (counts, signed) every `every_us`;
//! `kind = "reversal"`: `start`, `counts_per_ms`, reversing every
//! `half_period_ms` (a triangle: out and back). Time `t` counts from the
//! moment the profile is set (0 for the TOML's own). Positions wrap at the
//! encoder's resolution, as a shaft does.

use serde::Deserialize;

use crate::config::Error;
use crate::Result;

/// One motion profile.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Motion {
    /// Constant speed.
    Constant {
        /// Position at t = 0.
        start: u64,
        /// Counts per millisecond (signed).
        counts_per_ms: f64,
    },
    /// A step of `step` counts every `every_us`.
    Steps {
        /// Position at t = 0.
        start: u64,
        /// Counts per step (signed).
        step: i64,
        /// Time between steps, µs.
        every_us: f64,
    },
    /// Constant speed that reverses every `half_period_ms`.
    Reversal {
        /// Position at t = 0.
        start: u64,
        /// Counts per millisecond of the outward leg (signed).
        counts_per_ms: f64,
        /// Time of one leg, ms.
        half_period_ms: f64,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Table {
    motion: Motion,
}

impl Motion {
    /// A profile from TOML text holding a `[motion]` table (`origin` names it in errors).
    pub fn from_toml(text: &str, origin: &str) -> Result<Motion> {
        let t: Table = toml::from_str(text).map_err(|e| Error::Toml {
            origin: origin.to_string(),
            line: None,
            message: e
                .to_string()
                .split_whitespace()
                .collect::<Vec<_>>()
                .join(" "),
        })?;
        t.motion.validate(origin)?;
        Ok(t.motion)
    }

    /// Checks the numbers, naming the field and the fix.
    pub fn validate(&self, origin: &str) -> Result<()> {
        let finite = |field: &str, v: f64| {
            if v.is_finite() && v.abs() < 1e15 {
                Ok(())
            } else {
                Err(Error::field(
                    origin,
                    field,
                    format!("{v}"),
                    "give a finite number",
                ))
            }
        };
        match *self {
            Motion::Constant { counts_per_ms, .. } => finite("motion.counts_per_ms", counts_per_ms),
            Motion::Steps { every_us, .. } if !(every_us > 0.0 && every_us.is_finite()) => {
                Err(Error::field(
                    origin,
                    "motion.every_us",
                    format!("{every_us}"),
                    "give the time between steps in µs, more than 0",
                ))
            }
            Motion::Steps { .. } => Ok(()),
            Motion::Reversal {
                counts_per_ms,
                half_period_ms,
                ..
            } => {
                finite("motion.counts_per_ms", counts_per_ms)?;
                if half_period_ms > 0.0 && half_period_ms.is_finite() {
                    Ok(())
                } else {
                    Err(Error::field(
                        origin,
                        "motion.half_period_ms",
                        format!("{half_period_ms}"),
                        "give the time of one leg in ms, more than 0",
                    ))
                }
            }
        }
    }

    /// The position `t_ns` after the profile was set, wrapped to `bits` bits.
    pub fn position_at(&self, t_ns: f64, bits: u32) -> u64 {
        let offset: i128 = match *self {
            Motion::Constant { counts_per_ms, .. } => (counts_per_ms * t_ns / 1e6).floor() as i128,
            Motion::Steps { step, every_us, .. } => {
                (t_ns / (every_us * 1e3)).floor() as i128 * step as i128
            }
            Motion::Reversal {
                counts_per_ms,
                half_period_ms,
                ..
            } => {
                let leg = half_period_ms * 1e6;
                let k = (t_ns / leg).floor();
                let into = t_ns - k * leg;
                // Even legs go out from the start, odd ones come back.
                let along = if (k as i64) % 2 == 0 {
                    into
                } else {
                    leg - into
                };
                (counts_per_ms * along / 1e6).floor() as i128
            }
        };
        let start = match *self {
            Motion::Constant { start, .. }
            | Motion::Steps { start, .. }
            | Motion::Reversal { start, .. } => start,
        };
        let modulus: i128 = if bits >= 64 {
            1i128 << 64
        } else {
            1i128 << bits
        };
        (start as i128 + offset).rem_euclid(modulus) as u64
    }
}

/// A profile and the emulator cycle it was set at.
#[derive(Debug, Clone, PartialEq)]
pub struct Running {
    /// The profile.
    pub motion: Motion,
    /// Emulator cycle at t = 0.
    pub since: u64,
}

impl Running {
    /// The position at emulator cycle `cycle` of a clock of `period_ps`.
    pub fn position(&self, cycle: u64, period_ps: u64, bits: u32) -> u64 {
        let t_ns = cycle.saturating_sub(self.since) as f64 * period_ps as f64 / 1e3;
        self.motion.position_at(t_ns, bits)
    }

    /// The position at emulator cycle `cycle` of the clock `tb`, timed from
    /// the exact `n x 10^12 / f_emu` (any clock, whole picoseconds or not).
    pub fn position_on(&self, cycle: u64, tb: &model::Timebase, bits: u32) -> u64 {
        let t_ns = tb.ps_at(cycle.saturating_sub(self.since)) as f64 / 1e3;
        self.motion.position_at(t_ns, bits)
    }
}

/// The motion profiles of an emulator's devices (chain positions), for
/// every protocol: set one with [`Motions::set`], and before each emulator
/// cycle ask [`Motions::position`] for the position to hold.
#[derive(Debug, Clone, Default)]
pub struct Motions {
    running: Vec<Option<Running>>,
}

impl Motions {
    /// Device `device` follows the `[motion]` table in `toml` from emulator cycle `cycle` on.
    pub fn set(&mut self, device: usize, toml: &str, cycle: u64) -> Result<()> {
        let motion = Motion::from_toml(toml, "set_motion")?;
        if self.running.len() <= device {
            self.running.resize(device + 1, None);
        }
        self.running[device] = Some(Running {
            motion,
            since: cycle,
        });
        Ok(())
    }

    /// Device `device` no longer moves (the testbench set its position).
    pub fn stop(&mut self, device: usize) {
        if let Some(r) = self.running.get_mut(device) {
            *r = None;
        }
    }

    /// Whether any device moves.
    pub fn any(&self) -> bool {
        self.running.iter().any(|r| r.is_some())
    }

    /// The position device `device` holds at `cycle`, if it moves.
    pub fn position(&self, device: usize, cycle: u64, period_ps: u64, bits: u32) -> Option<u64> {
        self.running
            .get(device)?
            .as_ref()
            .map(|r| r.position(cycle, period_ps, bits))
    }

    /// [`Motions::position`] on the clock `tb` ([`Running::position_on`]).
    pub fn position_on(
        &self,
        device: usize,
        cycle: u64,
        tb: &model::Timebase,
        bits: u32,
    ) -> Option<u64> {
        self.running
            .get(device)?
            .as_ref()
            .map(|r| r.position_on(cycle, tb, bits))
    }
}
