//! The Modbus RTU monitor: the master's side of the half-duplex RS-485 line
//! (seed 001, 3.1.7, the SAR58K24's seventh mode).
//!
//! Pins in: bit 0 the master's receiver output (R), bit 1 its driver input
//! (D), bit 2 its driver enable (DE). Polls are decoded by
//! [`model::modbus::decode`] (the decoder of `tbgen decode modbus`) from the
//! wire at the master (D while DE is on, else R) and DE, one poll at a time:
//! when DE rises for the next request, the poll before is decoded and its
//! line dropped. The checks ([`super::uart`] for the shared ones), each with
//! one monitor cycle of tolerance:
//!
//! * character timing: every edge of a request character within the baud
//!   rate tolerance of the bit grid (`monitor.baud_tolerance_percent`, 2:
//!   the seed gives none; the Modbus serial-line guide's 2 % of a sender
//!   beside a receiver's own), the parity bit (`parity`) right, the stop
//!   bit high and a full bit;
//! * t1.5 (Modbus over serial line 2.5.1.1; the devices discard such a
//!   request): at most t1.5 of silence between the characters of a request;
//! * t3.5 (seed 001, 3.1.7: "each frame contains at least 3.5 bytes of time
//!   interval between its start and end"): a request only after t3.5 of
//!   silence on the line, either direction;
//! * turnaround: DE off within `monitor.release_bits` (1) bit times of the
//!   request's last stop bit; never both drivers on; DE never switched on
//!   inside a device's character;
//! * response timeout: after a request to one station (not the broadcast
//!   address 0), the next request only after an answer began or the
//!   master's `timeout_us` (`[master] timeout_us`, `monitor.timeout_us`).
//!
//! t1.5 and t3.5 are the fixed 750 and 1750 µs above 19200 baud
//! ([`model::modbus::frames`]). t1.5 is measured from a stop bit's middle,
//! where a receiver has seen the character end; t3.5 before a request from
//! the end of the last stop bit, the silence on the line the serial-line
//! specification asks for (a master counting from the middle leaves half a
//! bit less).

use serde::Deserialize;
use serde_json::Value;

use model::modbus::decode::{self, Options};
use model::modbus::{frames, BenchConfig};

use super::uart::{self, Limits, Line, Rules, Watch};
use super::{field, first_given, limit, listens_only, proto_table, sub, Base};
use crate::config;
use crate::config::Error;
use crate::{Emulator, Pins, Result};

/// The rules, as the seed states them (or the project's reading).
pub const RULE_CHARACTER: &str = "character timing (seed 001 3.1.7: asynchronous characters, start, 8 data LSB first, the configured parity, stop; baud rate tolerance: the project's reading, docs/timing/modbus.md)";
/// See [`RULE_CHARACTER`].
pub const RULE_T15: &str = "t1.5 (seed 001 3.1.7 frames; Modbus over serial line 2.5.1.1: at most 1.5 characters of silence inside a frame, 750 us above 19200 baud)";
/// See [`RULE_CHARACTER`].
pub const RULE_T35: &str = "t3.5 (seed 001 3.1.7: each frame has at least 3.5 bytes of time interval before it, 1750 us above 19200 baud)";
/// See [`RULE_CHARACTER`].
pub const RULE_RELEASE: &str = "turnaround (seed 001 3.1.7, half-duplex RS-485: the master releases the line after its request)";
/// See [`RULE_CHARACTER`].
pub const RULE_ANSWER: &str = "turnaround (seed 001 3.1.7, half-duplex RS-485: one driver at a time, never during a device's answer)";
/// See [`RULE_CHARACTER`].
pub const RULE_TIMEOUT: &str = "response timeout (the master waits for the answer or its timeout before the next request; the seed gives no figure: [master] timeout_us)";

/// The monitor's own table (`[monitor]`), every field optional.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct MonitorTable {
    timeout_us: Option<f64>,
    baud_tolerance_percent: Option<f64>,
    release_bits: Option<f64>,
}

/// The emulator's tables a monitor leaves alone.
#[derive(Debug, Clone, Default, Deserialize)]
pub(crate) struct EmulatorOwn {
    #[allow(dead_code)]
    random: Option<toml::Value>,
    #[allow(dead_code)]
    checks: Option<toml::Value>,
}

/// A Modbus RTU monitor.
pub struct ModbusMonitor {
    base: Base,
    watch: Watch,
    line: Line,
    options: Options,
}

fn json(index: usize, t: decode::Transaction) -> Value {
    let mut v = serde_json::to_value(t).unwrap_or(Value::Null);
    v["index"] = Value::from(index);
    v
}

