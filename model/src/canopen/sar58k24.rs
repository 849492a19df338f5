//! The SAR58K24 in its CAN mode (seed 001 §3.4): its own command set on
//! 0x200 + node ("2NN"), answers on 0x100 + node ("1NN"), a configuration
//! channel on 0x7E5; 250 kbit/s and node 0x20 from the factory, cycle time 100 ms.
//!
//! The answer identifier: the manual's function-code table lists PDO
//! 0x181..0x1FF (0x180 + node), but its worked example answers on **0x120**
//! for node 0x20, its command tables write the answer as `1NN`, and its
//! capture shows node 0xFF answering on 0x1FF: every example says 0x100 +
//! node, with nodes up to 0xFF. `answer_base = 0x100` is the default;
//! `answer_base = 0x180` (nodes 1 to 127) follows the function-code table.
//!
//! ```text
//!  request (0x200+NN, DLC 8)   answer (0x100+NN, DLC 8)       reading (docs/timing/canopen.md)
//!  01 NN 00 ..                 <pos low> <pos high> 00 ..       start: position every cycle (factory 100 ms)
//!  80 NN 00 ..                 <pos low> <pos high> 00 ..       "click": one position
//!  22 NN 00 ..                 22 00 00 ..                      direction: toggles (`direction = "toggle"`)
//!  20 NN 00 ..                 20 00 00 ..                      zero ("centered"): position becomes 0
//!  31 NN TT 00 ..              31 00 00 ..                      timed send TT times a second; the same bytes stop it
//!  configuration (0x7E5, answers on 0x7E5):
//!  04 01 00 ..                 (none)                           enter configuration mode
//!  11 <node> 00 ..             11 00 00 ..                      new node, from the next power-on
//!  13 00 <code> 00 ..          13 00 00 ..                      new bit rate: 00 = 1 M, 02 = 500 K, 03 = 250 K
//! ```
//! Positions wider than 16 bits continue in D2, D3 (little-endian, as D0, D1).

use serde::{Deserialize, Serialize};

use super::node::Device;
use crate::can::frame::Frame;
use crate::{ConfigError, Result};

/// The configuration channel's identifier.
pub const CONFIG_ID: u32 = 0x7E5;

/// Bit-rate codes of the `13 00 <code>` command (seed 001 §3.4 ③): code → kbit/s.
pub fn bit_rate_of_code(code: u8) -> Option<u32> {
    match code {
        0x00 => Some(1000),
        0x02 => Some(500),
        0x03 => Some(250),
        _ => None,
    }
}

/// What `22 NN` does (the manual prints the same code for "carry over" and
/// "reverse carry").
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    /// Each `22 NN` toggles the counting direction (as `31 NN TT` both starts and stops).
    #[default]
    Toggle,
    /// `22 NN` sets forward, `23 NN` reverse (a guessed second code).
    Codes22And23,
}

/// The SAR58K24 CAN-mode encoder (`[sar_can]` of a scenario).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SarCanConfig {
    /// Node at power-on (factory 0x20).
    pub node: u8,
    /// Bit rate at power-on, kbit/s (factory 250).
    pub bit_rate_kbps: u32,
    /// Resolution, bits (the manual's example: 14).
    pub bits: u32,
    /// Cycle time of the start command, ms (factory 100).
    pub cycle_ms: u32,
    /// Raw position at power-on.
    pub raw_position: u64,
    /// Counts per second.
    pub speed_cps: f64,
    /// Reading of `22 NN`.
    pub direction: Direction,
    /// Answer identifier base: 0x100 (the manual's examples) or 0x180 (its function-code table).
    pub answer_base: u16,
}

impl Default for SarCanConfig {
    fn default() -> Self {
        SarCanConfig {
            node: 0x20,
            bit_rate_kbps: 250,
            bits: 14,
            cycle_ms: 100,
            raw_position: 0,
            speed_cps: 0.0,
            direction: Direction::Toggle,
            answer_base: 0x100,
        }
    }
}

