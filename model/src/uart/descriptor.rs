//! The UART receiver (8N1 and parity) protocol's descriptor: every name the tree knows it by
//! (see [`crate::protocol`]).

use crate::protocol::Protocol;

/// UART receiver (8N1 and parity).
pub const PROTOCOL: Protocol = Protocol {
    stem: "uart",
    title: "UART receiver (8N1 and parity)",
    module: "uart",
    core: "uart_rx",
    emulator: None,
    closed_loops: &[],
    diagram: None,
    historical: &[],
    rules: &[],
};
