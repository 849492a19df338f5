//! The compliance matrices, `docs/compliance/<protocol>.md`: every clause of
//! a protocol's standard ([`model::compliance`]) with the tests that
//! exercise it, the scenarios they run and what they assert, and the
//! clauses no test exercises as gap rows.
//!
//! The clauses are data in `model` (their words written once); each test
//! declares what it exercises beside itself with [`exercise!`] (the test
//! function must exist: the compiler checks the name), naming clauses by id
//! and never restating their words. `compliance_matrices_are_current`
//! writes the matrices from both and fails when a committed one is stale,
//! when a test names a clause, role or scenario that does not exist, or when
//! a scenario has no vectors.

use std::fmt::Write as _;
use std::path::Path;

use model::compliance::{Role, Roles, Standard};

/// What one test exercises.
pub(crate) struct Exercise {
    /// The test function's name.
    pub test: &'static str,
    /// The built-in scenarios it runs.
    pub scenarios: &'static [&'static str],
    /// What it asserts, in a few words (the check that observes the clauses).
    pub observes: &'static str,
    /// The clauses it exercises, by id, each with the node's role
    /// ([`Role::Any`] for a clause held in one row).
    pub clauses: &'static [(&'static str, Role)],
}

/// `exercise!(test_fn, ["scenario", ..], "what it asserts", [("clause", Role), ..])`:
/// an [`Exercise`] of the test function `test_fn`, which must be in scope.
macro_rules! exercise {
    ($test:ident, [$($s:literal),* $(,)?], $observes:literal, [$(($c:literal, $r:ident)),* $(,)?]) => {
        $crate::compliance::Exercise {
            test: {
                const _: fn() = $test;
                stringify!($test)
            },
            scenarios: &[$($s),*],
            observes: $observes,
            clauses: &[$(($c, model::compliance::Role::$r)),*],
        }
    };
}
pub(crate) use exercise;

/// The exercises each protocol's tests declare.
fn exercises(protocol: &str) -> &'static [Exercise] {
    match protocol {
        "can" => crate::can::families::tests::EXERCISES,
        "canopen" => crate::canopen::tests::compliance::EXERCISES,
        _ => &[],
    }
}

/// Where a protocol's exercises are declared, for messages.
fn declared_in(protocol: &str) -> &'static str {
    match protocol {
        "can" => "tbgen/src/can/families.rs",
        "canopen" => "tbgen/src/canopen/compliance.rs",
        _ => "nowhere (tbgen/src/compliance.rs: `exercises`)",
    }
}

/// Checks every exercise against the standard and the built-in scenarios:
/// each clause id exists and takes the role given, each scenario is a
/// built-in of the protocol with committed vectors.
fn validate(standard: &Standard, ex: &[Exercise], root: &Path) -> Result<(), String> {
    let file = declared_in(standard.protocol);
    let builtins = crate::builtin::all().map_err(|e| e.to_string())?;
    for e in ex {
        let at = format!("{file}: exercise of `{}`", e.test);
        if e.clauses.is_empty() || e.scenarios.is_empty() {
            return Err(format!(
                "{at}: names no clause or no scenario (give both, or remove the exercise)"
            ));
        }
        for &(id, role) in e.clauses {
            let Some(c) = standard.clause(id) else {
                return Err(format!(
                    "{at}: clause `{id}` is not a clause of {} (model/src/{}/clauses.rs): use one of its ids or add the clause there",
                    standard.title, standard.protocol
                ));
            };
            let fits = match c.roles {
                Roles::Any => role == Role::Any,
                Roles::TransmitterAndReceiver => role != Role::Any,
            };
            if !fits {
                return Err(format!(
                    "{at}: clause `{id}` is held {}, not with role `{role:?}`",
                    match c.roles {
                        Roles::Any => "in one row (role `Any`)",
                        Roles::TransmitterAndReceiver => "as `Transmitter` and as `Receiver`",
                    }
                ));
            }
        }
        for &name in e.scenarios {
            let Some(s) = builtins.iter().find(|s| s.name == name) else {
                return Err(format!(
                    "{at}: scenario `{name}` is not a built-in scenario (scenarios/{}/)",
                    standard.protocol
                ));
            };
            if s.table() != standard.protocol {
                return Err(format!(
                    "{at}: scenario `{name}` is a `{}` scenario, not `{}`",
                    s.table(),
                    standard.protocol
                ));
            }
            let hex = root.join(format!("vectors/{}/{name}.hex", s.core()));
            if !hex.is_file() {
                return Err(format!(
                    "{at}: scenario `{name}` has no vectors ({}): run `make vectors`",
                    hex.display()
                ));
            }
        }
    }
    Ok(())
}

/// A table cell: no line breaks or pipes.
fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

