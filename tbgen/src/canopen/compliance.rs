// The clauses of `model::canopen::clauses` (seed 003) each CANopen test
// exercises; `docs/compliance/canopen.md` is written from this list.
// Included into the tests' module by `include!`, so that `exercise!` names
// the test functions themselves.

/// What each CANopen test exercises of seed 003.
pub(crate) mod compliance {
    use super::*;
    use crate::compliance::{exercise, Exercise};

    pub(crate) const EXERCISES: &[Exercise] = &[
        exercise!(the_setup_example_frame_by_frame, ["canopen_setup_example"], "every frame on the bus: boot-up 0x8C with no data, the SDO download of 6200h and its confirmation on 0x60C and 0x58C, NMT 01 0C on 0, the position on 0x18C every 10 ms", [("cob-id", Any), ("boot-up", Any), ("emergency", Any), ("nmt", Any), ("sdo-rx", Any), ("sdo-tx", Any), ("pdo1-tx", Any), ("setup-sdo", Any), ("setup-start", Any), ("setup-position", Any)]),
        exercise!(cyclic_pdos_at_two_rates, ["canopen_cyclic_1ms_1000k", "canopen_cyclic_5ms_125k"], "PDO1 periods within a bit of the cyclic timer, the position's steps", [("pdo1-tx", Any), ("setup-position", Any)]),
        exercise!(tpdo2_after_every_second_sync, ["canopen_sync_tpdo2"], "SYNC on 0x080 with no data, PDO2 on 0x287 after every second", [("sync", Any), ("pdo2-tx", Any)]),
        exercise!(scaling_example_a_through_the_master, ["canopen_scaling_cyclic"], "the position of the note's cyclic example (1000 units, 32 000 range) and cyclic operation chosen", [("scaling-formula", Any), ("cyclic-operation", Any)]),
        exercise!(scaling_example_b_and_preset_through_the_master, ["canopen_scaling_non_cyclic_preset"], "the non-cyclic example (100 units, 5000 range), preset 1200: 6509h holds -3799, the output 1200", [("scaling-formula", Any), ("non-cyclic-operation", Any), ("preset", Any), ("preset-offset", Any)]),
        exercise!(an_sdo_abort_is_reported_and_stops_the_master, ["canopen_sdo_abort"], "6001h below its range refused (abort TOO_LOW), the master FAILED", [("scaling-range", Any)]),
        exercise!(every_abort_code_through_the_master, ["canopen_abort_range"], "5001h outside 1 to 127 refused (abort RANGE)", [("object-5001", Any)]),
        exercise!(node_guarding_and_the_life_guarding_emergency, ["canopen_node_guarding"], "the guarding answers on 0x708 with the toggle bit, the life-guarding emergency 8130h on 0x88", [("nodeguard", Any), ("emergency", Any), ("setup-emergency", Any)]),
        exercise!(eight_entries_and_the_heartbeat, ["canopen_eight_params_heartbeat"], "the master's SDO requests in order, 6001h before 6002h", [("scaling-order", Any)]),
        exercise!(a_node_change_takes_effect_after_the_reset, ["canopen_node_change_reset"], "5001h = 5 confirmed on the old node, the boot-up and PDOs on the new one after the NMT reset", [("object-5001", Any), ("address-switch", Any)]),
        exercise!(a_bit_rate_change_takes_effect_after_the_reset, ["canopen_bit_rate_change_reset"], "5000h = 4 confirmed, the encoder at the new rate after the NMT reset (the master no longer reads it)", [("object-5000", Any)]),
        exercise!(an_encoder_at_another_bit_rate_is_never_seen, ["canopen_other_bit_rate"], "an encoder whose switch gives another rate: only error frames, node lost", [("bit-rate-switch", Any)]),
        exercise!(three_encoders_only_the_masters_node_runs, ["canopen_three_encoders"], "three boot-ups on 0x81, 0x82, 0x83; only the master's node configured and started", [("cob-id", Any), ("address-switch", Any)]),
    ];
}