impl SarCanConfig {
    /// Checks the fields.
    pub fn validate(&self, field: &str) -> Result<()> {
        if ![0x100, 0x180].contains(&self.answer_base) {
            return Err(ConfigError::invalid(format!("{field}.answer_base"), format!("{:#x}", self.answer_base), "give 0x100 (the manual's examples: 0x120 for node 0x20) or 0x180 (its function-code table)"));
        }
        let top = if self.answer_base == 0x100 {
            0xFF
        } else {
            0x7F
        };
        if !(1..=top).contains(&self.node) {
            return Err(ConfigError::invalid(
                format!("{field}.node"),
                format!("{:#x}", self.node),
                format!("give a node from 0x01 to {top:#x} (factory 0x20)"),
            ));
        }
        if ![1000, 500, 250].contains(&self.bit_rate_kbps) {
            return Err(ConfigError::invalid(
                format!("{field}.bit_rate_kbps"),
                format!("{}", self.bit_rate_kbps),
                "give 1000, 500 or 250 (the rates of seed 001 §3.4 ③)",
            ));
        }
        if !(10..=32).contains(&self.bits) {
            return Err(ConfigError::invalid(
                format!("{field}.bits"),
                format!("{}", self.bits),
                "give 10 to 32 bits",
            ));
        }
        if self.cycle_ms == 0 {
            return Err(ConfigError::invalid(
                format!("{field}.cycle_ms"),
                "0",
                "give the cycle time in ms, at least 1",
            ));
        }
        if !self.speed_cps.is_finite() || self.speed_cps.abs() > 1e9 {
            return Err(ConfigError::invalid(
                format!("{field}.speed_cps"),
                format!("{}", self.speed_cps),
                "give at most 1e9 counts per second",
            ));
        }
        if self.raw_position >> self.bits != 0 {
            return Err(ConfigError::invalid(
                format!("{field}.raw_position"),
                format!("{}", self.raw_position),
                format!("give a position below 2^{}", self.bits),
            ));
        }
        Ok(())
    }
}

/// The encoder.
#[derive(Debug, Clone)]
pub struct SarCan {
    cfg: SarCanConfig,
    node: u8,
    rate: u32,
    next_node: u8,
    next_rate: u32,
    config_mode: bool,
    reverse: bool,
    zero: u64,
    raw_base: u64,
    raw_ns: u64,
    period_ns: Option<u64>,
    next_at: u64,
}

impl SarCan {
    /// Before power-on.
    pub fn new(cfg: &SarCanConfig) -> Result<SarCan> {
        cfg.validate("sar_can")?;
        Ok(SarCan {
            cfg: cfg.clone(),
            node: cfg.node,
            rate: cfg.bit_rate_kbps,
            next_node: cfg.node,
            next_rate: cfg.bit_rate_kbps,
            config_mode: false,
            reverse: false,
            zero: 0,
            raw_base: cfg.raw_position,
            raw_ns: 0,
            period_ns: None,
            next_at: 0,
        })
    }

    /// Node in use.
    pub fn node(&self) -> u8 {
        self.node
    }

    /// The configuration it was made from.
    pub fn config(&self) -> &SarCanConfig {
        &self.cfg
    }

    /// Node and bit rate (kbit/s) from the next power-on (set on 0x7E5).
    pub fn pending(&self) -> (u8, u32) {
        (self.next_node, self.next_rate)
    }

    /// In configuration mode (after `04 01` on 0x7E5, until the next power-on).
    pub fn config_mode(&self) -> bool {
        self.config_mode
    }

    /// Sending by itself: after start (`01`) or a timed send (`31 NN TT`), until stopped.
    pub fn sending(&self) -> bool {
        self.period_ns.is_some()
    }

    /// Counting reversed (`22 NN`).
    pub fn reversed(&self) -> bool {
        self.reverse
    }

    /// Moves the disk to `raw` at `now_ns`.
    pub fn set_raw(&mut self, raw: u64, now_ns: u64) {
        self.raw_base = raw & self.mask();
        self.raw_ns = now_ns;
    }

    fn mask(&self) -> u64 {
        (1u64 << self.cfg.bits) - 1
    }

    /// The position it reports at `now_ns`.
    pub fn position(&self, now_ns: u64) -> u64 {
        let m = self.mask() as i128 + 1;
        let moved =
            (self.cfg.speed_cps * now_ns.saturating_sub(self.raw_ns) as f64 * 1e-9).round() as i128;
        let raw = (self.raw_base as i128 + moved).rem_euclid(m);
        let p = (raw - self.zero as i128).rem_euclid(m);
        (if self.reverse { (m - p) % m } else { p }) as u64
    }

