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

/// What every `tbgen decode <protocol>` prints: the envelope of a `gen`
/// transcript for a capture. A capture has no scenario, system clock or
/// parameters, so those fields give way to the file and the signals read.
/// Each transaction uses the field names and meanings of the model's
/// transaction in the `gen` transcript for everything the line shows
/// (positions, bits, CRC status, errors); what only the model knows (the
/// value the encoder was told to send, cycle numbers) is left out, and times
/// are in picoseconds (`start_ps`). Each decoder's test decodes the waves
/// `gen` writes and asserts every field it emits equals `gen`'s field of the
/// same name.
#[derive(Debug, Serialize)]
pub struct Decoded<'a, T: Serialize> {
    /// [`FORMAT`], the same marker as a `gen` transcript.
    pub format: &'static str,
    /// Always `"decode"`, so a reader can tell a decoded capture from a
    /// model run.
    pub source: &'static str,
    /// The decoder (`biss`, `endat`, `esl`, `tformat`).
    pub protocol: &'a str,
    /// The VCD file read.
    pub file: String,
    /// Role of each signal read → its dotted path in the file.
    pub signals: std::collections::BTreeMap<&'static str, String>,
    /// Transactions in order.
    pub transactions: &'a [T],
}

impl<'a, T: Serialize> Decoded<'a, T> {
    /// The envelope of `transactions` decoded from `file`.
    pub fn new(protocol: &'a str, file: &std::path::Path, signals: &[(&'static str, &str)], transactions: &'a [T]) -> Self {
        Decoded {
            format: FORMAT,
            source: "decode",
            protocol,
            file: file.display().to_string(),
            signals: signals.iter().map(|&(role, name)| (role, name.to_string())).collect(),
            transactions,
        }
    }
}
