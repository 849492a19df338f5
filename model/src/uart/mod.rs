//! The 10-bit frame receiver shared by ESL (seed 000, 10 Mbps) and Tamagawa
//! T-format (seed 002, 2.5 Mbps, "permissible jitter ±100 ns"): start bit 0,
//! 8 data bits LSB first, stop bit 1, line idle high. [`Receiver`] is the
//! model of `hdl/rtl/uart_rx.v`; [`Transmitter`] is an ideal-or-not sender
//! (baud error, jitter) for benches; [`Bench`] wires them for the `uart_rx`
//! core's own vectors.
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
mod receiver;
mod transmitter;
mod wire_tap;

pub use bench::{Bench, BenchConfig, LowPulse, Transaction};
pub use receiver::{In, Out, Receiver, ReceiverConfig, State};
pub use transmitter::Transmitter;
pub use wire_tap::WireTap;

/// The sender baud errors (in percent, positive = sender fast) between which
/// a receiver with `clocks_per_bit` samples every bit of a frame inside the
/// bit, when each edge may also move by up to `jitter_cycles`.
pub fn tolerance(clocks_per_bit: u64, jitter_cycles: f64) -> (f64, f64) {
    let c = clocks_per_bit as f64;
    let half = (clocks_per_bit / 2) as f64;
    // Stop-bit sample at s = HALF + 9C (+1 worst case); it must be after the
    // stop bit starts (9T + jitter) and before it ends (10T - jitter).
    let slowest_t = (half + 9.0 * c - jitter_cycles) / 9.0; // T below this: sample after 9T
    let fastest_t = (half + 9.0 * c + 1.0 + jitter_cycles) / 10.0; // T above this: sample before 10T
    // Sender fast by δ has T = C / (1 + δ).
    let low = (c / slowest_t - 1.0) * 100.0;
    let high = (c / fastest_t - 1.0) * 100.0;
    (low, high)
}

#[cfg(test)]
mod tests;
