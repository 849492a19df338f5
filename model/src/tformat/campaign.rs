//! Fault campaign: random answer frame sets of every Data ID with random
//! bits inverted anywhere in them (start bits, data bits, delimiters), run
//! through the host's cycle model (its `uart_rx` framing, the field count,
//! the CRC, the control field and ca0/ca1), counted by the number of
//! inverted bits.
//!
//! # What `X^8 + 1` cannot see
//! The CRC is the XOR of the bytes, so it checks each of the eight bit
//! columns with a parity of its own. Two inverted data bits in the same
//! column of two different fields cancel. The host's other checks catch
//! some of those pairs: one in the control field (`o_err_cf`: it is not the
//! request's), or one turning ca0/ca1 on in a readout's status field
//! (`o_err_comm`). [`crc_blind_pair`] is exactly the rest, the pairs that
//! pass every check; the tests hold the host to it in both directions.
//!
//! The host runs at 6 clocks per bit here (f_sys 15 MHz, the receiver's
//! minimum) so that 100 000 operations take seconds; the checks are the same
//! at any whole number of clocks per bit.

use std::collections::BTreeMap;

use rand::seq::index::sample;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::encoder::frame_bits;
use super::frames::{self, DataId, Status};
use super::host::{Host, HostConfig, In};

/// Clocks per bit of the campaign's host (2.5 Mbps at 15 MHz).
pub const CLOCKS_PER_BIT: u64 = 6;
/// The answer's start bit follows the request's last delimiter after 3 µs.
const ANSWER_DELAY: u64 = 45;

/// The campaign host's configuration: 10 µs timeout, the shortest reset gap.
pub fn host_config() -> HostConfig {
    HostConfig {
        clocks_per_bit: CLOCKS_PER_BIT,
        timeout_clocks: 150,
        repeat_gap_clocks: 20 * CLOCKS_PER_BIT,
    }
}

/// Detected and undetected corruptions for one number of inverted bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Counts {
    /// The host raised at least one error flag.
    pub detected: u64,
    /// The host reported the corrupted answer as clean.
    pub undetected: u64,
}

impl Counts {
    fn add(&mut self, detected: bool) {
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

/// The campaign's result.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Report {
    /// `inverted bits -> counts`.
    pub by_flips: BTreeMap<usize, Counts>,
    /// `Data ID code -> counts`.
    pub by_data_id: BTreeMap<u8, Counts>,
    /// Two-bit corruptions [`crc_blind_pair`] calls blind: how many, and how many escaped.
    pub blind_pairs: Counts,
    /// Two-bit corruptions that escaped although [`crc_blind_pair`] says a check sees them.
    pub unexplained_pair_escapes: u64,
}

impl Report {
    /// All corruptions run.
    pub fn total(&self) -> u64 {
        self.by_flips.values().map(Counts::total).sum()
    }
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "inverted bits | answers | detected | undetected | undetected rate"
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
        writeln!(f, "Data ID | answers | detected | undetected")?;
        for (id, c) in &self.by_data_id {
            writeln!(
                f,
                "{id:>7X} | {:>7} | {:>8} | {:>10}",
                c.total(),
                c.detected,
                c.undetected
            )?;
        }
        write!(f, "total {}", self.total())
    }
}

/// A random clean answer to a request for `id`, as a good encoder sends it
/// (ca0 = ca1 = 0; position, alarms, EEPROM address, busy and data random).
pub fn random_answer(rng: &mut impl Rng, id: DataId) -> Vec<u8> {
    if id.is_eeprom() {
        let (address, busy) = (rng.random_range(0..80u8), rng.random_bool(0.2));
        return frames::eeprom_answer(id, address, busy, if busy { 0 } else { rng.random() });
    }
    let status = Status {
        ea0: rng.random_bool(0.2),
        ea1: rng.random_bool(0.2),
        ..Status::default()
    };
    frames::readout(
        id,
        status,
        rng.random(),
        rng.random(),
        rng.random::<u8>() & !0x10,
    )
}

/// Whether inverting wire bits `a` and `b` (field × 10 + bit, bit 0 the start
/// bit, 9 the delimiter) of an answer to `id` escapes every check of the
/// host: both are data bits of the same column in two different fields, none
/// is the control field, and none is ca0/ca1 of a readout's status field.
pub fn crc_blind_pair(id: DataId, a: usize, b: usize) -> bool {
    let ((fa, ba), (fb, bb)) = ((a / 10, a % 10), (b / 10, b % 10));
    let data = |bit: usize| (1..=8).contains(&bit);
    let comm = |field: usize, bit: usize| !id.is_eeprom() && field == 1 && bit >= 7;
    data(ba) && ba == bb && fa != fb && fa != 0 && fb != 0 && !comm(fa, ba) && !comm(fb, bb)
}

