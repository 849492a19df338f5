//! `tbgen timing esl`: the ESL request-to-answer budget of a scenario, phase
//! by phase, and the position-read rate, beside what the cycle model
//! measures for the same set-up. `tbgen decode esl`: a captured line turned
//! into the transcript of host operations, judged by the host's own checks.

use std::fmt::Write as _;
use std::path::Path;

use serde::Serialize;

use crate::capture::{self, UartByte};
use crate::{Error, Result};

use model::esl::{frames::DataId, BenchConfig};
use model::testbench;
use model::Setup;

/// The budget for one request of `data_id` (a Table 3 code) to encoder 0 of the scenario.
pub fn timing_report(cfg: &BenchConfig, name: &str, data_id: u8) -> Result<String, model::ConfigError> {
    let id = DataId::from_code(data_id).ok_or_else(|| {
        model::ConfigError::invalid("data_id", format!("{data_id:#x} is not in Table 3"), "give 1, 2, 4, 5, 6, 8, 9, 0xA .. 0xF")
    })?;
    let tb = cfg.timebase()?;
    let hc = cfg.host_config()?;
    let ec = cfg.encoder_config(0)?;
    let c = hc.clocks_per_bit;
    let d = cfg.cable.delay_cycles(&tb);
    let n_req = model::esl::frames::request(0, data_id, 0, 0).len() as u64;
    let n_ans = id.answer_fields() as u64;
    let ns = |cycles: u64| cycles as f64 * tb.period_ps() as f64 / 1e3;
    // Phases in system clocks, as the host sees its own pins.
    let phases = [
        (10 * n_req * c, format!("request: {n_req} field(s) of 10 bits (CF, CRC-8 frame), driver on")),
        (d, "cable to the encoder".to_string()),
        (ec.answer_delay, "encoder answer delay (seed: 2.0 µs typ.)".to_string()),
        (d, "cable back to the host".to_string()),
        (10 * n_ans * c - c / 2, format!("answer: {n_ans} fields back to back (Table 12), up to the last stop-bit sample")),
        (c + 5, "one idle bit ends the frame set, plus synchroniser and output registers".to_string()),
    ];
    let total: u64 = phases.iter().map(|p| p.0).sum();
    let mut s = String::new();
    let _ = writeln!(s, "scenario: {name}");
    let _ = writeln!(
        s,
        "ESL Data ID {data_id:X} at {} Mbps, f_sys = {} MHz ({c} clocks per bit), cable {} m",
        cfg.baud / 1e6,
        tb.f_sys_hz() as f64 / 1e6,
        cfg.cable.length_m
    );
    for (cycles, what) in &phases {
        let _ = writeln!(s, "  {cycles:>8} cycles {:>10.1} ns  {what}", ns(*cycles));
    }
    let _ = writeln!(s, "  {total:>8} cycles {:>10.1} ns  request start to o_done (budget)", ns(total));
    let _ = writeln!(s, "position-read rate (back to back): {:.0} reads/s", 1e9 / ns(total + 1));
    // The cycle model on two back-to-back requests of the same Data ID to
    // the first encoder, without injected faults.
    let mut one = cfg.clone();
    let address = cfg.encoders[0].address;
    one.ops = vec![model::esl::Operation { data_id, address, broadcast: false, mem_address: 0, data: 0, gap_us: 0.0 }; 2];
    one.encoders.truncate(1);
    let e = &mut one.encoders[0];
    e.flips.clear();
    e.truncations.clear();
    e.sequence_jumps.clear();
    e.foreign_address_answers.clear();
    e.baud_error_percent = 0.0;
    one.request_flips.clear();
    one.intruders.clear();
    let run = testbench::run_to_end(one.bench()?);
    if let [a, b, ..] = run.transactions.as_slice() {
        let latency = a.done_cycle - a.start_cycle;
        let period = b.start_cycle - a.start_cycle;
        let _ = writeln!(
            s,
            "model: start to o_done {latency} cycles ({:.1} ns, budget {:+} cycles), start to start {period} cycles = {:.0} reads/s{}",
            ns(latency),
            latency as i64 - total as i64,
            1e9 / ns(period),
            if a.errors.is_empty() { String::new() } else { format!(", errors {:?}", a.errors) }
        );
    }
    Ok(s)
}

/// Budget and model, as numbers: (budget cycles, model start-to-o_done cycles).
pub fn budget_and_model(cfg: &BenchConfig, data_id: u8) -> Result<(u64, u64), model::ConfigError> {
    let report = timing_report(cfg, "", data_id)?;
    let budget = report.lines().find(|l| l.contains("(budget)")).and_then(|l| l.split_whitespace().find_map(|w| w.parse::<u64>().ok())).unwrap_or(0);
    let model = report
        .lines()
        .find(|l| l.starts_with("model:"))
        .and_then(|l| l.split("o_done ").nth(1))
        .and_then(|r| r.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or(0);
    Ok((budget, model))
}

/// How the capture's host was configured where the line cannot tell.
#[derive(Debug, Clone, Copy)]
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
        DecodeOptions { baud: 10e6, broadcast_address: 7, busy_tries: 3, rs_tolerance: 1 }
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
    pub results: model::esl::frames::Decoded,
    /// The errors the host flags for these frame sets.
    pub errors: Vec<&'static str>,
}

