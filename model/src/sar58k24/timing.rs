//! The numbers `tbgen timing sar` prints: frame time per baud rate, the
//! highest refresh rate of the manual's list whose period holds the frame,
//! and the trigger-to-position latency of the handshake modes.

use super::encoder::{frame_seconds, BAUD_RATES, REFRESH_RATES_HZ};
use super::frames;
use crate::uart::Parity;

/// One row of the budget: a baud rate.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Baud.
    pub baud: f64,
    /// One frame, characters back to back, µs.
    pub frame_us: f64,
    /// The highest listed refresh rate whose period holds the frame (0: none).
    pub max_listed_refresh_hz: f64,
    /// Trigger's falling edge to the host's `o_valid`: T3, then the frame
    /// up to the middle of its last stop bit, µs (plus 3 system clocks).
    pub trigger_to_position_us: f64,
}

/// The budget for `bits`, `parity` and the acquisition time `t3_us`, one row per listed baud rate.
pub fn budget(bits: u32, parity: Parity, t3_us: f64) -> Vec<Row> {
    let chars = (frames::frame_len(bits) * parity.frame_bits()) as f64;
    BAUD_RATES
        .iter()
        .map(|&baud| {
            let frame_us = frame_seconds(bits, baud, parity) * 1e6;
            let max_listed_refresh_hz = REFRESH_RATES_HZ
                .iter()
                .copied()
                .filter(|r| 1e6 / r >= frame_us)
                .fold(0.0, f64::max);
            Row {
                baud,
                frame_us,
                max_listed_refresh_hz,
                trigger_to_position_us: t3_us + (chars - 0.5) / baud * 1e6,
            }
        })
        .collect()
}

/// The budget as a Markdown table.
pub fn table(bits: u32, parity: Parity, t3_us: f64) -> String {
    let mut s = format!(
        "SAR58K24 asynchronous frame, {bits} bits ({} bytes), parity {parity:?}, T3 = {t3_us} µs\n\n| baud | frame | highest listed refresh rate | trigger to position |\n|---|---|---|---|\n",
        frames::frame_len(bits)
    );
    for r in budget(bits, parity, t3_us) {
        s += &format!(
            "| {} | {:.1} µs | {} Hz | {:.1} µs |\n",
            r.baud, r.frame_us, r.max_listed_refresh_hz, r.trigger_to_position_us
        );
    }
    s
}