/// Runs `trials` operations, each of a random Data ID, and inverts 1 to
/// `max_flips` distinct random bits of one answer (for a reset, one of the
/// ten). Four in ten trials invert one bit, three in ten two, the rest 3 to
/// `max_flips`.
pub fn run(trials: u64, max_flips: usize, seed: u64) -> Report {
    run_with(trials, max_flips, seed, true)
}

/// [`run`], with fast-forward through quiet cycles or stepping every cycle.
pub fn run_with(trials: u64, max_flips: usize, seed: u64, fast_forward: bool) -> Report {
    let mut host = Host::new(host_config()).expect("campaign host configuration is valid");
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut report = Report::default();
    for _ in 0..trials {
        let id = DataId::ALL[rng.random_range(0..DataId::ALL.len())];
        let answer = random_answer(&mut rng, id);
        let bits = answer.len() * 10;
        let k = match rng.random_range(0..10) {
            0..=3 => 1,
            4..=6 => 2,
            _ => rng.random_range(3..=max_flips.max(3)),
        }
        .min(bits);
        let flips = sample(&mut rng, bits, k).into_vec();
        let which = if id.is_reset() {
            rng.random_range(0..10)
        } else {
            0
        };
        let detected = flagged(&mut host, id, &answer, which, &flips, fast_forward);
        report.by_flips.entry(k).or_default().add(detected);
        report
            .by_data_id
            .entry(id.code())
            .or_default()
            .add(detected);
        if k == 2 {
            if crc_blind_pair(id, flips[0], flips[1]) {
                report.blind_pairs.add(detected);
            } else if !detected {
                report.unexplained_pair_escapes += 1;
            }
        }
    }
    report
}

/// Whether a host asking for `id` flags the operation when answer number
/// `which` carries `answer` with wire bits `flips` inverted (every other
/// answer of a reset is clean).
pub fn detected(id: DataId, answer: &[u8], which: usize, flips: &[usize]) -> bool {
    let mut host = Host::new(host_config()).expect("campaign host configuration is valid");
    flagged(&mut host, id, answer, which, flips, true)
}

/// One operation of an idle `host`; the scripted encoder answers every
/// request `ANSWER_DELAY` after the host's driver turns off.
fn flagged(
    host: &mut Host,
    id: DataId,
    answer: &[u8],
    which: usize,
    flips: &[usize],
    fast_forward: bool,
) -> bool {
    let clean: Vec<bool> = answer.iter().flat_map(|&b| frame_bits(b)).collect();
    let mut corrupted = clean.clone();
    for &i in flips {
        corrupted[i] = !corrupted[i];
    }
    let mut input = In {
        i_start: true,
        i_data_id: id.code(),
        i_address: answer.get(1).map_or(0, |a| a & 0x7F),
        i_wdata: 0,
        i_rx: true,
    };
    let (mut driving, mut answers, mut wire, mut from) = (false, 0, &clean, None::<u64>);
    let mut t = 0;
    while t < 200_000u64 {
        // Fast-forward while the host only counts and the scripted line
        // holds its level: up to the next bit boundary of the answer.
        if fast_forward && t > 0 {
            let next_change = match from {
                None => u64::MAX,
                Some(f) if t - 1 < f => f,
                Some(f) => f + ((t - 1 - f) / CLOCKS_PER_BIT + 1) * CLOCKS_PER_BIT,
            };
            let quiet = host.quiet(&input).min(next_change - t);
            if quiet > 0 && quiet < u64::MAX {
                host.skip(quiet);
                t += quiet;
                continue;
            }
        }
        let out = host.step(&input);
        input.i_start = false;
        if driving && !out.o_tx_en {
            wire = if answers == which { &corrupted } else { &clean };
            from = Some(t + ANSWER_DELAY);
            answers += 1;
        }
        driving = out.o_tx_en;
        input.i_rx = match from {
            Some(f) if t >= f => wire
                .get(((t - f) / CLOCKS_PER_BIT) as usize)
                .copied()
                .unwrap_or(true),
            _ => true,
        };
        if out.o_done {
            return out.o_err_crc
                || out.o_err_timeout
                || out.o_err_frame
                || out.o_err_cf
                || out.o_err_comm;
        }
        t += 1;
    }
    unreachable!("the host ends every operation within its timeout and quiet wait")
}
