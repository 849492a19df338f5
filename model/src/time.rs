//! The system clock: every duration in the project becomes a whole number of
//! its cycles, with the rounding stated where it happens.
//!
//! Scenario files speak in physical units (MHz, kHz, µs, metres); models speak
//! in cycles. This module is the only place where one becomes the other, so a
//! reviewer can check every conversion in one page.

use crate::{ConfigError, Result};

/// Picoseconds per second. VCD files use a 1 ps timescale: a clock whose
/// period is a whole number of picoseconds (50, 64, 80, 100 MHz) is written
/// exactly; any other (48, 60, 120, 150 MHz, whatever a board has) has each
/// cycle's time rounded to the nearest picosecond from the exact
/// `n × 10^12 / f_sys` ([`Timebase::ps_at`]), so no edge is more than 0.5 ps
/// off, and the error never accumulates however long the run. Models count
/// cycles, never picoseconds, so the rounding touches the waves' time axis
/// only, never a vector.
pub const PS_PER_S: u64 = 1_000_000_000_000;

/// The system clock of a model and of the RTL core that mirrors it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Timebase {
    f_sys_hz: u64,
}

impl Timebase {
    /// A system clock of `f_sys_hz`, any whole number of hertz up to 1 GHz.
    pub fn new(f_sys_hz: u64) -> Result<Self> {
        if f_sys_hz == 0 || f_sys_hz > 1_000_000_000 {
            return Err(ConfigError::invalid(
                "f_sys_mhz",
                format!("{} Hz is not a usable system clock", f_sys_hz),
                "give a frequency between 1 Hz and 1000 MHz",
            ));
        }
        Ok(Timebase { f_sys_hz })
    }

    /// A system clock given in MHz, as scenario files give it.
    pub fn from_mhz(f_sys_mhz: f64) -> Result<Self> {
        let hz = (f_sys_mhz * 1e6).round();
        if !f_sys_mhz.is_finite() || f_sys_mhz <= 0.0 || hz < 1.0 {
            return Err(ConfigError::invalid(
                "f_sys_mhz",
                format!("{f_sys_mhz} MHz: the system clock must be above 0 and finite"),
                "give the FPGA's system clock in MHz, e.g. 50, 64, 80 or 100",
            ));
        }
        if !(hz.is_finite() && hz >= 1.0) || (hz - f_sys_mhz * 1e6).abs() > 1e-3 {
            return Err(ConfigError::invalid(
                "f_sys_mhz",
                format!("{} MHz is not a whole number of hertz", f_sys_mhz),
                "give the system clock in MHz with at most 6 decimals",
            ));
        }
        Timebase::new(hz as u64)
    }

    /// The system clock frequency in hertz.
    pub fn f_sys_hz(&self) -> u64 {
        self.f_sys_hz
    }

    /// Whether the period is a whole number of picoseconds (then every
    /// time in the waves is exact).
    pub fn period_is_whole_ps(&self) -> bool {
        PS_PER_S % self.f_sys_hz == 0
    }

    /// One system-clock period in picoseconds, rounded to the nearest (exact
    /// when [`Timebase::period_is_whole_ps`]; else at most 0.5 ps off, e.g.
    /// 20 833 ps for 48 MHz's 20 833.3 ps).
    pub fn period_ps(&self) -> u64 {
        (PS_PER_S + self.f_sys_hz / 2) / self.f_sys_hz
    }

    /// The period in picoseconds as a real number, exact to the float: the
    /// conversions of durations to cycles use it.
    fn period_ps_f64(&self) -> f64 {
        if self.period_is_whole_ps() {
            self.period_ps() as f64
        } else {
            PS_PER_S as f64 / self.f_sys_hz as f64
        }
    }

    /// The time of cycle `n` in picoseconds: `n × 10^12 / f_sys` rounded to
    /// the nearest, so at most 0.5 ps off at every cycle (exact for a
    /// whole-picosecond period), with no error carried from cycle to cycle.
    pub fn ps_at(&self, cycle: u64) -> u64 {
        let f = self.f_sys_hz as u128;
        ((cycle as u128 * PS_PER_S as u128 + f / 2) / f) as u64
    }

