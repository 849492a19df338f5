//! The EnDat monitor: the master's clock and data pins.
//!
//! Pins in: bit 0 the clock at the master, bit 1 its data driver's level (D),
//! bit 2 its driver enable (DE), bit 3 the data at its receiver (R). The line
//! at the master is D while DE is on, else R (what a probe on the pair at the
//! master shows; for a capture of the pair alone tie DE low and give the pair
//! as R). Transfers are decoded by [`model::endat::decode`], the decode core
//! of `tbgen decode endat` (the master's own receive and check logic judges
//! every frame). The checks, each with one monitor cycle of tolerance per
//! measured time, are the master-side limits of seed 004 (HEIDENHAIN EnDat
//! 2.2) that a pin monitor can see:
//!
//! * `f_c` (2.3.2 table; 2.1.1 "with deviating duty cycle f_c = 1/(2 t_min)"):
//!   every clock phase within a transfer at least `1 / (2 f_c,max)`: 2 MHz
//!   without delay compensation (2.1.1), 8 MHz with it (2.1.2);
//!   every period (`F_k` to `F_(k+1)`, from `F2`) at most `1 / 100 kHz`;
//! * on-off ratio (2.3.2 table: ±10 %): every period from `F2` has its high
//!   and low phase within 10 % of the period of each other (the project's
//!   reading, `docs/timing/endat.md`, "Odd dividers");
//! * `t_ST` (2.3, 2.3.2 note 8): the first low phase (`F1` to `R1`, the time
//!   the encoder has to switch its send block off before the master drives)
//!   at least 2 µs when the clock is 2 to 8 MHz, 1 µs at 16 MHz (linear
//!   between); below 2 MHz only the `f_c` phase rule;
//! * send block (2.3: "the send block is activated in the subsequent
//!   electronics with the second falling edge ... after the mode word [it]
//!   deactivates the send block again"): the master's driver enable goes on
//!   only from `F2` of a transfer, and is off again at `R8` (`R37` after the
//!   29-bit block of a type 2.1 parameter command), where the encoder drives;
//! * `t_m` (2.3.2, recovery time I): the next transfer's first falling edge
//!   at least the encoder's `t_m` after the previous transfer's last clock
//!   edge (type 2.2 frames: `encoder.t_m_us`, type 2.1: `t_m21_us`), and not
//!   while the line at the master is still low (the encoder holds it low
//!   for `t_m`);
//! * `t_R` (2.3.2, recovery time II, "time before the next query can be
//!   received"): after recovery time I the line is high at the encoder at
//!   least 500 ns before the next first falling edge (measured at the master
//!   and corrected by the round trip, cable both ways and the encoder's
//!   output delay: the encoder sees the line rise that much earlier and the
//!   edge that much later);
//! * after an error (appendix A2, 4.2.1: "after an error handling, the
//!   maximum t_m of 30 µs must at least be waited before the next command"):
//!   a transfer without start bit (`no_start_bit`, `line_not_driven`,
//!   `framing`) is followed by at least 30 µs of high clock;
//! * `t_b` (2.3.2: "EnDat 2.1 commands: t_b > 1 ms"): after a type 2.1 mode
//!   command the next transfer at least 1 ms after its last clock edge;
//! * delay measurement (2.1.2): with delay compensation, the propagation
//!   time is measured "with reduced clock pulse frequency (100 kHz to
//!   200 kHz)", "at least three times", and "following each power
//!   interruption": every measurement frame (a `000111` transfer at a clock
//!   below `meas_frame_below_khz`, 500 kHz) has each high and low phase
//!   within 45 to 55 % of a 100 to 200 kHz period (2.25 to 5.5 µs), a run of
//!   them has at least three frames, and the first other transfer comes
//!   after one.
//!
//! Transfers end when the clock has been high for more than twice the
//! transfer's first high phase (the decoder's rule); one is decoded at the
//! next transfer's start, or 10 µs after its last edge (by then the
//! encoder's last bits have crossed the cable back). Its count and last
//! value cover the transfer in progress too (decoded as far as it got).
//!
//! Configuration (a whole scenario file will do): `[monitor]` fields below;
//! defaults from `[master]` (`delay_comp`, `meas_clock_khz`), `[encoder]`
//! (`singleturn_bits + multiturn_bits`, `t_m_us`, `t_m21_us`,
//! `recovery_short`, `output_delay_ns`), `[cable]` and `[checks]` (`t_b_us`,
//! `max_clock_khz` with delay compensation).

