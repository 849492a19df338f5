//! SAR58K24 asynchronous serial (seed `001_dad17a172253ad83.txt`,
//! "Product communication", 3.1.1 to 3.3.4): 8N1 characters LSB first (odd or
//! even parity on request), 2400 to 115200 baud, position frames
//! `FF 81 <2, 3 or 4 data bytes, high first> <checksum>` in six modes: timed
//! send, timed + clear, pulse handshake, handshake + clear, bus command,
//! bus + clear. Modbus RTU, the seventh mode, is `model::modbus`.
//!
//! [`frames`] is the frame layer, [`Encoder`] the emulator, [`Host`] the
//! model of `hdl/rtl/sar_async_host.v`, [`Bench`] all of them on a cable.
//! The timing diagrams are in [`Host`]'s module (`host.rs`) and `docs/timing/sar58k24.md`.
//!
//! # Readings where the manual is silent or contradicts itself
//! * One protocol, three electrical forms: 3.1.x (RS-485 TXD±), 3.2.x
//!   (single-ended ETXD) and 3.3.x (RS-422 with a differential trigger
//!   clock) differ in wiring only; the model is the logic level.
//! * Bus answers carry `Bx` as second byte by default ([`frames::AnswerTag`]).
//! * The `AA 81 CC DD` command row of 3.2.5/3.2.6 is a garbled copy; only
//!   `BC AA Bx` and `BC AA Cx` are commands.
//! * CLR: a low level of at least `clr_min_low_us` (10 µs) zeroes; the
//!   manual gives the level only. T3: `acquisition_us` (20 µs), a field.
//! * Zeroing commands are answered with a frame of the new position
//!   (`answer_zeroing`), the manual being silent.
//! * The encoder's answer to a bus command follows after `answer_delay_us`.

mod bench;
pub mod campaign;
pub mod decode;
pub mod descriptor;
mod encoder;
pub mod frames;
mod host;
pub mod rules;
pub mod timing;

pub use crate::uart::{FaultKind, FrameFault};
pub use bench::{
    divider, Bench, BenchConfig, HostSettings, OpKind, Operation, SecondDriver, Transaction,
};
pub use encoder::{
    frame_seconds, max_refresh_hz, Encoder, EncoderConfig, EncoderIn, EncoderSettings, Mode,
    OutputCode, SentFrame, BAUD_RATES, REFRESH_RATES_HZ,
};
pub use frames::{checksum, data_bytes, decode, encode, AnswerTag, FrameError, HEADER};
pub use host::{Host, HostConfig, In, Out, State};
