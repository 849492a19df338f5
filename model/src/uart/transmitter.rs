//! A sender of 10-bit frames with a baud error and jitter, for benches: it
//! places each bit edge at its exact time in picoseconds and rounds to the
//! system clock, so a 3 % fast sender drifts as a real one does.

use std::collections::VecDeque;

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::Parity;

/// One frame the transmitter has started: its first cycle and its byte.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Sent {
    /// Cycle of the start bit's falling edge.
    pub start_cycle: u64,
    /// The byte.
    pub byte: u8,
}

/// The first cycle from `from` on whose start (`cycle × period_ps`) is at
/// or after `t_ps`: the cycle in which an edge or a driver change at `t_ps`
/// shows, by the comparison the models' `step`s make (fast-forward: the
/// cycles before it are quiet). Cycle × period stays below 2^53 ps (the
/// vector format's 32-bit cycles), so the product is exact in `f64` either way.
pub fn first_cycle_at(from: u64, period_ps: u64, t_ps: f64) -> u64 {
    let estimate = (t_ps / period_ps as f64).ceil();
    let mut c = if estimate > from as f64 {
        estimate.min(1e18) as u64
    } else {
        from
    };
    while c > from && ((c - 1) * period_ps) as f64 >= t_ps {
        c -= 1;
    }
    while ((c * period_ps) as f64) < t_ps {
        c += 1;
    }
    c
}

/// The sender.
#[derive(Debug, Clone)]
pub struct Transmitter {
    period_ps: f64,
    bit_ps: f64,
    jitter_ps: f64,
    rng: Pcg64Mcg,
    /// Pending levels as (time in ps, level), in time order.
    edges: VecDeque<(f64, bool)>,
    queued_until_ps: f64,
    level: bool,
    cycle: u64,
    sent: Vec<Sent>,
    pending_frames: VecDeque<(f64, u8)>,
    parity: Parity,
}

impl Transmitter {
    /// A sender at `baud × (1 + error_percent / 100)` on a system clock of
    /// `period_ps`, each edge moved by up to ±`jitter_ps`.
    pub fn new(period_ps: u64, baud: f64, error_percent: f64, jitter_ps: f64, seed: u64) -> Self {
        Transmitter {
            period_ps: period_ps as f64,
            bit_ps: 1e12 / (baud * (1.0 + error_percent / 100.0)),
            jitter_ps,
            rng: Pcg64Mcg::seed_from_u64(seed),
            edges: VecDeque::new(),
            queued_until_ps: 0.0,
            level: true,
            cycle: 0,
            sent: Vec::new(),
            pending_frames: VecDeque::new(),
            parity: Parity::None,
        }
    }

    /// The same sender with a parity bit after the data bits (11-bit frames).
    pub fn with_parity(mut self, parity: Parity) -> Self {
        self.parity = parity;
        self
    }

    /// Bits per character on the line: 10, or 11 with parity.
    pub fn frame_bits(&self) -> usize {
        self.parity.frame_bits()
    }

    /// Queues raw levels (first level first, one per bit time) to start no
    /// earlier than `at_ps`, after `gap_bits` idle bits following the
    /// previous frame: a character with a wrong parity or stop bit, a
    /// truncated one, a break. Returns the start time in ps.
    pub fn send_levels(&mut self, levels: &[bool], at_ps: f64, gap_bits: f64) -> f64 {
        let start = at_ps.max(self.queued_until_ps + gap_bits * self.bit_ps);
        let mut previous = self.edges.back().map_or(self.level, |e| e.1);
        for (i, &b) in levels.iter().enumerate() {
            if b != previous {
                let j = if self.jitter_ps > 0.0 {
                    self.rng.random_range(-self.jitter_ps..=self.jitter_ps)
                } else {
                    0.0
                };
                self.edges
                    .push_back((start + i as f64 * self.bit_ps + j, b));
                previous = b;
            }
        }
        if !previous {
            self.edges
                .push_back((start + levels.len() as f64 * self.bit_ps, true));
        }
        self.queued_until_ps = start + levels.len() as f64 * self.bit_ps;
        start
    }

