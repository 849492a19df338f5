//! The EnDat 2.2 protocol's descriptor: every name the tree knows it by
//! (see [`crate::protocol`]).

use crate::protocol::{ClosedLoop, Diagram, Emulator, Protocol};

/// EnDat 2.2.
pub const PROTOCOL: Protocol = Protocol {
    stem: "endat",
    title: "EnDat 2.2",
    module: "endat",
    core: "endat_master",
    emulator: Some(Emulator {
        kind: "endat",
        aliases: &[],
        module: "endat_encoder_emu",
        monitor_module: "endat_monitor",
    }),
    closed_loops: &[ClosedLoop {
        name: "endat_master",
        top: "endat_master",
        // Icarus seconds per transaction (60 transactions on each configuration,
        // start-up included, 2-core machine loaded about 3), the chosen one first:
        // pos22_1mhz_20m 0.018, pos22_500khz_50m 0.031, pos22_4mhz_100m_short 0.063
        quick: "pos22_1mhz_20m",
        bench_transactions: 100,
        cocotb: Some("endat"),
    }],
    diagram: Some(Diagram {
        file: "endat_position",
        scenario: "endat_pos21_1mhz",
        title:
            "EnDat 2.1: position request and answer (HEIDENHAIN EnDat 2.2 D297403, position values)",
    }),
    historical: &[],
    rules: super::rules::RULES,
};
