//! `tbgen timing tformat`: the T-format request-to-answer budget of a
//! scenario, phase by phase, and the position-read rate, beside what the
//! cycle model measures for the same set-up.

use std::fmt::Write as _;

use model::testbench;
use model::tformat::{frames::DataId, BenchConfig, Operation};
use model::Setup;

/// The budget for requests of `data_id` (a code: 0, 1, 2, 3, 6, 7, 8, 0xC, 0xD).
pub fn timing_report(cfg: &BenchConfig, name: &str, data_id: u8) -> Result<String, model::ConfigError> {
    let id = DataId::from_code(data_id).ok_or_else(|| {
        model::ConfigError::invalid("data_id", format!("{data_id:#x} is not in Table 1"), "give 0, 1, 2, 3, 6, 7, 8, 0xC or 0xD")
    })?;
    let tb = cfg.timebase()?;
    let hc = cfg.host_config()?;
    let ec = cfg.encoder_config()?;
    let c = hc.clocks_per_bit;
    let d = cfg.cable.delay_cycles(&tb);
    let n_req = model::tformat::frames::request(id, 0, 0).len() as u64;
    let n_ans = id.answer_fields() as u64;
    let ns = |cycles: u64| cycles as f64 * tb.period_ps() as f64 / 1e3;
    // Phases in system clocks, as the host sees its own pins.
    let phases = [
        (10 * n_req * c, format!("request: {n_req} field(s) of 10 bits, driver on")),
        (d, "cable to the encoder".to_string()),
        (ec.answer_delay, "encoder answer delay (seed: 3 µs typ.)".to_string()),
        (d, "cable back to the host".to_string()),
        (10 * n_ans * c - c / 2, format!("answer: {n_ans} fields back to back, up to the last stop-bit sample")),
        (c + 5, "one idle bit ends the frame set, plus synchroniser and output registers".to_string()),
    ];
    let total: u64 = phases.iter().map(|p| p.0).sum();
    let mut s = String::new();
    let _ = writeln!(s, "scenario: {name}");
    let _ = writeln!(s, "T-format Data ID {data_id:X} at {} Mbps, f_sys = {} MHz ({c} clocks per bit), cable {} m", cfg.baud / 1e6, tb.f_sys_hz() as f64 / 1e6, cfg.cable.length_m);
    for (cycles, what) in &phases {
        let _ = writeln!(s, "  {cycles:>8} cycles {:>10.1} ns  {what}", ns(*cycles));
    }
    let _ = writeln!(s, "  {total:>8} cycles {:>10.1} ns  request start to o_done (budget)", ns(total));
    let _ = writeln!(s, "position-read rate (back to back): {:.0} reads/s", 1e9 / ns(total + 1));
    // The cycle model on two back-to-back requests of the same Data ID.
    let mut one = cfg.clone();
    one.ops = vec![Operation { data_id, address: 0, data: 0, gap_us: 0.0 }; 2];
    one.encoder.flips.clear();
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
    let number_before = |marker: &str| -> Option<u64> {
        let line = report.lines().find(|l| l.contains(marker))?;
        line.split_whitespace().find_map(|w| w.parse::<u64>().ok())
    };
    let budget = number_before("(budget)").unwrap_or(0);
    let model = report
        .lines()
        .find(|l| l.starts_with("model:"))
        .and_then(|l| l.split("o_done ").nth(1))
        .and_then(|r| r.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or(0);
    Ok((budget, model))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builtin;
    use crate::scenario::Setup;

    #[test]
    fn the_budget_equals_the_models_cycle_for_every_data_id_and_cable() {
        for name in ["tformat_readout_all_ids", "tformat_long_cable_100m"] {
            let s = builtin::find(name).unwrap();
            let Setup::Tformat(cfg) = &s.setup else { panic!("{name} is not T-format") };
            for id in [0x0, 0x1, 0x2, 0x3, 0x6, 0xD] {
                let (budget, model) = budget_and_model(cfg, id).unwrap();
                assert!(budget > 1000, "{name} id {id}: no budget");
                assert_eq!(model, budget, "{name}, Data ID {id:X}");
            }
        }
    }
}
