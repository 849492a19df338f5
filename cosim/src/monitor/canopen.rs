//! The CANopen monitor: the CAN monitor's pins and rules ([`super::can`])
//! and, on the frames it decodes, CANopen DS 301 / DS 406 (seed 003, the
//! Leine & Linde gateway) and the SAR58K24 CAN mode (seed 001 §3.4), each
//! frame read by `model::canopen::interpret` as `tbgen decode canopen`
//! reads it. The master's frames (see [`super::can`]) are held to the
//! CANopen rule book ([`model::canopen::rules`]: SDO, NMT start, node
//! guarding, guarding with heartbeat, SYNC period, SAR58K24 command) as
//! well as the CAN one, by the watcher the CANopen emulator feeds too.
//!
//! Configuration: the scenario's `[canopen]` table (`f_sys_mhz`,
//! `bit_rate_kbps`, `tq_per_bit`, `sample_point`, `sjw`, `[master]`,
//! `[[encoders]]`, `[[sar]]`), `[monitor]` with the CAN monitor's fields
//! and `sdo_timeout_us`, `sync_period_us`, `guard_time_ms`,
//! `guard_tolerance_percent`, `sar_answer_timeout_us`.

use serde_json::Value;

use model::can::rules::{Sampled, Seen};
use model::canopen::cob::{classify, Service};
use model::canopen::rules::Watch;

use super::can::{CanWatch, Rules};
use super::{listens_only, Base};
use crate::config;
use crate::{Emulator, Pins, Result};

impl Rules for Watch {
    fn sample(&mut self, t_ps: u64, rx: bool, tx: bool) -> Sampled {
        Watch::sample(self, t_ps, rx, tx)
    }
    fn can(&self) -> &model::can::rules::Watch {
        Watch::can(self)
    }
}

/// A CANopen monitor.
pub struct CanopenMonitor {
    watch: CanWatch<Watch>,
    last_position: Option<u64>,
}

fn le32(d: &[u8]) -> u64 {
    d.iter()
        .take(4)
        .enumerate()
        .fold(0, |a, (k, &b)| a | (b as u64) << (8 * k))
}

/// The position of a TPDO1/TPDO2 another node sent.
fn position(s: &Seen) -> Option<u64> {
    let f = &s.frame;
    (!s.by_master
        && f.error.is_none()
        && !f.ide
        && matches!(classify(f.id as u16), Service::Tpdo1(_) | Service::Tpdo2(_))
        && f.data.len() >= 4)
        .then(|| le32(&f.data))
}

impl CanopenMonitor {
    /// A monitor from TOML text (`origin` names it in errors) at `f_mon_hz`.
    pub fn from_toml(text: &str, origin: &str, f_mon_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "canopen")?;
        config::emulator_clock(
            f_mon_hz,
            &tables.emulator,
            crate::canopen::MAX_BIT_RATE_KHZ,
            "the CANopen monitor",
            origin,
        )?;
        let limits = crate::canopen::limits(text, origin, f_mon_hz)?;
        Ok(CanopenMonitor {
            watch: CanWatch::new(
                Base::new(f_mon_hz),
                Watch::new(limits),
                CanopenMonitor::json,
            ),
            last_position: None,
        })
    }

    fn json(s: &Seen) -> Value {
        let mut v = super::can::json(s);
        if s.frame.error.is_none() {
            let m = model::canopen::interpret::interpret(&s.frame.frame());
            v["service"] = serde_json::to_value(m.service).unwrap_or(Value::Null);
            v["meaning"] = Value::from(m.text);
        } else {
            v["service"] = Value::Null;
            v["meaning"] = Value::from(format!(
                "damaged frame ({})",
                s.frame.error.as_deref().unwrap_or("")
            ));
        }
        v
    }
}

impl Emulator for CanopenMonitor {
    fn kind(&self) -> &'static str {
        "canopen_monitor"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        for s in self.watch.step(pins) {
            if let Some(p) = position(&s) {
                self.last_position = Some(p);
            }
        }
        self.watch.base.step_out()
    }

    fn set_position(&mut self, _: usize, _: u64) -> Result<()> {
        Err(listens_only("canopen_monitor", "position to set"))
    }

    fn set_status(&mut self, _: usize, _: &str, _: bool) -> Result<()> {
        Err(listens_only("canopen_monitor", "status to set"))
    }

    fn schedule_fault(&mut self, _: &str) -> Result<()> {
        Err(listens_only(
            "canopen_monitor",
            "frames to send or faults to schedule",
        ))
    }

    /// Frames seen so far (complete ones, damaged ones included).
    fn count(&self) -> u64 {
        self.watch.counts().0
    }

    /// `field`: 0 data, 1 identifier, 2 DLC of the last frame; 3 intact
    /// frames, 4 the master's frames; 5 the position (bytes 0..3 little
    /// endian) of the last TPDO1/TPDO2 another node sent.
    fn last_value(&self, field: usize) -> Option<u64> {
        if field == 5 {
            let pending = self.watch.pending().iter().rev().find_map(position);
            return pending.or(self.last_position);
        }
        self.watch.value(field)
    }

    fn last_status(&self, _: usize, name: &str) -> Result<bool> {
        self.watch.status("canopen_monitor", name)
    }

    fn transcript(&self) -> Value {
        let pending = self
            .watch
            .pending()
            .iter()
            .map(CanopenMonitor::json)
            .collect();
        self.watch
            .base
            .transcript("canopen", &["rx", "tx"], pending)
    }

    fn checks(&mut self) -> &mut crate::check::Checks {
        &mut self.watch.base.checks
    }
}
