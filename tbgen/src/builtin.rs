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
    ("tformat/readout_all_ids.toml", include_str!("../../scenarios/tformat/readout_all_ids.toml")),
    ("tformat/eeprom_write_read.toml", include_str!("../../scenarios/tformat/eeprom_write_read.toml")),
    ("tformat/reset_multi_turn.toml", include_str!("../../scenarios/tformat/reset_multi_turn.toml")),
    ("tformat/abnormal_requests.toml", include_str!("../../scenarios/tformat/abnormal_requests.toml")),
    ("tformat/no_answer.toml", include_str!("../../scenarios/tformat/no_answer.toml")),
    ("tformat/long_cable_100m.toml", include_str!("../../scenarios/tformat/long_cable_100m.toml")),
    ("tformat/answer_bit_flips.toml", include_str!("../../scenarios/tformat/answer_bit_flips.toml")),
    ("tformat/baud_minus_3.toml", include_str!("../../scenarios/tformat/baud_minus_3.toml")),
    ("tformat/baud_plus_3.toml", include_str!("../../scenarios/tformat/baud_plus_3.toml")),
    ("tformat/baud_plus_6.toml", include_str!("../../scenarios/tformat/baud_plus_6.toml")),
    ("tformat/jitter_100ns.toml", include_str!("../../scenarios/tformat/jitter_100ns.toml")),
    ("tformat/line_stuck_low.toml", include_str!("../../scenarios/tformat/line_stuck_low.toml")),
    ("tformat/line_stuck_high.toml", include_str!("../../scenarios/tformat/line_stuck_high.toml")),
    ("tformat/second_driver.toml", include_str!("../../scenarios/tformat/second_driver.toml")),
    ("tformat/truncated_answer.toml", include_str!("../../scenarios/tformat/truncated_answer.toml")),
    ("biss/seed_16bit.toml", include_str!("../../scenarios/biss/seed_16bit.toml")),
    ("biss/width_12bit.toml", include_str!("../../scenarios/biss/width_12bit.toml")),
    ("biss/width_24bit.toml", include_str!("../../scenarios/biss/width_24bit.toml")),
    ("biss/width_64bit.toml", include_str!("../../scenarios/biss/width_64bit.toml")),
    ("biss/clock_1mhz_100m.toml", include_str!("../../scenarios/biss/clock_1mhz_100m.toml")),
    ("biss/clock_2_5mhz_50m.toml", include_str!("../../scenarios/biss/clock_2_5mhz_50m.toml")),
    ("biss/clock_5mhz_0m.toml", include_str!("../../scenarios/biss/clock_5mhz_0m.toml")),
    ("biss/clock_10mhz_100m.toml", include_str!("../../scenarios/biss/clock_10mhz_100m.toml")),
    ("biss/chain_3slaves.toml", include_str!("../../scenarios/biss/chain_3slaves.toml")),
    ("biss/register_read.toml", include_str!("../../scenarios/biss/register_read.toml")),
    ("biss/register_write.toml", include_str!("../../scenarios/biss/register_write.toml")),
    ("biss/fault_bit_flips.toml", include_str!("../../scenarios/biss/fault_bit_flips.toml")),
    ("biss/fault_no_ack.toml", include_str!("../../scenarios/biss/fault_no_ack.toml")),
    ("biss/fault_stuck_high.toml", include_str!("../../scenarios/biss/fault_stuck_high.toml")),
    ("biss/fault_stuck_low.toml", include_str!("../../scenarios/biss/fault_stuck_low.toml")),
    ("biss/fault_start_late.toml", include_str!("../../scenarios/biss/fault_start_late.toml")),
    ("biss/fault_delay_beyond.toml", include_str!("../../scenarios/biss/fault_delay_beyond.toml")),
    ("biss/fault_crc4_read.toml", include_str!("../../scenarios/biss/fault_crc4_read.toml")),
    ("biss/fault_crc4_address.toml", include_str!("../../scenarios/biss/fault_crc4_address.toml")),
    ("biss/calibration_drift.toml", include_str!("../../scenarios/biss/calibration_drift.toml")),
    ("biss/command_chain.toml", include_str!("../../scenarios/biss/command_chain.toml")),
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
    ("endat/mrs_areas_22.toml", include_str!("../../scenarios/endat/mrs_areas_22.toml")),
    ("endat/additional_data.toml", include_str!("../../scenarios/endat/additional_data.toml")),
    ("endat/fault_type2_22.toml", include_str!("../../scenarios/endat/fault_type2_22.toml")),
    ("endat/recovery_time_switch.toml", include_str!("../../scenarios/endat/recovery_time_switch.toml")),
    ("endat/datum_shift_linear.toml", include_str!("../../scenarios/endat/datum_shift_linear.toml")),
    ("endat/pos22_48bit_4mhz.toml", include_str!("../../scenarios/endat/pos22_48bit_4mhz.toml")),
    ("esl/readout_all_ids.toml", include_str!("../../scenarios/esl/readout_all_ids.toml")),
    ("esl/clear_commands_8x.toml", include_str!("../../scenarios/esl/clear_commands_8x.toml")),
    ("esl/eeprom_page_write_read.toml", include_str!("../../scenarios/esl/eeprom_page_write_read.toml")),
    ("esl/eeprom_busy.toml", include_str!("../../scenarios/esl/eeprom_busy.toml")),
    ("esl/daisy_chain.toml", include_str!("../../scenarios/esl/daisy_chain.toml")),
    ("esl/baud_minus_3.toml", include_str!("../../scenarios/esl/baud_minus_3.toml")),
    ("esl/baud_plus_3.toml", include_str!("../../scenarios/esl/baud_plus_3.toml")),
    ("esl/baud_minus_6.toml", include_str!("../../scenarios/esl/baud_minus_6.toml")),
    ("esl/baud_plus_6.toml", include_str!("../../scenarios/esl/baud_plus_6.toml")),
    ("esl/fault_answer_bit_flips.toml", include_str!("../../scenarios/esl/fault_answer_bit_flips.toml")),
    ("esl/fault_abnormal_requests.toml", include_str!("../../scenarios/esl/fault_abnormal_requests.toml")),
    ("esl/fault_sequence_and_channels.toml", include_str!("../../scenarios/esl/fault_sequence_and_channels.toml")),
    ("esl/fault_truncated_no_answer_intruder.toml", include_str!("../../scenarios/esl/fault_truncated_no_answer_intruder.toml")),
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
