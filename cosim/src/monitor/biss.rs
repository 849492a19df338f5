//! The BiSS-C monitor: MA as the master drives it and SLO at the master.
//!
//! Pins in: bit 0 MA at the master, bit 1 SLO at the master's receiver.
//! Frames are decoded by [`model::biss::decode`] (control frames, register
//! accesses and commands included). The master's timing is held to the rule
//! book [`model::biss::rules`] (`TMAS`, `TMASH`, `TMASL`, `timeout`; the
//! emulator holds it to the same), the limits from `[monitor]`, else
//! `[checks]` ([`crate::biss::BissChecks`]), each within the seed's range:
//! `min_tmas_ns`, `min_tmash_ns`, `min_tmasl_ns`, and `monitor.timeout_us`
//! (default the slaves' longest `timeout_us`, the seed's 16 µs).
//!
//! A frame is handed to the decoder when the next one starts (the slave's
//! timeout over, the rule book's frame).

use serde::Deserialize;
use serde_json::Value;

use model::biss::decode::{Decoder, Layout};
use model::biss::SlaveSettings;
use model::wire::Signal;

use model::biss::rules::Watch;

use super::{first_given, limit, listens_only, proto_table, Base};
use crate::biss::{limits, BissChecks, MAX_CLOCK_KHZ};
use crate::config::{self, Error};
use crate::{Emulator, Pins, Result};

/// The monitor's own table (`[monitor]`), every field optional.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct MonitorTable {
    min_tmas_ns: Option<f64>,
    min_tmash_ns: Option<f64>,
    min_tmasl_ns: Option<f64>,
    timeout_us: Option<f64>,
}

/// A BiSS-C monitor.
pub struct BissMonitor {
    base: Base,
    layout: Layout,
    decoder: Decoder,
    ma: Signal,
    slo: Signal,
    watch: Watch,
}

impl BissMonitor {
    /// A monitor from TOML text (`origin` names it in errors) at `f_mon_hz`.
    pub fn from_toml(text: &str, origin: &str, f_mon_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "biss")?;
        config::emulator_clock(
            f_mon_hz,
            &tables.emulator,
            MAX_CLOCK_KHZ,
            "the BiSS-C monitor",
            origin,
        )?;
        let whole = proto_table(text, origin, "biss")?;
        let checks: BissChecks = config::decode_in(&whole, "checks", origin)?;
        let mon: MonitorTable = config::decode_in(&whole, "monitor", origin)?;
        let slaves: Vec<SlaveSettings> = match whole.get("slaves") {
            Some(v) => v
                .clone()
                .try_into()
                .map_err(|e: toml::de::Error| Error::Toml {
                    origin: origin.to_string(),
                    line: None,
                    message: format!(
                        "table `slaves`: {}",
                        e.to_string()
                            .split_whitespace()
                            .collect::<Vec<_>>()
                            .join(" ")
                    ),
                })?,
            None => vec![SlaveSettings::default()],
        };
        if slaves.is_empty() || slaves.len() > model::biss::MAX_SLAVES {
            return Err(Error::field(
                origin,
                "slaves",
                format!("{} slaves", slaves.len()),
                format!("give 1 to {} [[slaves]] tables", model::biss::MAX_SLAVES),
            ));
        }
        for (i, s) in slaves.iter().enumerate() {
            if !(1..=64).contains(&s.bits) || !(1..=8).contains(&s.crc_width) {
                return Err(Error::field(
                    origin,
                    format!("slaves[{i}]"),
                    format!("{} bits, CRC width {}", s.bits, s.crc_width),
                    "give 1 to 64 bits and a CRC width of 1 to 8",
                ));
            }
        }
        let longest = slaves.iter().map(|s| s.timeout_us).fold(0.0, f64::max);
        let timeout = limit(
            origin,
            "monitor.timeout_us",
            mon.timeout_us.unwrap_or(longest),
            "give the slaves' BiSS timeout in µs (seed: 16)",
        )?;
        let given = |field: &'static str, m: Option<f64>, c: f64, checks_field: &'static str| {
            first_given([(field, m), (checks_field, Some(c))], c)
        };
        let tmas = given(
            "monitor.min_tmas_ns",
            mon.min_tmas_ns,
            checks.min_tmas_ns,
            "checks.min_tmas_ns",
        );
        let tmash = given(
            "monitor.min_tmash_ns",
            mon.min_tmash_ns,
            checks.min_tmash_ns,
            "checks.min_tmash_ns",
        );
        let tmasl = given(
            "monitor.min_tmasl_ns",
            mon.min_tmasl_ns,
            checks.min_tmasl_ns,
            "checks.min_tmasl_ns",
        );
        let limits = limits(
            timeout,
            [(tmas.1, tmas.0), (tmash.1, tmash.0), (tmasl.1, tmasl.0)],
        )
        .map_err(|e| Error::config(origin, e))?;
        let mut base = Base::new(f_mon_hz);
        for note in model::rules::resolution_notes(f_mon_hz, &limits.least()) {
            base.checks.note(note);
        }
        Ok(BissMonitor {
            base,
            layout: Layout {
                bits: slaves.iter().map(|s| s.bits).collect(),
                crc_width: slaves.iter().map(|s| s.crc_width).collect(),
                crc_poly: slaves.iter().map(|s| s.crc_poly).collect(),
                timeout_ps: Some(limits.timeout),
            },
            decoder: Decoder::default(),
            ma: Signal::named("ma"),
            slo: Signal::named("slo"),
            watch: Watch::new(limits),
        })
    }

    /// The frames since the last decoded one (the decoder's state is not changed).
    fn pending(&self) -> Vec<Value> {
        let mut d = self.decoder.clone();
        d.feed(&self.ma, &self.slo, &self.layout)
            .into_iter()
            .map(|f| serde_json::to_value(f).unwrap_or(Value::Null))
            .collect()
    }

    fn flush(&mut self, now: u64) {
        let frames = self.decoder.feed(&self.ma, &self.slo, &self.layout);
        self.base.done.extend(
            frames
                .into_iter()
                .map(|f| serde_json::to_value(f).unwrap_or(Value::Null)),
        );
        self.ma.forget_before(now);
        self.slo.forget_before(now);
    }

    fn last(&self) -> Option<Value> {
        self.pending()
            .pop()
            .or_else(|| self.base.done.last().cloned())
    }
}

