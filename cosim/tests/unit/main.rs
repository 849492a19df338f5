//! cosim's unit tests: the emulators' configurations and stepping, the C
//! ABI, the motion profiles and the pin-level monitors, one file per module
//! of `src/` (`biss.rs` tests `cosim::biss`, `monitor_can.rs` tests
//! `cosim::monitor::can`).
//!
//! They are an integration test rather than `#[cfg(test)]` modules inside
//! the library so that `make test`'s build compiles cosim once: a library
//! with unit tests is compiled a second time, whole, for its test binary
//! (about 100 s of CPU on the 2-core machine). They reach the
//! library through its public API only.

mod bad_values;
mod biss;
mod can;
mod canopen;
mod endat;
mod esl;
mod ffi;
mod modbus;
mod monitor;
mod monitor_can;
mod monitor_half_duplex;
mod monitor_uart;
mod motion;
mod registry;
mod rules;
mod sar58k24;
mod ssi;
mod tformat;
mod vhdl_wrappers;

use model::uart::Parity;

/// The characters of `bytes` as line levels, `c` cycles per bit (8N1): a
/// host's request to the SAR58K24 and Modbus emulators.
fn levels(bytes: &[u8], c: usize) -> Vec<bool> {
    bytes
        .iter()
        .flat_map(|&b| Parity::None.levels(b))
        .flat_map(|bit| std::iter::repeat_n(bit, c))
        .collect()
}
