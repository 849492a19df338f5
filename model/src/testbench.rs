//! The two traits every protocol implements so that `tbgen` can drive it
//! without knowing it: [`Setup`] (a scenario's configuration of master,
//! device, cable and host) and [`Testbench`] (the running set-up, one system
//! clock per [`Testbench::step`]).
//!
//! Adding a protocol means writing its `BenchConfig: Setup` and its
//! `Bench: Testbench` in `model/src/<proto>/`, then one line in `tbgen`'s
//! protocol registry (`tbgen/src/lib.rs`, see the README's "Adding a
//! protocol"). A protocol module uses the shared modules (`time`, `line`,
//! `crc`, `uart`, `angle`, `gray`, `bits`...), never another protocol's.

use serde::Serialize;

use crate::trace::{Layout, Sample, Sink};
use crate::{Result, Timebase};

/// One transaction of a transcript.
pub trait Transaction: Serialize {
    /// First and last cycle of the transaction (host request to result).
    fn span(&self) -> (u64, u64);
}

/// A running set-up: host, master, cable and device, stepped together.
pub trait Testbench {
    /// What the transcript records per transaction.
    type Transaction: Transaction;
    /// The signals each sample carries.
    fn layout(&self) -> &Layout;
    /// One system-clock cycle of the whole set-up; fills `sample` in place
    /// when there is one (a run that records nothing passes `None` and saves
    /// the copying).
    fn step(&mut self, sample: Option<&mut Sample>);
    /// Whether the host is done and the tail has run.
    fn finished(&self) -> bool;
    /// Cycles stepped so far.
    fn cycle(&self) -> u64;
    /// The transactions so far, consuming the bench.
    fn into_transactions(self) -> Vec<Self::Transaction>;
}

/// A scenario's configuration of one protocol: what `tbgen` needs to run it
/// and to label its outputs.
pub trait Setup: Clone + std::fmt::Debug {
    /// The running set-up this configuration builds.
    type Bench: Testbench;
    /// The Verilog core the vectors drive (`ssi_master`).
    const CORE: &'static str;
    /// The scenario file's table for this protocol (`ssi`).
    const TABLE: &'static str;
    /// Checks every field; the error names the field within the table.
    fn validate(&self) -> Result<()>;
    /// The system clock.
    fn timebase(&self) -> Result<Timebase>;
    /// The core's Verilog parameters, in the order vector headers list them.
    fn verilog_parameters(&self) -> Result<Vec<(&'static str, u64)>>;
    /// Builds the set-up in its reset state.
    fn bench(&self) -> Result<Self::Bench>;
}

/// The result of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Run<T> {
    /// Cycles simulated.
    pub cycles: u64,
    /// One entry per transaction, in order.
    pub transactions: Vec<T>,
}

/// Runs `bench` to the end, handing every cycle's sample to `sink`.
pub fn run<B: Testbench, S: Sink>(mut bench: B, sink: &mut S) -> std::result::Result<Run<B::Transaction>, S::Error> {
    let mut sample = Sample::for_layout(bench.layout());
    while !bench.finished() {
        bench.step(Some(&mut sample));
        sink.sample(bench.cycle() - 1, &sample)?;
    }
    let cycles = bench.cycle();
    Ok(Run { cycles, transactions: bench.into_transactions() })
}

/// Runs `bench` to the end recording nothing (for tests and benchmarks).
pub fn run_to_end<B: Testbench>(mut bench: B) -> Run<B::Transaction> {
    while !bench.finished() {
        bench.step(None);
    }
    Run { cycles: bench.cycle(), transactions: bench.into_transactions() }
}
