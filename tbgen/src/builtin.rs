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
    let mut all = FILES.iter().map(|(file, text)| Scenario::parse(text, &format!("scenarios/{file}"))).collect::<Result<Vec<_>>>()?;
    all.sort_by_key(|s| crate::PROTOCOLS.iter().position(|p| p.table == s.table()));
    Ok(all)
}

/// The built-in scenario called `name`.
pub fn find(name: &str) -> Result<Scenario> {
    all()?.into_iter().find(|s| s.name == name).ok_or_else(|| Error::UnknownScenario(name.to_string()))
}

/// A built-in scenario by name, or a scenario file by path (ending in `.toml`).
pub fn resolve(arg: &str) -> Result<Scenario> {
    if arg.ends_with(".toml") {
        let path = std::path::Path::new(arg);
        if path.exists() {
            return Scenario::load(path);
        }
        return Err(Error::UnknownScenario(arg.to_string()));
    }
    find(arg)
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
            assert!(file.starts_with(&format!("{}/", s.table())), "{file} holds a [{}] scenario", s.table());
        }
    }
}
