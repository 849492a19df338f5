//! The built-in scenarios: the TOML files under `scenarios/`, compiled in so
//! that `tbgen list` and `tbgen gen <name>` work from any folder. Each file
//! is also a worked example for writing one's own.

use crate::scenario::Scenario;
use crate::{Error, Result};

/// `(file name, text)` of every built-in scenario: each `.toml` under
/// `scenarios/<table>/` (not `scenarios/bench/`), collected by `build.rs`
/// in folder then file-name order.
pub const FILES: &[(&str, &str)] = include!(concat!(env!("OUT_DIR"), "/builtin_files.rs"));

/// Every built-in scenario, parsed, in listing order: registry order
/// (`crate::PROTOCOLS`), then file name.
pub fn all() -> Result<Vec<Scenario>> {
    let mut all = FILES
        .iter()
        .map(|(file, text)| Scenario::parse(text, &format!("scenarios/{file}")))
        .collect::<Result<Vec<_>>>()?;
    all.sort_by_key(|s| crate::PROTOCOLS.iter().position(|p| p.table == s.table()));
    Ok(all)
}

/// The built-in scenario called `name`; a name that is not one gets the
/// nearest built-in names as a suggestion.
pub fn find(name: &str) -> Result<Scenario> {
    let all = all()?;
    if let Some(i) = all.iter().position(|s| s.name == name) {
        return Ok(all.into_iter().nth(i).expect("position found"));
    }
    let mut near: Vec<(usize, &str)> = all
        .iter()
        .map(|s| (distance(name, &s.name), s.name.as_str()))
        .collect();
    near.sort();
    let best = near.first().map(|n| n.0).unwrap_or(usize::MAX);
    let close: Vec<String> = near
        .iter()
        .take_while(|n| n.0 == best && best <= name.len().max(4) / 3)
        .map(|n| format!("`{}`", n.1))
        .collect();
    let hint = if close.is_empty() {
        String::new()
    } else {
        format!(" (did you mean {}?)", close.join(" or "))
    };
    Err(Error::UnknownScenario(name.to_string(), hint))
}

/// Edit distance (insertions, deletions, substitutions) between two names.
fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let next = (diag + usize::from(ca != *cb))
                .min(row[j] + 1)
                .min(row[j + 1] + 1);
            diag = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

/// A built-in scenario by name, or a scenario file by path (ending in `.toml`).
pub fn resolve(arg: &str) -> Result<Scenario> {
    if arg.ends_with(".toml") {
        return Scenario::load(std::path::Path::new(arg));
    }
    find(arg)
}

/// Every scenario of `args` (names or files); two that would write files of
/// the same name into one folder are refused.
pub fn resolve_all(args: &[String]) -> Result<Vec<Scenario>> {
    let chosen = args
        .iter()
        .map(|a| resolve(a))
        .collect::<Result<Vec<_>>>()?;
    for (i, s) in chosen.iter().enumerate() {
        if let Some(t) = chosen[..i].iter().find(|t| t.name == s.name) {
            return Err(Error::Scenario {
                file: s.origin.clone(),
                message: format!("name `{}` is also the name of {}: both would write {0}.hex, .vcd, .json and .gtkw; rename one or generate them into separate --out folders", s.name, t.origin),
            });
        }
    }
    Ok(chosen)
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_builtin_parses_and_names_are_unique() {
        let all = super::all().unwrap();
        let mut names: Vec<_> = all.iter().map(|s| s.name.clone()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), super::FILES.len());
    }

    #[test]
    fn every_scenario_folder_holds_scenarios_of_its_own_table() {
        // scenarios/<table>/ is the protocol's folder: a file in another
        // protocol's folder would be listed and generated under the wrong name.
        for (file, text) in super::FILES {
            let s = crate::scenario::Scenario::parse(text, file).unwrap();
            assert!(
                file.starts_with(&format!("{}/", s.table())),
                "{file} holds a [{}] scenario",
                s.table()
            );
        }
    }

    #[test]
    fn a_mistyped_name_gets_the_nearest_names() {
        let msg = super::find("ssi_seed_12bits").unwrap_err().to_string();
        assert!(msg.contains("did you mean `ssi_seed_12bit`?"), "{msg}");
        let msg = super::find("qqqqqqqqqqqq").unwrap_err().to_string();
        assert!(!msg.contains("did you mean"), "{msg}");
    }

    #[test]
    fn two_scenarios_of_one_name_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("mine.toml");
        std::fs::write(&file, "name = \"ssi_seed_12bit\"\n[ssi]\npositions = [1]\n").unwrap();
        let args = vec!["ssi_seed_12bit".to_string(), file.display().to_string()];
        let msg = super::resolve_all(&args).unwrap_err().to_string();
        assert!(
            msg.contains("name `ssi_seed_12bit` is also the name of scenarios/ssi/seed_12bit.toml"),
            "{msg}"
        );
    }

    #[test]
    fn a_missing_or_binary_file_is_reported_as_such_with_exit_status_2() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("nothere.toml");
        let e = super::resolve(&missing.display().to_string()).unwrap_err();
        assert!(
            e.to_string()
                .contains("nothere.toml: no such scenario file"),
            "{e}"
        );
        assert_eq!(e.exit_code(), 2);
        let binary = dir.path().join("bin.toml");
        std::fs::write(&binary, [0u8, 159, 146, 150, 255]).unwrap();
        let e = super::resolve(&binary.display().to_string()).unwrap_err();
        assert!(e.to_string().contains("not a text file"), "{e}");
        assert_eq!(e.exit_code(), 2);
    }
}
