//! Fault campaign: random standard and extended frames with random bits
//! inverted between SOF and the CRC delimiter, counted by the number of
//! inverted bits as detected (a stuff, CRC or form error, or a frame of
//! another length) or undetected (a frame accepted that differs from the
//! one sent).
//!
//! The receiver is [`frame::parse`], the destuffing parser; [`cross_check`]
//! runs the same corruptions through the cycle model of the controller and
//! requires the same verdict on every one.
//!
//! # What CAN lets through
//! CRC-15 alone detects every pattern of up to 5 inverted bits in a frame
//! of CAN length (Hamming distance 6), but stuffing comes first: an inverted
//! bit that creates or removes a stuff condition makes the receiver drop or
//! keep a bit, shifting everything after it; a second inversion can shift
//! it back, and what the CRC then sees is a burst that it misses with a
//! probability near 2^-15. E. Tran (CMU, 1999) measured 1.3 × 10^-7 for
//! random double-bit errors; random sampling of 10^5 corruptions cannot
//! expect to see one, so [`shift_pairs`] searches the pairs that shift and
//! shift back exhaustively and counts what passes.

use std::collections::BTreeMap;

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::controller::{Controller, ControllerConfig, In};
use super::frame::{self, stuff, Frame};
use super::timing::BitTiming;

/// Detected and undetected corruptions.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Counts {
    /// A receiver flagged the frame.
    pub detected: u64,
    /// A receiver accepted a frame other than the one sent.
    pub undetected: u64,
    /// A receiver accepted the frame sent (inversions that cancel; the CRC
    /// covers every bit, so only a bit outside what the frame reports, such
    /// as r0 or SRR with a CRC that still matches, could give this).
    pub harmless: u64,
}

/// What a receiver made of one corrupted frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Flagged.
    Detected,
    /// Accepted, another frame than the one sent.
    Undetected,
    /// Accepted, the frame sent.
    Harmless,
}

impl Counts {
    fn add(&mut self, v: Verdict) {
        match v {
            Verdict::Detected => self.detected += 1,
            Verdict::Undetected => self.undetected += 1,
            Verdict::Harmless => self.harmless += 1,
        }
    }
}

/// The campaign's result: inverted bits -> counts.
pub type Report = BTreeMap<usize, Counts>;

/// A random frame: standard or extended, data or remote, DLC 0 to 8.
pub fn random_frame(rng: &mut impl Rng) -> Frame {
    let ide = rng.random_bool(0.3);
    let rtr = rng.random_bool(0.1);
    let dlc = rng.random_range(0..=8u8);
    let id = if ide {
        rng.random_range(0..1u32 << 29)
    } else {
        rng.random_range(0..1u32 << 11)
    };
    let data = if rtr {
        Vec::new()
    } else {
        (0..dlc).map(|_| rng.random()).collect()
    };
    Frame {
        id,
        ide,
        rtr,
        dlc,
        data,
    }
}

/// Wire bits SOF through the CRC delimiter, the ACK slot dominant, and EOF.
fn wire(f: &Frame) -> Vec<bool> {
    f.wire_bits(true)
}

/// Inverts `flips` distinct random bits from SOF to the CRC delimiter.
pub fn corrupt(rng: &mut impl Rng, f: &Frame, flips: usize) -> (Vec<bool>, Vec<usize>) {
    let mut w = wire(f);
    let protected = stuff(&f.destuffed_bits()).len() + 1;
    let mut at: Vec<usize> =
        rand::seq::index::sample(rng, protected, flips.min(protected)).into_vec();
    at.sort_unstable();
    for &i in &at {
        w[i] = !w[i];
    }
    (w, at)
}

/// The parser's verdict.
pub fn verdict(sent: &Frame, wire: &[bool]) -> Verdict {
    match frame::parse(wire) {
        Ok(p) if p.frame == *sent => Verdict::Harmless,
        Ok(_) => Verdict::Undetected,
        Err(_) => Verdict::Detected,
    }
}

