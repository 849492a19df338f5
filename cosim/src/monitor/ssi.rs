//! The SSI monitor: the master's clock and the data at its receiver.
//!
//! Pins in: bit 0 the SSI clock at the master, bit 1 the data at the
//! master's receiver. Reads are decoded by [`model::ssi::decode`]; the
//! checks (seed 001, SAR58K24 manual, SSI section (2): "T_cs > 4 µs;
//! 100 kHz < f_clk < 250 kHz; T_m > 500 µs"), each with one monitor cycle of
//! tolerance, on the clock as it leaves the master:
//!
//! * `T_cs`: the first low phase of a read (storing falling edge to the
//!   first rising edge) at least `checks.t_cs_min_us` (4 µs);
//! * clock range: every later half period of a read within
//!   `checks.min_clock_khz` to `checks.max_clock_khz` (100 to 250 kHz);
//! * `T_m`: a read starts only when the previous read's last rising edge is
//!   at least `monitor.t_m_us` back (default the encoder's `monoflop_us`,
//!   the seed's 500 µs when there is no `[encoder]`), so the monoflop has
//!   run out.
//!
//! A read ends when the clock has stayed high for more than three of its
//! half periods (the decoder's rule); before its first bit, three of the
//! slowest allowed half periods.
//!
//! Configuration (a whole scenario file will do): `[monitor]` with `bits`,
//! `code`, `double_read`, `wire_check` (default: the `[master]` table's,
//! else the `[encoder]`'s bits and code) and `t_m_us`; `[checks]` as the
//! emulator's ([`crate::ssi::SsiChecks`]).

use serde::Deserialize;
use serde_json::Value;

use model::ssi::decode::{self, Layout};
use model::ssi::{Code, EncoderSettings};
use model::wire::Signal;

use super::{field, first_given, limit, listens_only, proto_table, sub, us, Base};
use crate::config::{self, Error};
use crate::ssi::{SsiChecks, MAX_CLOCK_KHZ};
use crate::{Emulator, Pins, Result};

/// The rules, as the seed states them.
pub const RULE_T_CS: &str = "T_cs (seed 001 SAR58K24 manual, SSI (2): T_cs > 4 us)";
/// See [`RULE_T_CS`].
pub const RULE_CLOCK: &str =
    "clock range (seed 001 SAR58K24 manual, SSI (2): 100 kHz < f_clk < 250 kHz)";
/// See [`RULE_T_CS`].
pub const RULE_T_M: &str = "T_m (seed 001 SAR58K24 manual, SSI (2): T_m > 500 us; a new read only after the monoflop time)";

/// The monitor's own table (`[monitor]`), every field optional.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct MonitorTable {
    bits: Option<u32>,
    code: Option<Code>,
    double_read: Option<bool>,
    wire_check: Option<bool>,
    t_m_us: Option<f64>,
}

#[derive(Debug, Clone, Default)]
struct Watch {
    clk: bool,
    last_edge: u64,
    in_read: bool,
    edges: u32,
    half: Option<u64>,
    read_end: Option<u64>,
}

/// An SSI monitor.
pub struct SsiMonitor {
    base: Base,
    layout: Layout,
    /// Limits in ps: least and most half period, least T_cs, least T_m.
    half_min: u64,
    half_max: u64,
    t_cs: u64,
    t_m: u64,
    clk: Signal,
    data: Signal,
    watch: Watch,
}

