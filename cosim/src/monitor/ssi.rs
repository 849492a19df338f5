//! The SSI monitor: the master's clock and the data at its receiver.
//!
//! Pins in: bit 0 the SSI clock at the master, bit 1 the data at the
//! master's receiver. Reads are decoded by [`model::ssi::decode`]; the
//! master's timing is held to the rule book [`model::ssi::rules`] (`T_cs`,
//! `f_clk`, `T_m`; the emulator holds it to the same), with the limits of
//! `[checks]` ([`crate::ssi::SsiChecks`]) and `T_m` from `monitor.t_m_us`
//! (default the encoder's `monoflop_us`, the seed's 500 µs when there is no
//! `[encoder]`). A read is handed to the decoder when the next one starts.
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

use model::ssi::rules::Watch;

use super::{field, first_given, limit, listens_only, proto_table, sub, Base};
use crate::config::{self, Error};
use crate::ssi::{SsiChecks, MAX_CLOCK_KHZ};
use crate::{Emulator, Pins, Result};

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

/// An SSI monitor.
pub struct SsiMonitor {
    base: Base,
    layout: Layout,
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
        let limits = checks
            .limits(t_m_us)
            .map_err(|e| Error::config(origin, e))?;
        let mut base = Base::new(f_mon_hz);
        for note in model::rules::resolution_notes(f_mon_hz, &limits.least()) {
            base.checks.note(note);
        }
        Ok(SsiMonitor {
            base,
            layout: Layout {
                bits: Some(bits),
                gray: code == Code::Gray,
                double_read,
                wire_check,
            },
            clk: Signal::named("clk"),
            data: Signal::named("data"),
            watch: Watch::new(limits),
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
        let seen = self.watch.sample(self.base.exact_ps(), clk);
        if seen.started {
            self.flush(now);
        }
        for b in &seen.breaches {
            self.base.breach(b);
        }
        // Before the line clock is seen idle high (a master in reset), the
        // decoder sees it idle, as the emulator's device does.
        self.clk.push(now, clk || !self.watch.seen_idle());
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
