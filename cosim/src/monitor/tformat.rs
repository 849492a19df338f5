//! The T-format monitor: the host's side of the half-duplex RS-485 pair.
//!
//! Pins in: bit 0 the host's receiver output (R: the line as the host
//! hears it), bit 1 its driver input (D), bit 2 its driver enable (DE).
//! Transactions are decoded by [`model::tformat::decode`] (the decoder of
//! `tbgen decode tformat`) from the wire at the host (D while DE is on, else
//! R) and DE. The rules are the rule book's, [`model::tformat::rules`]
//! (seed 002, Tamagawa TS5669 N127), decided by its watcher, which the
//! emulator feeds too: the jitter of every request edge (6.1), the fields
//! back to back (7.2) and as many as the Data ID takes, DE released within
//! 1.5 µs of the last delimiter (7.1), no request during the answer (10),
//! and a reset's ten requests 40 ms or more apart (9).
//!
//! Configuration (the emulator's file or a whole scenario will do): `baud`,
//! `[host] timeout_us` (the answer timeout the decoder applies, 10),
//! `[encoder] reset_interval_us`, and `[monitor]` with `timeout_us`,
//! `jitter_ns`, `max_gap_bits`, `release_us`, `reset_interval_us`.

use serde::Deserialize;
use serde_json::Value;

use model::tformat::decode::{Decoder, Transaction};
use model::tformat::rules::{watch, Limits, Watch};
use model::wire::uart_bytes;

use super::half_duplex::{line_settings, transceiver, ExchangeDecoder, Exchanges, Side, Window};
use super::{field, host_timeout_us, limit, listens_only, proto_table, sub, Base};
use crate::config::{self, Error};
use crate::{Emulator, Pins, Result};

/// The monitor's own table (`[monitor]`), every field optional.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct MonitorTable {
    timeout_us: Option<f64>,
    jitter_ns: Option<f64>,
    max_gap_bits: Option<f64>,
    release_us: Option<f64>,
    reset_interval_us: Option<f64>,
}

/// The decoder and the bit time.
#[derive(Debug, Clone)]
struct Decode(Decoder, u64);

impl ExchangeDecoder for Decode {
    fn exchange(&mut self, line: &Exchanges, (start, fall, next): Window) -> Option<Value> {
        let (wire, heard) = (
            uart_bytes(&line.wire, self.1),
            uart_bytes(&line.heard, self.1),
        );
        self.0
            .exchange(start, fall, next, &wire, &heard, &line.heard)
            .map(json)
    }

    fn finish(&mut self) -> Option<Value> {
        self.0.finish().map(json)
    }
}

fn json(t: Transaction) -> Value {
    serde_json::to_value(t).unwrap_or(Value::Null)
}

/// A T-format monitor.
pub struct TformatMonitor {
    side: Side<Decode>,
    watch: Watch,
}