    /// The fewest whole cycles that last at least `ns` nanoseconds: for
    /// minimum times a datasheet guarantees (`t_m`, `T_cs`, recovery times).
    pub fn cycles_at_least_ns(&self, ns: f64) -> u64 {
        let exact = ns * 1e3 / self.period_ps_f64();
        // Tolerate float noise so that 4000 ns at 50 MHz is exactly 200 cycles.
        (exact - 1e-9).ceil().max(0.0) as u64
    }

    /// The whole number of cycles nearest to `ns` nanoseconds: for delays that
    /// are estimates rather than limits (cable propagation).
    pub fn cycles_nearest_ns(&self, ns: f64) -> u64 {
        (ns * 1e3 / self.period_ps_f64()).round().max(0.0) as u64
    }

    /// The divider that makes a bit clock of `f_hz` from `f_sys`: it must be
    /// exact (a whole number of system clocks per period) and at least
    /// `min` (the core's fewest cycles per period). It may be odd: the
    /// period then splits into phases one cycle apart ([`BitClock`]).
    /// `field` names the scenario field the frequency came from.
    pub fn divider(&self, f_hz: f64, field: &str, min: u64) -> Result<BitClock> {
        let ratio = self.f_sys_hz as f64 / f_hz;
        let divider = ratio.round();
        if !(ratio.is_finite()) || (ratio - divider).abs() > 1e-6 || divider < min as f64 {
            let suggestion = if ratio.is_finite() {
                ratio.clamp(min as f64, 1e12).round() as u64
            } else {
                min
            };
            return Err(ConfigError::invalid(
                field,
                format!(
                    "{} kHz is f_sys / {:.3}, not f_sys divided by a whole number of at least {}",
                    f_hz / 1e3,
                    ratio,
                    min
                ),
                format!(
                    "use {} kHz (f_sys / {}) or change f_sys_mhz",
                    self.f_sys_hz as f64 / suggestion as f64 / 1e3,
                    suggestion
                ),
            ));
        }
        Ok(BitClock::of(divider as u64))
    }
}

/// A bit clock made by dividing the system clock: its period in cycles and
/// how the period splits into a high and a low phase. An even period splits
/// in halves; an odd one gives the HIGH phase the extra cycle (`high = low +
/// 1`). Why high: the SSI and EnDat masters sample a bit a fixed number of
/// cycles after a falling edge, and the bit left the encoder at the rising
/// edge before it, so the cable's round trip is budgeted in the high phase
/// (EnDat 2.2 §2.1.1: with a duty cycle other than 1:1 the shorter phase
/// sets the clock limit); BiSS-C samples by the measured delay, whatever
/// the split, and its frame ends and gaps are high levels (TMASH). The
/// seeds' minimum phase times (BiSS-C TMASH and TMASL > 25 ns, EnDat
/// t_HI and t_LO >= 0.2 µs) then bind the shorter LOW phase.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BitClock {
    /// System clocks per period (`CLOCKS_PER_BIT`).
    pub period: u64,
    /// System clocks of the high phase (`HIGH_CLOCKS`): `period - period / 2`.
    pub high: u64,
    /// System clocks of the low phase (`LOW_CLOCKS`): `period / 2`.
    pub low: u64,
}

impl BitClock {
    /// The split of a period of `period` cycles: halves, or the high phase
    /// one cycle longer when `period` is odd.
    pub fn of(period: u64) -> Self {
        BitClock {
            period,
            high: period - period / 2,
            low: period / 2,
        }
    }

    /// The phase parameters a vector header lists: none when the phases are
    /// equal (the RTL's defaults, `CLOCKS_PER_BIT / 2` each, so vectors of
    /// even dividers are what they always were), `HIGH_CLOCKS` and
    /// `LOW_CLOCKS` otherwise, under the names `names`.
    pub fn parameters(high: u64, low: u64, names: [&'static str; 2]) -> Vec<(&'static str, u64)> {
        if high == low {
            Vec::new()
        } else {
            vec![(names[0], high), (names[1], low)]
        }
    }
}
