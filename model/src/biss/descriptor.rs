//! The BiSS-C protocol's descriptor: every name the tree knows it by
//! (see [`crate::protocol`]).

use crate::protocol::{ClosedLoop, Diagram, Emulator, Protocol};

/// BiSS-C.
pub const PROTOCOL: Protocol = Protocol {
    stem: "biss",
    title: "BiSS-C",
    module: "biss",
    core: "biss_master",
    emulator: Some(Emulator {
        kind: "biss",
        aliases: &[],
        module: "biss_slave_emu",
        monitor_module: "biss_monitor",
    }),
    closed_loops: &[ClosedLoop {
        name: "biss_master",
        top: "biss_master",
        // Icarus seconds per transaction (60 transactions on each configuration,
        // start-up included, 2-core machine loaded about 3), the chosen one first:
        // chain_2500khz_100m 0.026, seed_10mhz_10m 0.021, wide_1mhz_50m 0.031
        // (the chain is kept: two slaves over 100 m, 0.005 s dearer)
        quick: "chain_2500khz_100m",
        bench_transactions: 60,
        cocotb: Some("biss"),
    }],
    diagram: Some(Diagram {
        file: "biss_frame",
        scenario: "biss_seed_16bit",
        title: "BiSS-C: one 16-bit frame (SAR58K24 user's manual, Synchronous serial, BiSS-C)",
    }),
    historical: &[],
    rules: crate::biss::rules::RULES,
};
