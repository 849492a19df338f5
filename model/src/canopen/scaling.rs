//! Scaling and preset exactly as the gateway note writes them (seed 003 §3,
//! §4), in signed arithmetic:
//!
//! ```text
//!  A               = measuring_units_per_revolution * singleturn_position / 8192     (§3.2, integer)
//!  current         = revolution_number * measuring_units_per_revolution + A
//!  cyclic (A.)     : range = units_per_rev * 2^x, x <= 12 → output = (current + offset) mod range
//!  non-cyclic (B.) : otherwise, 0 <= current + offset < range → as is; outside → range (the note:
//!                    "the encoder outputs the total measuring range value"; `Clamp` clamps instead)
//!  preset (§4.2)   : offset = preset − current   (a previous offset is not in `current`)
//! ```
//! The operating mode is chosen when the range (6002h) is received, so the
//! units per revolution (6001h) must be sent first (§3.1 NOTE).

use serde::{Deserialize, Serialize};

/// What a non-cyclic encoder outputs outside its range (named configuration
/// `non_cyclic_limit`).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum NonCyclicLimit {
    /// The total measuring range value (the note's words, §3.2.1 B).
    #[default]
    TotalRange,
    /// 0 below the range, range − 1 above it.
    Clamp,
}

/// The scaling state: 6000h bits, 6001h, 6002h, the mode chosen at the
/// last 6002h, and the offset 6509h.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Scaling {
    /// Singleturn resolution of the encoder disk (8192 for 13 bits).
    pub st_res: u64,
    /// Revolutions of the multiturn disks (4096 for 12 bits; 1 singleturn).
    pub revs: u64,
    /// 6000h bit 0: code sequence counter-clockwise (raw position inverted).
    pub ccw: bool,
    /// 6000h bit 2: scaling function on.
    pub scaling: bool,
    /// 6001h.
    pub units_per_rev: u32,
    /// 6002h.
    pub range: u32,
    /// Cyclic operation (chosen when 6002h was received).
    pub cyclic: bool,
    /// 6509h.
    pub offset: i32,
    /// Outside a non-cyclic range.
    pub limit: NonCyclicLimit,
}

/// Whether `range` = `units_per_rev` × 2^x with x ≤ 12 (binary scaling, §3.2.1 A).
pub fn is_binary(units_per_rev: u32, range: u32) -> bool {
    (0..=12).any(|x| (units_per_rev as u64) << x == range as u64)
}

impl Scaling {
    /// Unscaled, for a disk of `st_res` × `revs` positions.
    pub fn new(st_res: u64, revs: u64, limit: NonCyclicLimit) -> Scaling {
        Scaling {
            st_res,
            revs,
            ccw: false,
            scaling: false,
            units_per_rev: st_res as u32,
            range: (st_res * revs).min(u32::MAX as u64) as u32,
            cyclic: true,
            offset: 0,
            limit,
        }
    }

    /// Positions of the raw disk.
    pub fn raw_range(&self) -> u64 {
        self.st_res * self.revs
    }

    /// The range the output lives in: 6002h with scaling on, the raw range without.
    pub fn out_range(&self) -> u64 {
        if self.scaling {
            self.range as u64
        } else {
            self.raw_range()
        }
    }

    /// Sets 6002h and chooses the mode (§3.2.1).
    pub fn set_range(&mut self, range: u32) {
        self.range = range;
        self.cyclic = is_binary(self.units_per_rev, range);
    }

    /// `current_position` of §4.2: the scaled position before the offset.
    pub fn current(&self, raw: u64) -> i64 {
        let raw = raw % self.raw_range();
        let raw = if self.ccw {
            self.raw_range() - 1 - raw
        } else {
            raw
        };
        if !self.scaling {
            return raw as i64;
        }
        let (st, rev) = (raw % self.st_res, raw / self.st_res);
        let a = self.units_per_rev as u64 * st / self.st_res;
        (rev * self.units_per_rev as u64 + a) as i64
    }

    /// The output position (6004h) for the raw disk position `raw`.
    pub fn output(&self, raw: u64) -> u32 {
        let v = self.current(raw) + self.offset as i64;
        let range = self.out_range() as i64;
        let cyclic = !self.scaling || self.cyclic;
        if cyclic {
            v.rem_euclid(range) as u32
        } else if (0..range).contains(&v) {
            v as u32
        } else {
            match self.limit {
                NonCyclicLimit::TotalRange => range as u32,
                NonCyclicLimit::Clamp => v.clamp(0, range - 1) as u32,
            }
        }
    }

    /// The offset a preset to `preset` sets at raw position `raw` (§4.2).
    pub fn preset_offset(&self, preset: u32, raw: u64) -> i32 {
        (preset as i64 - self.current(raw)) as i32
    }
}
