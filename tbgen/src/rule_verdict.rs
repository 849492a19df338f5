//! `tbgen timing`'s rule verdict: the scenario's own master, as the model
//! drives its line, held to its protocol's rule book (`model::<proto>::rules`)
//! by the same edge watcher the emulator and the monitor feed, so that a
//! scenario whose master breaks a seed's limit says so before any
//! simulator runs, with the rule the emulator and the monitor would print.

use std::fmt::Write as _;

use model::rules::{self, Breach, Rule};
use model::testbench::{self, Setup};
use model::trace::{Layout, Sample, Sink};
use model::ConfigError;

/// Feeds the line signals `names` of every cycle to `watch` (time in ps at
/// `f_sys_hz`, the levels in the order of `names`) and keeps the breaches.
struct Watcher<'a, F: FnMut(u64, &[bool]) -> Vec<Breach>> {
    columns: Vec<usize>,
    f_sys_hz: u64,
    levels: Vec<bool>,
    watch: F,
    breaches: &'a mut Vec<Breach>,
}

impl<F: FnMut(u64, &[bool]) -> Vec<Breach>> Sink for Watcher<'_, F> {
    type Error = std::convert::Infallible;

    fn sample(&mut self, cycle: u64, s: &Sample) -> Result<(), Self::Error> {
        for (level, &c) in self.levels.iter_mut().zip(&self.columns) {
            *level = s.line[c] != 0;
        }
        let t = rules::ps_at(cycle, self.f_sys_hz);
        self.breaches.extend((self.watch)(t, &self.levels));
        Ok(())
    }
}

/// Runs `setup`'s bench, feeding the line signals `names` to `watch`.
fn run<S: Setup>(
    setup: &S,
    names: &[&str],
    watch: impl FnMut(u64, &[bool]) -> Vec<Breach>,
) -> Result<Vec<Breach>, ConfigError> {
    let bench = setup.bench()?;
    let layout: &Layout = model::testbench::Testbench::layout(&bench);
    let columns = names
        .iter()
        .map(|n| {
            layout
                .line
                .iter()
                .position(|p| p.name == *n)
                .unwrap_or_else(|| panic!("the bench's line has no `{n}`"))
        })
        .collect();
    let mut breaches = Vec::new();
    let mut sink = Watcher {
        columns,
        f_sys_hz: setup.timebase()?.f_sys_hz(),
        levels: vec![false; names.len()],
        watch,
        breaches: &mut breaches,
    };
    let Ok(_) = testbench::run(bench, &mut sink);
    Ok(breaches)
}

/// The verdict's lines: every rule of `book`, met or broken (its breaches
/// counted, the first shown), and what the clock cannot resolve.
fn render(book: &[&'static Rule], breaches: &[Breach], notes: Vec<String>) -> String {
    let mut s = String::from(
        "rules (the rule book the emulator and the monitor hold a master to, on the model's own line):\n",
    );
    for rule in book {
        let mine: Vec<&Breach> = breaches
            .iter()
            .filter(|b| std::ptr::eq(b.rule, *rule))
            .collect();
        match mine.first() {
            None => {
                let _ = writeln!(s, "  met     {}", rule.label());
            }
            Some(b) => {
                let _ = writeln!(
                    s,
                    "  BROKEN  {} ({} times; first at {:.3} us: {})",
                    rule.label(),
                    mine.len(),
                    rules::us(b.at_ps),
                    b.detail
                );
            }
        }
    }
    for n in notes {
        let _ = writeln!(s, "  note    {n}");
    }
    s
}

/// An SSI scenario's reader, held to `model::ssi::rules` with its
/// encoder's monoflop time.
pub fn ssi(cfg: &model::ssi::BenchConfig) -> Result<String, ConfigError> {
    use model::ssi::rules::{Limits, Watch, RULES};
    let limits = Limits::seed(cfg.encoder.monoflop_us);
    let notes = rules::resolution_notes(cfg.timebase()?.f_sys_hz(), &limits.least());
    let mut w = Watch::new(limits);
    let breaches = run(cfg, &["ssi_clk_master"], |t, l| w.sample(t, l[0]).breaches)?;
    Ok(render(RULES, &breaches, notes))
}

/// A BiSS-C scenario's master, held to `model::biss::rules` with its
/// slaves' longest timeout.
pub fn biss(cfg: &model::biss::BenchConfig) -> Result<String, ConfigError> {
    use model::biss::rules::{Limits, Watch, RULES};
    let timeout = cfg.slaves.iter().map(|s| s.timeout_us).fold(0.0, f64::max);
    let limits = Limits::seed(timeout);
    let notes = rules::resolution_notes(cfg.timebase()?.f_sys_hz(), &limits.least());
    let mut w = Watch::new(limits);
    let breaches = run(cfg, &["ma_master", "slo_master"], |t, l| {
        w.sample(t, l[0], l[1]).breaches
    })?;
    Ok(render(RULES, &breaches, notes))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Setup as S;

    fn verdict(name: &str) -> String {
        let s = crate::builtin::find(name).unwrap();
        match &s.setup {
            S::Ssi(cfg) => ssi(cfg).unwrap(),
            S::Biss(cfg) => biss(cfg).unwrap(),
            _ => panic!("{name}"),
        }
    }

    /// The seed's readers meet every rule; a reader clocked at 1 MHz with a
    /// 1 us T_cs breaks the seed's f_clk (100 to 250 kHz) and T_cs (4 us),
    /// and meets T_m (its encoder's monoflop time is shorter than its pause).
    #[test]
    fn the_seed_masters_meet_every_rule_and_a_1_mhz_reader_breaks_f_clk() {
        for name in ["ssi_seed_12bit", "biss_seed_16bit"] {
            let v = verdict(name);
            assert!(!v.contains("BROKEN"), "{name}:\n{v}");
            assert!(v.matches("  met ").count() >= 3, "{name}:\n{v}");
        }
        let v = verdict("ssi_long_cable_1mhz");
        let broken: Vec<&str> = v.lines().filter(|l| l.contains("BROKEN")).collect();
        assert_eq!(broken.len(), 2, "{v}");
        assert!(
            broken[0].contains("T_cs (seed 001") && broken[1].contains("f_clk (seed 001"),
            "{v}"
        );
        assert!(v.contains("  met     T_m (seed 001"), "{v}");
    }
}
