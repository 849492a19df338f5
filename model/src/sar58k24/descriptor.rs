//! The SAR58K24 asynchronous serial protocol's descriptor: every name the tree knows it by
//! (see [`crate::protocol`]).

use crate::protocol::{ClosedLoop, Diagram, Emulator, Historical, Protocol};

/// SAR58K24 asynchronous serial.
pub const PROTOCOL: Protocol = Protocol {
    stem: "sar",
    title: "SAR58K24 asynchronous serial",
    module: "sar58k24",
    core: "sar_async_host",
    emulator: Some(Emulator {
        kind: "sar58k24",
        aliases: &["sar"],
        module: "sar58k24_encoder_emu",
        monitor_module: "sar58k24_monitor",
    }),
    closed_loops: &[
        ClosedLoop {
            name: "sar_async_host",
            top: "sar_async_host",
            // Icarus seconds per transaction, the chosen one first:
            // handshake_gray_31250_100m 0.013, bus_32bit_15625_10m 0.019, timed_16bit_115200 0.053
            quick: "handshake_gray_31250_100m",
            bench_transactions: 40,
            cocotb: Some("sar58k24"),
        },
    ],
    diagram: Some(Diagram {
        file: "sar_timed",
        scenario: "sar_seed_timed_14bit",
        title: "SAR58K24 asynchronous: one timed frame (SAR58K24 user's manual, 3.1.1 to 3.3.4)",
    }),
    historical: &[
        Historical {
            name: "sar58k24",
            why: "the model's module `model::sar58k24` (and `cosim::sar58k24`), the device's name, which users import; the emulator kind, which the Verilog wrapper passes and the transcripts name (the stem `sar` is an alias of it), and the cocotb test `test_sar58k24.py`",
        },
        Historical {
            name: "sar58k24_encoder_emu",
            why: "the Verilog wrapper, named after the device like the other wrappers; examples/ and users' testbenches instantiate it",
        },
        Historical {
            name: "sar58k24_monitor",
            why: "the Verilog monitor and its plusargs (`+sar58k24_monitor_config`), which users' testbenches set",
        },
    ],
    rules: crate::sar58k24::rules::RULES,
};
