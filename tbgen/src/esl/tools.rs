//! `tbgen timing esl`: the ESL request-to-answer budget of a scenario, phase
//! by phase, and the position-read rate, beside what the cycle model
//! measures for the same set-up. `tbgen decode esl`: a captured line turned
//! into the transcript of host operations, judged by the host's own checks.

use std::fmt::Write as _;
use std::path::Path;

use crate::capture;
use crate::{Error, Result};

pub use model::esl::decode::{sort_errors, DecodeOptions, DecodedOp};

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

/// Reads the host's driver enable `tx_en` and the line at the host `line`
/// from the capture `path` and decodes them ([`model::esl::decode`]).
pub fn decode(path: &Path, tx_en: &str, line: &str, opt: &DecodeOptions) -> Result<Vec<DecodedOp>> {
    let signals = capture::read(path, &[(tx_en, "--tx-en"), (line, "--line")])?;
    if !(opt.baud > 0.0 && opt.baud <= 1e9) {
        return Err(Error::Decode(format!("decode esl: --baud {}: give a bit rate in bit/s, e.g. 10e6", opt.baud)));
    }
    Ok(model::esl::decode::decode(&signals[0], &signals[1], opt))
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
