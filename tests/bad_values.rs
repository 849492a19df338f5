//! Whatever number a scenario file holds, `tbgen` answers with vectors or
//! with an error naming the file, the line and a field; never a panic (the
//! workspace's crates keep overflow checks and debug assertions in the
//! profile the tests run in, so an arithmetic overflow is a panic here).
//!
//! Every number of every built-in scenario (each entry of each array too)
//! is set, one at a time, to each of a list of awkward values (zero,
//! negative, NaN, infinities, huge, tiny, just past 16, 31 and 32 bits; a
//! float where an integer belongs); the scenario is parsed and checked, and
//! a set-up that is accepted is built and stepped a few thousand cycles. A
//! set-up that takes NaN fails the test too: NaN is never a setting.
//! About 60 000 set-ups, 3 s.
//!
//! The model's own property tests (`model/tests/no_panics.rs`) vary many
//! fields at once for a few protocols; this sweep reaches every protocol
//! through the registry, so a new protocol is covered by its scenarios.

use model::testbench::Testbench;
use model::Setup;
use tbgen::builtin;
use tbgen::scenario::{Scenario, Visitor};
use toml::Value;

#[path = "support/sweep.rs"]
mod sweep;
use sweep::{awkward_values, caught, dotted, leaf_mut, numeric_leaves, quiet_panics, shown, Key};

/// Cycles an accepted set-up is stepped: past power-up and a first
/// transaction of most scenarios, few enough for thousands of set-ups.
const CYCLES: u64 = 3_000;

/// Builds the bench of an accepted set-up and steps it.
struct StepAWhile;

impl Visitor for StepAWhile {
    type Output = Result<u64, String>;
    fn visit<S: Setup>(self, cfg: &S) -> Self::Output {
        let mut bench = cfg.bench().map_err(|e| e.to_string())?;
        while !bench.finished() && bench.cycle() < CYCLES {
            bench.step(None);
        }
        Ok(bench.cycle())
    }
}

#[derive(Default)]
struct Tally {
    tried: usize,
    refused: usize,
    built_refused: usize,
    stepped: usize,
    panics: Vec<String>,
    unplaced: Vec<String>,
    /// NaN is never a setting: a set-up that takes one has lost a check.
    took_nan: Vec<String>,
}

fn try_value(tally: &mut Tally, scenario: &Scenario, doc: &Value, path: &[Key], new: Value) {
    let mut doc = doc.clone();
    let nan = matches!(new, Value::Float(v) if v.is_nan());
    let origin = format!("{}+{}={}", scenario.origin, dotted(path), shown(&new));
    *leaf_mut(&mut doc, path) = new;
    let text = toml::to_string(&doc).expect("a TOML document serialises");
    tally.tried += 1;
    let outcome = caught(|| match Scenario::parse(&text, &origin) {
        Err(e) => Err(e.to_string()),
        Ok(s) => Ok(s.setup.accept(StepAWhile)),
    });
    match outcome {
        Err(panic) => tally.panics.push(format!("{origin}: {panic}")),
        Ok(Err(message)) => {
            tally.refused += 1;
            // The file and a line, `<origin>:<line>:`, then the field.
            let placed = message
                .strip_prefix(&format!("{origin}:"))
                .is_some_and(|rest| rest.starts_with(|c: char| c.is_ascii_digit()));
            if !placed || !message.contains("field") {
                tally.unplaced.push(format!("{origin}: {message}"));
            }
        }
        Ok(Ok(Err(_))) => tally.built_refused += 1,
        Ok(Ok(Ok(_))) => {
            tally.stepped += 1;
            if nan {
                tally.took_nan.push(origin);
            }
        }
    }
}

#[test]
fn every_number_in_a_scenario_is_accepted_or_refused_by_file_line_and_field() {
    quiet_panics();
    let mut tally = Tally::default();
    let mut left_out = Vec::new();
    for scenario in builtin::all().expect("built-ins parse") {
        let text = builtin::FILES
            .iter()
            .find(|(file, _)| scenario.origin == format!("scenarios/{file}"))
            .expect("a built-in's text")
            .1;
        // toml's Value holds i64: a scenario with a u64 above it (a 64-bit
        // position) is left out; its fields are in other scenarios too.
        let Ok(doc) = toml::from_str::<Value>(text) else {
            left_out.push(scenario.name.clone());
            continue;
        };
        let table = scenario.table();
        let mut leaves = Vec::new();
        numeric_leaves(
            &doc[table],
            &mut vec![Key::Field(table.into())],
            &mut leaves,
        );
        for (path, integer) in leaves {
            // A float where an integer belongs must be refused by name too.
            for new in awkward_values(integer) {
                try_value(&mut tally, &scenario, &doc, &path, new);
            }
        }
    }
    println!(
        "{} values tried: {} refused by the scenario's checks, {} refused when the bench was built, {} accepted and stepped up to {CYCLES} cycles",
        tally.tried, tally.refused, tally.built_refused, tally.stepped
    );
    println!("left out (numbers beyond i64): {left_out:?}");
    assert!(left_out.len() <= 3, "most built-ins are swept");
    assert!(
        tally.panics.is_empty(),
        "{} panics:\n{}",
        tally.panics.len(),
        tally.panics.join("\n")
    );
    assert!(
        tally.unplaced.is_empty(),
        "{} errors without the file and a line:\n{}",
        tally.unplaced.len(),
        tally.unplaced.join("\n")
    );
    assert!(
        tally.took_nan.is_empty(),
        "{} set-ups took NaN:\n{}",
        tally.took_nan.len(),
        tally.took_nan.join("\n")
    );
    assert_eq!(
        tally.built_refused, 0,
        "a set-up the checks accept must build"
    );
    assert!(
        tally.refused > tally.tried / 4 && tally.stepped > tally.tried / 10,
        "the sweep reaches both sides"
    );
}
