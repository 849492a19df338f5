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
    ("endat/pos21_1mhz.toml", include_str!("../../scenarios/endat/pos21_1mhz.toml")),
    ("endat/pos22_ad_8mhz_100m.toml", include_str!("../../scenarios/endat/pos22_ad_8mhz_100m.toml")),
    ("endat/memory_21.toml", include_str!("../../scenarios/endat/memory_21.toml")),
    ("endat/continuous_clock.toml", include_str!("../../scenarios/endat/continuous_clock.toml")),
    ("endat/params_22_2mhz.toml", include_str!("../../scenarios/endat/params_22_2mhz.toml")),
    ("endat/test_comm_21.toml", include_str!("../../scenarios/endat/test_comm_21.toml")),
    ("endat/clock_100khz.toml", include_str!("../../scenarios/endat/clock_100khz.toml")),
    ("endat/clock_4mhz.toml", include_str!("../../scenarios/endat/clock_4mhz.toml")),
    ("endat/clock_16mhz.toml", include_str!("../../scenarios/endat/clock_16mhz.toml")),
    ("endat/fault_absent_stuck.toml", include_str!("../../scenarios/endat/fault_absent_stuck.toml")),
    ("endat/fault_bit_flips.toml", include_str!("../../scenarios/endat/fault_bit_flips.toml")),
    ("endat/fault_busy.toml", include_str!("../../scenarios/endat/fault_busy.toml")),
    ("endat/fault_delay_drift.toml", include_str!("../../scenarios/endat/fault_delay_drift.toml")),
    ("endat/fault_error_types.toml", include_str!("../../scenarios/endat/fault_error_types.toml")),
    ("endat/fault_line.toml", include_str!("../../scenarios/endat/fault_line.toml")),
    ("endat/fault_meas_inconsistent.toml", include_str!("../../scenarios/endat/fault_meas_inconsistent.toml")),
    ("endat/fault_start_late.toml", include_str!("../../scenarios/endat/fault_start_late.toml")),
    ("endat/fault_stuck_high.toml", include_str!("../../scenarios/endat/fault_stuck_high.toml")),
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
