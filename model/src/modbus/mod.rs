//! Modbus RTU as the SAR58K24 speaks it (seed `001_dad17a172253ad83.txt`,
//! 3.1.7): function 03 reading one register (up to 16 bits) or two (17 to
//! 32 bits) from 0x0000, data high byte first, CRC-16 low byte first
//! (`modbus-crc16` of [`crate::crc`]); the address query `FF A0 40 38`
//! answered `FF A0 <address> <CRC>`; factory defaults address 1, 19200
//! baud, no parity.
//!
//! [`Master`] is the model of `hdl/rtl/modbus_master.v` (timing diagram in
//! its docs), [`Device`] the SAR58K24 in Modbus mode, [`Bench`] both on a
//! cable, [`frames`] the frame layer.
//!
//! # Where the manual is silent (the Modbus serial-line specification is followed)
//! * t3.5 between frames, fixed 1750 µs above 19200 baud; t1.5 inside a
//!   frame, 750 µs above 19200 baud: a frame with a longer silence inside is
//!   discarded whole (device) or flagged `o_err_frame` (master).
//! * No answer to a broadcast (address 0), to another address, to a bad
//!   CRC, to a spoiled frame.
//! * Exceptions: function | 0x80 with 01 (unknown function), 02 (registers
//!   other than 0x0000..0x0001), 03 (count 0 or above 125; and, this
//!   project's choice, count 1 from an encoder above 16 bits, which one
//!   register cannot hold).
//! * "Change the device address": function 06 writing the new address
//!   (1..247) to holding register 0x0010, answered by the echo; the new
//!   address holds from the next request ([`frames::ADDRESS_REGISTER`]).
//! * The request's count field is registers (the examples' `00 01` /
//!   `00 02`), not "the number of bytes" of the prose.

mod bench;
pub mod campaign;
pub mod decode;
pub mod descriptor;
mod device;
pub mod frames;
mod master;
pub mod rules;
pub mod timing;

pub use bench::{Bench, BenchConfig, MasterSettings, OpKind, Operation, SecondDriver, Transaction};
pub use device::{Device, DeviceConfig, DeviceSettings, Seen, Verdict};
pub use master::{In, Master, MasterConfig, Out, State, MAX_CHARS, RECV_LIMIT_CHARS};
