//! The host operations of an ESL line at the host, from the host's driver
//! enable and the line: the decode core of `tbgen decode esl` (from a
//! capture) and of the co-simulation monitor `esl_monitor` (from the pins it
//! samples). Characters are read with [`crate::wire::uart_bytes`] at the
//! nominal rate; those whose start bit falls while the host drives are its
//! request, the rest up to the next request the answer; requests are grouped
//! into operations as the host does and each answer judged with the model's
//! checks ([`crate::esl::frames::check`]).
//!
//! [`Decoder`] takes one exchange at a time, so a monitor hands it each
//! exchange as it ends and keeps no more of the line; [`decode`] runs it
//! over a whole capture.

use serde::Serialize;

use crate::esl::frames::{self, DataId};
use crate::esl::{MAX_FIELDS, REPEATS};
use crate::wire::{uart_bytes, Signal, UartByte};

/// How the capture's host was configured where the line cannot tell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DecodeOptions {
    /// Bit rate (10 Mbps).
    pub baud: f64,
    /// The broadcast address (7).
    pub broadcast_address: u8,
    /// Requests a memory access may take while busy (3).
    pub busy_tries: u64,
    /// RS tolerance in RS LSBs (1).
    pub rs_tolerance: u16,
}

impl Default for DecodeOptions {
    fn default() -> Self {
        DecodeOptions {
            baud: 10e6,
            broadcast_address: 7,
            busy_tries: 3,
            rs_tolerance: 1,
        }
    }
}

/// One host operation read off the line: the fields of the `gen`
/// transcript's transaction that the line shows (cycle numbers give way to
/// `start_ps`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DecodedOp {
    /// 0-based operation number.
    pub index: usize,
    /// The driver enable's rising edge of the operation's first request, ps.
    pub start_ps: u64,
    /// The Data ID code of the request's control field.
    pub data_id: u8,
    /// Its encoder address.
    pub address: u8,
    /// Sent to the broadcast address.
    pub broadcast: bool,
    /// Requests on the line for this operation.
    pub requests: usize,
    /// The last request frame set.
    pub sent: Vec<u8>,
    /// The last answer frame set.
    pub received: Vec<u8>,
    /// Every request's characters on the line (driver on), in order.
    pub wire_requests: Vec<Vec<u8>>,
    /// For each of `wire_requests`, every character after it up to the next
    /// request (driver off).
    pub wire_answers: Vec<Vec<u8>>,
    /// The host's result outputs after the operation, under the model's names.
    #[serde(flatten)]
    pub results: frames::Decoded,
    /// The errors the host flags for these frame sets.
    pub errors: Vec<&'static str>,
}

/// The host's view of a line, one exchange at a time (a request and what
/// followed it up to the next request): what it keeps from one operation to
/// the next and the operation still open (B, C, D take 8 requests; a busy
/// memory answer is repeated).
#[derive(Debug, Clone)]
pub struct Decoder {
    opt: DecodeOptions,
    host: HostState,
    open: Option<(DecodedOp, u8, u64)>,
    count: usize,
}

impl Decoder {
    /// A decoder for a host configured as `opt`.
    pub fn new(opt: DecodeOptions) -> Self {
        Decoder {
            opt,
            host: HostState {
                seq: [(false, 0, 0); 8],
                out: frames::Decoded::default(),
                page: frames::DEFAULT_PAGE,
            },
            open: None,
            count: 0,
        }
    }

    /// Picoseconds per bit.
    pub fn bit_ps(&self) -> u64 {
        (1e12 / self.opt.baud).round() as u64
    }

    /// One exchange: the host's driver on from `rise` to `fall`, the next
    /// exchange starting at `next` (`u64::MAX`: none); `bytes` the
    /// characters of the line, at least those from `rise` to `next`.
    /// Returns the operation this exchange completed, if any.
    pub fn exchange(
        &mut self,
        rise: u64,
        fall: u64,
        next: u64,
        bytes: &[UartByte],
    ) -> Option<DecodedOp> {
        let request: Vec<UartByte> = bytes
            .iter()
            .copied()
            .filter(|b| (rise..fall).contains(&b.start_ps))
            .collect();
        let answer: Vec<UartByte> = bytes
            .iter()
            .copied()
            .filter(|b| (fall..next).contains(&b.start_ps))
            .collect();
        let sent: Vec<u8> = request.iter().map(|b| b.value).collect();
        let cf = frames::parse_control_field(sent.first().copied().unwrap_or(0));
        let (mut op, repeats, tries) = match self.open.take() {
            Some(o) => o,
            None => {
                let repeated = DataId::from_code(cf.code).is_some_and(|d| d.is_repeated());
                let op = DecodedOp {
                    index: self.count,
                    start_ps: rise,
                    data_id: cf.code,
                    address: cf.address,
                    broadcast: cf.address == self.opt.broadcast_address,
                    requests: 0,
                    sent: Vec::new(),
                    received: Vec::new(),
                    wire_requests: Vec::new(),
                    wire_answers: Vec::new(),
                    results: frames::Decoded::default(),
                    errors: Vec::new(),
                };
                self.count += 1;
                (op, if repeated { REPEATS } else { 1 }, self.opt.busy_tries)
            }
        };
        op.requests += 1;
        op.sent = sent;
        op.received = answer.iter().map(|b| b.value).collect();
        op.wire_requests.push(op.sent.clone());
        op.wire_answers.push(op.received.clone());
        let (retry, tries) = self.host.finish(&mut op, &answer, tries, &self.opt);
        let repeats = if retry { repeats } else { repeats - 1 };
        op.results = self.host.out;
        if retry || repeats > 0 {
            self.open = Some((op, repeats, tries));
            None
        } else {
            sort_errors(std::slice::from_mut(&mut op));
            Some(op)
        }
    }