impl SsiMonitor {
    /// A monitor from TOML text (`origin` names it in errors) at `f_mon_hz`.
    pub fn from_toml(text: &str, origin: &str, f_mon_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "ssi")?;
        let whole = proto_table(text, origin, "ssi")?;
        let checks: SsiChecks = config::decode_in(&whole, "checks", origin)?;
        let mut settings = tables.emulator.clone();
        settings.max_line_clock_khz = settings
            .max_line_clock_khz
            .or(Some(checks.max_clock_khz.max(MAX_CLOCK_KHZ)));
        config::emulator_clock(
            f_mon_hz,
            &settings,
            MAX_CLOCK_KHZ,
            "the SSI monitor",
            origin,
        )?;
        let encoder: EncoderSettings = config::decode_in(&whole, "encoder", origin)?;
        let master = sub(&whole, "master", origin)?;
        let mon: MonitorTable = config::decode_in(&whole, "monitor", origin)?;
        let (bits, bits_field) = first_given(
            [
                ("monitor.bits", mon.bits),
                (
                    "master.bits",
                    field(&master, "bits", origin, "master.bits")?,
                ),
                ("encoder.bits", Some(encoder.bits)),
            ],
            0,
        );
        if !(1..=64).contains(&bits) {
            return Err(Error::field(
                origin,
                bits_field,
                format!("{bits} bits"),
                "give 1 to 64 bits",
            ));
        }
        let code = mon
            .code
            .or(field(&master, "code", origin, "master.code")?)
            .unwrap_or(encoder.code);
        let double_read = mon
            .double_read
            .or(field(&master, "double_read", origin, "master.double_read")?)
            .unwrap_or(false);
        let wire_check = mon
            .wire_check
            .or(field(&master, "wire_check", origin, "master.wire_check")?)
            .unwrap_or(false);
        let (t_m_us, t_m_field) = first_given(
            [
                ("monitor.t_m_us", mon.t_m_us),
                ("encoder.monoflop_us", Some(encoder.monoflop_us)),
            ],
            0.0,
        );
        let t_m_us = limit(
            origin,
            t_m_field,
            t_m_us,
            "give the encoder's monoflop time in µs (seed: 500)",
        )?;
        if !(checks.min_clock_khz > 0.0 && checks.min_clock_khz <= checks.max_clock_khz) {
            return Err(Error::field(
                origin,
                "checks.min_clock_khz",
                format!("{} to {} kHz", checks.min_clock_khz, checks.max_clock_khz),
                "give 0 < min_clock_khz <= max_clock_khz (seed: 100 and 250)",
            ));
        }
        let t_cs_us = limit(
            origin,
            "checks.t_cs_min_us",
            checks.t_cs_min_us,
            "give the least T_cs in µs (seed: 4)",
        )?;
        let base = Base::new(f_mon_hz);
        let tol = base.period_ps;
        let ps = |us: f64| (us * 1e6).round() as u64;
        Ok(SsiMonitor {
            half_min: ps(1e3 / (2.0 * checks.max_clock_khz)).saturating_sub(tol),
            half_max: ps(1e3 / (2.0 * checks.min_clock_khz)) + tol,
            t_cs: ps(t_cs_us).saturating_sub(tol),
            t_m: ps(t_m_us).saturating_sub(tol),
            base,
            layout: Layout {
                bits: Some(bits),
                gray: code == Code::Gray,
                double_read,
                wire_check,
            },
            clk: Signal::named("clk"),
            data: Signal::named("data"),
            watch: Watch {
                clk: true,
                ..Watch::default()
            },
        })
    }

    /// The reads of the line since the last decoded one.
    fn pending(&self) -> Vec<Value> {
        let first = self.base.done.len();
        decode::bursts(&self.clk, &self.data)
            .into_iter()
            .enumerate()
            .map(|(k, (start, end, bits))| match decode::read(first + k, start, end, bits.clone(), &self.layout) {
                Ok(r) => serde_json::to_value(r).unwrap_or(Value::Null),
                Err(e) => serde_json::json!({"index": first + k, "start_ps": start, "end_ps": end, "received_bits": bits, "position": null, "errors": [format!("bit_count: {e}")]}),
            })
            .collect()
    }

    /// Hands the line so far to the decoder and forgets it (at a read's start).
    fn flush(&mut self, now: u64) {
        let reads = self.pending();
        self.base.done.extend(reads);
        self.clk.forget_before(now);
        self.data.forget_before(now);
    }

    fn check(&mut self, now: u64, clk: bool) {
        let w = &mut self.watch;
        if clk == w.clk {
            let half = w.half.unwrap_or(self.half_max);
            if clk && w.in_read && now - w.last_edge > 3 * half {
                w.in_read = false;
                w.read_end = Some(w.last_edge);
            }
            return;
        }
        let len = now - w.last_edge;
        w.clk = clk;
        w.last_edge = now;
        if !clk && !w.in_read {
            let gap = w.read_end.map(|end| now - end);
            *w = Watch {
                clk,
                last_edge: now,
                in_read: true,
                edges: 1,
                half: None,
                read_end: w.read_end,
            };
            if let Some(gap) = gap.filter(|&g| g < self.t_m) {
                let want = self.t_m + self.base.period_ps;
                self.base.violation(now, RULE_T_M, format!("read started {:.3} us after the last clock edge of the previous read; T_m is {:.3} us", us(gap), us(want)));
            }
            return;
        }
        if !w.in_read {
            return;
        }
        w.edges += 1;
        if w.edges == 2 {
            if len < self.t_cs {
                self.base
                    .violation(now, RULE_T_CS, format!("first low phase {:.3} us", us(len)));
            }
            return;
        }
        w.half.get_or_insert(len);
        if len < self.half_min || len > self.half_max {
            let phase = if clk { "low" } else { "high" };
            self.base.violation(
                now,
                RULE_CLOCK,
                format!(
                    "clock {phase} for {:.3} us within a read (half period {:.3} to {:.3} us)",
                    us(len),
                    us(self.half_min + self.base.period_ps),
                    us(self.half_max - self.base.period_ps)
                ),
            );
        }
    }

    fn last(&self) -> Option<Value> {
        self.pending()
            .pop()
            .or_else(|| self.base.done.last().cloned())
    }
}

