//! Reading the characters of an asynchronous line with an optional parity
//! bit: what the SAR58K24 and Modbus RTU decoders share (`tbgen decode
//! sar|modbus`, the co-simulation monitors `sar58k24_monitor` and
//! `modbus_monitor`). ([`crate::wire::uart_bytes`] reads the 10-bit
//! characters of ESL and T-format; this reader adds the parity bit of the
//! SAR58K24 and Modbus characters, and says which fault a character had.)

use serde::Serialize;

use super::Parity;
use crate::wire::Signal;

/// One character read off the line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Char {
    /// Falling edge of the start bit, ps.
    pub start_ps: u64,
    /// The data bits, LSB first on the wire.
    pub value: u8,
    /// The parity bit disagreed with the data.
    pub parity_error: bool,
    /// The stop bit read low.
    pub framing_error: bool,
    /// The host's driver was on at the start bit (a request character).
    pub from_host: bool,
}

impl Char {
    /// The end of the stop bit, ps, at `bit_ps` per bit.
    pub fn end_ps(&self, bit_ps: u64, parity: Parity) -> u64 {
        self.start_ps + parity.frame_bits() as u64 * bit_ps
    }
}

/// Reads every character of `line` at `bit_ps` per bit, each bit sampled in
/// its middle from the start bit's falling edge: a start bit high again at
/// its middle is a glitch and skipped; a character with a low stop bit is
/// kept and flagged, and the next start bit is looked for once the line is
/// high again. `tx_en` (the host's driver enable) marks request characters.
pub fn chars(line: &Signal, tx_en: Option<&Signal>, bit_ps: u64, parity: Parity) -> Vec<Char> {
    let bits = parity.frame_bits() as u64;
    let mut out = Vec::new();
    let mut from = 0u64;
    // A line low from the start of the capture is not a start bit.
    if line.changes.first().is_some_and(|&(t, v)| t == 0 && !v) {
        match line.next_level(0, true) {
            Some(t) => from = t,
            None => return out,
        }
    }
    while let Some(fall) = line.next_level(from, false) {
        let mid = |k: u64| fall + k * bit_ps + bit_ps / 2;
        if line.level_at(mid(0)) {
            from = line.next_level(fall + 1, true).unwrap_or(fall + 1);
            continue;
        }
        let value = (0..8).fold(0u8, |acc, k| acc | ((line.level_at(mid(k + 1)) as u8) << k));
        let parity_error = parity != Parity::None && line.level_at(mid(9)) != parity.bit(value);
        let stop = line.level_at(mid(bits - 1));
        out.push(Char {
            start_ps: fall,
            value,
            parity_error,
            framing_error: !stop,
            from_host: tx_en.is_some_and(|e| e.level_at(fall)),
        });
        from = if stop {
            mid(bits - 1)
        } else {
            line.next_level(mid(bits - 1), true).unwrap_or(u64::MAX)
        };
        if from == u64::MAX {
            break;
        }
    }
    out
}

/// Splits `chars` into bursts: a new burst begins at a character from the
/// other side (host or device), or after a silence of more than `gap_ps`
/// from the end of the previous character.
pub fn bursts(chars: &[Char], bit_ps: u64, parity: Parity, gap_ps: u64) -> Vec<Vec<Char>> {
    let mut out: Vec<Vec<Char>> = Vec::new();
    for &c in chars {
        match out.last_mut() {
            Some(b)
                if b.last().is_some_and(|p| {
                    p.from_host == c.from_host && c.start_ps <= p.end_ps(bit_ps, parity) + gap_ps
                }) =>
            {
                b.push(c)
            }
            _ => out.push(vec![c]),
        }
    }
    out
}

/// The bytes of `chars`.
pub fn values(chars: &[Char]) -> Vec<u8> {
    chars.iter().map(|c| c.value).collect()
}