use serde::Deserialize;
use serde_json::Value;

use model::endat::decode::{Burst, Decoder, Options};
use model::endat::{frame_kind, Command, EncoderSettings, FrameKind, MasterSettings, BLOCK_BITS};
use model::line::CableConfig;
use model::wire::Signal;

use super::{first_given, limit, listens_only, proto_table, us, Base};
use crate::config::{self, Error};
use crate::endat::{EndatChecks, MAX_CLOCK_KHZ};
use crate::{Emulator, Pins, Result};

/// The rules, as the seed states them.
pub const RULE_FC_MAX: &str = "f_c (seed 004 EnDat 2.2, 2.3.2 and 2.1.1: f_c up to 2 MHz without, 8 MHz with delay compensation; with deviating duty cycle f_c = 1/(2 t_min))";
/// See [`RULE_FC_MAX`].
pub const RULE_FC_MIN: &str = "f_c (seed 004 EnDat 2.2, 2.3.2: f_c at least 100 kHz)";
/// See [`RULE_FC_MAX`].
pub const RULE_ON_OFF: &str =
    "on-off ratio (seed 004 EnDat 2.2, 2.3.2: on-off ratio error within 10 %)";
/// See [`RULE_FC_MAX`].
pub const RULE_T_ST: &str = "t_ST (seed 004 EnDat 2.2, 2.3 and 2.3.2 note 8: the first clock's low level t_ST = 2 us for f_c = 2 to 8 MHz, 1 us at 16 MHz)";
/// See [`RULE_FC_MAX`].
pub const RULE_SEND_BLOCK: &str = "send block (seed 004 EnDat 2.2, 2.3: the master drives the data line from the second falling clock edge through its mode word, and switches off before the encoder sends)";
/// See [`RULE_FC_MAX`].
pub const RULE_T_M: &str = "t_m (seed 004 EnDat 2.2, 2.3.2: recovery time I; the next transfer only after the encoder's t_m)";
/// See [`RULE_FC_MAX`].
pub const RULE_T_R: &str = "t_R (seed 004 EnDat 2.2, 2.3.2: recovery time II t_R >= 500 ns, time before the next query can be received)";
/// See [`RULE_FC_MAX`].
pub const RULE_T_ERR: &str = "t_m after an error (seed 004 EnDat 2.2, appendix A2 4.2.1: after an error handling the maximum t_m of 30 us must at least be waited before the next command)";
/// See [`RULE_FC_MAX`].
pub const RULE_T_B: &str = "t_b (seed 004 EnDat 2.2, 2.3.2: t_b > 1 ms between EnDat 2.1 commands)";
/// See [`RULE_FC_MAX`].
pub const RULE_MEAS_CLOCK: &str = "measurement clock (seed 004 EnDat 2.2, 2.1.2: the propagation time is measured with a reduced clock of 100 kHz to 200 kHz)";
/// See [`RULE_FC_MAX`].
pub const RULE_MEAS_COUNT: &str = "delay measurement (seed 004 EnDat 2.2, 2.1.2: measured at least three times, automatically after each power interruption, before compensated transfers)";

/// How long after a transfer's last clock edge it is decoded (if no transfer starts before), ps: seed 004
/// 2.3.2's longest high phase `t_HI` (10 µs); the round trip of any cable is shorter.
const SETTLE_PS: u64 = 10_000_000;

/// The monitor's own table (`[monitor]`), every field optional.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct MonitorTable {
    pos_bits: Option<u32>,
    delay_comp: Option<bool>,
    max_clock_khz: Option<f64>,
    min_clock_khz: Option<f64>,
    on_off_percent: Option<f64>,
    t_st_us: Option<f64>,
    t_m_us: Option<f64>,
    t_m21_us: Option<f64>,
    t_r_us: Option<f64>,
    round_trip_ns: Option<f64>,
    t_err_us: Option<f64>,
    t_b_us: Option<f64>,
    meas_clock_khz: Option<f64>,
    meas_frame_below_khz: Option<f64>,
    meas_frames_min: Option<u32>,
}

