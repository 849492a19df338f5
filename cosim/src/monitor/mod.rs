//! Pin-level monitors and protocol checkers: they watch the master's line
//! pins on a monitor clock, decode what crossed the wire with the same
//! decode cores `tbgen decode` uses (`model::<proto>::decode`), and hold the
//! master to every timing limit the seeds state, each violation reported
//! with its time and the seed's rule (file and section).
//!
//! A monitor only listens: it is an [`Emulator`](crate::Emulator) with no
//! outputs (pins out are 0 but for the violation flag), so the wrappers'
//! machinery (`hdl/emu/emu_api.vh`, the DPI-C and VPI bindings, the C ABI
//! of [`crate::ffi`]) carries it unchanged: `emu_open("ssi_monitor", ...)`.
//! Its transcript (`transactions`, as `tbgen decode` writes, plus
//! `violations`) is a capture `tbgen check` accepts.
//!
//! Transactions are decoded one at a time: when the next one starts, the
//! line since the previous start is handed to the decode core and dropped,
//! so a long run keeps only one transaction's edges in memory.

pub mod biss;
pub mod can;
pub mod canopen;
pub mod endat;
pub mod esl;
pub mod half_duplex;
pub mod modbus;
pub mod sar;
pub mod ssi;
pub mod tformat;
pub mod uart;

use serde_json::Value;

use crate::check::{Checks, VIOLATION_PENDING};
use crate::config::Error;
use crate::Result;

/// What every monitor shares: the clock, the violations, the decoded list.
#[derive(Debug, Clone)]
pub struct Base {
    /// The monitor clock.
    pub f_mon_hz: u64,
    /// Its period, ps.
    pub period_ps: u64,
    /// Monitor cycles so far.
    pub cycle: u64,
    /// The violations.
    pub checks: Checks,
    /// Transactions decoded so far (JSON, as `tbgen decode` writes them).
    pub done: Vec<Value>,
}

impl Base {
    /// A monitor base at `f_mon_hz`.
    pub fn new(f_mon_hz: u64) -> Self {
        let period_ps = model::time::PS_PER_S / f_mon_hz.max(1);
        Base {
            f_mon_hz,
            period_ps,
            cycle: 0,
            checks: Checks::new(period_ps),
            done: Vec::new(),
        }
    }

    /// The time of the current cycle, ps: `cycle x 10^12 / f_mon`, exact
    /// (a period rounded to whole ps would drift a cycle from the line's
    /// own bit times within a few thousand bits at a baud-rate clock).
    pub fn now_ps(&self) -> u64 {
        self.exact_ps()
    }

    /// The monitor cycle nearest `t_ps`.
    fn cycle_at(&self, t_ps: u64) -> u64 {
        let ps = model::time::PS_PER_S as u128;
        ((t_ps as u128 * self.f_mon_hz as u128 + ps / 2) / ps) as u64
    }

    /// A violation at time `t_ps` (the edge that broke the rule).
    pub fn violation(&mut self, t_ps: u64, rule: &'static str, detail: String) {
        let cycle = self.cycle_at(t_ps);
        self.checks.push(cycle, rule, detail);
    }

    /// A breach of a rule of the rule book.
    pub fn breach(&mut self, b: &model::rules::Breach) {
        let cycle = self.cycle_at(b.at_ps);
        self.checks.push(cycle, b.rule.label(), b.detail.clone());
    }

    /// The time of the current cycle, ps, exact to the picosecond (a
    /// rule book's watcher measures with it).
    pub fn exact_ps(&self) -> u64 {
        model::rules::ps_at(self.cycle, self.f_mon_hz)
    }

    /// The pins out after a step: only the violation flag.
    pub fn step_out(&mut self) -> crate::Pins {
        self.cycle += 1;
        crate::Pins(if self.checks.pending() {
            VIOLATION_PENDING
        } else {
            0
        })
    }

    /// The transcript: the protocol, the clock, every transaction and every violation.
    pub fn transcript(&self, protocol: &str, pins: &[&str], pending: Vec<Value>) -> Value {
        let mut list = self.done.clone();
        list.extend(pending);
        serde_json::json!({
            "protocol": protocol,
            "monitor": true,
            "pins": pins,
            "f_mon_hz": self.f_mon_hz,
            "transactions": list,
            "violations": self.checks.all(),
            "notes": self.checks.notes(),
        })
    }
}

/// Picoseconds to microseconds, for messages.
pub fn us(ps: u64) -> f64 {
    ps as f64 / 1e6
}

/// The refusal of every control that would change the line: a monitor only listens.
pub fn listens_only(kind: &str, what: &str) -> Error {
    Error::Usage(format!("{kind} is a monitor: it only watches the master's pins and has no {what}; call it on the emulator instance"))
}

/// Reads one optional field of a TOML table as `T`, naming `origin` and the field in the error.
pub fn field<T: serde::de::DeserializeOwned>(
    table: &toml::Table,
    key: &str,
    origin: &str,
    path: &str,
) -> Result<Option<T>> {
    match table.get(key) {
        None => Ok(None),
        Some(v) => v
            .clone()
            .try_into()
            .map(Some)
            .map_err(|e: toml::de::Error| Error::Toml {
                origin: origin.to_string(),
                line: None,
                message: format!(
                    "{} in `{path}`",
                    e.to_string()
                        .split_whitespace()
                        .collect::<Vec<_>>()
                        .join(" ")
                ),
            }),
    }
}

/// The first of `sources` that is given, in order of precedence, with the
/// field it came from (`("monitor.t_m_us", ..)`, `("encoder.monoflop_us",
/// ..)`), else `default` under the first field: an error then names the
/// field the user wrote, not the monitor's own when it was not set.
pub fn first_given<T, const N: usize>(
    sources: [(&'static str, Option<T>); N],
    default: T,
) -> (T, &'static str) {
    let first = sources[0].0;
    sources
        .into_iter()
        .find_map(|(field, v)| v.map(|v| (v, field)))
        .unwrap_or((default, first))
}

/// A limit given in a monitor table must be a finite non-negative number.
pub fn limit(origin: &str, path: &str, v: f64, fix: &str) -> Result<f64> {
    if (0.0..1e9).contains(&v) {
        Ok(v)
    } else {
        Err(Error::field(origin, path, format!("{v}"), fix))
    }
}

/// The host's answer timeout, µs, of a half-duplex monitor: the
/// monitor's own `timeout_us`, else the `[host]` table's, else `default_us`
/// (the protocol's), refused unless a finite non-negative time.
pub fn host_timeout_us(
    monitor: Option<f64>,
    host: &toml::Table,
    origin: &str,
    default_us: f64,
) -> Result<f64> {
    let (timeout, from) = first_given(
        [
            ("monitor.timeout_us", monitor),
            (
                "host.timeout_us",
                field(host, "timeout_us", origin, "host.timeout_us")?,
            ),
        ],
        default_us,
    );
    limit(
        origin,
        from,
        timeout,
        "give the host's answer timeout in µs",
    )
}

/// The protocol's table of a configuration (`[<proto>]` of a scenario file,
/// else the top level), whole: a monitor also reads the `[master]` table
/// the emulators leave alone (the layout the master reads).
pub fn proto_table(text: &str, origin: &str, proto: &str) -> Result<toml::Table> {
    let root: toml::Table = text.parse().map_err(|e: toml::de::Error| Error::Toml {
        origin: origin.to_string(),
        line: None,
        message: e
            .to_string()
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" "),
    })?;
    Ok(match root.get(proto) {
        Some(toml::Value::Table(t)) => t.clone(),
        _ => root,
    })
}

pub use crate::config::sub;
