//! Fast-forward ([`Testbench::quiet_cycles`] and [`Testbench::skip`]) is
//! invisible: for every built-in scenario and every bench scenario, a bench
//! that skips whatever stretch it calls quiet runs in lockstep with one
//! stepped every cycle, and
//! - every cycle's complete sample (inputs, expected outputs, care masks,
//!   line and decoded signals) is the same, a skipped cycle's sample being
//!   the last stepped one but for the free-running counters among the
//!   decoded signals ([`Testbench::counters`]), which the next stepped
//!   cycle's sample checks;
//! - both finish on the same cycle with the same transcript.
//!
//! Recording runs step every cycle, so the vectors, waves and transcripts
//! `tbgen gen` writes are the stepping ones; this test is what lets
//! campaigns and `tbgen bench` use the fast-forward and still mean them.

use model::testbench::Testbench;
use model::trace::Sample;
use tbgen::builtin;
use tbgen::scenario::{Scenario, Visitor};

/// Cycles run and cycles skipped.
struct Lockstep<'a>(&'a str);

impl Visitor for Lockstep<'_> {
    type Output = (u64, u64);
    fn visit<S: model::Setup>(self, cfg: &S) -> (u64, u64) {
        let name = self.0;
        let mut stepped = cfg.bench().expect("a built-in scenario builds");
        let mut skipping = cfg.bench().expect("a built-in scenario builds");
        let mut want = Sample::for_layout(stepped.layout());
        let mut got: Option<Sample> = None;
        let mut skipped = 0;
        while !skipping.finished() {
            assert!(!stepped.finished(), "{name}: the fast-forwarded bench runs past the end, cycle {}", stepped.cycle());
            let quiet = skipping.quiet_cycles();
            if quiet == 0 {
                let mut sample = got.take().unwrap_or_else(|| Sample::for_layout(skipping.layout()));
                skipping.step(Some(&mut sample));
                stepped.step(Some(&mut want));
                assert_eq!(sample, want, "{name}: cycle {} differs after fast-forwards", stepped.cycle() - 1);
                got = Some(sample);
                continue;
            }
            let start = skipping.cycle();
            skipping.skip(quiet);
            skipped += quiet;
            let counters = skipping.counters();
            for _ in 0..quiet {
                assert!(!stepped.finished(), "{name}: the skip from cycle {start} by {quiet} runs past the end");
                stepped.step(Some(&mut want));
                // Before the first step there is no sample to compare with:
                // the skipped cycles must then all show the first one.
                let reference = got.get_or_insert_with(|| want.clone());
                assert_eq!(
                    reference.without_counters(counters),
                    want.without_counters(counters),
                    "{name}: cycle {} changes within the {quiet} cycles skipped from cycle {start}",
                    stepped.cycle() - 1
                );
            }
            assert_eq!(skipping.cycle(), stepped.cycle(), "{name}: skip({quiet}) from cycle {start} lands on the wrong cycle");
        }
        assert!(stepped.finished(), "{name}: the fast-forwarded bench finished at cycle {}, stepping did not", skipping.cycle());
        let cycles = stepped.cycle();
        let to_json = |t: Vec<_>| serde_json::to_string(&t).expect("transactions serialise");
        assert_eq!(to_json(skipping.into_transactions()), to_json(stepped.into_transactions()), "{name}: transcripts differ");
        (cycles, skipped)
    }
}

fn bench_scenarios() -> Vec<Scenario> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/bench");
    let mut paths: Vec<_> = std::fs::read_dir(&dir).expect("scenarios/bench exists").map(|e| e.unwrap().path()).collect();
    paths.sort();
    paths.iter().map(|p| Scenario::load(p).expect("a bench scenario parses")).collect()
}

#[test]
fn fast_forward_matches_stepping_on_every_scenario() {
    let mut scenarios = builtin::all().expect("built-ins parse");
    scenarios.extend(bench_scenarios());
    let mut skipped_by_core = std::collections::BTreeMap::<&str, (u64, u64)>::new();
    for s in &scenarios {
        let (cycles, skipped) = s.setup.accept(Lockstep(&s.name));
        let entry = skipped_by_core.entry(s.core()).or_default();
        entry.0 += cycles;
        entry.1 += skipped;
    }
    for (core, (cycles, skipped)) in &skipped_by_core {
        println!("{core:>14}: {skipped} of {cycles} cycles skipped ({:.1} %)", 100.0 * *skipped as f64 / *cycles as f64);
    }
    // The protocols with quiet stretches do skip them, so the comparison
    // above is not of two stepped runs.
    for core in ["ssi_master", "biss_master", "endat_master", "esl_host", "tformat_host", "sar_async_host", "modbus_master", "uart_rx", "can_controller", "canopen_master"] {
        let (cycles, skipped) = skipped_by_core[core];
        assert!(skipped * 2 > cycles, "{core}: only {skipped} of {cycles} cycles skipped");
    }
}
