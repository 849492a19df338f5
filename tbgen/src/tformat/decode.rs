//! `tbgen decode tformat`: the line at a T-format host, captured as a VCD,
//! turned into the transactions of the `gen` transcript.
//!
//! Two scalars are read: the RS-485 line at the host and the host's driver
//! enable. The bytes alone cannot say who sent them (the answer begins with
//! the request's own control field), and the driver enable is what a
//! capture at a half-duplex transceiver has beside the line. Every
//! character is read with [`capture::uart_bytes`] twice:
//!
//! * on the line itself: the wire (`wire_requests`, `wire_answers`). A
//!   character whose start bit falls while the host drives is a request
//!   character; every other one belongs to the answer of the latest request,
//!   up to the next request.
//! * on what the host's receiver hears, the line forced high while the host
//!   drives (it is deaf then): the answer the host checks, with the seed's
//!   frame rules (7.2: the answer begins within the timeout after the
//!   request, and ends when no start bit follows a field within one bit
//!   time; the host stops listening 120 bits after the answer began).
//!
//! The answer is checked as the host does (CRC, field count and framing,
//! control field, ca0/ca1) and its fields go into registers that hold their
//! value, as the host's outputs do, so that `abs`, `sf`, ... equal the `gen`
//! transcript's even after a short or missing answer. The ten requests of a
//! reset (Data ID 7, 8, C) are one transaction, their errors ORed. What only
//! the model knows is left out: the request the host meant to send (`sent`,
//! which another driver can override on the wire), cycle numbers, the
//! encoder's own position.

use std::path::Path;

use model::tformat::frames::DataId;
use serde::Serialize;

use crate::capture::{self, Signal, UartByte};
use crate::transcript::Decoded;
use crate::Result;

/// Bit times after an answer's first start bit at which the host stops
/// receiving (`model::tformat::host::ANSWER_LIMIT_BITS`: the longest answer
/// and one field more).
const ANSWER_LIMIT_BITS: u64 = 120;

/// The most fields the host stores (Data ID 3's answer).
const MAX_FIELDS: usize = 11;

/// What the decoder needs besides the file.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Dotted path of the line at the host.
    pub line: String,
    /// Dotted path of the host's driver enable.
    pub tx_en: String,
    /// Bit rate, bit/s.
    pub baud: u64,
    /// The host's answer timeout, µs (`[tformat.host] timeout_us`).
    pub timeout_us: f64,
}

impl Default for Options {
    fn default() -> Self {
        Options { line: "top.line.line_at_host".into(), tx_en: "top.line.tx_en_host".into(), baud: 2_500_000, timeout_us: 10.0 }
    }
}

/// One host operation read off the line; the fields mean what they mean in
/// the `gen` transcript (`model::tformat::Transaction`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Transaction {
    /// 0-based operation number.
    pub index: usize,
    /// The host's driver turning on for the first request, ps.
    pub start_ps: u64,
    /// The Data ID of the request's control field on the wire (`null` if no
    /// request character could be read).
    pub data_id: Option<u8>,
    /// The answer's fields as the host's receiver heard them, up to the end
    /// of the frame set (the last answer, for a reset; at most 11).
    pub received: Vec<u8>,
    /// Every request frame set on the wire.
    pub wire_requests: Vec<Vec<u8>>,
    /// For each request, every character on the wire after it up to the next request.
    pub wire_answers: Vec<Vec<u8>>,
    /// Single-turn data (17 bits), held from the last answer that set it.
    pub abs: u32,
    /// Multi-turn data, held likewise.
    pub abm: u16,
    /// Status field, held likewise.
    pub sf: u8,
    /// ENID, held likewise.
    pub enid: u8,
    /// ALMC, held likewise.
    pub almc: u8,
    /// EEPROM address field, held likewise.
    pub adf: u8,
    /// EEPROM data field, held likewise.
    pub edf: u8,
    /// `crc`, `timeout`, `frame`, `cf_mismatch`, `comm_alarm`, in that order.
    pub errors: Vec<&'static str>,
}

/// The host's output registers and its field store: they keep their values
/// from one answer to the next.
#[derive(Debug, Default)]
struct Registers {
    fields: [u8; MAX_FIELDS],
    abs: u32,
    abm: u16,
    sf: u8,
    enid: u8,
    almc: u8,
    adf: u8,
    edf: u8,
}

/// One request and what followed it up to the next.
struct Exchange {
    start_ps: u64,
    end_ps: u64,
    request: Vec<u8>,
    answer: Vec<u8>,
}

