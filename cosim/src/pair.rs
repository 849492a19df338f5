//! The half-duplex RS-485 pair between a master and an emulated device, as
//! every half-duplex emulator (EnDat, T-format, later ESL) steps it: the
//! master's driver (level and enable from its pins) and the device's cross
//! [`model::line::HalfDuplexLine`]; the master sees the device's side only
//! (its receiver is the wrapper's output, read while its own driver is off),
//! and both drivers on at once is reported once per overlap.

use model::line::{DelayLine, Drive, HalfDuplexLine};

use crate::check::{Checks, VIOLATION_PENDING};
use crate::Pins;

/// The pair and what the master's end shows of the device.
#[derive(Debug, Clone)]
pub struct Pair {
    line: HalfDuplexLine,
    enable_at_master: DelayLine,
    in_contention: bool,
}

impl Pair {
    /// A pair of `delay` cycles each way, idle high (fail-safe biasing).
    pub fn new(delay: u64) -> Self {
        Pair {
            line: HalfDuplexLine::new(delay, true),
            enable_at_master: DelayLine::new(delay, false),
            in_contention: false,
        }
    }

    /// The master's driver from the pins in (bit 1 level, bit 2 enable).
    pub fn master_drive(pins: Pins) -> Drive {
        Drive {
            enable: pins.0 & 4 != 0,
            level: pins.0 & 2 != 0,
        }
    }

    /// One cycle with both drives; returns the level at the device's receiver.
    /// A new overlap of both drivers is pushed to `checks` under `rule`.
    pub fn step(
        &mut self,
        master: Drive,
        device: Drive,
        cycle: u64,
        checks: &mut Checks,
        rule: &'static str,
    ) -> bool {
        let (at_master, at_device) = self.line.step(master, device);
        let contention = at_master.contention || at_device.contention;
        if contention && !self.in_contention {
            checks.push(
                cycle,
                rule,
                "master and device drove the pair at once".into(),
            );
        }
        self.in_contention = contention;
        at_device.level
    }

    /// The pins out after the device drove `device` this cycle: bit 0 its
    /// level at the master's end (idle high while it does not drive there),
    /// bit 1 its driver enable there, bit 7 a violation waiting.
    pub fn pins_out(&mut self, device: Drive, checks: &Checks, stuck: Option<bool>) -> Pins {
        let far = self
            .line
            .sensed(
                Drive {
                    enable: false,
                    level: true,
                },
                device,
            )
            .0;
        let enable = self.enable_at_master.step(device.enable);
        let flag = if checks.pending() {
            VIOLATION_PENDING
        } else {
            0
        };
        Pins(stuck.unwrap_or(far.level) as u32 | (enable as u32) << 1 | flag)
    }

    /// Cycles with both drivers on so far.
    pub fn contention_cycles(&self) -> u64 {
        self.line.contention_cycles()
    }
}
