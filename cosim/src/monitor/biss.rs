//! The BiSS-C monitor: MA as the master drives it and SLO at the master.
//!
//! Pins in: bit 0 MA at the master, bit 1 SLO at the master's receiver.
//! Frames are decoded by [`model::biss::decode`] (control frames, register
//! accesses and commands included). The checks (seed 001, SAR58K24 manual,
//! BiSS-C, "the maximum transmission timing": "TMAS: the allowed clock
//! cycle is > 100 ns; TMASH: high level duration > 25 ns; TMASL: low level
//! duration > 25 ns; ... Timeout: BiSS timeout 16 µs"), each with one monitor
//! cycle of tolerance, within a frame (its first falling MA edge to its last
//! MA edge):
//!
//! * `TMAS`: every MA period (rising edge to rising edge) at least
//!   `monitor.min_tmas_ns` (default `checks.min_tmas_ns`, 100 ns);
//! * `TMASH`: every MA high phase at least `monitor.min_tmash_ns` (25 ns);
//! * `TMASL`: every MA low phase, the first included, at least
//!   `monitor.min_tmasl_ns` (25 ns);
//! * timeout: a frame starts only `monitor.timeout_us` (default the
//!   slaves' longest `timeout_us`, the seed's 16 µs) after the previous
//!   frame's last MA edge, and only while SLO is high at the master (the
//!   slave has ended its timeout, as the master can see it).
//!
//! The seed gives no longest TMAS: a pause longer than the slave's timeout
//! ends the frame at the slave, which the decoder then reports (a short
//! frame, no start bit or a failed CRC). A frame ends when MA has not
//! changed for more than three of its half periods (the decoder's rule).

use serde::Deserialize;
use serde_json::Value;

use model::biss::decode::{Decoder, Layout};
use model::biss::SlaveSettings;
use model::wire::Signal;

use super::{limit, listens_only, proto_table, us, Base};
use crate::biss::{BissChecks, MAX_CLOCK_KHZ};
use crate::config::{self, Error};
use crate::{Emulator, Pins, Result};

/// The rules, as the seed states them.
pub const RULE_TMAS: &str = "TMAS (seed 001 SAR58K24 manual, BiSS-C timing: TMAS > 100 ns)";
/// See [`RULE_TMAS`].
pub const RULE_TMASH: &str = "TMASH (seed 001 SAR58K24 manual, BiSS-C timing: MA high > 25 ns)";
/// See [`RULE_TMAS`].
pub const RULE_TMASL: &str = "TMASL (seed 001 SAR58K24 manual, BiSS-C timing: MA low > 25 ns)";
/// See [`RULE_TMAS`].
pub const RULE_TIMEOUT: &str = "timeout (seed 001 SAR58K24 manual, BiSS-C timing: BiSS timeout 16 us; the master starts a frame only after it, SLO high)";

/// The monitor's own table (`[monitor]`), every field optional.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct MonitorTable {
    min_tmas_ns: Option<f64>,
    min_tmash_ns: Option<f64>,
    min_tmasl_ns: Option<f64>,
    timeout_us: Option<f64>,
}

#[derive(Debug, Clone, Default)]
struct Watch {
    ma: bool,
    last_edge: u64,
    last_rise: Option<u64>,
    in_frame: bool,
    half: Option<u64>,
    frame_end: Option<u64>,
}

/// A BiSS-C monitor.
pub struct BissMonitor {
    base: Base,
    layout: Layout,
    decoder: Decoder,
    /// Least TMAS, TMASH, TMASL and timeout, ps (less one cycle of tolerance).
    tmas: u64,
    tmash: u64,
    tmasl: u64,
    timeout: u64,
    ma: Signal,
    slo: Signal,
    slo_now: bool,
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
        let base = Base::new(f_mon_hz);
        let tol = base.period_ps;
        let ps = |ns: f64| ((ns * 1e3).round() as u64).saturating_sub(tol);
        let tmas = limit(
            origin,
            "monitor.min_tmas_ns",
            mon.min_tmas_ns.unwrap_or(checks.min_tmas_ns),
            "give the least MA period in ns (seed: 100)",
        )?;
        let tmash = limit(
            origin,
            "monitor.min_tmash_ns",
            mon.min_tmash_ns.unwrap_or(25.0),
            "give the least MA high time in ns (seed: 25)",
        )?;
        let tmasl = limit(
            origin,
            "monitor.min_tmasl_ns",
            mon.min_tmasl_ns.unwrap_or(25.0),
            "give the least MA low time in ns (seed: 25)",
        )?;
        let timeout = limit(
            origin,
            "monitor.timeout_us",
            mon.timeout_us.unwrap_or(longest),
            "give the slaves' BiSS timeout in µs (seed: 16)",
        )?;
        Ok(BissMonitor {
            tmas: ps(tmas),
            tmash: ps(tmash),
            tmasl: ps(tmasl),
            timeout: ps(timeout * 1e3),
            base,
            layout: Layout {
                bits: slaves.iter().map(|s| s.bits).collect(),
                crc_width: slaves.iter().map(|s| s.crc_width).collect(),
                crc_poly: slaves.iter().map(|s| s.crc_poly).collect(),
            },
            decoder: Decoder::default(),
            ma: Signal::named("ma"),
            slo: Signal::named("slo"),
            slo_now: true,
            watch: Watch {
                ma: true,
                ..Watch::default()
            },
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

    fn check(&mut self, now: u64, ma: bool) {
        let w = &mut self.watch;
        if ma == w.ma {
            if w.in_frame && w.half.is_some_and(|h| now - w.last_edge > 3 * h) {
                w.in_frame = false;
                w.frame_end = Some(w.last_edge);
            }
            return;
        }
        let len = now - w.last_edge;
        w.ma = ma;
        w.last_edge = now;
        if !w.in_frame {
            if ma {
                return; // MA back high after a CDM = 1 hold
            }
            let gap = w.frame_end.map(|end| now - end);
            *w = Watch {
                ma,
                last_edge: now,
                in_frame: true,
                frame_end: w.frame_end,
                ..Watch::default()
            };
            if let Some(gap) = gap.filter(|&g| g < self.timeout) {
                self.base.violation(now, RULE_TIMEOUT, format!("frame started {:.3} us after the previous frame's last MA edge; the slave's timeout is {:.3} us", us(gap), us(self.timeout + self.base.period_ps)));
            } else if !self.slo_now {
                self.base.violation(now, RULE_TIMEOUT, "frame started while SLO was still low at the master (the slave's timeout not over)".to_string());
            }
            return;
        }
        w.half.get_or_insert(len);
        if ma {
            if len < self.tmasl {
                self.base.violation(
                    now,
                    RULE_TMASL,
                    format!("MA low for {:.1} ns within a frame", len as f64 / 1e3),
                );
            }
            if let Some(r) = w.last_rise.filter(|&r| now - r < self.tmas) {
                self.base.violation(
                    now,
                    RULE_TMAS,
                    format!("MA period {:.1} ns within a frame", (now - r) as f64 / 1e3),
                );
            }
            self.watch.last_rise = Some(now);
        } else if len < self.tmash {
            self.base.violation(
                now,
                RULE_TMASH,
                format!("MA high for {:.1} ns within a frame", len as f64 / 1e3),
            );
        }
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
        if !ma && self.watch.ma && !self.watch.in_frame {
            self.flush(now);
        }
        self.check(now, ma);
        self.slo_now = slo;
        self.ma.push(now, ma);
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
