//! The transactions of a T-format line at the host, from the line and the
//! host's driver enable: the decode core of `tbgen decode tformat` (from a
//! capture) and of the co-simulation monitor `tformat_monitor` (from the
//! pins it samples).
//!
//! Every character is read with [`crate::wire::uart_bytes`] twice:
//!
//! * on the line itself: the wire (`wire_requests`, `wire_answers`). A
//!   character whose start bit falls while the host drives is a request
//!   character; every other one belongs to the answer of the latest request,
//!   up to the next request.
//! * on what the host's receiver hears, the line forced high while the host
//!   drives (it is deaf then): the answer the host checks, with the seed's
//!   frame rules (seed 002, 7.2: the answer begins within the timeout after
//!   the request, and ends when no start bit follows a field within one bit
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
//!
//! [`Decoder`] takes one exchange (a request and what followed it up to the
//! next request) at a time, so a monitor hands it each exchange as it ends
//! and keeps no more of the line; [`decode`] runs it over a whole capture.

use serde::Serialize;

use crate::tformat::frames::DataId;
use crate::wire::{uart_bytes, Signal, UartByte};

/// Bit times after an answer's first start bit at which the host stops
/// receiving (`crate::tformat::host::ANSWER_LIMIT_BITS`: the longest answer
/// and one field more).
const ANSWER_LIMIT_BITS: u64 = 120;

/// The most fields the host stores (Data ID 3's answer).
const MAX_FIELDS: usize = 11;

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
#[derive(Debug, Clone, Default)]
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

/// The host's view of a line, one exchange at a time: its registers and the
/// transaction still open (a reset collects ten requests).
#[derive(Debug, Clone)]
pub struct Decoder {
    bit_ps: u64,
    timeout_ps: u64,
    regs: Registers,
    open: Option<Transaction>,
    count: usize,
}

impl Decoder {
    /// A decoder at `baud` bit/s with the host's answer timeout `timeout_us`.
    pub fn new(baud: u64, timeout_us: f64) -> Self {
        Decoder {
            bit_ps: 1_000_000_000_000 / baud.max(1),
            timeout_ps: (timeout_us * 1e6) as u64,
            regs: Registers::default(),
            open: None,
            count: 0,
        }
    }

    /// Picoseconds per bit.
    pub fn bit_ps(&self) -> u64 {
        self.bit_ps
    }

