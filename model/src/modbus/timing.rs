//! The numbers `tbgen timing modbus` prints: character time, t1.5, t3.5,
//! and the time and rate of one poll (request, the device's t3.5 and
//! turnaround, the answer, the master's t3.5).

use super::frames;
use crate::uart::Parity;

/// One row: a baud rate and a register count.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Baud.
    pub baud: f64,
    /// Registers read.
    pub registers: u8,
    /// One character, µs.
    pub char_us: f64,
    /// t1.5, µs.
    pub t15_us: f64,
    /// t3.5, µs.
    pub t35_us: f64,
    /// One poll, µs.
    pub poll_us: f64,
}

impl Row {
    /// Polls per second, back to back.
    pub fn poll_hz(&self) -> f64 {
        1e6 / self.poll_us
    }
}

/// The poll budget at `baud` for `registers` (1 or 2), with the device
/// answering `answer_delay_us` after it recognised the request.
pub fn poll(baud: f64, parity: Parity, registers: u8, answer_delay_us: f64) -> Row {
    let bits = parity.frame_bits();
    let char_us = frames::char_seconds(baud, bits) * 1e6;
    let t15_us = frames::t15_seconds(baud, bits) * 1e6;
    let t35_us = frames::t35_seconds(baud, bits) * 1e6;
    let answer_chars = 5.0 + 2.0 * registers as f64;
    let poll_us = 8.0 * char_us + t35_us + answer_delay_us + answer_chars * char_us + t35_us;
    Row {
        baud,
        registers,
        char_us,
        t15_us,
        t35_us,
        poll_us,
    }
}

/// The budget as a Markdown table for the manual's baud rates and 115200.
pub fn table(parity: Parity, answer_delay_us: f64) -> String {
    let mut s = format!("Modbus RTU poll, parity {parity:?}, device turnaround {answer_delay_us} µs after t3.5\n\n| baud | registers | character | t1.5 | t3.5 | poll | poll rate |\n|---|---|---|---|---|---|---|\n");
    for baud in [2400.0, 4800.0, 9600.0, 19_200.0, 57_600.0, 115_200.0] {
        for registers in [1, 2] {
            let r = poll(baud, parity, registers, answer_delay_us);
            s += &format!(
                "| {} | {} | {:.1} µs | {:.1} µs | {:.1} µs | {:.2} ms | {:.0} Hz |\n",
                r.baud,
                r.registers,
                r.char_us,
                r.t15_us,
                r.t35_us,
                r.poll_us / 1e3,
                r.poll_hz()
            );
        }
    }
    s
}
