//! The files of a model run, written and read.
//!
//! | module | what it does |
//! |---|---|
//! | [`wave`] | writes a run's samples as a VCD (`tbgen gen`, `tbgen bench`) |
//! | [`vectors`] | writes and reads golden vector files (docs/vectors.md) |
//! | [`capture`] | reads the value changes of a captured VCD's scalars (`tbgen decode`, `tbgen check`) |
//!
//! This is the part of tbgen that runs once per cycle or per value change;
//! it is a crate of its own so that it is compiled optimised while the rest
//! of tbgen is not (see Cargo.toml). tbgen re-exports `wave` and `vectors`
//! under its own name (`tbgen::wave`, `tbgen::vectors`).

pub mod capture;
pub mod vectors;
pub mod wave;