    /// One exchange: the host's driver on from `start_ps` to `end_ps`, the
    /// next exchange starting at `next_ps` (`u64::MAX`: none). `wire` and
    /// `heard` are the characters of the line and of what the host's
    /// receiver hears (`heard_line`), at least those from `start_ps` to
    /// `next_ps`. Returns the transaction this exchange closed (the one
    /// before, unless this request continues a reset).
    pub fn exchange(
        &mut self,
        start_ps: u64,
        end_ps: u64,
        next_ps: u64,
        wire: &[UartByte],
        heard: &[UartByte],
        heard_line: &Signal,
    ) -> Option<Transaction> {
        let (mut request, mut wire_answer) = (Vec::new(), Vec::new());
        for ch in wire
            .iter()
            .filter(|c| (start_ps..next_ps).contains(&c.start_ps))
        {
            if ch.start_ps < end_ps {
                request.push(ch.value)
            } else {
                wire_answer.push(ch.value)
            }
        }
        let answer: Vec<UartByte> = heard
            .iter()
            .filter(|c| c.start_ps >= end_ps && c.start_ps < next_ps)
            .copied()
            .collect();
        let request_cf = request.first().copied();
        let data_id = request_cf.map(|cf| (cf >> 3) & 0xF);
        let (received, errors) = check(
            &answer,
            request_cf,
            data_id,
            end_ps,
            self.timeout_ps,
            self.bit_ps,
            heard_line,
            &mut self.regs,
        );
        let reset = data_id
            .and_then(DataId::from_code)
            .is_some_and(|d| d.is_reset());
        let continues = self
            .open
            .as_ref()
            .is_some_and(|t| reset && t.data_id == data_id && t.wire_requests.len() < 10);
        let closed = if continues { None } else { self.open.take() };
        let index = self.count;
        let t = self.open.get_or_insert_with(|| Transaction {
            index,
            start_ps,
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
        if !continues {
            self.count += 1;
        }
        t.wire_requests.push(request);
        t.wire_answers.push(wire_answer);
        t.received = received;
        let r = &self.regs;
        (t.abs, t.abm, t.sf, t.enid, t.almc, t.adf, t.edf) =
            (r.abs, r.abm, r.sf, r.enid, r.almc, r.adf, r.edf);
        let merged: Vec<&'static str> = ["crc", "timeout", "frame", "cf_mismatch", "comm_alarm"]
            .into_iter()
            .filter(|e| t.errors.contains(e) || errors.contains(e))
            .collect();
        t.errors = merged;
        closed
    }

    /// The transaction still open (the last one so far).
    pub fn open(&self) -> Option<&Transaction> {
        self.open.as_ref()
    }

    /// Transactions begun so far (the open one included).
    pub fn count(&self) -> usize {
        self.count
    }

    /// Closes the open transaction.
    pub fn finish(&mut self) -> Option<Transaction> {
        self.open.take()
    }
}

/// Every transaction of a line at the host (`line`) with the host's driver
/// enable (`tx_en`), at `baud` bit/s with the host's answer timeout.
pub fn decode(line: &Signal, tx_en: &Signal, baud: u64, timeout_us: f64) -> Vec<Transaction> {
    let mut decoder = Decoder::new(baud, timeout_us);
    let bit_ps = decoder.bit_ps;
    let wire = uart_bytes(line, bit_ps);
    let heard_line = line.or(tx_en);
    let heard = uart_bytes(&heard_line, bit_ps);
    // Each request runs from the driver turning on to the next turning on.
    let rises: Vec<u64> = tx_en.edges().iter().filter(|e| e.1).map(|e| e.0).collect();
    let mut out = Vec::new();
    for (k, &rise) in rises.iter().enumerate() {
        let end = tx_en.next_level(rise, false).unwrap_or(u64::MAX);
        let next = rises.get(k + 1).copied().unwrap_or(u64::MAX);
        out.extend(decoder.exchange(rise, end, next, &wire, &heard, &heard_line));
    }
    out.extend(decoder.finish());
    out
}

/// The host's checks on one answer (the characters it heard after the
/// request ended at `request_end_ps`): the fields it stored and its errors;
/// the registers take the answer's fields as the host's outputs do.
#[allow(clippy::too_many_arguments)]
fn check(
    answer: &[UartByte],
    request_cf: Option<u8>,
    data_id: Option<u8>,
    request_end_ps: u64,
    timeout_ps: u64,
    bit_ps: u64,
    heard: &Signal,
    regs: &mut Registers,
) -> (Vec<u8>, Vec<&'static str>) {
    let Some(first) = answer
        .first()
        .filter(|c| c.start_ps - request_end_ps <= timeout_ps)
    else {
        return (Vec::new(), vec!["timeout"]);
    };
    // The frame set: fields that follow within one bit of idle after the one
    // before (after a framing error, from the line's return to high), and
    // begin before the host stops listening.
    let limit = first.start_ps.saturating_add(ANSWER_LIMIT_BITS * bit_ps);
    let resume = |c: &UartByte| {
        let stop_sample = c.start_ps.saturating_add(9 * bit_ps + bit_ps / 2);
        if c.framing_error {
            heard.next_level(stop_sample, true).unwrap_or(u64::MAX)
        } else {
            stop_sample
        }
    };
    let stop_sample = |c: &UartByte| c.start_ps.saturating_add(9 * bit_ps + bit_ps / 2);
    let mut set = vec![*first];
    for c in &answer[1..] {
        if stop_sample(c) >= limit
            || c.start_ps >= resume(&set[set.len() - 1]).saturating_add(bit_ps)
        {
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
    let expected = data_id
        .and_then(DataId::from_code)
        .map_or(MAX_FIELDS, |d| d.answer_fields());
    let crc_bad = set.iter().fold(0u8, |acc, c| acc ^ c.value) != 0;
    let frame_bad = set.iter().any(|c| c.framing_error)
        || set.len() != expected
        || resume(&set[set.len() - 1]).saturating_add(bit_ps) > limit;
    let cf_bad = Some(cf) != request_cf;
    let comm = !answered.is_some_and(|d| d.is_eeprom()) && f[1] & 0xC0 != 0;
    let errors = [
        (crc_bad, "crc"),
        (frame_bad, "frame"),
        (cf_bad, "cf_mismatch"),
        (comm, "comm_alarm"),
    ]
    .into_iter()
    .filter(|e| e.0)
    .map(|e| e.1)
    .collect();
    (
        set.iter().take(MAX_FIELDS).map(|c| c.value).collect(),
        errors,
    )
}
