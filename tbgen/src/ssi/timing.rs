//! `tbgen timing ssi`: the read cycle of a scenario's SSI reader, phase by
//! phase (`T_cs`, the clocked bits, the pause), and the position-read rate,
//! beside what the cycle model measures for the same set-up.

use std::fmt::Write as _;

use model::ssi::BenchConfig;
use model::testbench;
use model::Setup;

/// The budget of one read and the model's start to `o_done` of the
/// scenario's first clean read.
pub fn timing_report(cfg: &BenchConfig, name: &str) -> Result<String, model::ConfigError> {
    let m = cfg.master_config()?;
    let tb = cfg.timebase()?;
    let ns = |c: u64| c as f64 * tb.period_ps() as f64 / 1e3;
    let sampled = m.bits as u64 * if m.double_read { 2 } else { 1 } + m.wire_check as u64;
    let phases = [
        (m.t_cs_clocks, "T_cs: first low phase after the latching falling edge".to_string()),
        (sampled * m.clocks_per_bit, format!("{sampled} clocked bits ({} data{}{})", m.bits, if m.double_read { " read twice" } else { "" }, if m.wire_check { ", wire-check bit" } else { "" })),
    ];
    let latency: u64 = phases.iter().map(|p| p.0).sum();
    let mut s = String::new();
    let _ = writeln!(s, "scenario: {name}");
    let _ = writeln!(s, "SSI at f_sys / {} ({:.1} kHz), f_sys = {} MHz", m.clocks_per_bit, tb.f_sys_hz() as f64 / m.clocks_per_bit as f64 / 1e3, tb.f_sys_hz() as f64 / 1e6);
    for (cycles, what) in &phases {
        let _ = writeln!(s, "  {cycles:>8} cycles {:>12.1} ns  {what}", ns(*cycles));
    }
    let _ = writeln!(s, "  {latency:>8} cycles {:>12.1} ns  start to o_done (budget)", ns(latency));
    let _ = writeln!(s, "  {:>8} cycles {:>12.1} ns  pause: clock high before the next read (the encoder's monoflop)", m.pause_clocks, ns(m.pause_clocks));
    let _ = writeln!(s, "position-read rate (back to back, at most): {:.0} reads/s", 1e9 / ns(latency + m.pause_clocks));
    let run = testbench::run_to_end(cfg.bench()?);
    if let Some(t) = run.transactions.iter().find(|t| t.errors.is_empty()) {
        let _ = writeln!(s, "model: read {} start to o_done {} cycles ({:.1} ns, budget {:+} cycles)", t.index, t.done_cycle - t.start_cycle, ns(t.done_cycle - t.start_cycle), (t.done_cycle - t.start_cycle) as i64 - latency as i64);
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_budget_equals_the_models_clean_read_in_every_ssi_scenario() {
        let mut compared = 0;
        for s in crate::builtin::all().unwrap() {
            let Some(cfg) = s.setup.get::<BenchConfig>() else { continue };
            let r = timing_report(cfg, &s.name).unwrap();
            if let Some(line) = r.lines().find(|l| l.starts_with("model:")) {
                assert!(line.ends_with("budget +0 cycles)"), "{}: {r}", s.name);
                compared += 1;
            }
        }
        assert!(compared >= 8, "{compared} SSI scenarios compared");
    }

    #[test]
    fn the_seed_read_is_t_cs_and_12_bits() {
        // seed_12bit: 250 kHz at 50 MHz = 200 cycles per bit, T_cs = 200 cycles.
        let s = crate::builtin::find("ssi_seed_12bit").unwrap();
        let r = timing_report(s.setup.get::<BenchConfig>().unwrap(), &s.name).unwrap();
        assert!(r.contains("     2600 cycles"), "{r}");
    }
}
