//! The ESL monitor: the host's side of the half-duplex RS-485 bus.
//!
//! Pins in: bit 0 the host's receiver output (RO: the bus as the host hears
//! it), bit 1 its driver input (DI), bit 2 its driver enable (DE).
//! Operations are decoded by [`model::esl::decode`] (the decoder of `tbgen
//! decode esl`) from the wire at the host (DI while DE is on, else RO) and
//! DE. The rules are the rule book's, [`model::esl::rules`] (seed 000, QS35
//! ESL Safety protocol), decided by its watcher, which the emulator feeds
//! too: every request edge on the 10 Mbps bit grid (Table 1, Figure 1), the
//! frames back to back (Figure 1) and as many as the Data ID takes, DE
//! released within 1 µs of the last end bit (Figure 2), never driving
//! during an answer (Table 1: half duplex), and per encoder address B, C, D
//! eight times within the repeat window (Table 4), EEPROM reads more than
//! 200 µs and writes more than 6 ms apart (Figures 3, 5), and 18 ms after a
//! page change (Table 11).
//!
//! Configuration (the emulator's file or a whole scenario will do): `baud`,
//! `[[encoders]]` (address and the four times above), `[host]`
//! `broadcast_address`, `busy_tries`, `rs_tolerance` (how the decoder
//! judges answers), `[checks] bit_tolerance_percent`, and `[monitor]` with
//! `bit_tolerance_percent`, `max_gap_bits`, `release_us`, and the host
//! settings and encoder times above (for every address).

use serde::Deserialize;
use serde_json::Value;

use model::esl::decode::{DecodeOptions, DecodedOp, Decoder};
use model::esl::rules::{watch, Limits, Spacing, Watch};
use model::esl::EncoderSettings;
use model::wire::uart_bytes;

use super::half_duplex::{line_settings, transceiver, ExchangeDecoder, Exchanges, Side, Window};
use super::{field, limit, listens_only, proto_table, sub, Base};
use crate::config::{self, Error};
// The ALM flags by name, as the emulator takes them.
use crate::esl::ALARMS;
use crate::{Emulator, Pins, Result};

/// The error names of an operation (`model::esl::error_names`).
const ERRORS: [&str; 9] = [
    "crc1",
    "crc2",
    "timeout",
    "frame",
    "cf_mismatch",
    "comm_alarm",
    "sequence",
    "channel_mismatch",
    "busy",
];

/// The monitor's own table (`[monitor]`), every field optional.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct MonitorTable {
    bit_tolerance_percent: Option<f64>,
    max_gap_bits: Option<f64>,
    release_us: Option<f64>,
    broadcast_address: Option<u8>,
    busy_tries: Option<u64>,
    rs_tolerance: Option<u16>,
    repeat_window_us: Option<f64>,
    eeprom_read_us: Option<f64>,
    eeprom_write_us: Option<f64>,
    page_change_us: Option<f64>,
}

/// The decoder and the bit time.
#[derive(Debug, Clone)]
struct Decode(Decoder, u64);

impl ExchangeDecoder for Decode {
    fn exchange(&mut self, line: &Exchanges, (rise, fall, next): Window) -> Option<Value> {
        self.0
            .exchange(rise, fall, next, &uart_bytes(&line.wire, self.1))
            .map(json)
    }

    fn finish(&mut self) -> Option<Value> {
        self.0.finish().map(json)
    }
}

fn json(t: DecodedOp) -> Value {
    serde_json::to_value(t).unwrap_or(Value::Null)
}

/// An ESL monitor.
pub struct EslMonitor {
    side: Side<Decode>,
    watch: Watch,
}

