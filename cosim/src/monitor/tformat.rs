//! The T-format monitor: the host's side of the half-duplex RS-485 pair.
//!
//! Pins in: bit 0 the host's receiver output (R: the line as the host
//! hears it), bit 1 its driver input (D), bit 2 its driver enable (DE).
//! Transactions are decoded by [`model::tformat::decode`] (the decoder of
//! `tbgen decode tformat`) from the wire at the host (D while DE is on, else
//! R) and DE. The checks (seed 002, Tamagawa TS5669 N127), each with one
//! monitor cycle of tolerance, at the host's pins
//! ([`super::half_duplex`] for the shared ones):
//!
//! * character timing (6.1: "Transmission rate 2.5 Mbps, permissible
//!   jitter ±100 ns"; 6.3: 10-bit fields, start, 8 data LSB first,
//!   delimiter): every edge of a request field within `monitor.jitter_ns`
//!   (100) of the bit grid from the field's start edge, the delimiter high
//!   and a full bit, DE not released inside a field;
//! * a request's fields back to back (7.2, 8.2: "if there is no Start bit
//!   after the Delimiter, End of Frame is judged"): the next start bit
//!   within `monitor.max_gap_bits` (0.5) of the delimiter's end, and the
//!   request has the fields its Data ID takes (CF; Data ID 6: CF ADF EDF
//!   CRC; D: CF ADF CRC);
//! * turnaround (7.1: the answer comes "3 µs (typ.) after receiving the
//!   Delimiter"; 10: "Never transmit any Request to Smart Abs while it
//!   transmits the data"): DE off within `monitor.release_us` (1.5, half the
//!   typical answer delay) of the last delimiter's end; never DE on while
//!   the encoder drives R low against a 1 of the host, never DE switched on
//!   inside the encoder's answer;
//! * request spacing (9: resets 7, 8, C "10 times in one sequence ... with
//!   the interval of 40 ms or more"): each request of a reset at least
//!   `monitor.reset_interval_us` (default the encoder's
//!   `reset_interval_us`, 40 000) after the one before, and ten of them
//!   before another Data ID.
//!
//! Configuration (the emulator's file or a whole scenario will do): `baud`,
//! `[host] timeout_us` (the answer timeout the decoder applies, 10),
//! `[encoder] reset_interval_us`, and `[monitor]` with `timeout_us`,
//! `jitter_ns`, `max_gap_bits`, `release_us`, `reset_interval_us`.

use serde::Deserialize;
use serde_json::Value;

use model::tformat::decode::{Decoder, Transaction};
use model::tformat::frames::{self, DataId};
use model::wire::uart_bytes;

use super::half_duplex::{ExchangeDecoder, Exchanges, Limits, Request, Rules, Side, Window};
use super::{field, host_timeout_us, limit, listens_only, proto_table, sub, Base};
use crate::config::{self, Error};
use crate::{Emulator, Pins, Result};

/// The rules, as the seed states them.
pub const RULE_CHARACTER: &str = "character timing (seed 002 6.1: 2.5 Mbps, permissible jitter +-100 ns; 6.3: 10-bit fields, start, 8 data LSB first, delimiter)";
/// See [`RULE_CHARACTER`].
pub const RULE_GAP: &str = "request frame (seed 002 7.2, 8.2: no start bit after a delimiter ends the frame; a request's fields back to back)";
/// See [`RULE_CHARACTER`].
pub const RULE_FIELDS: &str = "request frame (seed 002 6.2, 6.3: a readout or reset request is CF alone, Data ID 6 CF ADF EDF CRC, Data ID D CF ADF CRC)";
/// See [`RULE_CHARACTER`].
pub const RULE_RELEASE: &str = "turnaround (seed 002 7.1: the answer comes 3 us (typ.) after the request's delimiter; the host releases the line before)";
/// See [`RULE_CHARACTER`].
pub const RULE_ANSWER: &str =
    "turnaround (seed 002 10: never transmit any request while the encoder transmits its data)";
/// See [`RULE_CHARACTER`].
pub const RULE_RESET: &str = "request spacing (seed 002 9: resets 7, 8, C: 10 times in one sequence, with the interval of 40 ms or more)";

