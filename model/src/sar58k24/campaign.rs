//! Fault campaign: random position frames (16, 24 or 32 bits, binary) with
//! random line bits inverted anywhere in them (start, data, stop), each
//! between idle gaps and followed by a clean frame, run through the host's
//! cycle model; counted by the number of inverted bits.
//!
//! # What the 8-bit sum can promise
//! The checksum is the low byte of the sum of the bytes before it. One
//! inverted data bit changes the sum by ±2^k (k < 8), never 0 mod 256: every
//! one-bit error is seen. Two inverted data bits in different bytes are
//! blind when their changes cancel: the same bit k, one 0→1 and one 1→0,
//! or bit 7 turned the same way in both (±128 ± 128 = ±256). Framing (start
//! and stop bits), the header `FF 81`, the length and the gaps see the
//! rest, with one hole: an inverted start bit makes the receiver start
//! inside the character, and the bytes it then reads are new ones that the
//! sum catches only with probability 255/256, so even one inverted bit can
//! escape (about 1 in 256 × 10 of them). [`blind`] decides, from the
//! corrupted levels alone, read bit by bit as any UART reads them, whether a
//! corruption leaves a well-formed frame; the tests hold the host to it in
//! both directions: it flags every corruption that [`blind`] calls visible
//! and accepts every one it calls blind.
//!
//! The host runs at 6 clocks per bit (the receiver's minimum) so that
//! 100 000 frames take seconds.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::encoder::Mode;
use super::frames;
use super::host::{Host, HostConfig, In};
pub use crate::uart::campaign::levels;
use crate::uart::campaign::{characters, corrupt, Tally};
use crate::uart::Parity;

/// Clocks per bit of the campaign's host.
pub const CLOCKS_PER_BIT: u64 = 6;

/// Idle bits before, between and after the frames (longer than the host's 15-bit gap).
const IDLE_BITS: usize = 20;

/// The campaign host for `bits`.
pub fn host_config(bits: u32) -> HostConfig {
    HostConfig {
        mode: Mode::TimedSend,
        bits,
        gray: false,
        parity: Parity::None,
        tag_address: false,
        zero_answer: true,
        clocks_per_bit: CLOCKS_PER_BIT,
        gap_clocks: 15 * CLOCKS_PER_BIT,
        stale_clocks: 0,
        timeout_clocks: 1000,
        trigger_low_clocks: 10,
        clr_low_clocks: 10,
    }
}

/// The campaign's result: the tally of [`crate::uart::campaign`] and the recoveries.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Report {
    /// Detected and undetected by inverted bits, and against [`blind`].
    pub tally: Tally,
    /// The clean frame after a corruption was not read (must be 0).
    pub lost_recoveries: u64,
}

impl std::ops::Deref for Report {
    type Target = Tally;
    fn deref(&self) -> &Tally {
        &self.tally
    }
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.tally.table(
            f,
            "frames",
            "8-bit sum promise: every inverted data bit seen; two are blind only when their changes cancel mod 256; a character re-framed by an inverted start bit passes with p = 1/256",
        )?;
        write!(
            f,
            "total {}, disagreements with the checks {}, clean frames lost after a corruption {}",
            self.total(),
            self.disagreements,
            self.lost_recoveries
        )
    }
}

/// Whether the corrupted `levels` (one per bit time, idle high before and
/// after) still read as one well-formed frame for `bits`: decoded bit by bit
/// as any UART does (a 0 after idle or after a stop bit starts a
/// character, eight data bits, a stop bit that must be 1, a low stop bit
/// waits for the line to rise), no framing error, exactly `L` characters,
/// and they decode (header `FF 81`, checksum). A flipped start bit makes
/// the receiver start inside the character: the characters it then reads
/// are new bytes, and the sum sees them only with probability 255/256.
pub fn blind(levels: &[bool], bits: u32) -> bool {
    characters(levels).is_some_and(|bytes| frames::decode(&bytes, bits).is_ok())
}

/// Runs a host over idle, the corrupted frame, idle, the clean frame, idle.
/// Returns (flagged or nothing accepted during the corrupted frame, clean frame read).
pub fn judge(bits: u32, corrupted: &[bool], clean: &[bool], clean_value: u32) -> (bool, bool) {
    judge_with(bits, corrupted, clean, clean_value, true)
}

/// [`judge`], with fast-forward through the host's quiet cycles
/// ([`Host::quiet`], never across a bit boundary, where the line may
/// change) or stepping every cycle.
pub fn judge_with(
    bits: u32,
    corrupted: &[bool],
    clean: &[bool],
    clean_value: u32,
    fast_forward: bool,
) -> (bool, bool) {
    let mut host = Host::new(host_config(bits)).expect("campaign host configuration is valid");
    let idle = vec![true; IDLE_BITS];
    let first_end = (IDLE_BITS + corrupted.len() + IDLE_BITS) as u64 * CLOCKS_PER_BIT;
    let line: Vec<bool> = idle
        .iter()
        .chain(corrupted)
        .chain(&idle)
        .chain(clean)
        .chain(&idle)
        .copied()
        .collect();
    let (mut flagged, mut accepted, mut recovered) = (false, false, false);
    let end = line.len() as u64 * CLOCKS_PER_BIT;
    let mut t = 0;
    while t < end {
        let input = In {
            i_rx: line[(t / CLOCKS_PER_BIT) as usize],
            ..In::default()
        };
        // A quiet cycle shows the last output again: no pulse, nothing to tally.
        let quiet = if fast_forward {
            host.quiet(&input).min(CLOCKS_PER_BIT - t % CLOCKS_PER_BIT)
        } else {
            0
        };
        if quiet > 0 {
            host.skip(quiet);
            t += quiet;
            continue;
        }
        let out = host.step(&input);
        let err = out.o_err_checksum
            || out.o_err_parity
            || out.o_err_frame
            || out.o_err_address
            || out.o_err_timeout;
        if t < first_end {
            flagged |= err;
            accepted |= out.o_valid;
        } else if out.o_valid {
            recovered = out.o_position == clean_value;
        }
        t += 1;
    }
    (flagged || !accepted, recovered)
}

/// Runs `trials` corruptions: four in ten invert one bit, three in ten two,
/// the rest 3 to `max_flips`.
pub fn run(trials: u64, max_flips: usize, seed: u64) -> Report {
    run_with(trials, max_flips, seed, true)
}

/// [`run`], with fast-forward through quiet cycles or stepping every cycle.
pub fn run_with(trials: u64, max_flips: usize, seed: u64, fast_forward: bool) -> Report {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut report = Report::default();
    for _ in 0..trials {
        let bits = [16u32, 24, 32][rng.random_range(0..3)];
        let value = if bits == 32 {
            rng.random::<u32>()
        } else {
            rng.random::<u32>() & ((1 << bits) - 1)
        };
        let clean = levels(&frames::encode(value, bits));
        let (k, corrupted) = corrupt(&mut rng, &clean, max_flips);
        let next = rng.random::<u32>() & 0xFFFF;
        let next_frame = levels(&frames::encode(next, bits));
        let (detected, recovered) = judge_with(
            bits,
            &corrupted,
            &next_frame,
            next & if bits == 32 {
                u32::MAX
            } else {
                (1 << bits) - 1
            },
            fast_forward,
        );
        report.tally.add(k, detected, blind(&corrupted, bits));
        if !recovered {
            report.lost_recoveries += 1;
        }
    }
    report
}