impl Emulator for SsiMonitor {
    fn kind(&self) -> &'static str {
        "ssi_monitor"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let now = self.base.now_ps();
        let (clk, data) = (pins.0 & 1 != 0, pins.0 & 2 != 0);
        let starts = !clk && self.watch.clk && !self.watch.in_read;
        if starts {
            self.flush(now);
        }
        self.check(now, clk);
        self.clk.push(now, clk);
        self.data.push(now, data);
        self.base.step_out()
    }

    fn set_position(&mut self, _: usize, _: u64) -> Result<()> {
        Err(listens_only("ssi_monitor", "position to set"))
    }

    fn set_status(&mut self, _: usize, _: &str, _: bool) -> Result<()> {
        Err(listens_only("ssi_monitor", "status to set"))
    }

    fn schedule_fault(&mut self, _: &str) -> Result<()> {
        Err(listens_only("ssi_monitor", "faults to schedule"))
    }

    /// Reads seen so far (the one in progress included).
    fn count(&self) -> u64 {
        (self.base.done.len() + self.pending().len()) as u64
    }

    /// The position of the last read seen.
    fn last_value(&self, _: usize) -> Option<u64> {
        self.last()?.get("position")?.as_u64()
    }

    /// `"errors"`: the last read had an error (double-read mismatch, wire check, bit count).
    fn last_status(&self, _: usize, name: &str) -> Result<bool> {
        match name {
            "errors" | "error" => Ok(self
                .last()
                .and_then(|r| r["errors"].as_array().map(|e| !e.is_empty()))
                .unwrap_or(false)),
            other => Err(Error::Usage(format!(
                "ssi_monitor: no status `{other}`; give \"error\""
            ))),
        }
    }

    fn transcript(&self) -> Value {
        self.base
            .transcript("ssi", &["clk", "data"], self.pending())
    }

    fn checks(&mut self) -> &mut crate::check::Checks {
        &mut self.base.checks
    }
}
