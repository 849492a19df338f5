//! SSI: the synchronous serial interface of absolute encoders (seed
//! `001_dad17a172253ad83.txt`, SAR58K24 manual, "Synchronous serial").
//!
//! The reader ([`Master`], Verilog `ssi_master`) clocks the encoder
//! ([`Encoder`]) over a cable ([`crate::line`]); [`Bench`] wires the three
//! together with a host that asks for reads.
//!
//! # What the seed fixes
//! Clock and data idle high. The first falling clock edge stores the value;
//! the encoder puts the MSB on the line with the first rising edge and one bit
//! with each rising edge after it. `T_cs > 4 µs`, `100 kHz < f_clk < 250 kHz`,
//! `T_m > 500 µs` ("varies according to the actual situation and products").
//! Too many clocks shift zeros in (a 12-bit value read with 14 clocks exceeds
//! 1000°) or, "if the timing is precisely matched", the high bits again; too
//! few clocks give the top bits only (8 of 12 bits: at most 22.4121° when
//! converted as 12 bits).
//!
//! # Cycle-level interpretation (the seed's timing figure is missing)
//! * The master samples each bit at a falling clock edge, the one after the
//!   rising edge that put it on the line, so an `n`-bit read has `n + 1`
//!   falling edges: the first stores the value, the others sample bits 1..n.
//! * `T_cs` is read as the length of the first low phase (the time from the
//!   storing edge to the first rising edge). `T_CS_CLOCKS` is at least half a
//!   clock period.
//! * The clock is high `HIGH_CLOCKS` and low `LOW_CLOCKS` cycles
//!   (`CLOCKS_PER_BIT / 2` each for an even divider). An odd divider (4 MHz
//!   from 100 MHz, `f_sys / 25`: 13 high, 12 low) gives the high phase the
//!   extra cycle: a bit leaves the encoder at a rising edge and is captured
//!   after the next falling edge, so the cable's round trip is budgeted in
//!   the high phase ([`crate::time::BitClock`], `docs/timing/ssi.md` "Odd dividers").
//! * After the last sample the clock returns high and stays high for
//!   `PAUSE_CLOCKS` (at least the encoder's `T_m`); the encoder holds the line
//!   low until its monoflop expires `T_m` after the last clock edge, then high.
//! * A sample is the level at the master's pin in the cycle the master drove the
//!   falling edge, plus `SAMPLE_DELAY` cycles (to compensate a long cable). Two
//!   synchroniser flops sit before the sampling logic, so the capture happens
//!   `2 + SAMPLE_DELAY` cycles after the falling edge, inside the low phase.
//! * Options: Gray decoding (serial: each binary bit is the previous binary bit
//!   XOR the Gray bit, MSB first), double read (clock `2n` bits from an
//!   encoder that repeats its value and compare the copies) and wire check
//!   (clock one bit more and require the `0` the encoder holds after its LSB,
//!   which catches a line stuck high). Double read and wire check exclude each
//!   other.
//!
//! ```text
//!  n = 3 bits, no options, H = HIGH_CLOCKS, L = LOW_CLOCKS
//!
//!  o_ssi_clk ‾‾‾‾‾\________/‾‾‾‾\____/‾‾‾‾\____/‾‾‾‾\____/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
//!  state     IDLE | LATCH  |HIGH|LOW |HIGH|LOW |HIGH|LOW | PAUSE      | IDLE
//!                 |<-T_CS->|<H >|<L >|
//!  data      ‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾X MSB    X b1     X LSB    X 0 ...(T_m)../‾‾‾‾‾
//!                 ^ store   ^ rise 1 ^ rise 2 ^ rise 3 ^ rise 4
//!  capture                       ^ fall 2 +2+SAMPLE_DELAY (MSB)
//!                                         ^ fall 3 (b1)   ^ fall 4 (LSB)
//!  o_busy    _____/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\____
//!  o_done    ___________________________________________/‾\__________________
//! ```
//! The cycle in which `o_done` pulses is the cycle the clock rises after the
//! last low phase; `o_position` and the error pulses are valid with it.

mod bench;
pub mod decode;
pub mod descriptor;
mod encoder;
mod master;
pub mod rules;

pub use bench::{
    Bench, BenchConfig, EncoderSettings, HostSettings, MasterSettings, StuckFault, Transaction,
};
pub use encoder::{AfterLsb, Encoder, EncoderConfig};
pub use master::{In, Master, MasterConfig, Out, State};

use serde::{Deserialize, Serialize};

/// How a position is coded on the wire.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum Code {
    /// Plain binary, MSB first.
    #[default]
    Binary,
    /// Reflected binary (Gray), MSB first.
    Gray,
}
