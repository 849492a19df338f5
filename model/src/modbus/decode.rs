//! The decode core of `tbgen decode modbus` and of the co-simulation monitor
//! `modbus_monitor`: the line at a Modbus RTU master and the master's
//! driver enable, turned into the polls of the `gen` transcript.
//!
//! Every character is read with its parity and stop bit
//! ([`crate::uart::line::chars`]). A poll runs from the driver turning on to
//! the next time it does: the characters sent while it is on are the
//! request, the others the answers on the wire. The answer is judged as
//! [`super::Master`] judges it: it begins within the timeout after the
//! request, ends after t3.5 of silence (counted, as the master counts it,
//! from each stop bit's middle), is spoiled by a parity or framing error or
//! a silence over t1.5 inside it, and is then checked for length, CRC,
//! address, exception, function and count (or, for the address change, the
//! echo). What only the model knows is left out: cycle numbers and the
//! operation the master meant (the request on the wire says it, unless
//! another driver spoiled it).

use serde::Serialize;

use super::frames;
use crate::uart::line::{chars, values, Char};
use crate::uart::Parity;
use crate::wire::Signal;

/// What the decoder needs besides the line.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Baud.
    pub baud: f64,
    /// Character format.
    pub parity: Parity,
    /// The master's answer timeout, µs (`[modbus.master] timeout_us`).
    pub timeout_us: f64,
    /// The devices send Gray code (`[[modbus.devices]] gray`).
    pub gray: bool,
}

/// One poll read off the line; the fields mean what they mean in the `gen`
/// transcript (`model::modbus::Transaction`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Transaction {
    /// 0-based poll number.
    pub index: usize,
    /// The master's driver turning on, ps.
    pub start_ps: u64,
    /// `read`, `query`, `set_address`, or `unknown` for a request it cannot name.
    pub op: &'static str,
    /// The station addressed (`null` for the query or an unreadable request).
    pub address: Option<u8>,
    /// Registers asked for by a read.
    pub count: Option<u8>,
    /// The request on the wire.
    pub request: Vec<u8>,
    /// The answer characters the master keeps (at most 9).
    pub received: Vec<u8>,
    /// The registers read.
    pub value: Option<u32>,
    /// The station the query returned, or the new address a good change confirmed.
    pub station: Option<u8>,
    /// The exception code.
    pub exception: Option<u8>,
    /// `parity`, `framing`, `gap`, `length`, `crc`, `address`, `exception`,
    /// `function`, `count`, `timeout`, in that order (the master's flags).
    pub errors: Vec<&'static str>,
    /// The request on the wire, as one list (the transcript's shape).
    pub wire_requests: Vec<Vec<u8>>,
    /// Every character on the wire after the request, up to the next one.
    pub wire_answers: Vec<Vec<u8>>,
}

/// Decodes the line at the master `line` with its driver enable `tx_en`:
/// one poll per rise of the driver enable.
pub fn decode(line: &Signal, tx_en: &Signal, options: &Options) -> Vec<Transaction> {
    let bit_ps = (1e12 / options.baud).round() as u64;
    let fb = options.parity.frame_bits();
    let t15_ps = (frames::t15_seconds(options.baud, fb) * 1e12) as u64;
    let t35_ps = (frames::t35_seconds(options.baud, fb) * 1e12) as u64;
    let timeout_ps = (options.timeout_us * 1e6) as u64;
    let char_ps = fb as u64 * bit_ps;
    let limit_ps = super::RECV_LIMIT_CHARS * char_ps + t35_ps;
    let chars = chars(line, Some(tx_en), bit_ps, options.parity);
    let rises: Vec<u64> = tx_en.edges().iter().filter(|e| e.1).map(|e| e.0).collect();
    let mut out = Vec::with_capacity(rises.len());
    for (index, &rise) in rises.iter().enumerate() {
        let fall = tx_en.next_level(rise, false).unwrap_or(u64::MAX);
        let next = rises.get(index + 1).copied().unwrap_or(u64::MAX);
        let request: Vec<u8> = chars
            .iter()
            .filter(|c| c.from_host && (rise..fall).contains(&c.start_ps))
            .map(|c| c.value)
            .collect();
        let answers: Vec<Char> = chars
            .iter()
            .filter(|c| !c.from_host && (fall..next).contains(&c.start_ps))
            .copied()
            .collect();
        let mut t = Transaction {
            index,
            start_ps: rise,
            op: "unknown",
            address: None,
            count: None,
            request: request.clone(),
            received: Vec::new(),
            value: None,
            station: None,
            exception: None,
            errors: Vec::new(),
            wire_requests: vec![request.clone()],
            wire_answers: vec![values(&answers)],
        };
        match request.as_slice() {
            [0xFF, 0xA0, ..] => t.op = "query",
            [a, 0x03, _, _, _, n, ..] => (t.op, t.address, t.count) = ("read", Some(*a), Some(*n)),
            [a, 0x06, ..] => (t.op, t.address) = ("set_address", Some(*a)),
            _ => {}
        }
        match answers.first() {
            Some(first) if first.start_ps <= fall.saturating_add(timeout_ps) => judge(
                &mut t,
                &answers,
                bit_ps,
                fb as u64,
                t15_ps,
                t35_ps,
                limit_ps,
                options.gray,
            ),
            _ => t.errors.push("timeout"),
        }
        out.push(t);
    }
    out
}

