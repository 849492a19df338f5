//! The Modbus RTU (SAR58K24's seventh mode) protocol's descriptor: every name the tree knows it by
//! (see [`crate::protocol`]).

use crate::protocol::{ClosedLoop, Diagram, Emulator, Protocol};

/// Modbus RTU (SAR58K24's seventh mode).
pub const PROTOCOL: Protocol = Protocol {
    stem: "modbus",
    title: "Modbus RTU (SAR58K24's seventh mode)",
    module: "modbus",
    core: "modbus_master",
    emulator: Some(Emulator {
        kind: "modbus",
        aliases: &[],
        module: "modbus_device_emu",
        monitor_module: "modbus_monitor",
    }),
    closed_loops: &[ClosedLoop {
        name: "modbus_master",
        top: "modbus_master",
        // Icarus seconds per transaction (60 transactions on each configuration,
        // start-up included, 2-core machine loaded about 3), the chosen one first:
        // read16_31250_8_clocks 0.023, read16_31250_fixed_t35 0.040, read32_15625_even_100m 0.052
        // (measured later, unloaded, after the register banks: docs/rtl.md)
        quick: "read16_31250_8_clocks",
        bench_transactions: 30,
        cocotb: Some("modbus"),
    }],
    diagram: Some(Diagram {
        file: "modbus_read",
        scenario: "modbus_seed_19200",
        title: "Modbus RTU: function 03 request and answer (SAR58K24 user's manual, 3.1.7)",
    }),
    historical: &[],
    rules: crate::modbus::rules::RULES,
};
