//! Tamagawa T-format (seed `002_088a60295d2565fd.txt`, Smart Abs TS5669 N127):
//! 2.5 Mbps half-duplex RS-485, 10-bit fields, Data IDs, CRC `X^8 + 1`.
//!
//! [`Host`] is the master (`hdl/rtl/tformat_host.v`, built on
//! `uart_rx`), [`Encoder`] the Smart Abs emulator, [`Bench`] both on a cable.
//! [`frames`] holds the field layouts.
//!
//! # One readout (Data ID 0), cycle-level interpretation
//! ```text
//!  host tx_en  _/‾‾‾ CF (10 bits) ‾‾\____________________________________________
//!  line        ‾\_s_sink_id_p_/‾‾‾‾‾‾‾‾‾‾‾\_CF_/\_SF_/\_ABS0_/\_ABS1_/\_ABS2_/\_CRC_/‾‾
//!                             |<-- 3 µs -->|<------ 6 fields back to back ------>|
//!  enc tx_en   ________________________/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\__
//!  host state  IDLE|  SEND  |    WAIT    |              RECV                  |+1 bit|done
//! ```
//! * The host drives only its request: driver enable from the first start bit
//!   to the end of the last delimiter, then off; its receiver is deaf while it
//!   drives ("never transmit any Request while it transmits the data").
//! * The encoder answers 3 µs (typ.) after the request's delimiter (7.1, 8.1).
//! * A frame set ends when no start bit follows a delimiter (7.2): the host
//!   waits one bit time of idle line after the last field.
//! * The host checks: the CRC (the XOR of all fields, CRC included, is 0), the
//!   number of fields the request asks for (Table 2; 4 for EEPROM), framing,
//!   the answer's control field against the request's (an abnormal request is
//!   answered with Data ID 3 data, Table 5), and ca0/ca1 in the status field.
//! * After a flawed answer the host waits in `QUIET` until its receiver has
//!   been idle for 20 bits (at most 120 bits: a stuck line cannot hang it;
//!   `RECV` is bounded the same way) before it reports `o_done`, so the next request
//!   cannot land on the rest of an answer whose framing was lost.
//! * Resets (7, 8, C) are one host operation: ten requests, each answered,
//!   `REPEAT_GAP_CLOCKS` apart (seed: 40 ms or more).
//!
//! # Interpretations where the figures are lost
//! * Sink code `010` in bits 0..2 of the control field (Data ID 0 = `0x02`,
//!   the byte public T-format material requests position with).
//! * Status field: bits 0..3 information (0), bit 4 ea0, bit 5 ea1, bit 6
//!   ca0, bit 7 ca1.
//! * EEPROM frame sets: write request CF ADF EDF CRC, read request CF ADF CRC;
//!   both answered CF ADF EDF CRC, ADF bit 7 = busy (Table 4).
//! * The answer to an abnormal request starts with Data ID 3's control field
//!   (`0x1A`): "the data as same as Data ID 3 is transmitted".
//! * Ten resets count only when each follows the one before by at least the
//!   reset interval and no other reset intervenes; a shorter interval starts
//!   the count again.

mod bench;
pub mod campaign;
pub mod decode;
pub mod descriptor;
mod encoder;
pub mod frames;
mod host;
pub mod rules;

pub use bench::{
    Bench, BenchConfig, HostSettings, LineFault, LineFaultKind, Operation, Transaction,
};
#[doc(hidden)]
pub use encoder::frame_bits;
pub use encoder::{
    AnswerFlip, AnswerTruncation, Encoder, EncoderConfig, EncoderSettings, EEPROM_SIZE,
};
pub use host::{always_flagged, tolerance, Host, HostConfig, In, Out, State, QUIET_BITS};
