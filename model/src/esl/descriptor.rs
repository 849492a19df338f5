//! The ESL safety serial protocol's descriptor: every name the tree knows it by
//! (see [`crate::protocol`]).

use crate::protocol::{ClosedLoop, Diagram, Emulator, Protocol};

/// ESL safety serial.
pub const PROTOCOL: Protocol = Protocol {
    stem: "esl",
    title: "ESL safety serial",
    module: "esl",
    core: "esl_host",
    emulator: Some(Emulator {
        kind: "esl",
        aliases: &[],
        module: "esl_encoder_emu",
        monitor_module: "esl_monitor",
    }),
    closed_loops: &[ClosedLoop {
        name: "esl_host",
        top: "esl_host",
        // Icarus seconds per transaction (60 transactions on each configuration,
        // start-up included, 2-core machine loaded about 3), the chosen one first:
        // readout_0m 0.032, readout_50m_fast 0.032, readout_100m_slow 0.053
        quick: "readout_0m",
        bench_transactions: 50,
        cocotb: Some("esl"),
    }],
    diagram: Some(Diagram {
        file: "esl_request",
        scenario: "esl_readout_all_ids",
        title: "ESL: a request and its answer (QS35-M40M-E12F, ESL Safety serial protocol)",
    }),
    historical: &[],
    rules: super::rules::RULES,
};
