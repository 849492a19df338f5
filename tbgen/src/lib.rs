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
//!
//! The generic modules (`scenario`, `builtin`, `generate`, `vectors` and
//! `wave` (from the `tracefile` crate), `gtkw`, `transcript`, `capture`,
//! `crc_cmd`, `error`) know no protocol. Each protocol has its own folder, `tbgen/src/<table>/`, holding
//! what is only its own: the [`registry::Protocol`] implementation of its
//! model's `BenchConfig` and, if it has them, its decoder (`tbgen decode
//! <table>`) and cycle budget (`tbgen timing <table>`). The protocols are
//! listed once, in the model (`model::with_protocols!`, see [`registry`]).

pub mod bench;
pub mod builtin;
pub mod capture;
pub mod check;
pub mod closed_loop;
#[cfg(test)]
mod compliance;
pub mod crc_cmd;
#[cfg(test)]
mod descriptor_tests;
pub mod error;
pub mod fields;
pub mod generate;
pub mod gtkw;
pub mod gtkwave_filter;
pub mod interrupt;
pub mod probes;
pub mod progress;
pub mod registry;
pub mod rule_verdict;
pub mod scenario;
pub mod testbench_ports;
pub mod transcript;

// The per-cycle writers and the capture reader, compiled optimised in a
// crate of their own (tracefile/Cargo.toml), under their old names.
pub use tracefile::{vectors, wave};

pub use error::{Error, Result};

// The protocol registry: the model's list (`model::with_protocols!`),
// `stem => Variant(model module)`, made into this crate's modules, `Setup`
// and `PROTOCOLS` by `registry::protocols!`.
use registry::protocols;
model::with_protocols!(protocols);
