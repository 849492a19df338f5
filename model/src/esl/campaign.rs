//! Fault campaign: random corruptions of the wire bits (start, data and stop
//! bits of every field) of random answer frame sets of every Data ID, read
//! by an ideal bit-level receiver with the host's framing rules and judged
//! by the host's own check ([`frames::check`]), counted by the number of
//! flipped bits. The cycle-level path (receiver timing, quiet wait) is
//! exercised bit by bit in the tests and the flip scenarios; this campaign
//! is about what the frame layer and the CRCs catch.

use std::collections::BTreeMap;

use rand::seq::index::sample;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::encoder::frame_bits;
use super::frames::{self, AnswerData, DataId, Status};

/// Detected and undetected corruptions for one number of flipped bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Counts {
    /// The host flagged the answer.
    pub detected: u64,
    /// The host accepted the corrupted answer.
    pub undetected: u64,
}

/// The campaign's result: counts by number of flipped bits.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Report {
    /// `flipped bits -> counts`.
    pub by_flips: BTreeMap<u32, Counts>,
}

impl Report {
    /// All corruptions run.
    pub fn total(&self) -> u64 {
        self.by_flips
            .values()
            .map(|c| c.detected + c.undetected)
            .sum()
    }

    /// All corruptions the host accepted.
    pub fn undetected(&self) -> u64 {
        self.by_flips.values().map(|c| c.undetected).sum()
    }
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "flipped_bits  detected  undetected")?;
        for (k, c) in &self.by_flips {
            writeln!(f, "{k:>12}  {:>8}  {:>10}", c.detected, c.undetected)?;
        }
        write!(f, "total {}", self.total())
    }
}

/// Reads a line (idle high before and after `bits`) as the host's receiver
/// does, one sample per bit: a field starts at a 0, its tenth bit must be 1
/// (else a framing error, and the receiver waits for a 1); the set ends when
/// the bit after a field is not a start bit. Returns the fields and whether
/// any had a bad stop bit.
pub fn receive(bits: &[bool]) -> (Vec<u8>, bool) {
    let at = |i: usize| bits.get(i).copied().unwrap_or(true);
    let mut fields = Vec::new();
    let mut framing = false;
    let Some(mut i) = bits.iter().position(|&b| !b) else {
        return (fields, false);
    };
    loop {
        let byte = (0..8).fold(0u8, |acc, k| acc | (at(i + 1 + k) as u8) << k);
        fields.push(byte);
        i += 9;
        if !at(i) {
            framing = true;
            while !at(i) && i < bits.len() {
                i += 1;
            }
        }
        i += 1;
        if at(i) || fields.len() > frames::DataId::Id1.answer_fields() {
            return (fields, framing);
        }
    }
}

/// Whether the host flags one answer of `id` built from `d` whose wire bits
/// `flips` (indices into the 10-bit fields, start bit of CF1 = 0) are inverted.
pub fn detected(id: DataId, d: &AnswerData, flips: &[usize]) -> bool {
    let set = frames::answer(id, d);
    let mut bits: Vec<bool> = set.iter().flat_map(|&b| frame_bits(b)).collect();
    for &f in flips {
        if let Some(b) = bits.get_mut(f) {
            *b = !*b;
        }
    }
    let (fields, framing) = receive(&bits);
    frames::check(id, d.cf, &fields, framing, 1).any()
}

/// Runs `trials` answers of random Data IDs and contents, each with 1 to
/// `max_flips` distinct wire bits flipped.
pub fn run(trials: u64, max_flips: u32, seed: u64) -> Report {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut report = Report::default();
    for _ in 0..trials {
        let id = DataId::ALL[rng.random_range(0..DataId::ALL.len())];
        let abs = rng.random::<u32>() & 0xFF_FFFF;
        let d = AnswerData {
            cf: id.control_field(rng.random_range(0..7)),
            status: Status {
                ready: true,
                ea0: rng.random_bool(0.1),
                ..Status::default()
            },
            alm1: rng.random(),
            alm2: rng.random(),
            abs,
            abm: rng.random(),
            rs: frames::redundant(abs, id),
            sc1: rng.random(),
            sc2: rng.random::<u8>() & 0x7F,
            enid: 0xD8,
            temp: rng.random(),
            adf: frames::adf(rng.random(), false),
            edf: rng.random(),
        };
        let n = 10 * id.answer_fields();
        let k = rng.random_range(1..=max_flips.min(n as u32));
        let flips = sample(&mut rng, n, k as usize).into_vec();
        let entry = report.by_flips.entry(k).or_default();
        if detected(id, &d, &flips) {
            entry.detected += 1;
        } else {
            entry.undetected += 1;
        }
    }
    report
}
