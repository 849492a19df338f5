//! The pieces the SAR58K24 and Modbus corruption campaigns share: the line
//! levels of 10-bit characters, a bit-level reading of corrupted levels as
//! any UART reads them, the random corruption (how many line bits, which),
//! and the tally of detected and undetected corruptions with its table.
//! Each protocol's `campaign` module adds what its own checks can promise
//! (the 8-bit sum, CRC-16) and runs its own host or master.

use std::collections::BTreeMap;

use rand::seq::index::sample;
use rand::Rng;

use super::Parity;

/// Detected and undetected corruptions.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Counts {
    /// The host or master flagged the frame (or accepted nothing).
    pub detected: u64,
    /// The corrupted frame was accepted without a flag.
    pub undetected: u64,
}

impl Counts {
    /// Counts one corruption.
    pub fn add(&mut self, detected: bool) {
        if detected {
            self.detected += 1;
        } else {
            self.undetected += 1;
        }
    }

    /// Corruptions counted.
    pub fn total(&self) -> u64 {
        self.detected + self.undetected
    }
}

/// Detected and undetected corruptions by the number of inverted bits,
/// against what the frame's own checks can see.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Tally {
    /// `inverted bits -> counts`.
    pub by_flips: BTreeMap<usize, Counts>,
    /// Corruptions the bit-level reference calls blind (a well-formed frame remains).
    pub blind: Counts,
    /// Corruptions judged otherwise than the reference (must be 0).
    pub disagreements: u64,
}

impl Tally {
    /// Counts one corruption of `flips` inverted bits.
    pub fn add(&mut self, flips: usize, detected: bool, blind: bool) {
        self.by_flips.entry(flips).or_default().add(detected);
        if blind {
            self.blind.add(detected);
        }
        if detected == blind {
            self.disagreements += 1;
        }
    }

    /// All corruptions run.
    pub fn total(&self) -> u64 {
        self.by_flips.values().map(Counts::total).sum()
    }

    /// The table of the counts (`unit`: what a row counts, `promise`: what
    /// the protocol's check can promise), without the closing total.
    pub fn table(
        &self,
        f: &mut std::fmt::Formatter<'_>,
        unit: &str,
        promise: &str,
    ) -> std::fmt::Result {
        writeln!(
            f,
            "inverted bits | {unit:>7} | detected | undetected | undetected rate"
        )?;
        for (k, c) in &self.by_flips {
            writeln!(
                f,
                "{k:>13} | {:>7} | {:>8} | {:>10} | {:.5}",
                c.total(),
                c.detected,
                c.undetected,
                c.undetected as f64 / c.total() as f64
            )?;
        }
        let all = self
            .by_flips
            .values()
            .fold(Counts::default(), |a, c| Counts {
                detected: a.detected + c.detected,
                undetected: a.undetected + c.undetected,
            });
        writeln!(
            f,
            "{:>13} | {:>7} | {:>8} | {:>10} | {:.5}",
            "all",
            all.total(),
            all.detected,
            all.undetected,
            all.undetected as f64 / all.total().max(1) as f64
        )?;
        writeln!(f, "{promise}")?;
        writeln!(
            f,
            "blind by the frame's own checks: {} (all {} accepted, as they must be)",
            self.blind.total(),
            self.blind.undetected
        )
    }
}

/// The line levels of `bytes`: start, data LSB first, stop, 10 bits a character.
pub fn levels(bytes: &[u8]) -> Vec<bool> {
    bytes.iter().flat_map(|&b| Parity::None.levels(b)).collect()
}

/// Reads `levels` (one per bit time, idle high before and after) bit by bit
/// as any UART does: a 0 after idle or after a stop bit starts a character,
/// eight data bits, a stop bit that must be 1. `None` at the first low stop
/// bit (a framing error); else the characters read.
pub fn characters(levels: &[bool]) -> Option<Vec<u8>> {
    let mut bytes = Vec::new();
    let mut i = 0;
    while i < levels.len() {
        if levels[i] {
            i += 1;
            continue;
        }
        let bit = |j: usize| levels.get(j).copied().unwrap_or(true);
        if !bit(i + 9) {
            return None;
        }
        bytes.push((1..=8).fold(0u8, |b, k| b | ((bit(i + k) as u8) << (k - 1))));
        i += 10;
    }
    Some(bytes)
}

/// `clean` with random bits inverted: four in ten corruptions invert one
/// bit, three in ten two, the rest 3 to `max_flips`. Returns (bits inverted, levels).
pub fn corrupt(rng: &mut impl Rng, clean: &[bool], max_flips: usize) -> (usize, Vec<bool>) {
    let k = match rng.random_range(0..10) {
        0..=3 => 1,
        4..=6 => 2,
        _ => rng.random_range(3..=max_flips.max(3)),
    };
    let mut corrupted = clean.to_vec();
    for i in sample(rng, clean.len(), k).into_vec() {
        corrupted[i] = !corrupted[i];
    }
    (k, corrupted)
}
