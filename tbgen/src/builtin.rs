//! The built-in scenarios: the TOML files under `scenarios/`, compiled in so
//! that `tbgen list` and `tbgen gen <name>` work from any folder. Each file
//! is also a worked example for writing one's own.

use crate::scenario::Scenario;
use crate::{Error, Result};

/// `(file name, text)` of every built-in scenario, in listing order.
pub const FILES: &[(&str, &str)] = &[
    ("ssi/seed_12bit.toml", include_str!("../../scenarios/ssi/seed_12bit.toml")),
    ("ssi/gray_double_read.toml", include_str!("../../scenarios/ssi/gray_double_read.toml")),
    ("ssi/too_many_clocks.toml", include_str!("../../scenarios/ssi/too_many_clocks.toml")),
    ("ssi/too_many_clocks_repeat.toml", include_str!("../../scenarios/ssi/too_many_clocks_repeat.toml")),
    ("ssi/too_few_clocks.toml", include_str!("../../scenarios/ssi/too_few_clocks.toml")),
    ("ssi/wire_check_stuck_high.toml", include_str!("../../scenarios/ssi/wire_check_stuck_high.toml")),
    ("ssi/stuck_low.toml", include_str!("../../scenarios/ssi/stuck_low.toml")),
    ("ssi/monoflop_violation.toml", include_str!("../../scenarios/ssi/monoflop_violation.toml")),
    ("ssi/long_cable_1mhz.toml", include_str!("../../scenarios/ssi/long_cable_1mhz.toml")),
    ("ssi/wide_64bit.toml", include_str!("../../scenarios/ssi/wide_64bit.toml")),
    ("uart/esl_10mbps_all_bytes.toml", include_str!("../../scenarios/uart/esl_10mbps_all_bytes.toml")),
    ("uart/tformat_2m5_jitter.toml", include_str!("../../scenarios/uart/tformat_2m5_jitter.toml")),
    ("uart/baud_plus_3.toml", include_str!("../../scenarios/uart/baud_plus_3.toml")),
    ("uart/baud_minus_3.toml", include_str!("../../scenarios/uart/baud_minus_3.toml")),
    ("uart/baud_plus_6.toml", include_str!("../../scenarios/uart/baud_plus_6.toml")),
    ("uart/glitch_and_break.toml", include_str!("../../scenarios/uart/glitch_and_break.toml")),
];

/// Every built-in scenario, parsed.
pub fn all() -> Result<Vec<Scenario>> {
    FILES.iter().map(|(file, text)| Scenario::parse(text, &format!("scenarios/{file}"))).collect()
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
}
