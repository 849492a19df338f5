//! The JSON transcript: every transaction of a run, what was sent, what was
//! decoded and which errors were flagged. `tbgen gen` writes it beside the
//! vectors; the `decode` commands of later protocols write the same shape
//! from a captured waveform.

use serde::Serialize;

/// A whole transcript.
#[derive(Debug, Serialize)]
pub struct Transcript<'a, T: Serialize> {
    /// Format marker and version.
    pub format: &'static str,
    /// The scenario name.
    pub scenario: &'a str,
    /// The core the vectors drive.
    pub core: &'a str,
    /// System clock in Hz.
    pub f_sys_hz: u64,
    /// Cycles simulated.
    pub cycles: u64,
    /// The core's Verilog parameters.
    pub parameters: std::collections::BTreeMap<String, u64>,
    /// Transactions in order.
    pub transactions: &'a [T],
}

/// Format marker of transcripts.
pub const FORMAT: &str = "tbgen-transcript 1";