impl ModbusMonitor {
    /// A monitor from TOML text (`origin` names it in errors) at `f_mon_hz`.
    pub fn from_toml(text: &str, origin: &str, f_mon_hz: u64) -> Result<Self> {
        let (_, _, cfg): (_, EmulatorOwn, BenchConfig) = crate::half_duplex::uart_bench(
            text,
            origin,
            f_mon_hz,
            "modbus",
            "the Modbus monitor",
            19_200.0,
        )?;
        let whole = proto_table(text, origin, "modbus")?;
        let mon: MonitorTable = config::decode_in(&whole, "monitor", origin)?;
        let master = sub(&whole, "master", origin)?;
        let (timeout, timeout_field) = first_given(
            [
                ("monitor.timeout_us", mon.timeout_us),
                (
                    "master.timeout_us",
                    field(&master, "timeout_us", origin, "master.timeout_us")?,
                ),
            ],
            5000.0,
        );
        let timeout = limit(
            origin,
            timeout_field,
            timeout,
            "give the master's answer timeout in µs",
        )?;
        let tol = limit(
            origin,
            "monitor.baud_tolerance_percent",
            mon.baud_tolerance_percent.unwrap_or(2.0),
            "give the baud rate tolerance of the master's characters in percent (2)",
        )?;
        let release = limit(
            origin,
            "monitor.release_bits",
            mon.release_bits.unwrap_or(1.0),
            "give the longest time from the request's last stop bit to DE off, in bit times (1)",
        )?;
        let fb = cfg.parity.frame_bits();
        let bit_ps = 1e12 / cfg.baud;
        let limits = Limits {
            bit_ps,
            parity: cfg.parity,
            tolerance: tol / 100.0,
            max_gap_ps: frames::t15_seconds(cfg.baud, fb) * 1e12,
            min_silence_ps: frames::t35_seconds(cfg.baud, fb) * 1e12,
            release_ps: release * bit_ps,
            timeout_ps: timeout * 1e6,
        };
        let rules = Rules {
            character: RULE_CHARACTER,
            gap: RULE_T15,
            silence: RULE_T35,
            release: RULE_RELEASE,
            answer: RULE_ANSWER,
            wait: RULE_TIMEOUT,
        };
        let options = Options {
            baud: cfg.baud,
            parity: cfg.parity,
            timeout_us: timeout,
            gray: cfg.devices.first().is_some_and(|d| d.gray),
        };
        Ok(ModbusMonitor {
            base: Base::new(f_mon_hz),
            watch: Watch::new(limits, rules),
            line: Line::new(),
            options,
        })
    }

    /// The polls not yet in `base.done` (the one in progress included).
    fn pending(&self) -> Vec<Value> {
        let n = self.base.done.len();
        decode::decode(&self.line.wire, &self.line.de, &self.options)
            .into_iter()
            .enumerate()
            .map(|(k, t)| json(n + k, t))
            .collect()
    }

    fn last(&self) -> Option<Value> {
        self.pending()
            .pop()
            .or_else(|| self.base.done.last().cloned())
    }
}

impl Emulator for ModbusMonitor {
    fn kind(&self) -> &'static str {
        "modbus_monitor"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let now = self.base.now_ps();
        let (rx, tx, de) = uart::pins(pins);
        if de && !self.line.de.level_at(now) && now > 0 {
            // A new request: the poll before it is complete.
            let polls = self.pending();
            self.base.done.extend(polls);
            self.line.cut(now - 1);
        }
        self.line.step(now, tx, de, rx);
        if let Some(r) = self.watch.step(&mut self.base, now, tx, de, rx) {
            if r.bytes.first().is_some_and(|&a| a != 0) {
                let end = now;
                self.watch.expect_answer(end);
            }
        }
        self.base.step_out()
    }

    fn set_position(&mut self, _: usize, _: u64) -> Result<()> {
        Err(listens_only("modbus_monitor", "position to set"))
    }

    fn set_status(&mut self, _: usize, _: &str, _: bool) -> Result<()> {
        Err(listens_only("modbus_monitor", "status to set"))
    }

    fn schedule_fault(&mut self, _: &str) -> Result<()> {
        Err(listens_only("modbus_monitor", "faults to schedule"))
    }

    /// Polls seen so far (the one in progress included).
    fn count(&self) -> u64 {
        (self.base.done.len() + self.pending().len()) as u64
    }

    /// The registers read by the last poll (as on the wire, Gray decoded for a Gray device).
    fn last_value(&self, _: usize) -> Option<u64> {
        self.last()?["value"].as_u64()
    }

    /// An error flag of the last poll (`parity`, `framing`, `gap`, `length`,
    /// `crc`, `address`, `exception`, `function`, `count`, `timeout`), or
    /// `valid` (no error).
    fn last_status(&self, _: usize, name: &str) -> Result<bool> {
        const FLAGS: [&str; 10] = [
            "parity",
            "framing",
            "gap",
            "length",
            "crc",
            "address",
            "exception",
            "function",
            "count",
            "timeout",
        ];
        let t = self
            .last()
            .ok_or_else(|| Error::Usage("modbus_monitor: no poll decoded yet".into()))?;
        let errors = t["errors"].as_array().cloned().unwrap_or_default();
        match name {
            "valid" => Ok(errors.is_empty()),
            f if FLAGS.contains(&f) => Ok(errors.iter().any(|x| x == f)),
            other => Err(Error::Usage(format!(
                "modbus_monitor: no status `{other}`; give valid or an error: {}",
                FLAGS.join(", ")
            ))),
        }
    }

    fn transcript(&self) -> Value {
        self.base
            .transcript("modbus", &["rx", "tx", "tx_en"], self.pending())
    }

    fn checks(&mut self) -> &mut crate::check::Checks {
        &mut self.base.checks
    }
}
