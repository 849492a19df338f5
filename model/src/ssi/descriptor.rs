//! The SSI (synchronous serial interface) protocol's descriptor: every name the tree knows it by
//! (see [`crate::protocol`]).

use crate::protocol::{ClosedLoop, Diagram, Emulator, Protocol};

/// SSI (synchronous serial interface).
pub const PROTOCOL: Protocol = Protocol {
    stem: "ssi",
    title: "SSI (synchronous serial interface)",
    module: "ssi",
    core: "ssi_master",
    emulator: Some(Emulator {
        kind: "ssi",
        aliases: &[],
        module: "ssi_encoder_emu",
        monitor_module: "ssi_monitor",
    }),
    closed_loops: &[ClosedLoop {
        name: "ssi_master",
        top: "ssi_master",
        // Icarus seconds per transaction (60 transactions on each configuration,
        // start-up included, 2-core machine loaded about 3), the chosen one first:
        // fast_1mhz_50m 0.006, gray_100khz_100m 0.008, seed_250khz_10m 0.014
        quick: "fast_1mhz_50m",
        bench_transactions: 50,
        cocotb: Some("ssi"),
    }],
    diagram: Some(Diagram {
        file: "ssi_read",
        scenario: "ssi_seed_12bit",
        title: "SSI: one 12-bit read, 495 (SAR58K24 user's manual, Synchronous serial, SSI (4))",
    }),
    historical: &[],
    rules: crate::ssi::rules::RULES,
};
