//! The EnDat monitor: the master's clock and data pins.
//!
//! Pins in: bit 0 the clock at the master, bit 1 its data driver's level (D),
//! bit 2 its driver enable (DE), bit 3 the data at its receiver (R). The line
//! at the master is D while DE is on, else R (what a probe on the pair at the
//! master shows; for a capture of the pair alone tie DE low and give the pair
//! as R). Transfers are decoded by [`model::endat::decode`], the decode core
//! of `tbgen decode endat` (the master's own receive and check logic judges
//! every frame). The master's timing is held to the rule book
//! [`model::endat::rules`] (`f_c`, `f_c min`, `on-off ratio`, `t_ST`, `send
//! block`, `t_m`, `t_R`, `t_m after an error`, `t_b`, `measurement clock`,
//! `delay measurement`; the emulator holds it to the same, from the same
//! limits, [`crate::endat::rule_config`]).
//!
//! A transfer is the rule book's ([`model::endat::rules`]); one is decoded
//! when it is over (at the next transfer's start, or 10 µs after its last
//! edge: by then the encoder's last bits have crossed the cable back). Its
//! count and last value cover the transfer in progress too (decoded as far
//! as it got).
//!
//! Configuration (a whole scenario file will do): `[monitor]` fields
//! (`pos_bits`, `delay_comp`, `max_clock_khz`, `min_clock_khz`,
//! `on_off_percent`, `t_st_us`, `t_m_us`, `t_m21_us`, `t_r_us`,
//! `round_trip_ns`, `t_err_us`, `t_b_us`, `meas_clock_khz`,
//! `meas_frame_below_khz`, `meas_frames_min`); defaults from `[master]`
//! (`delay_comp`, `meas_clock_khz`), `[encoder]` (`singleturn_bits +
//! multiturn_bits`, `t_m_us`, `t_m21_us`, `recovery_short`,
//! `output_delay_ns`), `[cable]` and `[checks]` (`t_b_us`, `max_clock_khz`
//! with delay compensation).

use serde_json::Value;

use model::endat::decode::{Decoder, Options};
use model::endat::rules::{self, Watch};
use model::wire::Signal;

use super::{listens_only, Base};
use crate::config::{self, Error};
use crate::endat::{rule_config, MAX_CLOCK_KHZ};
use crate::{Emulator, Pins, Result};

/// An EnDat monitor.
pub struct EndatMonitor {
    base: Base,
    opts: Options,
    decoder: Decoder,
    watch: Watch,
    clk: Signal,
    data: Signal,
}

impl EndatMonitor {
    /// A monitor from TOML text (`origin` names it in errors) at `f_mon_hz`.
    pub fn from_toml(text: &str, origin: &str, f_mon_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "endat")?;
        config::emulator_clock(
            f_mon_hz,
            &tables.emulator,
            MAX_CLOCK_KHZ,
            "the EnDat monitor",
            origin,
        )?;
        let rc = rule_config(text, origin)?;
        let range = model::endat::POSITION_BITS;
        if !range.contains(&rc.pos_bits) {
            return Err(Error::field(
                origin,
                "monitor.pos_bits",
                format!("{} bits", rc.pos_bits),
                format!(
                    "give {} to {} position bits (default: encoder.singleturn_bits + multiturn_bits)",
                    range.start(),
                    range.end()
                ),
            ));
        }
        let opts = Options {
            pos_bits: rc.pos_bits,
            meas_khz: rc.limits.delay_comp.then_some(rc.meas_clock_khz),
        };
        let mut base = Base::new(f_mon_hz);
        for note in model::rules::resolution_notes(f_mon_hz, &rc.limits.least()) {
            base.checks.note(note);
        }
        Ok(EndatMonitor {
            decoder: Decoder::new(&opts).map_err(|e| {
                Error::field(origin, "monitor.pos_bits", e, "give 1 to 48 position bits")
            })?,
            opts,
            base,
            watch: Watch::new(rc.limits),
            clk: Signal::named("clk"),
            data: Signal::named("data"),
        })
    }

    /// The transfers since the last decoded one (the decoder's state is not changed).
    fn pending(&self) -> Vec<Value> {
        let Some(b) = self.watch.burst() else {
            return Vec::new();
        };
        let mut d = self.decoder.clone();
        d.burst(b, &self.data, &self.opts)
            .into_iter()
            .map(|t| serde_json::to_value(t).unwrap_or(Value::Null))
            .collect()
    }

    fn last(&self) -> Option<Value> {
        self.pending()
            .pop()
            .or_else(|| self.base.done.last().cloned())
    }
}