impl EslMonitor {
    /// A monitor from TOML text (`origin` names it in errors) at `f_mon_hz`.
    pub fn from_toml(text: &str, origin: &str, f_mon_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "esl")?;
        let whole = proto_table(text, origin, "esl")?;
        let baud = crate::esl::baud(text, origin)?;
        let mut settings = tables.emulator.clone();
        settings.max_line_clock_khz = settings.max_line_clock_khz.or(Some(baud / 1e3));
        config::emulator_clock(
            f_mon_hz,
            &settings,
            baud / 1e3,
            "the ESL monitor (its line clock is the bit rate)",
            origin,
        )?;
        let mon: MonitorTable = config::decode_in(&whole, "monitor", origin)?;
        let host = sub(&whole, "host", origin)?;
        let checks = sub(&whole, "checks", origin)?;
        let tolerance = mon
            .bit_tolerance_percent
            .or(field(
                &checks,
                "bit_tolerance_percent",
                origin,
                "checks.bit_tolerance_percent",
            )?)
            .unwrap_or(3.0);
        if !(0.0..=20.0).contains(&tolerance) {
            return Err(Error::field(
                origin,
                "monitor.bit_tolerance_percent",
                format!("{tolerance}"),
                "give 0 to 20 %",
            ));
        }
        let broadcast_address = mon
            .broadcast_address
            .or(field(
                &host,
                "broadcast_address",
                origin,
                "host.broadcast_address",
            )?)
            .unwrap_or(7);
        let busy_tries = mon
            .busy_tries
            .or(field(&host, "busy_tries", origin, "host.busy_tries")?)
            .unwrap_or(3);
        let rs_tolerance = mon
            .rs_tolerance
            .or(field(&host, "rs_tolerance", origin, "host.rs_tolerance")?)
            .unwrap_or(1);
        if broadcast_address > 7 || !(1..=15).contains(&busy_tries) {
            return Err(Error::field(
                origin,
                "monitor.broadcast_address",
                format!("{broadcast_address}, busy_tries {busy_tries}"),
                "give a broadcast address 0..7 and busy_tries 1..15",
            ));
        }
        let mut limits = Limits::seed(baud, tolerance);
        line_settings(
            &mut limits.line,
            &model::esl::rules::RELEASE,
            mon.release_us,
            mon.max_gap_bits,
            origin,
        )?;
        let d = EncoderSettings::default();
        let encoders: Vec<toml::Table> =
            field(&whole, "encoders", origin, "encoders")?.unwrap_or_default();
        for a in 0..8u8 {
            let e = encoders.iter().find(|e| {
                e.get("address").and_then(|v| v.as_integer()) == Some(a as i64)
                    || (a == 0 && e.get("address").is_none())
            });
            let time = |key: &str, given: Option<f64>, default: f64| -> Result<f64> {
                let from_encoder = match e {
                    Some(t) => field::<f64>(t, key, origin, &format!("encoders.{key}"))?,
                    None => None,
                };
                limit(
                    origin,
                    &format!("monitor.{key}"),
                    given.or(from_encoder).unwrap_or(default),
                    "give a time in µs",
                )
            };
            limits.spacing[a as usize] = Spacing::of_us(
                time("repeat_window_us", mon.repeat_window_us, d.repeat_window_us)?,
                time("eeprom_read_us", mon.eeprom_read_us, d.eeprom_read_us)?,
                time("eeprom_write_us", mon.eeprom_write_us, d.eeprom_write_us)?,
                time("page_change_us", mon.page_change_us, d.page_change_us)?,
            );
        }
        let mut base = Base::new(f_mon_hz);
        for note in model::rules::resolution_notes(f_mon_hz, &limits.least()) {
            base.checks.note(note);
        }
        let bit_ps = (1e12 / baud).round() as u64;
        Ok(EslMonitor {
            side: Side::new(
                base,
                limits.line.bit_ps,
                Decode(
                    Decoder::new(DecodeOptions {
                        baud,
                        broadcast_address,
                        busy_tries,
                        rs_tolerance,
                    }),
                    bit_ps,
                ),
            ),
            watch: watch(limits),
        })
    }
}

impl Emulator for EslMonitor {
    fn kind(&self) -> &'static str {
        "esl_monitor"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        self.side.step(pins);
        let (tx, de, rx) = transceiver(pins);
        let seen = self.watch.sample(self.side.base.exact_ps(), tx, de, rx);
        self.side.breaches(&seen);
        self.side.base.step_out()
    }

    fn set_position(&mut self, _: usize, _: u64) -> Result<()> {
        Err(listens_only("esl_monitor", "position to set"))
    }

    fn set_status(&mut self, _: usize, _: &str, _: bool) -> Result<()> {
        Err(listens_only("esl_monitor", "status to set"))
    }

    fn schedule_fault(&mut self, _: &str) -> Result<()> {
        Err(listens_only("esl_monitor", "faults to schedule"))
    }

    /// Operations seen so far (the one in progress included; B, C, D's eight requests are one).
    fn count(&self) -> u64 {
        self.side.count()
    }

    /// `abm << 24 | abs` after the last operation (the host's registers: held through a short answer).
    fn last_value(&self, _: usize) -> Option<u64> {
        let t = self.side.last()?;
        Some(t["abm"].as_u64()? << 24 | t["abs"].as_u64()?)
    }

    /// An error of the last operation (`crc1`, `crc2`, `timeout`, `frame`,
    /// `cf_mismatch`, `comm_alarm`, `sequence`, `channel_mismatch`, `busy`)
    /// or an ALM flag (ALM1) after it.
    fn last_status(&self, _: usize, name: &str) -> Result<bool> {
        let t = self
            .side
            .last()
            .ok_or_else(|| Error::Usage("esl_monitor: no operation decoded yet".into()))?;
        if let Some(&(_, bit)) = ALARMS.iter().find(|a| a.0 == name) {
            return Ok(t["alm1"].as_u64().unwrap_or(0) >> bit & 1 == 1);
        }
        if ERRORS.contains(&name) {
            return Ok(t["errors"]
                .as_array()
                .is_some_and(|e| e.iter().any(|x| x == name)));
        }
        Err(Error::Usage(format!("esl_monitor: no status `{name}`; give an error ({}) or an ALM flag (xc, mt, led, lis, overspeed, mem, st, uv, ov)", ERRORS.join(", "))))
    }

    fn transcript(&self) -> Value {
        self.side.transcript("esl")
    }

    fn checks(&mut self) -> &mut crate::check::Checks {
        &mut self.side.base.checks
    }
}
