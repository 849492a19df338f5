//! Reading the characters of an asynchronous line with an optional parity
//! bit, and grouping them into the exchanges of a half-duplex host: what
//! `tbgen decode sar` and `tbgen decode modbus` share. The character reader
//! is [`model::uart::line`] (shared with the co-simulation monitors); this
//! module adds what only the command line needs.

use serde::Serialize;

pub use model::uart::line::{bursts, chars, values, Char};
use model::uart::Parity;

/// Parses `none`, `odd` or `even` for `--parity`.
pub fn parse_parity(s: &str) -> Result<Parity, String> {
    match s {
        "none" => Ok(Parity::None),
        "odd" => Ok(Parity::Odd),
        "even" => Ok(Parity::Even),
        _ => Err(format!("`{s}`: give none, odd or even")),
    }
}

/// The JSON a line decoder prints: `items` decoded by `protocol` from
/// `path`, whose line and driver enable were `line` and `tx_en`.
pub fn to_json<T: Serialize>(protocol: &str, path: &std::path::Path, line: &str, tx_en: &str, items: &[T]) -> crate::Result<String> {
    let decoded = crate::transcript::Decoded::new(protocol, path, &[("line", line), ("tx_en", tx_en)], items);
    Ok(serde_json::to_string_pretty(&decoded).expect("decoded items serialise") + "\n")
}

/// For the decoders' tests: the built-in scenario `name` generated into
/// `dir`; its VCD and its transcript.
#[cfg(test)]
pub fn generated(name: &str, dir: &std::path::Path) -> (crate::scenario::Scenario, std::path::PathBuf, serde_json::Value) {
    let s = crate::builtin::find(name).unwrap();
    let summary = crate::generate::generate(&s, dir).unwrap();
    let gen = serde_json::from_str(&std::fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
    (s, summary.files[1].clone(), gen)
}