/// Reads the host's driver enable and the line at the host, splits the
/// characters into requests (driver on) and answers (driver off), groups the
/// requests into operations as the host does (8 for B, C, D; repeats after a
/// busy memory answer) and judges each answer with the model's checks.
pub fn decode(path: &Path, tx_en: &str, line: &str, opt: &DecodeOptions) -> Result<Vec<DecodedOp>> {
    let signals = capture::read(path, &[(tx_en, "--tx-en"), (line, "--line")])?;
    let (en, ln) = (&signals[0], &signals[1]);
    if !(opt.baud > 0.0 && opt.baud <= 1e9) {
        return Err(Error::Decode(format!("decode esl: --baud {}: give a bit rate in bit/s, e.g. 10e6", opt.baud)));
    }
    let bit_ps = (1e12 / opt.baud).round() as u64;
    let bytes = capture::uart_bytes(ln, bit_ps);
    let edges = en.edges();
    let rises: Vec<u64> = edges.iter().filter(|e| e.1).map(|e| e.0).collect();
    let falls: Vec<u64> = edges.iter().filter(|e| !e.1).map(|e| e.0).collect();
    let mut host = HostState { seq: [(false, 0, 0); 8], out: model::esl::frames::Decoded::default(), page: model::esl::frames::DEFAULT_PAGE };
    let mut ops: Vec<DecodedOp> = Vec::new();
    let mut open: Option<(DecodedOp, u8, u64)> = None; // (op, repeats left, tries left)
    for (i, &rise) in rises.iter().enumerate() {
        let fall = falls.iter().copied().find(|&f| f > rise).unwrap_or(u64::MAX);
        let next = rises.get(i + 1).copied().unwrap_or(u64::MAX);
        let request: Vec<UartByte> = bytes.iter().copied().filter(|b| (rise..fall).contains(&b.start_ps)).collect();
        let answer: Vec<UartByte> = bytes.iter().copied().filter(|b| (fall..next).contains(&b.start_ps)).collect();
        let sent: Vec<u8> = request.iter().map(|b| b.value).collect();
        let cf = model::esl::frames::parse_control_field(sent.first().copied().unwrap_or(0));
        let (mut op, repeats, tries) = match open.take() {
            Some(o) => o,
            None => {
                let repeated = model::esl::frames::DataId::from_code(cf.code).is_some_and(|d| d.is_repeated());
                let op = DecodedOp {
                    index: ops.len(),
                    start_ps: rise,
                    data_id: cf.code,
                    address: cf.address,
                    broadcast: cf.address == opt.broadcast_address,
                    requests: 0,
                    sent: Vec::new(),
                    received: Vec::new(),
                    wire_requests: Vec::new(),
                    wire_answers: Vec::new(),
                    results: model::esl::frames::Decoded::default(),
                    errors: Vec::new(),
                };
                (op, if repeated { model::esl::REPEATS } else { 1 }, opt.busy_tries)
            }
        };
        op.requests += 1;
        op.sent = sent;
        op.received = answer.iter().map(|b| b.value).collect();
        op.wire_requests.push(op.sent.clone());
        op.wire_answers.push(op.received.clone());
        let (retry, tries) = host.finish(&mut op, &answer, tries, opt);
        let repeats = if retry { repeats } else { repeats - 1 };
        op.results = host.out;
        if retry || repeats > 0 {
            open = Some((op, repeats, tries));
        } else {
            ops.push(op);
        }
    }
    if let Some((op, _, _)) = open {
        ops.push(op);
    }
    Ok(ops)
}

/// What the host keeps from one operation to the next.
struct HostState {
    seq: [(bool, u8, u8); 8],
    out: model::esl::frames::Decoded,
    page: u8,
}

