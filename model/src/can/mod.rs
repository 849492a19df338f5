//! CAN 2.0 at bit level (ISO 11898-1, classical CAN): bit timing and
//! synchronisation, stuffing, CRC-15, acknowledgement, arbitration, error
//! detection and confinement, for the CAN encoders of seeds 001 (SAR58K24
//! CAN mode, 250 kbit/s default) and 003 (Leine & Linde CANopen DS 406
//! gateway, 10 kbit/s to 1 Mbit/s). The seeds do not restate CAN; this
//! module follows public descriptions of the standard, cited in
//! `docs/timing/can.md`.
//!
//! [`Controller`] is the node `hdl/rtl/can_controller.v` mirrors; [`Bus`]
//! is a wired-AND of nodes with transceiver loop delays, cable positions and
//! oscillator offsets; [`Emulator`] is a scripted generic node for test
//! benches; [`Bench`] puts the controller on a bus with emulated nodes.
//!
//! ```
//! use model::can::frame::Frame;
//!
//! // A standard data frame: its CRC-15 and the wire length with stuff bits.
//! let f = Frame::data(0x123, &[0x11, 0x22]);
//! assert_eq!(f.validate("frame"), Ok(()));
//! assert!(f.wire_bits(true).len() >= 1 + 11 + 1 + 6 + 16 + 15 + 3 + 7);
//! ```

pub mod bench;
pub mod bus;
pub mod campaign;
pub mod clauses;

pub mod controller;
pub mod decode;
pub mod descriptor;
pub mod emulator;
pub mod frame;
pub mod rules;
pub mod timing;

pub use bench::{Bench, BenchConfig, Transaction};
pub use bus::Bus;
pub use controller::{Controller, ControllerConfig, ErrorKind, In, Out, State};
pub use emulator::Emulator;
pub use timing::{BitClock, BitTiming};