/// The limits, ps (less one monitor cycle of tolerance where a least time,
/// plus one where a most).
#[derive(Debug, Clone)]
struct Limits {
    delay_comp: bool,
    max_clock_khz: f64,
    phase_min: u64,
    period_max: u64,
    on_off: f64,
    t_st_us: Option<f64>,
    t_m22: u64,
    t_m21: u64,
    t_r: u64,
    round_trip: u64,
    t_err: u64,
    t_b: u64,
    meas_below_khz: f64,
    meas_phase: (u64, u64),
    meas_frames_min: u32,
}

/// What the start of the next transfer is checked against: the last one.
#[derive(Debug, Clone)]
struct Previous {
    last_edge: u64,
    mode: Option<u8>,
    error: bool,
}

/// An EnDat monitor.
pub struct EndatMonitor {
    base: Base,
    opts: Options,
    decoder: Decoder,
    lim: Limits,
    clk: Signal,
    data: Signal,
    clk_now: bool,
    de_now: bool,
    line_now: bool,
    /// The last rise of the line while the master did not drive.
    line_rise: Option<u64>,
    cur: Option<Burst>,
    prev: Option<Previous>,
    meas_run: u32,
    measured: bool,
    unmeasured_reported: bool,
}

impl EndatMonitor {
    /// A monitor from TOML text (`origin` names it in errors) at `f_mon_hz`.
    pub fn from_toml(text: &str, origin: &str, f_mon_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "endat")?;
        config::emulator_clock(
            f_mon_hz,
            &tables.emulator,
            MAX_CLOCK_KHZ,
            "the EnDat monitor",
            origin,
        )?;
        let whole = proto_table(text, origin, "endat")?;
        let checks: EndatChecks = config::decode_in(&whole, "checks", origin)?;
        let encoder: EncoderSettings = config::decode_in(&whole, "encoder", origin)?;
        let master: MasterSettings = config::decode_in(&whole, "master", origin)?;
        let cable: CableConfig = config::decode_in(&whole, "cable", origin)?;
        let mon: MonitorTable = config::decode_in(&whole, "monitor", origin)?;
        let pos_bits = mon
            .pos_bits
            .unwrap_or(encoder.singleturn_bits + encoder.multiturn_bits);
        if !(1..=48).contains(&pos_bits) {
            return Err(Error::field(
                origin,
                "monitor.pos_bits",
                format!("{pos_bits} bits"),
                "give 1 to 48 position bits (default: encoder.singleturn_bits + multiturn_bits)",
            ));
        }
        let delay_comp = mon.delay_comp.unwrap_or(master.delay_comp);
        let max_clock_khz = mon.max_clock_khz.unwrap_or(if delay_comp {
            checks.max_clock_khz
        } else {
            2000.0
        });
        let min_clock_khz = mon.min_clock_khz.unwrap_or(100.0);
        if !(min_clock_khz > 0.0 && min_clock_khz <= max_clock_khz && max_clock_khz < 1e6) {
            return Err(Error::field(origin, "monitor.min_clock_khz", format!("{min_clock_khz} to {max_clock_khz} kHz"), "give 0 < min_clock_khz <= max_clock_khz (seed: 100 kHz, and 2000 without or 8000 with delay compensation)"));
        }
        let on_off = limit(
            origin,
            "monitor.on_off_percent",
            mon.on_off_percent.unwrap_or(10.0),
            "give the on-off ratio error in percent (seed: 10)",
        )?;
        let t_st_us = mon
            .t_st_us
            .map(|v| {
                limit(
                    origin,
                    "monitor.t_st_us",
                    v,
                    "give the least first low phase in µs (seed: 2 from 2 to 8 MHz)",
                )
            })
            .transpose()?;
        let short = encoder.recovery_short;
        let (t_m22, t_m22_field) = first_given(
            [
                ("monitor.t_m_us", mon.t_m_us),
                ("encoder.t_m_us", encoder.t_m_us),
            ],
            if short { 2.0 } else { 15.0 },
        );
        let t_m22 = limit(origin, t_m22_field, t_m22, "give the encoder's recovery time I of type 2.2 frames in µs (seed: 10 to 30, or 1.25 to 3.75)")?;
        let (t_m21, t_m21_field) = first_given(
            [
                ("monitor.t_m21_us", mon.t_m21_us),
                ("encoder.t_m21_us", Some(encoder.t_m21_us)),
            ],
            0.0,
        );
        let t_m21 = limit(
            origin,
            t_m21_field,
            t_m21,
            "give the encoder's recovery time I of type 2.1 frames in µs (seed: 10 to 30)",
        )?;
        let t_r = limit(
            origin,
            "monitor.t_r_us",
            mon.t_r_us.unwrap_or(0.5),
            "give recovery time II in µs (seed: at least 0.5)",
        )?;
        let round_trip = mon
            .round_trip_ns
            .unwrap_or(2.0 * cable.length_m * cable.ns_per_m + encoder.output_delay_ns);
        let round_trip = limit(
            origin,
            "monitor.round_trip_ns",
            round_trip,
            "give the round trip (cable both ways and the encoder's output delay) in ns",
        )?;
        let t_err = limit(
            origin,
            "monitor.t_err_us",
            mon.t_err_us.unwrap_or(30.0),
            "give the wait after an error in µs (seed: 30)",
        )?;
        let t_b = limit(
            origin,
            "monitor.t_b_us",
            mon.t_b_us.unwrap_or(checks.t_b_us),
            "give t_b in µs (seed: more than 1000)",
        )?;
        let meas_below_khz = limit(
            origin,
            "monitor.meas_frame_below_khz",
            mon.meas_frame_below_khz.unwrap_or(500.0),
            "give the clock below which a 000111 transfer is a delay measurement, kHz",
        )?;
        let meas_clock_khz = mon.meas_clock_khz.unwrap_or(master.meas_clock_khz);
        if !(meas_clock_khz > 0.0 && meas_clock_khz < 1e6) {
            return Err(Error::field(
                origin,
                "monitor.meas_clock_khz",
                format!("{meas_clock_khz} kHz"),
                "give the master's measuring clock in kHz (seed: 100 to 200)",
            ));
        }
        let base = Base::new(f_mon_hz);
        let tol = base.period_ps;
        let ps = |us: f64| (us * 1e6).round() as u64;
        let least = |us: f64| ps(us).saturating_sub(tol);
        let lim = Limits {
            delay_comp,
            max_clock_khz,
            phase_min: least(1e3 / (2.0 * max_clock_khz)),
            period_max: ps(1e3 / min_clock_khz) + tol,
            on_off: on_off / 100.0,
            t_st_us,
            t_m22: least(t_m22),
            t_m21: least(t_m21),
            t_r: least(t_r),
            round_trip: ps(round_trip / 1e3),
            t_err: least(t_err),
            t_b: least(t_b),
            meas_below_khz,
            meas_phase: (least(0.45 * 1e3 / 200.0), ps(0.55 * 1e3 / 100.0) + tol),
            meas_frames_min: mon.meas_frames_min.unwrap_or(3),
        };
        let opts = Options {
            pos_bits,
            meas_khz: delay_comp.then_some(meas_clock_khz),
        };
        Ok(EndatMonitor {
            decoder: Decoder::new(&opts).map_err(|e| {
                Error::field(origin, "monitor.pos_bits", e, "give 1 to 48 position bits")
            })?,
            opts,
            lim,
            base,
            clk: Signal::named("clk"),
            data: Signal::named("data"),
            clk_now: true,
            de_now: false,
            line_now: true,
            line_rise: None,
            cur: None,
            prev: None,
            meas_run: 0,
            measured: false,
            unmeasured_reported: false,
        })
    }

    /// The least first low phase at a clock of `khz`, ps (none below 2 MHz).
    fn t_st(&self, khz: f64) -> Option<u64> {
        let us = match self.lim.t_st_us {
            Some(v) => v,
            None if khz < 2000.0 * 0.97 => return None,
            None if khz <= 8000.0 => 2.0,
            None => (2.0 - (khz.min(16000.0) - 8000.0) / 8000.0).max(1.0),
        };
        Some(((us * 1e6).round() as u64).saturating_sub(self.base.period_ps))
    }

    /// The transfers since the last decoded one (the decoder's state is not changed).
    fn pending(&self) -> Vec<Value> {
        let Some(b) = &self.cur else {
            return Vec::new();
        };
        let mut d = self.decoder.clone();
        d.burst(b, &self.data, &self.opts)
            .into_iter()
            .map(|t| serde_json::to_value(t).unwrap_or(Value::Null))
            .collect()
    }

    fn last(&self) -> Option<Value> {
        self.pending()
            .pop()
            .or_else(|| self.base.done.last().cloned())
    }

    fn khz(b: &Burst) -> f64 {
        b.period().map_or(0.0, |p| 1e9 / p.max(1) as f64)
    }

    fn is_measurement(&self, b: &Burst) -> bool {
        self.lim.delay_comp
            && b.mode(&self.data) == Some(Command::Pos21.code())
            && Self::khz(b) < self.lim.meas_below_khz
    }

    /// The burst is over: decode it, check its measurement rules, remember it.
    fn finish(&mut self, now: u64) {
        let Some(b) = self.cur.take() else { return };
        let list = self.decoder.burst(&b, &self.data, &self.opts);
        let error = list.iter().any(|t| {
            t.errors.as_ref().is_some_and(|e| {
                e.iter()
                    .any(|e| matches!(e.as_str(), "no_start_bit" | "line_not_driven" | "framing"))
            })
        });
        let mode = b.mode(&self.data);
        let start = b.falls[0];
        if self.is_measurement(&b) {
            self.meas_run += 1;
            let (lo, hi) = self.lim.meas_phase;
            let mut edges: Vec<(u64, bool)> = b
                .falls
                .iter()
                .map(|&t| (t, false))
                .chain(b.rises.iter().map(|&t| (t, true)))
                .collect();
            edges.sort_unstable();
            let bad: Vec<(u64, u64, bool)> = edges
                .windows(2)
                .map(|w| (w[1].0, w[1].0 - w[0].0, w[1].1))
                .filter(|&(_, len, _)| len < lo || len > hi)
                .collect();
            if let Some(&(t, len, rose)) = bad.first() {
                let phase = if rose { "low" } else { "high" };
                self.base.violation(t, RULE_MEAS_CLOCK, format!("delay measurement frame at {:.3} us: clock {phase} for {:.3} us ({} phase(s) of this frame outside {:.3} to {:.3} us)", us(start), us(len), bad.len(), us(lo + self.base.period_ps), us(hi - self.base.period_ps)));
            }
        } else {
            self.end_of_measurement(start);
        }
        self.base.done.extend(
            list.into_iter()
                .map(|t| serde_json::to_value(t).unwrap_or(Value::Null)),
        );
        let last_edge = b
            .rises
            .last()
            .copied()
            .unwrap_or(start)
            .max(b.falls.last().copied().unwrap_or(start));
        self.prev = Some(Previous {
            last_edge,
            mode,
            error,
        });
        self.clk.forget_before(now);
        self.data.forget_before(now);
    }

    /// A transfer that is no measurement frame, starting at `start`: a run of measurement frames before it must
    /// have had enough frames, and with delay compensation there must have been one.
    fn end_of_measurement(&mut self, start: u64) {
        if self.meas_run > 0 {
            if self.meas_run < self.lim.meas_frames_min {
                self.base.violation(start, RULE_MEAS_COUNT, format!("a delay measurement of {} frame(s) before the transfer at {:.3} us; at least {}", self.meas_run, us(start), self.lim.meas_frames_min));
            }
            self.measured = true;
            self.meas_run = 0;
        } else if self.lim.delay_comp && !self.measured && !self.unmeasured_reported {
            self.unmeasured_reported = true;
            self.base.violation(start, RULE_MEAS_COUNT, format!("transfer at {:.3} us with delay compensation and no delay measurement before it (000111 frames at 100 to 200 kHz)", us(start)));
        }
    }

    /// A new transfer's first falling edge at `now`: the waits after the previous one.
    fn check_start(&mut self, now: u64) {
        if !self.de_now && !self.line_now {
            self.base.violation(now, RULE_T_M, "first falling clock edge while the data line at the master was still low (the encoder's recovery time I, or a line not idle)".to_string());
        }
        let Some(p) = self.prev.clone() else { return };
        let gap = now - p.last_edge;
        let is21 = p
            .mode
            .and_then(Command::from_code)
            .is_some_and(|c| !c.is_type22());
        let t_m = if is21 { self.lim.t_m21 } else { self.lim.t_m22 };
        let tol = self.base.period_ps;
        if is21 && gap < self.lim.t_b {
            self.base.violation(now, RULE_T_B, format!("next transfer {:.3} us after the last clock edge of a type 2.1 command ({:06b}); t_b is {:.3} us", us(gap), p.mode.unwrap_or(0), us(self.lim.t_b + tol)));
        } else if p.error && gap < self.lim.t_err {
            self.base.violation(now, RULE_T_ERR, format!("next transfer {:.3} us after the last clock edge of a transfer without start bit; wait at least {:.3} us", us(gap), us(self.lim.t_err + tol)));
        } else if gap < t_m {
            self.base.violation(now, RULE_T_M, format!("next transfer {:.3} us after the last clock edge of the previous one; the encoder's t_m is {:.3} us", us(gap), us(t_m + tol)));
        } else if let Some(rise) = self.line_rise.filter(|&r| r > p.last_edge && self.line_now) {
            let high = now - rise + self.lim.round_trip;
            if high < self.lim.t_r {
                self.base.violation(now, RULE_T_R, format!("the line rose at the master {:.3} us before the first falling edge ({:.3} us at the encoder with the round trip of {:.3} us); t_R is {:.3} us", us(now - rise), us(high), us(self.lim.round_trip), us(self.lim.t_r + tol)));
            }
        }
    }

    /// Phase rules at a clock edge within the burst in progress (`rose`: a rising edge at `now`).
    fn check_edge(&mut self, now: u64, rose: bool) {
        let Some(b) = &self.cur else { return };
        let (nf, nr) = (b.falls.len(), b.rises.len());
        let len = if rose {
            now - b.falls[nf - 1]
        } else {
            now - b.rises[nr - 1]
        };
        let phase = if rose { "low" } else { "high" };
        let mut found: Vec<(u64, &'static str, String)> = Vec::new();
        if len < self.lim.phase_min {
            found.push((
                now,
                RULE_FC_MAX,
                format!(
                    "clock {phase} for {:.3} us within a transfer (at {:.0} kHz at most: {:.3} us)",
                    us(len),
                    self.lim.max_clock_khz,
                    us(self.lim.phase_min + self.base.period_ps)
                ),
            ));
        }
        if !rose && nf >= 2 {
            let period = now - b.falls[nf - 1];
            let low = b.rises[nr - 1] - b.falls[nf - 1];
            if period > self.lim.period_max {
                found.push((
                    now,
                    RULE_FC_MIN,
                    format!(
                        "clock period {:.3} us within a transfer (100 kHz: 10 us at most)",
                        us(period)
                    ),
                ));
            }
            let diff = len.abs_diff(low) as f64;
            if diff > self.lim.on_off * period as f64 + 2.0 * self.base.period_ps as f64 {
                found.push((
                    now,
                    RULE_ON_OFF,
                    format!(
                        "clock high {:.3} us and low {:.3} us in a period of {:.3} us",
                        us(len),
                        us(low),
                        us(period)
                    ),
                ));
            }
            if nf == 2 {
                // F3: the clock is known, so is t_ST of its first low phase.
                let khz = 1e9 / period.max(1) as f64;
                let first = b.rises[0] - b.falls[0];
                if let Some(need) = self.t_st(khz).filter(|&n| first < n) {
                    found.push((
                        b.rises[0],
                        RULE_T_ST,
                        format!(
                            "first low phase {:.3} us at a {:.0} kHz clock; t_ST is {:.3} us",
                            us(first),
                            khz,
                            us(need + self.base.period_ps)
                        ),
                    ));
                }
            }
        }
        if rose {
            // R8 (R37 after a type 2.1 parameter command's block): the master's driver must be off.
            let k = nr + 1;
            let mode = b.mode(&self.data);
            let r_off = if mode.map(frame_kind) == Some(FrameKind::Param21) {
                8 + BLOCK_BITS as usize
            } else {
                8
            };
            if k == r_off && self.de_now {
                found.push((now, RULE_SEND_BLOCK, format!("the master's data driver still on at R{k} (mode {:06b}), where the encoder drives", mode.unwrap_or(0))));
            }
        }
        for (t, rule, detail) in found {
            self.base.violation(t, rule, detail);
        }
    }
}

