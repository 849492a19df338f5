//! The CANopen (DS 406 encoders, SAR58K24 in CAN mode) protocol's descriptor: every name the tree knows it by
//! (see [`crate::protocol`]).

use crate::protocol::{ClosedLoop, Emulator, Historical, Protocol};

/// CANopen (DS 406 encoders, SAR58K24 in CAN mode).
pub const PROTOCOL: Protocol = Protocol {
    stem: "canopen",
    title: "CANopen (DS 406 encoders, SAR58K24 in CAN mode)",
    module: "canopen",
    core: "canopen_master",
    emulator: Some(Emulator {
        kind: "canopen",
        aliases: &["sar58k24_can"],
        module: "canopen_encoder_emu",
        monitor_module: "canopen_monitor",
    }),
    closed_loops: &[
        ClosedLoop {
            name: "canopen_master",
            top: "canopen_master",
            // Icarus seconds per transaction, the chosen one first:
            // cyclic_250k_10tq 0.057, cyclic_250k 0.072, sync_1000k 0.081
            quick: "cyclic_250k_10tq",
            bench_transactions: 25,
            cocotb: None,
        },
        ClosedLoop {
            name: "sar58k24_can",
            top: "can_controller",
            // Icarus seconds per transaction, the chosen one first:
            // factory_250k_10tq 0.075, factory_250k 0.090, mixed_500k 0.087, node7f_1000k 0.102
            // (the three 10tq configurations, ten clock cycles per CAN bit, and
            // the rows they were set against re-measured on 300 transactions,
            // unloaded, 2026-11-24; their gain is smaller than their 1.6x to 3.2x
            // fewer cycles, since the emulator's work is per bit, not per cycle)
            quick: "factory_250k_10tq",
            bench_transactions: 20,
            cocotb: Some("sar58k24_can"),
        },
    ],
    diagram: None,
    historical: &[
        Historical {
            name: "sar58k24_can",
            why: "the SAR58K24 in CAN mode on the CANopen bus (`[[canopen.sar]]`): the emulator's alias, the closed loop `hdl/tb_cosim/sar58k24_can/` (can_controller and a command sequencer) and its cocotb test are named after the device, as its manual's CAN mode",
        },
    ],
    rules: super::rules::RULES,
};
