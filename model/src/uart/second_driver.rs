//! Another device driving a half-duplex UART line (`[[<table>.second_drivers]]`
//! of the SAR58K24 and Modbus scenarios): characters at the nominal rate,
//! or a short low glitch, from a given time, whatever else is on the line.

use serde::{Deserialize, Serialize};

use super::Parity;
use crate::{ConfigError, Result, Timebase};

/// Another driver on the line.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SecondDriver {
    /// Start, µs after reset.
    pub at_us: f64,
    /// The characters it sends at the nominal rate.
    #[serde(default)]
    pub bytes: Vec<u8>,
    /// A low pulse of this width (ns) before the characters: shorter than
    /// half a bit, a glitch the receiver must reject (`o_start_err` of
    /// `uart_rx`); 0 for none.
    #[serde(default)]
    pub glitch_ns: f64,
}

impl SecondDriver {
    /// Checks driver `i` of a scenario.
    pub fn validate(&self, i: usize) -> Result<()> {
        let something = !self.bytes.is_empty() || self.glitch_ns > 0.0;
        if !(0.0..1e8).contains(&self.at_us)
            || self.bytes.len() > 1000
            || !(0.0..1e6).contains(&self.glitch_ns)
            || !something
        {
            return Err(ConfigError::invalid(
                format!("second_drivers[{i}]"),
                format!(
                    "at_us {}, {} bytes, glitch_ns {}",
                    self.at_us,
                    self.bytes.len(),
                    self.glitch_ns
                ),
                "give at_us ≥ 0 and 1 to 1000 bytes, or a glitch_ns below 10^6",
            ));
        }
        Ok(())
    }

    /// The first cycle it drives and the level it drives in each cycle from
    /// then on (`clocks_per_bit` cycles a bit).
    pub fn cycle_levels(
        &self,
        tb: &Timebase,
        parity: Parity,
        clocks_per_bit: u64,
    ) -> (u64, Vec<bool>) {
        let glitch = if self.glitch_ns > 0.0 {
            tb.cycles_nearest_ns(self.glitch_ns).max(1) as usize
        } else {
            0
        };
        let mut levels = vec![false; glitch];
        if glitch > 0 && !self.bytes.is_empty() {
            levels.extend(std::iter::repeat_n(true, clocks_per_bit as usize));
        }
        levels.extend(
            self.bytes
                .iter()
                .flat_map(|&b| parity.levels(b))
                .flat_map(|bit| std::iter::repeat_n(bit, clocks_per_bit as usize)),
        );
        (tb.cycles_nearest_ns(self.at_us * 1e3), levels)
    }
}

/// Fast-forward of a host bench (SAR58K24, Modbus) before its models'
/// own limits: how many cycles from `cycle` pass with no operation starting
/// (`end` of the run, the host `busy` or `waiting`, the next start at
/// `start_at`), no start pulse falling (`just_started`) and no second driver
/// (its first cycle and its levels, one per cycle) beginning; 0 inside a
/// second driver's levels.
pub fn bench_quiet(
    cycle: u64,
    end: Option<u64>,
    busy: bool,
    start_at: u64,
    just_started: bool,
    drivers: &[(u64, Vec<bool>)],
) -> u64 {
    let host = match end {
        Some(end) => end.saturating_sub(cycle),
        None if busy => u64::MAX,
        None => start_at.saturating_sub(cycle),
    };
    if just_started {
        return 0;
    }
    let mut q = host;
    for (from, levels) in drivers {
        if cycle < *from {
            q = q.min(from - cycle);
        } else if cycle < from + levels.len() as u64 {
            return 0;
        }
    }
    q
}