impl Emulator for EndatMonitor {
    fn kind(&self) -> &'static str {
        "endat_monitor"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let now = self.base.exact_ps();
        let p = rules::Pins {
            clk: pins.0 & 1 != 0,
            d: pins.0 & 2 != 0,
            de: pins.0 & 4 != 0,
            r: pins.0 & 8 != 0,
        };
        // The data line first, so that the clock edge of this cycle sees it.
        self.data.push(now, if p.de { p.d } else { p.r });
        let seen = self.watch.sample(now, p);
        if let Some(b) = self.watch.take_finished() {
            let list = self.decoder.burst(&b, &self.data, &self.opts);
            self.base.done.extend(
                list.into_iter()
                    .map(|t| serde_json::to_value(t).unwrap_or(Value::Null)),
            );
            // Keep the line from the new transfer's first edge on.
            let keep = self.watch.burst().map_or(now, |c| c.falls[0]);
            self.clk.forget_before(keep);
            self.data.forget_before(keep);
        }
        for b in &seen.breaches {
            self.base.breach(b);
        }
        // Before the clock is seen idle high (a master in reset), the decoder sees it idle.
        self.clk.push(now, p.clk || !self.watch.seen_idle());
        self.base.step_out()
    }

    fn set_position(&mut self, _: usize, _: u64) -> Result<()> {
        Err(listens_only("endat_monitor", "position to set"))
    }

    fn set_status(&mut self, _: usize, _: &str, _: bool) -> Result<()> {
        Err(listens_only("endat_monitor", "status to set"))
    }

    fn schedule_fault(&mut self, _: &str) -> Result<()> {
        Err(listens_only("endat_monitor", "faults to schedule"))
    }

    /// Transactions seen so far (the one in progress included; a delay measurement is one).
    fn count(&self) -> u64 {
        (self.base.done.len() + self.pending().len()) as u64
    }

    /// The position (or test value) of the last transaction seen.
    fn last_value(&self, _: usize) -> Option<u64> {
        self.last()?.get("position")?.as_u64()
    }

    /// `"f1"`, `"f2"` (as the master reads them: F2 is low-active, `true` is no error), `"crc_ok"` (no `crc`
    /// error), `"error"` (any error flagged) of the last transaction seen.
    fn last_status(&self, _: usize, name: &str) -> Result<bool> {
        let t = self
            .last()
            .ok_or_else(|| Error::Usage("endat_monitor: no transfer decoded yet".into()))?;
        let errors: Vec<&str> = t["errors"]
            .as_array()
            .map(|e| e.iter().filter_map(|x| x.as_str()).collect())
            .unwrap_or_default();
        match name {
            "f1" | "f2" => t[name].as_bool().ok_or_else(|| {
                Error::Usage(format!(
                    "endat_monitor: the last transfer carried no {}",
                    name.to_uppercase()
                ))
            }),
            "crc_ok" => Ok(!errors.contains(&"crc")),
            "error" | "errors" => Ok(errors
                .iter()
                .any(|e| !matches!(*e, "f1_error" | "f2_error"))),
            other => Err(Error::Usage(format!(
                "endat_monitor: no status `{other}`; give \"f1\", \"f2\", \"crc_ok\" or \"error\""
            ))),
        }
    }

    fn transcript(&self) -> Value {
        self.base.transcript(
            "endat",
            &["clk", "data", "data_oe", "data_in"],
            self.pending(),
        )
    }

    fn checks(&mut self) -> &mut crate::check::Checks {
        &mut self.base.checks
    }
}
