//! The Modbus RTU monitor: the master's side of the half-duplex RS-485 line
//! (seed 001, 3.1.7, the SAR58K24's seventh mode).
//!
//! Pins in: bit 0 the master's receiver output (R), bit 1 its driver input
//! (D), bit 2 its driver enable (DE). Polls are decoded by
//! [`model::modbus::decode`] (the decoder of `tbgen decode modbus`) from the
//! wire at the master (D while DE is on, else R) and DE, one poll at a time:
//! when DE rises for the next request, the poll before is decoded and its
//! line dropped. The rules are the rule book's, [`model::modbus::rules`]
//! (characters, t1.5, t3.5, release, one driver, response timeout, CRC):
//! the monitor feeds its watcher the master's pins every cycle, as the
//! emulator does, and prints what it returns; the limits are the
//! emulator's ([`crate::modbus`]'s `rule_limits`: `[monitor]`, then
//! `[checks]`, then `[master] timeout_us`).

use serde::Deserialize;
use serde_json::Value;

use model::modbus::decode::{self, Options};
use model::modbus::rules::Watch;
use model::modbus::BenchConfig;

use super::uart::{self, Line};
use super::{listens_only, Base};
use crate::config::Error;
use crate::{Emulator, Pins, Result};

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
        let limits = crate::modbus::rule_limits(text, origin, &cfg)?;
        let timeout = limits.uart.timeout_ps as f64 / 1e6;
        let mut base = Base::new(f_mon_hz);
        for note in model::rules::resolution_notes(f_mon_hz, &limits.least()) {
            base.checks.note(note);
        }
        let options = Options {
            baud: cfg.baud,
            parity: cfg.parity,
            timeout_us: timeout,
            gray: cfg.devices.first().is_some_and(|d| d.gray),
        };
        Ok(ModbusMonitor {
            base,
            watch: Watch::new(limits),
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
        for b in self.watch.sample(self.base.exact_ps(), rx, tx, de) {
            self.base.breach(&b);
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