/// The master's verdict on the answer that begins with `answers[0]`.
#[allow(clippy::too_many_arguments)]
fn judge(
    t: &mut Transaction,
    answers: &[Char],
    bit_ps: u64,
    bits: u64,
    t15_ps: u64,
    t35_ps: u64,
    limit_ps: u64,
    gray: bool,
) {
    let stop_sample = |c: &Char| c.start_ps + (bits - 1) * bit_ps + bit_ps / 2;
    let first = answers[0].start_ps;
    let (mut parity, mut framing, mut gap, mut cut) = (false, false, false, false);
    let mut frame: Vec<Char> = Vec::new();
    for c in answers {
        if let Some(prev) = frame.last() {
            let silence = c.start_ps.saturating_sub(stop_sample(prev));
            if silence >= t35_ps {
                break;
            }
            gap |= silence > t15_ps;
        }
        if c.start_ps > first + limit_ps {
            cut = true;
            break;
        }
        parity |= c.parity_error;
        framing |= c.framing_error;
        frame.push(*c);
    }
    // The frame ends t3.5 after its last stop-bit sample: past the receive limit, the master cuts it first.
    cut |= frame
        .last()
        .is_some_and(|c| stop_sample(c) + t35_ps > first + limit_ps);
    let n = frame.len();
    let b: Vec<u8> = values(&frame);
    t.received = b[..n.min(super::MAX_CHARS)].to_vec();
    let length = cut || !(4..=super::MAX_CHARS).contains(&n);
    for (flag, name) in [
        (parity, "parity"),
        (framing, "framing"),
        (gap, "gap"),
        (length, "length"),
    ] {
        if flag {
            t.errors.push(name);
        }
    }
    if !t.errors.is_empty() {
        return;
    }
    if !frames::crc_ok(&b) {
        t.errors.push("crc");
        return;
    }
    let (function, address) = match t.op {
        "query" => (frames::QUERY_FUNCTION, frames::QUERY_ADDRESS),
        "set_address" => (frames::WRITE_SINGLE, t.request[0]),
        "read" => (frames::READ_HOLDING, t.request[0]),
        _ => {
            t.errors.push("function");
            return;
        }
    };
    if b[0] != address {
        t.errors.push("address");
    } else if t.op != "query" && b[1] == function | 0x80 && n == 5 {
        t.exception = Some(b[2]);
        t.errors.push("exception");
    } else if b[1] != function {
        t.errors.push("function");
    } else if t.op == "query" {
        if n == 5 {
            t.station = Some(b[2]);
        } else {
            t.errors.push("count");
        }
    } else if t.op == "set_address" {
        if n == 8 && t.request.len() >= 6 && b[..6] == t.request[..6] {
            t.station = Some(b[5]);
        } else {
            t.errors.push("count");
        }
    } else {
        let count = t.count.unwrap_or(0);
        if count == 0 || b[2] as usize != 2 * count as usize || n != 5 + 2 * count as usize {
            t.errors.push("count");
        } else {
            let len = if count == 1 { 2 } else { 4 };
            let v = b[3..3 + len].iter().fold(0u32, |v, &x| (v << 8) | x as u32);
            t.value = Some(if gray {
                crate::gray::from_gray(v as u64) as u32
            } else {
                v
            });
        }
    }
}
