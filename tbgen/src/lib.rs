//! `tbgen`: turns a scenario into golden vectors, waveforms and a transcript.
//!
//! A scenario (a TOML file, or one of the built-ins under `scenarios/`) says
//! which core, how it is configured, what the encoder and the cable do and
//! what the host asks for. [`generate::generate`] runs the model and writes
//! four files side by side:
//!
//! | file | what it is |
//! |---|---|
//! | `<name>.hex` | vectors for `$readmemh` (docs/vectors.md) |
//! | `<name>.vcd` | waveforms: line, core ports, decoded fields |
//! | `<name>.json` | transcript of every transaction |
//! | `<name>.gtkw` | GTKWave layout for the `.vcd` |
//!
//! ```no_run
//! use tbgen::{builtin, generate};
//! let scenario = builtin::find("ssi_seed_12bit").unwrap();
//! generate::generate(&scenario, std::path::Path::new("out")).unwrap();
//! ```

pub mod bench;
pub mod biss_tools;
pub mod builtin;
pub mod capture;
pub mod crc_cmd;
pub mod endat_decode;
pub mod error;
pub mod generate;
pub mod gtkw;
pub mod scenario;
pub mod timing_cmd;
pub mod tformat_decode;
pub mod tformat_tools;
pub mod esl_tools;
pub mod transcript;
pub mod vectors;
pub mod wave;

pub use error::{Error, Result};