/// Decodes `path` with `options`.
pub fn decode(path: &Path, options: &Options) -> Result<Vec<Transaction>> {
    let signals = capture::read(path, &[(&options.line, "--line"), (&options.tx_en, "--tx-en")])?;
    let (line, tx_en) = (&signals[0], &signals[1]);
    let bit_ps = 1_000_000_000_000 / options.baud;
    let timeout_ps = (options.timeout_us * 1e6) as u64;
    let wire = capture::uart_bytes(line, bit_ps);
    let heard_line = line.or(tx_en);
    let heard = capture::uart_bytes(&heard_line, bit_ps);
    // Each request runs from the driver turning on to the next turning on.
    let edges = tx_en.edges();
    let rises: Vec<u64> = edges.iter().filter(|e| e.1).map(|e| e.0).collect();
    let mut exchanges: Vec<Exchange> = rises
        .iter()
        .map(|&rise| Exchange { start_ps: rise, end_ps: tx_en.next_level(rise, false).unwrap_or(u64::MAX), request: Vec::new(), answer: Vec::new() })
        .collect();
    for ch in &wire {
        let Some(k) = rises.partition_point(|&r| r <= ch.start_ps).checked_sub(1) else { continue };
        let x = &mut exchanges[k];
        if ch.start_ps < x.end_ps { x.request.push(ch.value) } else { x.answer.push(ch.value) }
    }
    let mut regs = Registers::default();
    let mut out: Vec<Transaction> = Vec::new();
    for (k, x) in exchanges.iter().enumerate() {
        let next_ps = rises.get(k + 1).copied().unwrap_or(u64::MAX);
        let answer: Vec<UartByte> = heard.iter().filter(|c| c.start_ps >= x.end_ps && c.start_ps < next_ps).copied().collect();
        let request_cf = x.request.first().copied();
        let data_id = request_cf.map(|cf| (cf >> 3) & 0xF);
        let (received, errors) = check(&answer, request_cf, data_id, x.end_ps, timeout_ps, bit_ps, &heard_line, &mut regs);
        let reset = data_id.and_then(DataId::from_code).is_some_and(|d| d.is_reset());
        let continues = out.last().is_some_and(|t| reset && t.data_id == data_id && t.wire_requests.len() < 10);
        if !continues {
            out.push(Transaction {
                index: out.len(),
                start_ps: x.start_ps,
                data_id,
                received: Vec::new(),
                wire_requests: Vec::new(),
                wire_answers: Vec::new(),
                abs: 0,
                abm: 0,
                sf: 0,
                enid: 0,
                almc: 0,
                adf: 0,
                edf: 0,
                errors: Vec::new(),
            });
        }
        let t = out.last_mut().expect("pushed above");
        t.wire_requests.push(x.request.clone());
        t.wire_answers.push(x.answer.clone());
        t.received = received;
        (t.abs, t.abm, t.sf, t.enid, t.almc, t.adf, t.edf) = (regs.abs, regs.abm, regs.sf, regs.enid, regs.almc, regs.adf, regs.edf);
        let merged: Vec<&'static str> = ["crc", "timeout", "frame", "cf_mismatch", "comm_alarm"].into_iter().filter(|e| t.errors.contains(e) || errors.contains(e)).collect();
        t.errors = merged;
    }
    Ok(out)
}

