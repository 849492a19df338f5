//! Fault campaign: random answers to function 03 (one or two registers)
//! with random line bits inverted anywhere in them, each run through the
//! master's cycle model after its request; counted by the number of
//! inverted bits.
//!
//! # What CRC-16 can promise
//! The Modbus CRC-16 (generator 0x8005, with the factor x + 1) sees every
//! error of 1, 2 or 3 inverted data bits and any odd number of them, and
//! every burst of up to 16 bits, in frames as short as these (at most 9
//! bytes, far below the generator's period); it misses a random larger
//! pattern with probability 2^-16. Framing sees inverted start and stop
//! bits, except when an inverted start bit makes the receiver start inside
//! the character: the bytes it then reads are new ones, which the CRC sees
//! with probability 1 − 2^-16. [`blind`] reads the corrupted levels bit by
//! bit as any UART reads them and says whether a valid answer remains; the
//! tests hold the master to it in both directions.
//!
//! The master runs at 6 clocks per bit so that 100 000 answers take seconds.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::frames;
use super::master::{In, Master, MasterConfig};
pub use crate::uart::campaign::levels;
use crate::uart::campaign::{characters, corrupt, Tally};
use crate::uart::Parity;

/// Clocks per bit of the campaign's master.
pub const CLOCKS_PER_BIT: u64 = 6;

/// The campaign master: t1.5 and t3.5 of 10-bit characters, 2000-cycle timeout.
pub fn master_config() -> MasterConfig {
    MasterConfig {
        clocks_per_bit: CLOCKS_PER_BIT,
        parity: Parity::None,
        t15_clocks: 15 * CLOCKS_PER_BIT,
        t35_clocks: 35 * CLOCKS_PER_BIT,
        timeout_clocks: 2000,
    }
}

/// The campaign's result: the tally of [`crate::uart::campaign`].
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Report {
    /// Detected and undetected by inverted bits, and against [`blind`].
    pub tally: Tally,
}

impl std::ops::Deref for Report {
    type Target = Tally;
    fn deref(&self) -> &Tally {
        &self.tally
    }
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.tally.table(f, "answers", "CRC-16 promise: every 1, 2 or 3 inverted data bits and every odd number seen; a re-framed character passes with p = 2^-16")?;
        write!(
            f,
            "total {}, disagreements with the checks {}",
            self.total(),
            self.disagreements
        )
    }
}

/// Whether corrupted `levels` still read, bit by bit, as a valid answer of
/// station `address` to a read of `count` registers: no framing error,
/// CRC, address, function 03, byte count and length.
pub fn blind(levels: &[bool], address: u8, count: u8) -> bool {
    let Some(bytes) = characters(levels) else {
        return false;
    };
    let n = 5 + 2 * count as usize;
    bytes.len() == n
        && frames::crc_ok(&bytes)
        && bytes[0] == address
        && bytes[1] == frames::READ_HOLDING
        && bytes[2] == 2 * count
}

/// Whether the master flags the answer `levels` (sent 100 cycles after its
/// request) to a read of `count` registers from `address`.
pub fn detected(address: u8, count: u8, levels: &[bool]) -> bool {
    detected_with(address, count, levels, true)
}

/// [`detected`], with fast-forward through the master's quiet cycles
/// ([`Master::quiet`], never across a change of the answer's line level) or
/// stepping every cycle.
pub fn detected_with(address: u8, count: u8, levels: &[bool], fast_forward: bool) -> bool {
    const LIMIT: u64 = 100_000;
    let mut m = Master::new(master_config()).expect("campaign master configuration is valid");
    let mut input = In {
        i_start: true,
        i_address: address,
        i_count: count,
        ..In::default()
    };
    let (mut driving, mut from) = (false, None::<u64>);
    // The line level step t + 1 sees, set after step t.
    let rx_after = |t: u64, from: Option<u64>| match from {
        Some(f) if t >= f => levels
            .get(((t - f) / CLOCKS_PER_BIT) as usize)
            .copied()
            .unwrap_or(true),
        _ => true,
    };
    let mut t = 0;
    while t < LIMIT {
        if fast_forward && t > 0 {
            // Steps t .. t + n - 1 see the levels set after t - 1 .. t + n - 2:
            // all the same up to the next bit boundary of the answer (an
            // output that does not change sets no new `from`).
            let s = t - 1;
            let boundary = match from {
                Some(f) if s < f => f,
                Some(f) => f + ((s - f) / CLOCKS_PER_BIT + 1) * CLOCKS_PER_BIT,
                None => u64::MAX,
            };
            let n = m
                .quiet(&input)
                .min(boundary.saturating_sub(s))
                .min(LIMIT - t);
            if n > 0 {
                m.skip(n);
                t += n;
                input.i_rx = rx_after(t - 1, from);
                continue;
            }
        }
        let out = m.step(&input);
        input.i_start = false;
        if driving && !out.o_tx_en {
            from = Some(t + 100);
        }
        driving = out.o_tx_en;
        input.i_rx = rx_after(t, from);
        if out.o_done {
            return !out.o_valid;
        }
        t += 1;
    }
    unreachable!("the master ends every poll within its timeout and receive limit")
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
        let address = rng.random_range(1..=247u8);
        let count = rng.random_range(1..=2u8);
        let clean = levels(&frames::read_answer(address, count as u16, rng.random()));
        let (k, corrupted) = corrupt(&mut rng, &clean, max_flips);
        report.tally.add(
            k,
            detected_with(address, count, &corrupted, fast_forward),
            blind(&corrupted, address, count),
        );
    }
    report
}