    fn reply(&self, now_ns: u64) -> Frame {
        let p = self.position(now_ns).to_le_bytes();
        let mut d = [0u8; 8];
        let n = self.cfg.bits.div_ceil(8).max(2) as usize;
        d[..n].copy_from_slice(&p[..n]);
        Frame::data(self.answer_id(), &d)
    }

    fn answer_id(&self) -> u32 {
        self.cfg.answer_base as u32 + self.node as u32
    }

    fn ack(&self, id: u32, code: u8) -> Frame {
        Frame::data(id, &[code, 0, 0, 0, 0, 0, 0, 0])
    }
}

impl Device for SarCan {
    fn power_on(&mut self, now_ns: u64) -> Vec<Frame> {
        self.node = self.next_node;
        self.rate = self.next_rate;
        self.config_mode = false;
        self.period_ns = None;
        self.raw_ns = now_ns;
        Vec::new()
    }

    fn on_frame(&mut self, f: &Frame, now_ns: u64) -> Vec<Frame> {
        if f.rtr || f.ide || f.data.len() < 2 {
            return Vec::new();
        }
        let d = &f.data;
        if f.id == CONFIG_ID {
            return match (d[0], self.config_mode) {
                (0x04, _) if d[1] == 0x01 => {
                    self.config_mode = true;
                    Vec::new()
                }
                (0x11, true) if d[1] >= 1 && (self.cfg.answer_base == 0x100 || d[1] <= 0x7F) => {
                    self.next_node = d[1];
                    vec![self.ack(CONFIG_ID, 0x11)]
                }
                (0x13, true) if d.len() >= 3 && bit_rate_of_code(d[2]).is_some() => {
                    self.next_rate = bit_rate_of_code(d[2]).unwrap_or(self.rate);
                    vec![self.ack(CONFIG_ID, 0x13)]
                }
                _ => Vec::new(),
            };
        }
        if f.id != 0x200 + self.node as u32 || d[1] != self.node {
            return Vec::new();
        }
        let answer = self.answer_id();
        match d[0] {
            0x01 => {
                self.period_ns = Some(self.cfg.cycle_ms as u64 * 1_000_000);
                self.next_at = now_ns + self.cfg.cycle_ms as u64 * 1_000_000;
                vec![self.reply(now_ns)]
            }
            0x80 => vec![self.reply(now_ns)],
            0x20 => {
                // The zero is taken on the unreversed count, so that direction and zero commute.
                let was_rev = std::mem::replace(&mut self.reverse, false);
                self.zero = (self.zero + self.position(now_ns)) & self.mask();
                self.reverse = was_rev;
                vec![self.ack(answer, 0x20)]
            }
            0x22 => {
                self.reverse = match self.cfg.direction {
                    Direction::Toggle => !self.reverse,
                    Direction::Codes22And23 => false,
                };
                vec![self.ack(answer, 0x22)]
            }
            0x23 if self.cfg.direction == Direction::Codes22And23 => {
                self.reverse = true;
                vec![self.ack(answer, 0x23)]
            }
            0x31 => {
                let tt = d.get(2).copied().unwrap_or(0) as u64;
                if self.period_ns.is_some() || tt == 0 {
                    self.period_ns = None;
                } else {
                    let p = 1_000_000_000 / tt;
                    self.period_ns = Some(p);
                    self.next_at = now_ns + p;
                }
                vec![self.ack(answer, 0x31)]
            }
            _ => Vec::new(),
        }
    }

    fn poll(&mut self, now_ns: u64) -> Vec<Frame> {
        match self.period_ns {
            Some(p) if now_ns >= self.next_at => {
                self.next_at += p;
                vec![self.reply(now_ns)]
            }
            _ => Vec::new(),
        }
    }

    fn next_due_ns(&self) -> Option<u64> {
        self.period_ns.map(|_| self.next_at)
    }

    fn bit_rate_kbps(&self) -> u32 {
        self.rate
    }

    fn response_delay_us(&self) -> f64 {
        0.0
    }
}