/// `trials` corruptions, 1 to 6 inverted bits each (uniform), from `seed`.
pub fn run(trials: u64, seed: u64) -> Report {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut report = Report::new();
    for _ in 0..trials {
        let f = random_frame(&mut rng);
        let flips = rng.random_range(1..=6usize);
        let (w, _) = corrupt(&mut rng, &f, flips);
        report.entry(flips).or_default().add(verdict(&f, &w));
    }
    report
}

/// The cycle model's verdict on a wire bit stream (8 quanta of one cycle
/// per bit, the line fed directly): detected when the controller raised an
/// error before it reported a frame, or never reported one.
pub fn controller_verdict(sent: &Frame, wire: &[bool]) -> Verdict {
    let cfg = ControllerConfig {
        timing: BitTiming {
            brp: 1,
            prop_seg: 3,
            phase_seg1: 2,
            phase_seg2: 2,
            sjw: 1,
        },
        sync_stages: 2,
    };
    let mut c = Controller::new(cfg).expect("campaign timing is valid");
    let levels = std::iter::repeat_n(true, 12)
        .chain(wire.iter().copied())
        .chain(std::iter::repeat_n(true, 12));
    for level in levels {
        for _ in 0..8 {
            let o = c.step(&In {
                i_can_rx: level,
                ..In::default()
            });
            if o.o_err_bit || o.o_err_stuff || o.o_err_crc || o.o_err_form || o.o_err_ack {
                return Verdict::Detected;
            }
            if o.o_rx_valid {
                let f = Frame {
                    id: o.o_rx_id,
                    ide: o.o_rx_ide,
                    rtr: o.o_rx_rtr,
                    dlc: o.o_rx_dlc,
                    data: frame::unpack(o.o_rx_data, frame::data_len(o.o_rx_dlc, o.o_rx_rtr)),
                };
                return if f == *sent {
                    Verdict::Harmless
                } else {
                    Verdict::Undetected
                };
            }
        }
    }
    Verdict::Detected
}

/// Runs `trials` corruptions through parser and controller; returns the
/// number of corruptions on which they disagree.
pub fn cross_check(trials: u64, seed: u64) -> u64 {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let mut disagree = 0;
    for _ in 0..trials {
        let f = random_frame(&mut rng);
        let flips = rng.random_range(1..=3usize);
        let (w, _) = corrupt(&mut rng, &f, flips);
        if verdict(&f, &w) != controller_verdict(&f, &w) {
            disagree += 1;
        }
    }
    disagree
}

/// Exhaustive search over the double inversions of `frames` random frames
/// in which each inversion changes the stuffing (creates or removes a stuff
/// bit within the next six bits, so that the receiver's destuffed stream
/// shifts) and the second lies within 32 bits after the first: returns
/// (pairs tried, pairs undetected).
pub fn shift_pairs(frames: u64, seed: u64) -> (u64, u64) {
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let (mut tried, mut missed) = (0, 0);
    for _ in 0..frames {
        let f = random_frame(&mut rng);
        let w = wire(&f);
        let protected = stuff(&f.destuffed_bits()).len() + 1;
        for i in 0..protected {
            let mut one = w.clone();
            one[i] = !one[i];
            if !changes_stuffing(&w, &one, i) {
                continue;
            }
            for j in i + 1..protected.min(i + 33) {
                let mut two = one.clone();
                two[j] = !two[j];
                if !changes_stuffing(&one, &two, j) {
                    continue;
                }
                tried += 1;
                if verdict(&f, &two) != Verdict::Detected {
                    missed += 1;
                }
            }
        }
    }
    (tried, missed)
}

/// Whether inverting bit `i` creates or removes a stuff bit within the next six.
fn changes_stuffing(a: &[bool], b: &[bool], i: usize) -> bool {
    let stuff_positions = |w: &[bool]| -> Vec<usize> {
        let (mut run, mut last) = (0u32, true);
        let mut out = Vec::new();
        for (k, &x) in w.iter().enumerate().take(i + 7) {
            if run == 5 {
                out.push(k);
                run = 1;
                last = x;
                continue;
            }
            if x == last {
                run += 1;
            } else {
                run = 1;
                last = x;
            }
        }
        out
    };
    stuff_positions(a) != stuff_positions(b)
}
