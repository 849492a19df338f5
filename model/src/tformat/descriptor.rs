//! The Tamagawa T-format protocol's descriptor: every name the tree knows it by
//! (see [`crate::protocol`]).

use crate::protocol::{ClosedLoop, Diagram, Emulator, Protocol};

/// Tamagawa T-format.
pub const PROTOCOL: Protocol = Protocol {
    stem: "tformat",
    title: "Tamagawa T-format",
    module: "tformat",
    core: "tformat_host",
    emulator: Some(Emulator {
        kind: "tformat",
        aliases: &[],
        module: "tformat_encoder_emu",
        monitor_module: "tformat_monitor",
    }),
    closed_loops: &[ClosedLoop {
        name: "tformat_host",
        top: "tformat_host",
        // Icarus seconds per transaction (60 transactions on each configuration,
        // start-up included, 2-core machine loaded about 3), the chosen one first:
        // readout_50m_fast 0.013, readout_0m 0.013, readout_100m_slow 0.023
        quick: "readout_50m_fast",
        bench_transactions: 100,
        cocotb: Some("tformat"),
    }],
    diagram: Some(Diagram {
        file: "tformat_request",
        scenario: "tformat_readout_all_ids",
        title:
            "T-format: Data ID 0 request and answer (Tamagawa Smart Abs TS5669 N127, communication)",
    }),
    historical: &[],
    rules: super::rules::RULES,
};
