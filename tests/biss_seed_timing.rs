//! Every built-in BiSS-C scenario keeps the seed's line timing (seed 001,
//! BiSS-C timing table): every MA high and low phase longer than 25 ns
//! (TMASH, TMASL), and the slave busy at least 2 x TMAS after its ack
//! (Tbusy), checked on a full run of each scenario by
//! `model::biss::seed_timing::check` (the same runs `tbgen gen` writes as vectors).

use model::biss::BenchConfig;
use tbgen::builtin;

#[test]
fn every_builtin_biss_scenario_keeps_tmash_tmasl_and_t_busy() {
    let mut checked = 0;
    let mut report = Vec::new();
    for s in builtin::all().expect("built-ins parse") {
        let Some(cfg) = s.setup.get::<BenchConfig>() else {
            continue;
        };
        let bad = model::biss::seed_timing::check(cfg).expect("a built-in scenario builds");
        checked += 1;
        if !bad.is_empty() {
            report.push(format!(
                "{} ({} violations), first: {}",
                s.name,
                bad.len(),
                bad[0]
            ));
        }
    }
    assert!(checked >= 20, "only {checked} BiSS-C scenarios found");
    assert!(
        report.is_empty(),
        "seed timing violated:\n{}",
        report.join("\n")
    );
}
