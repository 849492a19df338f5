//! The CAN 2.0 controller protocol's descriptor: every name the tree knows it by
//! (see [`crate::protocol`]).

use crate::protocol::{ClosedLoop, Diagram, Emulator, Protocol};

/// CAN 2.0 controller.
pub const PROTOCOL: Protocol = Protocol {
    stem: "can",
    title: "CAN 2.0 controller",
    module: "can",
    core: "can_controller",
    emulator: Some(Emulator {
        kind: "can",
        aliases: &[],
        module: "can_node_emu",
        monitor_module: "can_monitor",
    }),
    closed_loops: &[ClosedLoop {
        name: "can_controller",
        top: "can_controller",
        // Icarus seconds per transaction (60 transactions on each configuration,
        // start-up included, 2-core machine loaded about 3), the chosen one first:
        // one_node_500k_10tq 0.021, one_node_125k 0.045, two_nodes_1000k 0.053
        quick: "one_node_500k_10tq",
        bench_transactions: 25,
        cocotb: Some("can"),
    }],
    diagram: Some(Diagram {
        file: "can_frame",
        scenario: "can_rate_250k",
        title: "CAN 2.0: one data frame (Bosch CAN 2.0 / ISO 11898-1; SAR58K24 CAN mode)",
    }),
    historical: &[],
    rules: super::rules::RULES,
};
