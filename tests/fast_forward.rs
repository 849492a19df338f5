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
use model::Setup;
use tbgen::builtin;
use tbgen::scenario::{Scenario, Visitor};

/// Cycles run and cycles skipped.
struct LockstepRun<'a>(&'a str);

impl Visitor for LockstepRun<'_> {
    type Output = (u64, u64);
    fn visit<S: model::Setup>(self, cfg: &S) -> (u64, u64) {
        let name = self.0;
        // lockstep compiled with the model: this test crate is not optimised (Cargo.toml).
        let run = cfg
            .bench()
            .expect("a built-in scenario builds")
            .lockstep_compiled(name, cfg.bench().expect("a built-in scenario builds"));
        let to_json = |t: &Vec<_>| serde_json::to_string(t).expect("transactions serialise");
        assert_eq!(
            to_json(&run.skipping),
            to_json(&run.stepped),
            "{name}: transcripts differ"
        );
        // The run campaigns and `tbgen bench` use, which records nothing:
        // a bench may then run its parts on their own events (CAN), which
        // the lockstep above, stepping whenever it records, does not show.
        let fast = cfg
            .bench()
            .expect("a built-in scenario builds")
            .run_to_end_compiled();
        assert_eq!(
            (fast.cycles, to_json(&fast.transactions)),
            (run.cycles, to_json(&run.stepped)),
            "{name}: the fast-forwarded run ends otherwise"
        );
        (run.cycles, run.skipped)
    }
}

fn bench_scenarios() -> Vec<Scenario> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/bench");
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .expect("scenarios/bench exists")
        .map(|e| e.unwrap().path())
        .collect();
    paths.sort();
    paths
        .iter()
        .map(|p| Scenario::load(p).expect("a bench scenario parses"))
        .collect()
}

#[test]
fn fast_forward_matches_stepping_on_every_scenario() {
    let mut scenarios = builtin::all().expect("built-ins parse");
    scenarios.extend(bench_scenarios());
    let mut skipped_by_core = std::collections::BTreeMap::<&str, (u64, u64)>::new();
    for s in &scenarios {
        let (cycles, skipped) = s.setup.accept(LockstepRun(&s.name));
        let entry = skipped_by_core.entry(s.core()).or_default();
        entry.0 += cycles;
        entry.1 += skipped;
    }
    for (core, (cycles, skipped)) in &skipped_by_core {
        println!(
            "{core:>14}: {skipped} of {cycles} cycles skipped ({:.1} %)",
            100.0 * *skipped as f64 / *cycles as f64
        );
    }
    // Every protocol has quiet stretches and skips them, so the comparison
    // above is not of two stepped runs.
    for core in tbgen::PROTOCOLS.iter().map(|p| p.core) {
        let (cycles, skipped) = *skipped_by_core
            .get(core)
            .unwrap_or_else(|| panic!("{core}: no scenario"));
        assert!(
            skipped * 2 > cycles,
            "{core}: only {skipped} of {cycles} cycles skipped"
        );
    }
}

/// The CAN bench runs each of its parts (the core, the monitor at its pin,
/// each emulated node) only on its own events when it records nothing
/// (`Bench::quiet_cycles`); in between a part is left behind and catches
/// up when it next steps. After every third step of such a run on every
/// CAN scenario, each part, brought to the current cycle, is in the state
/// stepping every part every cycle leaves it in: what `lockstep`, which
/// steps every part whenever it records, cannot show.
#[test]
fn can_parts_stepped_on_their_own_events_match_stepping() {
    let mut scenarios = builtin::all().expect("built-ins parse");
    scenarios.extend(bench_scenarios());
    let mut checked = 0;
    for s in &scenarios {
        let Some(cfg) = s.setup.get::<model::can::BenchConfig>() else {
            continue;
        };
        let name = &s.name;
        let (mut lazy, mut stepped) = (cfg.bench().expect("builds"), cfg.bench().expect("builds"));
        let mut steps = 0u64;
        let parts = |b: &model::can::Bench| format!("{:?}", (b.dut(), b.monitor(), b.nodes()));
        while !lazy.finished() {
            match lazy.quiet_cycles() {
                0 => lazy.step_due(),
                n => {
                    lazy.skip(n);
                    continue;
                }
            }
            steps += 1;
            // Every third step, so that parts also stay behind across
            // several steps of the others before they catch up.
            if steps % 3 != 0 {
                continue;
            }
            while stepped.cycle() < lazy.cycle() {
                stepped.step(None);
            }
            lazy.catch_up();
            assert_eq!(
                parts(&lazy),
                parts(&stepped),
                "{name}: a part differs after the step of cycle {}",
                lazy.cycle() - 1
            );
            checked += 1;
        }
        while stepped.cycle() < lazy.cycle() {
            stepped.step(None);
        }
        assert!(
            stepped.finished(),
            "{name}: stepping has not finished on cycle {}",
            lazy.cycle()
        );
    }
    assert!(checked > 10_000, "only {checked} steps compared");
}