impl TformatMonitor {
    /// A monitor from TOML text (`origin` names it in errors) at `f_mon_hz`.
    pub fn from_toml(text: &str, origin: &str, f_mon_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "tformat")?;
        let whole = proto_table(text, origin, "tformat")?;
        let baud: f64 = field::<f64>(&whole, "baud", origin, "baud")?.unwrap_or(2.5e6);
        if !(1e3..=50e6).contains(&baud) {
            return Err(Error::field(
                origin,
                "baud",
                format!("{baud} bit/s"),
                "give the bit rate in bit/s (seed 002: 2.5e6)",
            ));
        }
        let mut settings = tables.emulator.clone();
        settings.max_line_clock_khz = settings.max_line_clock_khz.or(Some(baud / 1e3));
        config::emulator_clock(
            f_mon_hz,
            &settings,
            baud / 1e3,
            "the T-format monitor (its line clock is the bit rate)",
            origin,
        )?;
        let mon: MonitorTable = config::decode_in(&whole, "monitor", origin)?;
        let host = sub(&whole, "host", origin)?;
        let encoder = sub(&whole, "encoder", origin)?;
        let timeout = host_timeout_us(mon.timeout_us, &host, origin, 10.0)?;
        let reset = limit(
            origin,
            "monitor.reset_interval_us",
            mon.reset_interval_us.or(field(&encoder, "reset_interval_us", origin, "encoder.reset_interval_us")?).unwrap_or(40_000.0),
            "give the least interval between the requests of a reset in µs (seed 002: 40 ms = 40000)",
        )?;
        let bad = |e: model::ConfigError| Error::config(origin, e);
        let mut limits = Limits::seed(baud, reset);
        if let Some(ns) = mon.jitter_ns {
            limits.set_jitter("monitor.jitter_ns", ns).map_err(bad)?;
        }
        line_settings(
            &mut limits.line,
            &model::tformat::rules::RELEASE,
            mon.release_us,
            mon.max_gap_bits,
            origin,
        )?;
        let mut base = Base::new(f_mon_hz);
        for note in model::rules::resolution_notes(f_mon_hz, &limits.least()) {
            base.checks.note(note);
        }
        let bit_ps = (1e12 / baud).round() as u64;
        Ok(TformatMonitor {
            side: Side::new(
                base,
                limits.line.bit_ps,
                Decode(Decoder::new(baud.round() as u64, timeout), bit_ps),
            ),
            watch: watch(limits),
        })
    }
}

impl Emulator for TformatMonitor {
    fn kind(&self) -> &'static str {
        "tformat_monitor"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        self.side.step(pins);
        let (tx, de, rx) = transceiver(pins);
        let seen = self.watch.sample(self.side.base.exact_ps(), tx, de, rx);
        self.side.breaches(&seen);
        self.side.base.step_out()
    }

    fn set_position(&mut self, _: usize, _: u64) -> Result<()> {
        Err(listens_only("tformat_monitor", "position to set"))
    }

    fn set_status(&mut self, _: usize, _: &str, _: bool) -> Result<()> {
        Err(listens_only("tformat_monitor", "status to set"))
    }

    fn schedule_fault(&mut self, _: &str) -> Result<()> {
        Err(listens_only("tformat_monitor", "faults to schedule"))
    }

    /// Transactions seen so far (the one in progress included; a reset's ten requests are one).
    fn count(&self) -> u64 {
        self.side.count()
    }

    /// `abm << 17 | abs` after the last transaction (the host's registers: held through a short answer).
    fn last_value(&self, _: usize) -> Option<u64> {
        let t = self.side.last()?;
        Some(t["abm"].as_u64()? << 17 | t["abs"].as_u64()?)
    }

    /// An error of the last transaction (`crc`, `timeout`, `frame`, `cf_mismatch`, `comm_alarm`) or an ALMC flag after it.
    fn last_status(&self, _: usize, name: &str) -> Result<bool> {
        let t = self
            .side
            .last()
            .ok_or_else(|| Error::Usage("tformat_monitor: no transaction decoded yet".into()))?;
        if let Some(&(_, bit)) = crate::tformat::ALARMS.iter().find(|a| a.0 == name) {
            return Ok(t["almc"].as_u64().unwrap_or(0) >> bit & 1 == 1);
        }
        match name {
            "crc" | "timeout" | "frame" | "cf_mismatch" | "comm_alarm" => Ok(t["errors"].as_array().is_some_and(|e| e.iter().any(|x| x == name))),
            other => Err(Error::Usage(format!(
                "tformat_monitor: no status `{other}`; give an error (crc, timeout, frame, cf_mismatch, comm_alarm) or an ALMC flag (over_speed, full_absolute, counting_error, counter_overflow, multi_turn_error, battery_error, battery_alarm)"
            ))),
        }
    }

    fn transcript(&self) -> Value {
        self.side.transcript("tformat")
    }

    fn checks(&mut self) -> &mut crate::check::Checks {
        &mut self.side.base.checks
    }
}