impl Emulator for BissMonitor {
    fn kind(&self) -> &'static str {
        "biss_monitor"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let now = self.base.now_ps();
        let (ma, slo) = (pins.0 & 1 != 0, pins.0 & 2 != 0);
        let seen = self.watch.sample(self.base.exact_ps(), ma, slo);
        if seen.started {
            self.flush(now);
        }
        for b in &seen.breaches {
            self.base.breach(b);
        }
        // Before the line clock is seen idle high (a master in reset), the
        // decoder sees it idle, as the emulator's device does.
        self.ma.push(now, ma || !self.watch.seen_idle());
        self.slo.push(now, slo);
        self.base.step_out()
    }

    fn set_position(&mut self, _: usize, _: u64) -> Result<()> {
        Err(listens_only("biss_monitor", "position to set"))
    }

    fn set_status(&mut self, _: usize, _: &str, _: bool) -> Result<()> {
        Err(listens_only("biss_monitor", "status to set"))
    }

    fn schedule_fault(&mut self, _: &str) -> Result<()> {
        Err(listens_only("biss_monitor", "faults to schedule"))
    }

    /// Frames seen so far (the one in progress included).
    fn count(&self) -> u64 {
        (self.base.done.len() + self.pending().len()) as u64
    }

    /// Slave `device`'s position in the last frame seen.
    fn last_value(&self, device: usize) -> Option<u64> {
        self.last()?
            .get("slaves")?
            .get(device)?
            .get("position")?
            .as_u64()
    }

    /// Slave `device`'s `"error"`, `"warning"` or `"crc_ok"` in the last frame seen.
    fn last_status(&self, device: usize, name: &str) -> Result<bool> {
        if !matches!(name, "error" | "warning" | "crc_ok") {
            return Err(Error::Usage(format!(
                "biss_monitor: no status `{name}`; give \"error\", \"warning\" or \"crc_ok\""
            )));
        }
        self.last()
            .and_then(|f| f.get("slaves")?.get(device)?.get(name)?.as_bool())
            .ok_or_else(|| {
                Error::Usage(format!(
                    "biss_monitor: no frame with slave {device} decoded yet"
                ))
            })
    }

    fn transcript(&self) -> Value {
        self.base.transcript("biss", &["ma", "slo"], self.pending())
    }

    fn checks(&mut self) -> &mut crate::check::Checks {
        &mut self.base.checks
    }
}
