//! The 10-bit frame receiver shared by ESL (seed 000, 10 Mbps) and Tamagawa
//! T-format (seed 002, 2.5 Mbps, "permissible jitter ±100 ns"): start bit 0,
//! 8 data bits LSB first, stop bit 1, line idle high. [`Receiver`] is the
//! model of `hdl/rtl/uart_rx.v`; [`Transmitter`] is an ideal-or-not sender
//! (baud error, jitter) for benches; [`Bench`] wires them for the `uart_rx`
//! core's own vectors. [`Tx`] is the model of `hdl/rtl/uart_tx.v`. The
//! SAR58K24 and Modbus add an optional parity bit ([`Parity`], `PARITY` in
//! the RTL: 11-bit frames, state `PARITY_BIT`, `o_parity_err`); with the
//! default `Parity::None` every machine is the 10-bit one, cycle for cycle.
//! [`FrameFault`] and [`send_with_faults`] are the faults device emulators
//! inject into what they send.
//!
//! # Cycle-level behaviour
//! `i_rx` passes two synchroniser flops. In `IDLE` the first synchronised 0
//! starts a frame: `START` counts `HALF = CLOCKS_PER_BIT / 2` cycles and
//! checks the line is still 0 (else the low pulse was a glitch:
//! `o_start_err`). `DATA` then samples every `CLOCKS_PER_BIT` cycles, eight
//! times, LSB first, and `STOP` samples once more: 1 gives `o_valid` with
//! `o_data`, 0 gives `o_frame_err` (and `RECOVER` waits for the line to go
//! high again, so a held-low line is one error, not a stream of frames).
//! After a good stop bit the receiver is back in `IDLE` at mid-stop-bit, in
//! time for a next start bit that follows without a gap.
//!
//! ```text
//!  i_rx      ‾‾‾‾‾\_____ start _____X  d0  X  d1  X ... X  d7  X‾‾‾ stop ‾‾‾‾
//!  state     IDLE | START (HALF) |  DATA (8 × CLOCKS_PER_BIT)  | STOP | IDLE
//!  samples                      ^ mid start  ^ mid d0 ...  ^ mid d7    ^ mid stop
//!  o_valid   _____________________________________________________________/‾\_
//! ```
//!
//! # Tolerance
//! The pin's falling edge is first seen 2 to 3 cycles later (synchroniser
//! plus the edge's position inside a cycle), so sample `k` (0 = start,
//! 9 = stop) reads the pin `HALF + k × CLOCKS_PER_BIT + u` cycles after the
//! true edge, `u ∈ [0, 1)`. With the sender's bit lasting `T` cycles, every
//! sample is inside its bit while `9 T < HALF + 9 CLOCKS_PER_BIT` and
//! `HALF + 9 CLOCKS_PER_BIT + 1 < 10 T`: [`tolerance`] returns those bounds
//! as a baud error in percent, less a given jitter. At 100 MHz and 10 Mbps
//! (`CLOCKS_PER_BIT` = 10) that is −5.26 % to +4.17 % without jitter.

mod bench;
pub mod campaign;
pub mod descriptor;
mod fault;
pub mod line;
mod receiver;
mod second_driver;
mod transmitter;
mod tx;
pub mod watch;
mod wire_tap;

use serde::{Deserialize, Serialize};

pub use bench::{Bench, BenchConfig, LowPulse, Transaction};
pub use fault::{send_with_faults, FaultKind, FrameFault};
pub use receiver::{stop_rest_clocks, In, Out, Receiver, ReceiverConfig, State};
pub use second_driver::{bench_quiet, SecondDriver};
pub use transmitter::{first_cycle_at, Transmitter};
pub use tx::{Tx, TxConfig, TxIn, TxOut, TxState};
pub use wire_tap::WireTap;

/// The sender baud errors (in percent, positive = sender fast) between which
/// a receiver with `clocks_per_bit` samples every bit of a frame inside the
/// bit, when each edge may also move by up to `jitter_cycles`.
pub fn tolerance(clocks_per_bit: u64, jitter_cycles: f64) -> (f64, f64) {
    tolerance_for(clocks_per_bit, jitter_cycles, Parity::None)
}

/// [`tolerance`] for frames with or without a parity bit: the stop bit is
/// bit 9 of a 10-bit frame, or bit 10 of an 11-bit one.
pub fn tolerance_for(clocks_per_bit: u64, jitter_cycles: f64, parity: Parity) -> (f64, f64) {
    let c = clocks_per_bit as f64;
    let half = (clocks_per_bit / 2) as f64;
    let k = (parity.frame_bits() - 1) as f64;
    // Stop-bit sample at s = HALF + kC (+1 worst case); it must be after the
    // stop bit starts (kT + jitter) and before it ends ((k+1)T - jitter).
    let slowest_t = (half + k * c - jitter_cycles) / k; // T below this: sample after kT
    let fastest_t = (half + k * c + 1.0 + jitter_cycles) / (k + 1.0); // T above this: sample before (k+1)T
                                                                      // Sender fast by δ has T = C / (1 + δ).
    let low = (c / slowest_t - 1.0) * 100.0;
    let high = (c / fastest_t - 1.0) * 100.0;
    (low, high)
}

/// The parity bit of an asynchronous character. The 10-bit families (ESL,
/// T-format) have none; the SAR58K24 manual sends 8N1 and adds "parity
/// check or even check ... according to customer requirements" (seed 001,
/// "Product communication"): the bit then follows the eighth data bit.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum Parity {
    /// No parity bit (10-bit frames).
    #[default]
    None,
    /// Odd parity: data bits and parity bit hold an odd number of ones.
    Odd,
    /// Even parity: data bits and parity bit hold an even number of ones.
    Even,
}

impl Parity {
    /// The parity bit for `byte` (meaningless for `None`: false).
    pub fn bit(self, byte: u8) -> bool {
        let ones = byte.count_ones() % 2 == 1;
        match self {
            Parity::None => false,
            Parity::Odd => !ones,
            Parity::Even => ones,
        }
    }

    /// Bits per character on the line, start and stop included.
    pub fn frame_bits(self) -> usize {
        if self == Parity::None {
            10
        } else {
            11
        }
    }

    /// The levels of one character, first bit first: start, data LSB first,
    /// the parity bit if any, stop.
    pub fn levels(self, byte: u8) -> Vec<bool> {
        let mut v = Vec::with_capacity(11);
        v.push(false);
        v.extend((0..8).map(|i| (byte >> i) & 1 == 1));
        if self != Parity::None {
            v.push(self.bit(byte));
        }
        v.push(true);
        v
    }

    /// The Verilog `PARITY` parameter: 0 none, 1 odd, 2 even.
    pub fn code(self) -> u64 {
        match self {
            Parity::None => 0,
            Parity::Odd => 1,
            Parity::Even => 2,
        }
    }
}
