//! ESL safety protocol of the QS35 encoder (seed `000_639d4f4573fb0912.txt`):
//! 10 Mbps half-duplex RS-485, 10-bit fields, CRC-8 (non-safety) and two
//! CRC-16 channels (safety), memory and registers, daisy chain.
//!
//! [`Host`] is the master (`hdl/rtl/esl_host.v`, built on `uart_rx` and
//! `crc_serial`), [`Encoder`] the QS35 emulator, [`Bench`] host, bus and
//! encoders. [`frames`] holds the field layouts of Table 12;
//! [`campaign`] the random-corruption campaign. `docs/timing/esl.md`
//! documents every decision.
//!
//! # One safety readout (Data ID 1), cycle-level interpretation
//! ```text
//!  host tx_en  _/‾‾ CF CRC (20 bits) ‾‾\_________________________________________________
//!  line        ‾\_CF_/\_CRC_/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_CF1_/\_SF1_/ .. \_SC1_/\_CRC1.1_/\_CRC1.2_/\_CF2_/ .. \_CRC2.2_/‾‾
//!                           |<--- 2 µs --->|<------------ 18 fields back to back ------------------>|
//!  enc tx_en   __________________________/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\__
//!  host state  IDLE| SEND  |    WAIT      |                     RECV                             |+1 bit|done
//! ```
//! * The host drives only its request (CF and its CRC-8 frame; memory access
//!   adds ADF and EDF): driver enable from the first start bit to the end of
//!   the last stop bit; its receiver is deaf while it drives.
//! * The encoder answers 2 µs (typ.) after the request's last stop bit.
//! * A frame set ends when no start bit follows a stop bit: the host waits
//!   one bit of idle receiver after the last field.
//! * The host checks both CRCs, the field count of Table 12, framing, CF1/CF2
//!   against the request, CA0/CA1, SC1/SC2 continuity per encoder address,
//!   RS against ABS, and the memory busy flag.
//! * B, C, D are one host operation: 8 requests, each answered,
//!   `REPEAT_GAP_CLOCKS` apart. A memory access answered busy is repeated
//!   after the read or write time, up to `BUSY_TRIES` requests; an accepted
//!   EEPROM write holds the operation for the write time, a page change for
//!   the 18 ms page delay.

mod bench;
pub mod campaign;
pub mod decode;
pub mod descriptor;
mod encoder;
pub mod frames;
mod host;
pub mod rules;

pub use bench::{
    error_names, request_for, Bench, BenchConfig, HostSettings, Intruder, Operation, RequestFlip,
    Transaction,
};
pub use encoder::{
    frame_bits, AnswerFlip, Encoder, EncoderConfig, EncoderSettings, MemoryInit, Request,
    SequenceJump, Truncation, PAGES,
};
pub use host::{Host, HostConfig, In, Out, State, MAX_FIELDS, QUIET_BITS, REPEATS};