impl HostState {
    /// `model::esl::Host::finish` on bytes: errors into `op`, results into
    /// `self.out`; returns (repeat after busy, tries left).
    fn finish(&mut self, op: &mut DecodedOp, answer: &[UartByte], tries: u64, opt: &DecodeOptions) -> (bool, u64) {
        use model::esl::frames::{self, DataId};
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
        let values: Vec<u8> = answer.iter().take(model::esl::MAX_FIELDS).map(|b| b.value).collect();
        let framing = answer.iter().any(|b| b.framing_error) || answer.len() > model::esl::MAX_FIELDS;
        let request_cf = op.sent.first().copied().unwrap_or(0);
        let d = frames::decode(id, &values);
        let mut k = frames::check(id, request_cf, &values, framing, opt.rs_tolerance);
        let (mem_address, wdata) = (op.sent.get(1).map_or(0, |a| a >> 1), op.sent.get(2).copied().unwrap_or(0));
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
    const ORDER: [&str; 9] = ["crc1", "crc2", "timeout", "frame", "cf_mismatch", "comm_alarm", "sequence", "channel_mismatch", "busy"];
    for op in ops {
        op.errors.sort_by_key(|e| ORDER.iter().position(|o| o == e));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builtin;
    use crate::scenario::Setup;

    #[test]
    fn the_budget_equals_the_models_cycle_for_every_data_id() {
        for name in ["esl_readout_all_ids", "esl_clear_commands_8x"] {
            let s = builtin::find(name).unwrap();
            let Setup::Esl(cfg) = &s.setup else { panic!("{name} is not ESL") };
            for id in [0x1, 0x2, 0x4, 0x5, 0x6, 0x8, 0x9, 0xA, 0xE] {
                let (budget, model) = budget_and_model(cfg, id).unwrap();
                assert!(budget > 500, "{name} id {id}: no budget");
                assert_eq!(model, budget, "{name}, Data ID {id:X}");
            }
        }
    }

    #[test]
    fn decoding_every_esl_scenarios_line_gives_the_transcripts_fields() {
        // Each built-in ESL scenario: `gen` writes the VCD and the transcript;
        // the decoder reads the VCD and every field it emits must equal the
        // transcript's field of the same name. Where the line and the host's
        // receiver legitimately see different bytes, the scenario is listed
        // with the reason: there each operation's fields are compared up to
        // the first that differs, and every operation the model flags must be
        // flagged by the decoder too.
        let line_differs: &[(&str, &str)] = &[
            ("esl_baud_minus_6", "the host samples outside the bits; the line decoder samples at the nominal rate from each start edge"),
            ("esl_baud_plus_6", "as above"),
            ("esl_fault_answer_bit_flips", "a flipped start or stop bit splits the answer differently at the host (it stops at the first idle bit) and on the line"),
            ("esl_fault_truncated_no_answer_intruder", "the intruder's low pulse is sampled differently by the 8-clock receiver and the ideal line decoder"),
            ("esl_fault_answer_shapes", "a 19th field: the host keeps the 18 fields an answer can have (it counts the rest, flagged `frame`), the line decoder lists every field it reads"),
        ];
        let dir = tempfile::tempdir().unwrap();
        let (mut compared, mut wire_sets) = (0, 0);
        for s in builtin::all().unwrap().into_iter().filter(|s| s.core() == "esl_host") {
            let Setup::Esl(cfg) = &s.setup else { unreachable!() };
            let summary = crate::generate::generate(&s, dir.path()).unwrap();
            let transcript: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
            let opt = DecodeOptions {
                baud: cfg.baud,
                broadcast_address: cfg.host.broadcast_address,
                busy_tries: cfg.host.busy_tries,
                rs_tolerance: cfg.host.rs_tolerance as u16,
            };
            let mut ops = decode(&summary.files[1], "top.line.tx_en_host", "top.line.line_at_host", &opt).unwrap();
            sort_errors(&mut ops);
            let decoded = serde_json::to_value(&ops).unwrap();
            let want = transcript["transactions"].as_array().unwrap();
            let got = decoded.as_array().unwrap();
            let exempt = line_differs.iter().any(|(n, _)| *n == s.name);
            if !exempt {
                assert_eq!(got.len(), want.len(), "{}: operations", s.name);
            }
            // The wire bytes agree in every scenario, exempt ones included:
            // both readers listen all the time and sample at the nominal rate.
            let wire = |ops: &[serde_json::Value], f: &str| -> Vec<serde_json::Value> { ops.iter().flat_map(|o| o[f].as_array().unwrap().clone()).collect() };
            for f in ["wire_requests", "wire_answers"] {
                assert_eq!(wire(got, f), wire(want, f), "{}: {f}", s.name);
                wire_sets += wire(got, f).len();
            }
            for (g, w) in got.iter().zip(want) {
                if exempt {
                    let flagged = |v: &serde_json::Value| !v["errors"].as_array().unwrap().is_empty();
                    assert_eq!(flagged(g), flagged(w), "{}: operation {} flagged by one reader only", s.name, g["index"]);
                }
                for (field, value) in g.as_object().unwrap() {
                    // The request flips of this scenario are made on the line: the
                    // line shows the corrupted request, the transcript the one the
                    // host meant. Everything judged from it still agrees.
                    if field == "start_ps" || (field == "sent" && !cfg.request_flips.is_empty()) {
                        continue;
                    }
                    if exempt && value != &w[field] {
                        break;
                    }
                    assert_eq!(value, &w[field], "{}: operation {} field {field}", s.name, g["index"]);
                    compared += 1;
                }
            }
        }
        assert!(compared > 1000, "only {compared} fields compared");
        assert!(wire_sets > 150, "only {wire_sets} wire frame sets compared");
    }
}