/// The ALMC flags by name and their bit (seed 002 6.3.4; the emulator's names).
const ALMC: [(&str, u8); 7] = [
    ("over_speed", 0),
    ("full_absolute", 1),
    ("counting_error", 2),
    ("counter_overflow", 3),
    ("multi_turn_error", 5),
    ("battery_error", 6),
    ("battery_alarm", 7),
];

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
    reset_interval: u64,
    /// A reset sequence in progress: Data ID, requests so far, start of the last.
    reset: Option<(u8, u32, u64)>,
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
        let jitter = limit(
            origin,
            "monitor.jitter_ns",
            mon.jitter_ns.unwrap_or(100.0),
            "give the jitter allowed on a request's edges in ns (seed 002: 100)",
        )?;
        let gap = limit(
            origin,
            "monitor.max_gap_bits",
            mon.max_gap_bits.unwrap_or(0.5),
            "give the longest idle line between two fields of a request, in bits",
        )?;
        let release = limit(
            origin,
            "monitor.release_us",
            mon.release_us.unwrap_or(1.5),
            "give the longest time from the request's last delimiter to DE off, in µs",
        )?;
        let reset = limit(
            origin,
            "monitor.reset_interval_us",
            mon.reset_interval_us.or(field(&encoder, "reset_interval_us", origin, "encoder.reset_interval_us")?).unwrap_or(40_000.0),
            "give the least interval between the requests of a reset in µs (seed 002: 40 ms = 40000)",
        )?;
        let base = Base::new(f_mon_hz);
        let bit_ps = (1e12 / baud).round() as u64;
        let limits = Limits {
            bit_ps: 1e12 / baud,
            tolerance: 0.0,
            jitter_ps: jitter * 1e3,
            max_gap_ps: gap * 1e12 / baud,
            release_ps: (release * 1e6).round() as u64,
        };
        let rules = Rules {
            character: RULE_CHARACTER,
            gap: RULE_GAP,
            release: RULE_RELEASE,
            answer: RULE_ANSWER,
        };
        Ok(TformatMonitor {
            reset_interval: ((reset * 1e6).round() as u64).saturating_sub(base.period_ps),
            side: Side::new(
                base,
                limits,
                rules,
                Decode(Decoder::new(baud.round() as u64, timeout), bit_ps),
            ),
            reset: None,
        })
    }

    fn on_request(&mut self, r: Request) {
        let Some(&cf) = r.fields.first() else { return };
        let code = (cf >> 3) & 0xF;
        let id = DataId::from_code(code);
        if let Some(id) = id.filter(|_| !r.damaged) {
            let want = frames::request(id, 0, 0).len();
            if r.fields.len() != want {
                self.side.base.violation(
                    r.end_ps,
                    RULE_FIELDS,
                    format!(
                        "a request of {} field(s) for Data ID {code:X}, which takes {want}",
                        r.fields.len()
                    ),
                );
            }
        }
        let reset = id.is_some_and(|d| d.is_reset());
        match self.reset {
            Some((rid, k, last)) if reset && rid == code => {
                let gap = r.start_ps - last;
                if gap < self.reset_interval {
                    self.side.base.violation(r.start_ps, RULE_RESET, format!("request {} of reset Data ID {code:X} {:.3} ms after the one before; at least {:.3} ms", k + 1, gap as f64 / 1e9, (self.reset_interval + self.side.base.period_ps) as f64 / 1e9));
                }
                self.reset = (k + 1 < 10).then_some((rid, k + 1, r.start_ps));
            }
            prev => {
                if let Some((rid, k, _)) = prev {
                    self.side.base.violation(r.start_ps, RULE_RESET, format!("reset Data ID {rid:X} sent {k} time(s), then Data ID {code:X}: a reset takes 10 requests in one sequence"));
                }
                self.reset = reset.then_some((code, 1, r.start_ps));
            }
        }
    }
}

impl Emulator for TformatMonitor {
    fn kind(&self) -> &'static str {
        "tformat_monitor"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        if let Some(r) = self.side.step(pins) {
            self.on_request(r);
        }
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
        if let Some(&(_, bit)) = ALMC.iter().find(|a| a.0 == name) {
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