impl Emulator for EndatMonitor {
    fn kind(&self) -> &'static str {
        "endat_monitor"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let now = self.base.now_ps();
        let (clk, d, de, rx) = (
            pins.0 & 1 != 0,
            pins.0 & 2 != 0,
            pins.0 & 4 != 0,
            pins.0 & 8 != 0,
        );
        let line = if de { d } else { rx };
        // A burst is over once a falling edge would no longer continue it; it is decoded 10 us (t_HI's maximum)
        // after its last edge, when every bit the encoder sent has crossed the cable back (or at the next start).
        let settled = |b: &Burst| b.rises.last().is_some_and(|&r| now - r > SETTLE_PS);
        if clk
            && self.clk_now
            && self
                .cur
                .as_ref()
                .is_some_and(|b| b.falls.len() >= 2 && !b.continues_at(now) && settled(b))
        {
            self.finish(now);
        }
        // The data line first, so that the clock edge of this cycle sees it.
        self.data.push(now, line);
        if clk != self.clk_now {
            self.clk_now = clk;
            if clk {
                if self.cur.is_some() {
                    self.check_edge(now, true);
                    if let Some(b) = self.cur.as_mut() {
                        b.rises.push(now);
                    }
                }
            } else if self.cur.as_ref().is_some_and(|b| b.continues_at(now)) {
                self.check_edge(now, false);
                if let Some(b) = self.cur.as_mut() {
                    b.falls.push(now);
                }
            } else {
                if self.cur.is_some() {
                    self.finish(now);
                }
                self.check_start(now);
                self.cur = Some(Burst {
                    falls: vec![now],
                    rises: Vec::new(),
                });
            }
        }
        self.clk.push(now, clk);
        if de && !self.de_now && self.cur.as_ref().is_none_or(|b| b.falls.len() < 2) {
            let when = if self.cur.is_some() {
                "between the first and the second falling clock edge (t_ST)"
            } else {
                "outside a transfer"
            };
            self.base.violation(
                now,
                RULE_SEND_BLOCK,
                format!("the master switched its data driver on {when}"),
            );
        }
        if !de && line && !self.line_now {
            self.line_rise = Some(now);
        }
        self.de_now = de;
        self.line_now = line;
        self.base.step_out()
    }

    fn set_position(&mut self, _: usize, _: u64) -> Result<()> {
        Err(listens_only("endat_monitor", "position to set"))
    }

    fn set_status(&mut self, _: usize, _: &str, _: bool) -> Result<()> {
        Err(listens_only("endat_monitor", "status to set"))
    }

    fn schedule_fault(&mut self, _: &str) -> Result<()> {
        Err(listens_only("endat_monitor", "faults to schedule"))
    }

    /// Transactions seen so far (the one in progress included; a delay measurement is one).
    fn count(&self) -> u64 {
        (self.base.done.len() + self.pending().len()) as u64
    }

    /// The position (or test value) of the last transaction seen.
    fn last_value(&self, _: usize) -> Option<u64> {
        self.last()?.get("position")?.as_u64()
    }

    /// `"f1"`, `"f2"` (as the master reads them: F2 is low-active, `true` is no error), `"crc_ok"` (no `crc`
    /// error), `"error"` (any error flagged) of the last transaction seen.
    fn last_status(&self, _: usize, name: &str) -> Result<bool> {
        let t = self
            .last()
            .ok_or_else(|| Error::Usage("endat_monitor: no transfer decoded yet".into()))?;
        let errors: Vec<&str> = t["errors"]
            .as_array()
            .map(|e| e.iter().filter_map(|x| x.as_str()).collect())
            .unwrap_or_default();
        match name {
            "f1" | "f2" => t[name].as_bool().ok_or_else(|| {
                Error::Usage(format!(
                    "endat_monitor: the last transfer carried no {}",
                    name.to_uppercase()
                ))
            }),
            "crc_ok" => Ok(!errors.contains(&"crc")),
            "error" | "errors" => Ok(errors
                .iter()
                .any(|e| !matches!(*e, "f1_error" | "f2_error"))),
            other => Err(Error::Usage(format!(
                "endat_monitor: no status `{other}`; give \"f1\", \"f2\", \"crc_ok\" or \"error\""
            ))),
        }
    }

    fn transcript(&self) -> Value {
        self.base.transcript(
            "endat",
            &["clk", "data", "data_oe", "data_in"],
            self.pending(),
        )
    }

    fn checks(&mut self) -> &mut crate::check::Checks {
        &mut self.base.checks
    }
}