    /// Queues `byte` as [`Transmitter::send`] does, its levels `levels`
    /// (a wrong parity or stop bit): the frame is still reported by
    /// [`Transmitter::sent`] as `byte`'s.
    pub fn send_byte_levels(&mut self, byte: u8, levels: &[bool], at_ps: f64, gap_bits: f64) {
        let start = self.send_levels(levels, at_ps, gap_bits);
        self.pending_frames.push_back((start, byte));
    }

    /// The length of one bit in ps.
    pub fn bit_ps(&self) -> f64 {
        self.bit_ps
    }

    /// Queues `byte` to start no earlier than `at_ps`, after `gap_bits` idle
    /// bits following the previous frame.
    pub fn send(&mut self, byte: u8, at_ps: f64, gap_bits: f64) {
        if self.parity == Parity::None {
            let start = at_ps.max(self.queued_until_ps + gap_bits * self.bit_ps);
            let mut bits = [true; 10];
            bits[0] = false;
            for (i, b) in bits.iter_mut().enumerate().take(9).skip(1) {
                *b = (byte >> (i - 1)) & 1 == 1;
            }
            let mut previous = true;
            for (i, &b) in bits.iter().enumerate() {
                if b != previous {
                    let j = if self.jitter_ps > 0.0 {
                        self.rng.random_range(-self.jitter_ps..=self.jitter_ps)
                    } else {
                        0.0
                    };
                    self.edges
                        .push_back((start + i as f64 * self.bit_ps + j, b));
                    previous = b;
                }
            }
            self.pending_frames.push_back((start, byte));
            self.queued_until_ps = start + 10.0 * self.bit_ps;
        } else {
            let levels = self.parity.levels(byte);
            let start = self.send_levels(&levels, at_ps, gap_bits);
            self.pending_frames.push_back((start, byte));
        }
    }

    /// The time in ps at which everything queued has been sent.
    pub fn idle_from_ps(&self) -> f64 {
        self.queued_until_ps
    }

    /// The level the line keeps until the next edge falls due.
    pub fn level(&self) -> bool {
        self.level
    }

    /// Frames started so far.
    pub fn sent(&self) -> &[Sent] {
        &self.sent
    }

    /// How many of the next [`Transmitter::step`]s change nothing: no edge
    /// and no frame start falls due in them, so the line keeps its level
    /// (fast-forward; `u64::MAX` once everything queued is sent).
    pub fn quiet(&self) -> u64 {
        let next = [
            self.edges.front().map(|e| e.0),
            self.pending_frames.front().map(|f| f.0),
        ]
        .into_iter()
        .flatten()
        .fold(f64::INFINITY, f64::min);
        if next == f64::INFINITY {
            return u64::MAX;
        }
        first_cycle_at(self.cycle, self.period_ps as u64, next) - self.cycle
    }

    /// The same as `n` calls of [`Transmitter::step`], for `n` up to
    /// [`Transmitter::quiet`]: only the cycle count moves.
    pub fn skip(&mut self, n: u64) {
        self.cycle += n;
    }

    /// The line level during the current cycle; then advances one cycle.
    /// An edge at time `t` shows from the first cycle that starts at or after `t`.
    pub fn step(&mut self) -> bool {
        let now = self.cycle as f64 * self.period_ps;
        while let Some(&(t, level)) = self.edges.front() {
            if t > now {
                break;
            }
            self.level = level;
            self.edges.pop_front();
        }
        while let Some(&(t, byte)) = self.pending_frames.front() {
            if t > now {
                break;
            }
            self.sent.push(Sent {
                start_cycle: self.cycle,
                byte,
            });
            self.pending_frames.pop_front();
        }
        self.cycle += 1;
        self.level
    }
}
