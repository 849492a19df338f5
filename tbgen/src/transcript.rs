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
    pub fn new(
        protocol: &'a str,
        file: &std::path::Path,
        signals: &[(&'static str, &str)],
        transactions: &'a [T],
    ) -> Self {
        Decoded {
            format: FORMAT,
            source: "decode",
            protocol,
            file: file.display().to_string(),
            signals: signals
                .iter()
                .map(|&(role, name)| (role, name.to_string()))
                .collect(),
            transactions,
        }
    }
}

/// The bytes a transcript of a half-duplex host (T-format, ESL) says were on
/// the wire at the host, in order: each request's `wire_requests`, then its
/// `wire_answers`. `None` if the transcript is not of that shape (one answer
/// list per request, one wire request per request sent).
pub fn wire_bytes(transcript: &serde_json::Value) -> Option<Vec<u64>> {
    let bytes = |set: &serde_json::Value| -> Option<Vec<u64>> {
        set.as_array()?.iter().map(|b| b.as_u64()).collect()
    };
    let mut expected = Vec::new();
    for t in transcript["transactions"].as_array()? {
        let (requests, answers) = (
            t["wire_requests"].as_array()?,
            t["wire_answers"].as_array()?,
        );
        if requests.len() != answers.len()
            || t["requests"]
                .as_u64()
                .is_some_and(|sent| requests.len() as u64 != sent)
        {
            return None;
        }
        for (request, answer) in requests.iter().zip(answers) {
            expected.extend(bytes(request)?);
            expected.extend(bytes(answer)?);
        }
    }
    Some(expected)
}

/// sigrok's `uart` decoder on the line at a half-duplex host at `baud`: it
/// must find, in order, every character the transcript says was on the wire
/// ([`wire_bytes`]), faults included.
pub fn sigrok_wire_bytes(
    transcript: &serde_json::Value,
    baud: f64,
) -> Option<crate::registry::SigrokCheck> {
    Some(crate::registry::SigrokCheck {
        decoder: format!("uart:rx=line_at_host:baudrate={}", baud as u64),
        annotation: "uart=rx-data",
        expected: wire_bytes(transcript)?
            .into_iter()
            .map(|b| Some(b as u128))
            .collect(),
    })
}
