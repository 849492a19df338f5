//! Cycle-accurate models of the master side of position-encoder interfaces,
//! of the encoders they talk to, and of the cable between them.
//!
//! Time is a count of system-clock cycles of a documented frequency `f_sys`
//! ([`time::Timebase`]). Every model is a synchronous machine stepped once per
//! rising edge of that clock: `step(&mut self, &In) -> Out`, where `In` and `Out`
//! are plain structs whose field names equal the Verilog port names of the
//! matching core in `hdl/rtl/`. The caller owns time; nothing here sleeps,
//! reads a wall clock or keeps hidden timers.
//!
//! ```
//! use model::ssi::{Bench, BenchConfig};
//!
//! // The seed's 12-bit SSI example (SAR58K24 manual): the encoder holds 495.
//! let mut cfg = BenchConfig::seed_example();
//! cfg.positions = vec![495];
//! let run = model::testbench::run_to_end(Bench::new(&cfg).unwrap());
//! assert_eq!(run.transactions[0].position, Some(495));
//! ```

pub mod angle;
pub mod biss;
pub mod bits;
pub mod can;
pub mod canopen;
pub mod compliance;
pub mod crc;
pub mod endat;
pub mod error;
pub mod esl;
pub mod gray;
pub mod half_duplex;
pub mod line;
pub mod modbus;
pub mod ports;
pub mod protocol;
pub mod rules;
pub mod sar58k24;
pub mod ssi;
pub mod testbench;
pub mod tformat;
pub mod time;
pub mod toml_place;
pub mod trace;
pub mod uart;
pub mod wire;

pub use error::{ConfigError, Result};
pub use ports::{Port, Ports};
pub use testbench::{Run, Setup, Testbench, Transaction};
pub use time::Timebase;