    /// The operation still open (waiting for more requests), if any.
    pub fn open(&self) -> Option<&DecodedOp> {
        self.open.as_ref().map(|o| &o.0)
    }

    /// Operations begun so far (the open one included).
    pub fn count(&self) -> usize {
        self.count
    }

    /// Closes the open operation.
    pub fn finish(&mut self) -> Option<DecodedOp> {
        self.open.take().map(|(mut op, _, _)| {
            sort_errors(std::slice::from_mut(&mut op));
            op
        })
    }
}

/// Reads the host's driver enable and the line at the host, splits the
/// characters into requests (driver on) and answers (driver off), groups the
/// requests into operations as the host does (8 for B, C, D; repeats after a
/// busy memory answer) and judges each answer with the model's checks.
pub fn decode(en: &Signal, ln: &Signal, opt: &DecodeOptions) -> Vec<DecodedOp> {
    let mut decoder = Decoder::new(*opt);
    let bytes = uart_bytes(ln, decoder.bit_ps());
    let edges = en.edges();
    let rises: Vec<u64> = edges.iter().filter(|e| e.1).map(|e| e.0).collect();
    let falls: Vec<u64> = edges.iter().filter(|e| !e.1).map(|e| e.0).collect();
    let mut ops = Vec::new();
    for (i, &rise) in rises.iter().enumerate() {
        let fall = falls
            .iter()
            .copied()
            .find(|&f| f > rise)
            .unwrap_or(u64::MAX);
        let next = rises.get(i + 1).copied().unwrap_or(u64::MAX);
        ops.extend(decoder.exchange(rise, fall, next, &bytes));
    }
    ops.extend(decoder.finish());
    ops
}

/// What the host keeps from one operation to the next.
#[derive(Debug, Clone)]
struct HostState {
    seq: [(bool, u8, u8); 8],
    out: frames::Decoded,
    page: u8,
}

impl HostState {
    /// `model::esl::Host::finish` on bytes: errors into `op`, results into
    /// `self.out`; returns (repeat after busy, tries left).
    fn finish(
        &mut self,
        op: &mut DecodedOp,
        answer: &[UartByte],
        tries: u64,
        opt: &DecodeOptions,
    ) -> (bool, u64) {
        let mut flag = |name: &'static str, on: bool| {
            if on && !op.errors.contains(&name) {
                op.errors.push(name);
            }
        };
        let timeout = answer.is_empty();
        let address = usize::from(op.address & 7);
        if op.broadcast {
            flag("cf_mismatch", !timeout);
            return (false, tries);
        }
        if timeout {
            flag("timeout", true);
            self.seq[address].0 = false;
            return (false, tries);
        }
        let Some(id) = DataId::from_code(op.data_id) else {
            flag("cf_mismatch", true);
            return (false, tries);
        };
        let values: Vec<u8> = answer.iter().take(MAX_FIELDS).map(|b| b.value).collect();
        let framing = answer.iter().any(|b| b.framing_error) || answer.len() > MAX_FIELDS;
        let request_cf = op.sent.first().copied().unwrap_or(0);
        let d = frames::decode(id, &values);
        let mut k = frames::check(id, request_cf, &values, framing, opt.rs_tolerance);
        let (mem_address, wdata) = (
            op.sent.get(1).map_or(0, |a| a >> 1),
            op.sent.get(2).copied().unwrap_or(0),
        );
        if id.is_memory() && !k.any() {
            k.cf |= d.adf >> 1 != mem_address;
            if id == DataId::IdF && d.adf & 1 == 0 && d.edf != wdata {
                k.cf = true;
            }
        }
        self.out = d;
        let clean = !(k.crc1 || k.crc2 || k.frame || k.cf || k.comm);
        let mut seq_bad = false;
        if id.is_safety() && clean {
            let (known, sc1, sc2) = self.seq[address];
            seq_bad = known && (d.sc1 != sc1.wrapping_add(1) || d.sc2 != (sc2 + 1) & 0x7F);
            self.seq[address] = (true, d.sc1, d.sc2);
        } else if id.is_safety() {
            self.seq[address].0 = false;
        }
        let mut retry = false;
        let mut tries = tries;
        let mut busy_error = false;
        if id.is_memory() && clean {
            let busy = d.adf & 1 == 1;
            tries = tries.saturating_sub(1);
            if busy && tries == 0 {
                busy_error = true;
            } else if busy {
                retry = true;
            } else if id == DataId::IdF && mem_address == frames::PAGE_REGISTER {
                self.page = wdata & 0xF;
            }
        }
        for (on, name) in [
            (k.crc1, "crc1"),
            (k.crc2, "crc2"),
            (k.frame, "frame"),
            (k.cf, "cf_mismatch"),
            (k.comm, "comm_alarm"),
            (seq_bad, "sequence"),
            (k.rs, "channel_mismatch"),
            (busy_error, "busy"),
        ] {
            flag(name, on);
        }
        (retry, tries)
    }
}

/// The order of the model's error names ([`model::esl::error_names`]), so
/// that a decoded list compares equal to the transcript's.
pub fn sort_errors(ops: &mut [DecodedOp]) {
    const ORDER: [&str; 9] = [
        "crc1",
        "crc2",
        "timeout",
        "frame",
        "cf_mismatch",
        "comm_alarm",
        "sequence",
        "channel_mismatch",
        "busy",
    ];
    for op in ops {
        op.errors.sort_by_key(|e| ORDER.iter().position(|o| o == e));
    }
}