/// The matrix of one standard.
fn document(standard: &Standard, ex: &[Exercise]) -> String {
    let rows: usize = standard.clauses().map(|c| c.rows().len()).sum();
    let hit = |id: &'static str, role: Role| {
        ex.iter()
            .filter(move |e| e.clauses.iter().any(|&(c, r)| c == id && r == role))
    };
    let gaps = standard
        .clauses()
        .flat_map(|c| c.rows().iter().map(move |&r| (c.id, r)))
        .filter(|&(id, r)| hit(id, r).next().is_none())
        .count();
    let mut s = format!(
        "# Compliance matrix: {proto}\n\n\
         Every clause of {title} that the project holds its `{proto}` core to, with the tests that exercise it,\n\
         the scenarios they run and what they assert; a clause no test exercises is a **gap** row. Generated by\n\
         `cargo test --release -p tbgen --lib compliance` from the clauses (`model/src/{proto}/clauses.rs`, the words\n\
         written once) and the exercises the tests declare beside themselves (`{file}`);\n\
         `WRITE_COMPLIANCE_MD=1` with that command rewrites it, and the test fails while this file is stale.\n\n\
         Each test runs its scenarios through the model and asserts its transcript; every scenario named also has\n\
         vectors (`vectors/<core>/<scenario>.hex`) that the RTL replays in Icarus and Verilator, every output\n\
         compared every cycle, so what a test asserts of the model holds\n\
         of the core. A clause the rule book quotes (`docs/rules.md`) is also watched on the master's pins by the\n\
         monitor and the emulator in every closed loop.\n\n\
         {n} clauses, {rows} rows: {done} exercised, {gaps} gaps.\n",
        proto = standard.protocol,
        title = standard.title,
        file = declared_in(standard.protocol),
        n = standard.clauses().count(),
        done = rows - gaps,
    );
    for (group, clauses) in standard.groups {
        let _ = write!(
            s,
            "\n## {group}\n\n| clause | section: the standard's words | role | scenarios | test: what it asserts |\n|---|---|---|---|---|\n"
        );
        for c in clauses.iter() {
            for (k, &role) in c.rows().iter().enumerate() {
                let found: Vec<&Exercise> = hit(c.id, role).collect();
                let (scenarios, tests) = if found.is_empty() {
                    ("**gap**".to_string(), "no test exercises it".to_string())
                } else {
                    let mut names: Vec<&str> = found
                        .iter()
                        .flat_map(|e| e.scenarios.iter().copied())
                        .collect();
                    names.sort_unstable();
                    names.dedup();
                    let names: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
                    let tests: Vec<String> = found
                        .iter()
                        .map(|e| format!("`{}`: {}", e.test, cell(e.observes)))
                        .collect();
                    (names.join(", "), tests.join("<br>"))
                };
                let rule = c
                    .rule()
                    .map(|r| format!("<br>rule book `{}` on the master's pins", r.name))
                    .unwrap_or_default();
                // The words once per clause: a second role's row refers to the first.
                let text = if k == 0 {
                    format!("{}: \"{}\"", cell(c.section()), cell(c.words()))
                } else {
                    "(the row above)".to_string()
                };
                let _ = writeln!(
                    s,
                    "| `{}`: {} | {text} | {} | {scenarios} | {tests}{rule} |",
                    c.id,
                    cell(c.short),
                    role.name()
                );
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn root() -> &'static Path {
        Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
    }

    /// `docs/compliance/<protocol>.md` is what the exercises and clauses give.
    #[test]
    fn compliance_matrices_are_current() {
        for standard in model::compliance::standards() {
            let ex = exercises(standard.protocol);
            validate(standard, ex, root()).unwrap_or_else(|e| panic!("{e}"));
            let path = root().join(format!("docs/compliance/{}.md", standard.protocol));
            let fresh = document(standard, ex);
            if std::env::var_os("WRITE_COMPLIANCE_MD").is_some() {
                std::fs::create_dir_all(path.parent().unwrap()).unwrap();
                std::fs::write(&path, &fresh).unwrap();
            }
            let committed = std::fs::read_to_string(&path).unwrap_or_default();
            assert!(
                committed == fresh,
                "{} is not what the exercises give: run `WRITE_COMPLIANCE_MD=1 cargo test --release -p tbgen --lib compliance` and commit it",
                path.display()
            );
        }
    }

    /// Clause ids are unique within a standard.
    #[test]
    fn every_clause_has_one_id() {
        for standard in model::compliance::standards() {
            let ids: Vec<&str> = standard.clauses().map(|c| c.id).collect();
            for (i, id) in ids.iter().enumerate() {
                assert!(
                    !ids[i + 1..].contains(id),
                    "{}: clause `{id}` twice",
                    standard.protocol
                );
            }
        }
    }

    fn probe() {}

    /// A test naming a clause, a role or a scenario that does not exist
    /// fails the suite, with the file and the fix.
    #[test]
    fn an_unknown_clause_role_or_scenario_is_refused() {
        let standard = &model::can::clauses::STANDARD;
        let bad = [
            exercise!(probe, ["can_err_bit"], "x", [("fc-13", Transmitter)]),
            exercise!(probe, ["can_err_bit"], "x", [("fc-1", Any)]),
            exercise!(probe, ["can_err_bit"], "x", [("bit-error", Receiver)]),
            exercise!(probe, ["can_err_bits"], "x", [("bit-error", Any)]),
            exercise!(probe, ["ssi_seed_12bit"], "x", [("bit-error", Any)]),
        ];
        for (e, says) in bad.iter().zip([
            "clause `fc-13` is not a clause",
            "not with role `Any`",
            "not with role `Receiver`",
            "`can_err_bits` is not a built-in",
            "is a `ssi` scenario",
        ]) {
            let err = validate(standard, std::slice::from_ref(e), root()).unwrap_err();
            assert!(
                err.contains(says)
                    && err.contains("tbgen/src/can/families.rs")
                    && err.contains("`probe`"),
                "{err}"
            );
        }
        assert_eq!(validate(standard, exercises("can"), root()), Ok(()));
    }
}
