//! BiSS-C: the bidirectional synchronous serial interface of absolute
//! encoders (seed `001_dad17a172253ad83.txt`, SAR58K24 manual, "Synchronous
//! serial", BiSS-C part).
//!
//! The master ([`Master`], Verilog `biss_master`) clocks a chain of one to
//! three slaves ([`Slave`], wired together by [`Chain`]) over a cable
//! ([`crate::line`]); [`Bench`] adds a host that starts frames and register
//! accesses.
//!
//! ```
//! use model::biss::{Bench, BenchConfig};
//!
//! // Seed 001, BiSS-C: 16-bit 1000101011100011 = 35555 = 195.3094°, nE = 1, nW = 0.
//! let run = Bench::new(&BenchConfig::seed_example()).unwrap().run_to_end();
//! let slave = &run.transactions[0].slaves[0];
//! assert_eq!((slave.position, slave.angle_deg, slave.warning, slave.crc_ok), (35555, 195.3094, true, true));
//! assert!(slave.sent_bits.ends_with("001010")); // the CRC 110101, inverted on the wire
//! ```
//!
//! # What the seed fixes
//! MA and SLO idle high. "The first rising edge of MA+ is used to latch the
//! sensor state. The second rising edge of MA+ triggers the encoder to pull
//! SLO+ low" (the ack). SLO stays low until the start bit `1`, which is
//! followed by a `0` (CDS), the data MSB first, the error bit nE and the
//! warning bit nW (both active low) and a 6-bit CRC, `x^6 + x + 1`, initial
//! value 0, over data, nE and nW, sent inverted ([`crate::crc::BISS_CRC6`]).
//! The example: data `1000101011100011`, nE = 1, nW = 0 give CRC `110101`,
//! sent as `001010`; 35555 of 2^16 is 195.3094°. `TMAS > 100 ns` (MA up to
//! 10 MHz), `t_busy` at least 2 × TMAS, BiSS timeout 16 µs.
//!
//! # Cycle-level interpretation (the seed's timing figure is missing)
//! * **MA** is `f_sys / CLOCKS_PER_BIT`, high for `HIGH_CLOCKS` and low for
//!   `LOW_CLOCKS` cycles (`H = CLOCKS_PER_BIT/2` each for an even divider),
//!   starting low from idle. The slave changes SLO after each rising edge of
//!   MA at its pin. An odd divider (10 MHz from 90 MHz, `f_sys / 9`) gives the
//!   high phase the extra cycle: samples are placed by the measured delay,
//!   whatever the split, and the levels that end and separate frames are
//!   high (TMASH); the seed's TMASH/TMASL > 25 ns then bind the low phase
//!   ([`crate::time::BitClock`], `docs/timing/biss.md` "Odd dividers").
//! * **Line-delay compensation** (every frame): the master counts the cycles
//!   from its second rising edge to the first low level at the output of its
//!   two-flop SLO synchroniser (`o_delay`: cable both ways, the slave's output
//!   delay, the synchroniser). Then it samples SLO every `CLOCKS_PER_BIT`
//!   cycles, the first time `H + CLOCKS_PER_BIT` cycles after that ack edge:
//!   the middle of every bit cell as it arrives, whatever the cable. The
//!   clock keeps running until the last CRC bit has been sampled, so a long
//!   cable costs extra MA periods (which the slave answers with `0`).
//! * **Start-up calibration**: the first `CAL_FRAMES` frames are sampled by
//!   their own ack and their delays averaged (`o_delay_mean`); later frames
//!   are sampled as if their ack had come at the mean, unless it departs by
//!   more than `DELAY_TOL` (sampled by its own ack, `o_err_drift`).
//! * An ack later than `MAX_DELAY` cycles is not compensated: the master stops
//!   the clock (MA high) and watches SLO for `TIMEOUT_CLOCKS`: a late ack
//!   flags `o_err_delay`, none at all `o_err_ack` (slave absent, SLO stuck high
//!   or an open RS-485 line, which idles high).
//! * The start bit must come within `TIMEOUT_CLOCKS` of the ack (`o_err_start`).
//! * **Frame** on SLO: ack, start, then for each slave in chain order its CDS
//!   bit, data, nE, nW and CRC (width and polynomial per slave). After the
//!   last bit the slave holds SLO low until its BiSS timeout (no MA edge for
//!   `t_timeout`), then high.
//! * **End of frame**: after the last sample the master stops MA at the next
//!   half-period boundary where MA equals `!CDM` (the BiSS-C control bit is
//!   the inverted MA level during the timeout), waits for SLO low (the
//!   slave's timeout phase) and then high (the slave is ready again), at most
//!   `TIMEOUT_CLOCKS` from the stop (`o_err_timeout`), and returns MA high;
//!   a frame that held MA low (CDM = 1) raises it `H` cycles before `o_done`,
//!   so every MA high phase lasts at least `H + 1` cycles, also between
//!   back-to-back frames (seed: TMASH > 25 ns).
//! * A start while SLO is low (slave still in its timeout, or the line stuck
//!   low) is refused: `o_done` with `o_err_line` in the next cycle.
//! * **Register access** (BiSS-C control frame): one CDM bit per frame out,
//!   one CDS bit per frame back; see [`control`] and `docs/timing/biss.md`.
//!   It is one host operation: after `i_reg_start` the master runs the sync
//!   and control frames itself, back to back (IDLE restarts in the cycle
//!   after `o_done`), and ends with `o_reg_done`. BiSS-C commands (`CTS = 0`,
//!   `i_cmd_start`) run the same way.
//!
//! ```text
//!  one slave, 2 data bits, CRC shown as c5..c0, H = CLOCKS_PER_BIT / 2, no cable
//!
//!  o_ma   ‾‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\_ ... _/‾‾\__/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
//!  edge         1     2     3     4     5     6     7           n   (CDM = 0: MA stops high)
//!               latch ack
//!  SLO    ‾‾‾‾‾‾‾‾‾‾‾‾\_________/‾‾‾‾‾X CDS X d1  X d0  X nE ...X c0 X 0 ... 0 (t_timeout) /‾‾‾
//!                     |<-t_busy->| start
//!  sample             ^ack  (o_delay = cycles from edge 2 to ack at the synchroniser)
//!                        ^ack + H + k * CLOCKS_PER_BIT, k = 1, 2, ... (cell middles)
//!  state  IDLE| ACK      | START    | CDS | DATA      |ERR|WARN| CRC  | STOP | TIMEOUT | IDLE
//!  o_slave_valid                                                  /‾\ (per slave)
//!  o_done                                                                             /‾\
//! ```

mod bench;
pub mod campaign;
pub mod control;
pub mod decode;
pub mod descriptor;
mod master;
pub mod rules;
pub mod seed_timing;
mod slave;

pub use bench::{
    Bench, BenchConfig, CmdOp, CmdResult, DelayStep, FlipFault, HostSettings, MasterSettings,
    RegOp, RegResult, SlaveResult, SlaveSettings, StuckFault, Transaction,
};
pub use master::{In, Master, MasterConfig, Out, State, DATA_BITS, MAX_SLAVES, SYNC_STAGES};
pub use slave::{Chain, ControlFaults, Slave, SlaveConfig};

/// A CRC of the BiSS-C family with another width or polynomial: initial value
/// 0, sent inverted, MSB first, like [`crate::crc::BISS_CRC6`].
pub fn data_crc(width: u32, poly: u64) -> crate::crc::Algorithm {
    let all_ones = if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    };
    crate::crc::Algorithm {
        width,
        poly,
        wire_xor: all_ones,
        ..crate::crc::BISS_CRC6
    }
}