/// The host's checks on one answer (the characters it heard after the
/// request ended at `request_end_ps`): the fields it stored and its errors;
/// the registers take the answer's fields as the host's outputs do.
#[allow(clippy::too_many_arguments)]
fn check(answer: &[UartByte], request_cf: Option<u8>, data_id: Option<u8>, request_end_ps: u64, timeout_ps: u64, bit_ps: u64, heard: &Signal, regs: &mut Registers) -> (Vec<u8>, Vec<&'static str>) {
    let Some(first) = answer.first().filter(|c| c.start_ps - request_end_ps <= timeout_ps) else {
        return (Vec::new(), vec!["timeout"]);
    };
    // The frame set: fields that follow within one bit of idle after the one
    // before (after a framing error, from the line's return to high), and
    // begin before the host stops listening.
    let limit = first.start_ps.saturating_add(ANSWER_LIMIT_BITS * bit_ps);
    let resume = |c: &UartByte| {
        let stop_sample = c.start_ps.saturating_add(9 * bit_ps + bit_ps / 2);
        if c.framing_error { heard.next_level(stop_sample, true).unwrap_or(u64::MAX) } else { stop_sample }
    };
    let stop_sample = |c: &UartByte| c.start_ps.saturating_add(9 * bit_ps + bit_ps / 2);
    let mut set = vec![*first];
    for c in &answer[1..] {
        if stop_sample(c) >= limit || c.start_ps >= resume(&set[set.len() - 1]).saturating_add(bit_ps) {
            break;
        }
        set.push(*c);
    }
    for (slot, c) in regs.fields.iter_mut().zip(&set) {
        *slot = c.value;
    }
    let f = regs.fields;
    let cf = f[0];
    let answered = DataId::from_code((cf >> 3) & 0xF);
    match answered {
        Some(DataId::Id6 | DataId::IdD) => (regs.adf, regs.edf) = (f[1], f[2]),
        _ => {
            regs.sf = f[1];
            match answered {
                Some(DataId::Id1) => regs.abm = u16::from_le_bytes([f[2], f[3]]),
                Some(DataId::Id2) => regs.enid = f[2],
                Some(DataId::Id3) => {
                    regs.abs = u32::from_le_bytes([f[2], f[3], f[4] & 0x01, 0]);
                    regs.enid = f[5];
                    regs.abm = u16::from_le_bytes([f[6], f[7]]);
                    regs.almc = f[9];
                }
                _ => regs.abs = u32::from_le_bytes([f[2], f[3], f[4] & 0x01, 0]),
            }
        }
    }
    let expected = data_id.and_then(DataId::from_code).map_or(MAX_FIELDS, |d| d.answer_fields());
    let crc_bad = set.iter().fold(0u8, |acc, c| acc ^ c.value) != 0;
    let frame_bad = set.iter().any(|c| c.framing_error) || set.len() != expected || resume(&set[set.len() - 1]).saturating_add(bit_ps) > limit;
    let cf_bad = Some(cf) != request_cf;
    let comm = !answered.is_some_and(|d| d.is_eeprom()) && f[1] & 0xC0 != 0;
    let errors = [(crc_bad, "crc"), (frame_bad, "frame"), (cf_bad, "cf_mismatch"), (comm, "comm_alarm")].into_iter().filter(|e| e.0).map(|e| e.1).collect();
    (set.iter().take(MAX_FIELDS).map(|c| c.value).collect(), errors)
}

/// The JSON `tbgen decode tformat` prints.
pub fn to_json(path: &Path, options: &Options, transactions: &[Transaction]) -> Result<String> {
    let decoded = Decoded::new("tformat", path, &[("line", &options.line), ("tx_en", &options.tx_en)], transactions);
    serde_json::to_string_pretty(&decoded).map_err(|e| crate::Error::Decode(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Setup;
    use crate::{builtin, generate};

    #[test]
    fn decoding_the_line_of_every_tformat_scenario_gives_back_every_field_of_gens_transcript() {
        let dir = tempfile::tempdir().unwrap();
        let (mut scenarios, mut compared) = (0, 0);
        for s in builtin::all().unwrap().into_iter().filter(|s| s.core() == "tformat_host") {
            let Setup::Tformat(cfg) = &s.setup else { unreachable!("{} runs tformat_host", s.name) };
            let summary = generate::generate(&s, dir.path()).unwrap();
            let gen: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
            let options = Options { baud: cfg.baud as u64, timeout_us: cfg.host.timeout_us, ..Options::default() };
            let decoded = decode(&summary.files[1], &options).unwrap();
            let gen = gen["transactions"].as_array().unwrap();
            assert_eq!(decoded.len(), gen.len(), "{}: transactions", s.name);
            let period_ps = 1_000_000 / cfg.f_sys_mhz as u64;
            for (d, g) in decoded.iter().zip(gen) {
                // The driver turns on at the edge that takes the start pulse.
                assert_eq!(d.start_ps, g["start_cycle"].as_u64().unwrap() * period_ps, "{} #{}: start", s.name, d.index);
                for (key, value) in serde_json::to_value(d).unwrap().as_object().unwrap() {
                    if key != "start_ps" {
                        assert_eq!(value, &g[key], "{} #{}: `{key}` decoded vs gen", s.name, d.index);
                        compared += 1;
                    }
                }
            }
            scenarios += 1;
        }
        assert!(scenarios >= 15 && compared >= 15 * 20, "{scenarios} scenarios, {compared} fields compared");
    }

    #[test]
    fn a_capture_without_the_driver_enable_names_the_option_that_fixes_it() {
        let s = builtin::find("tformat_no_answer").unwrap();
        let dir = tempfile::tempdir().unwrap();
        let summary = generate::generate(&s, dir.path()).unwrap();
        let options = Options { tx_en: "top.line.de".into(), ..Options::default() };
        let e = decode(&summary.files[1], &options).unwrap_err().to_string();
        assert!(e.contains("top.line.de") && e.contains("--tx-en") && e.contains("tformat_no_answer.vcd"), "{e}");
    }
}
