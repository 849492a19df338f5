//! Faults a device emulator injects into the byte strings it sends: an
//! inverted level, a truncation, a gap inside the frame, noise before it,
//! silence, a wrong address. Shared by the SAR58K24 and Modbus emulators.

use serde::{Deserialize, Serialize};

use super::{Parity, Transmitter};

/// Something a device emulator does wrong to one of its frames (the
/// scenario's `[[<table>.encoder.faults]]`): shared by the SAR58K24 modes
/// and Modbus, whose emulators send byte strings through a [`Transmitter`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FrameFault {
    /// 0-based number of the frame the encoder sends.
    pub frame: usize,
    /// What goes wrong.
    pub kind: FaultKind,
    /// The character concerned (0 = `FF`).
    #[serde(default)]
    pub byte: usize,
    /// `flip`: the level inverted in that character (0 start, 1..8 data
    /// LSB first, 9 parity or stop, 10 stop with parity).
    #[serde(default)]
    pub bit: usize,
    /// `gap`: idle bit times inserted before the character.
    #[serde(default)]
    pub gap_bits: f64,
    /// `noise`: bytes sent just before character `byte` (0: before the
    /// frame); `retag`: the address byte; `replace`: character `byte`;
    /// `insert`: characters inserted before character `byte`.
    #[serde(default)]
    pub bytes: Vec<u8>,
}

/// The kinds of [`FrameFault`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum FaultKind {
    /// One level inverted: a data bit (checksum), the parity bit, the stop bit (framing).
    Flip,
    /// Only the first `byte` characters are sent.
    Truncate,
    /// An idle gap before character `byte`.
    Gap,
    /// `bytes` sent back to back just before character `byte` (0: before
    /// the frame; inside it otherwise).
    Noise,
    /// The frame is not sent at all (no answer).
    Silent,
    /// The protocol's address byte is `bytes[0]`, its check recomputed (an
    /// answer claiming another address): the SAR58K24's second byte, the
    /// Modbus address. The emulator applies it; [`send_with_faults`] ignores it.
    Retag,
    /// Character `byte` is `bytes[0]`, the check recomputed (a well-formed
    /// frame with a wrong field: a Modbus answer's function or byte count).
    /// The emulator applies it; [`send_with_faults`] ignores it.
    Replace,
    /// `bytes` inserted before character `byte`, the check recomputed (a
    /// well-formed frame of the wrong length: a Modbus address-query answer
    /// with an extra character). The Modbus emulator applies it (when
    /// `byte` lies before the answer's CRC); [`send_with_faults`] ignores
    /// it, and the SAR58K24 encoder, whose frames have one length, refuses it.
    Insert,
}

impl FrameFault {
    /// Checks the fault against a frame of `len` characters; the error is
    /// (problem, fix).
    pub fn validate(&self, len: usize, parity: Parity) -> Result<(), (String, String)> {
        let bits = parity.frame_bits();
        let ok = match self.kind {
            FaultKind::Flip => self.byte < len && self.bit < bits,
            FaultKind::Truncate => self.byte < len,
            FaultKind::Gap => {
                self.byte > 0 && self.byte < len && (0.0..=1e5).contains(&self.gap_bits)
            }
            FaultKind::Noise => !self.bytes.is_empty() && self.bytes.len() <= 64 && self.byte < len,
            FaultKind::Silent => true,
            FaultKind::Retag => self.bytes.len() == 1,
            FaultKind::Replace => self.bytes.len() == 1 && self.byte + 1 < len,
            FaultKind::Insert => {
                !self.bytes.is_empty()
                    && self.bytes.len() <= 64
                    && self.byte > 0
                    && self.byte + 1 < len
            }
        };
        if ok {
            return Ok(());
        }
        Err((
            format!("{:?} with byte {}, bit {}, {} bytes", self.kind, self.byte, self.bit, self.bytes.len()),
            format!("a frame has {len} characters of {bits} bits: flip needs byte < {len} and bit < {bits}; truncate byte < {len}; gap 0 < byte < {len}; noise 1 to 64 bytes before byte < {len}; retag one byte; replace one byte at byte < {}", len - 1),
        ))
    }
}

/// Queues `bytes` on `tx` from `now_ps` with `faults` applied (the
/// characters, each possibly preceded by noise or a gap and flipped, up to a
/// truncation). `Silent`, `Retag` and `Replace` are the caller's.
pub fn send_with_faults(
    tx: &mut Transmitter,
    bytes: &[u8],
    faults: &[FrameFault],
    parity: Parity,
    now_ps: f64,
) {
    let keep = faults
        .iter()
        .find(|f| f.kind == FaultKind::Truncate)
        .map_or(bytes.len(), |f| f.byte);
    for (i, &b) in bytes.iter().enumerate().take(keep) {
        let mut gap = faults
            .iter()
            .filter(|f| f.kind == FaultKind::Gap && f.byte == i)
            .map(|f| f.gap_bits)
            .sum::<f64>();
        for f in faults
            .iter()
            .filter(|f| f.kind == FaultKind::Noise && f.byte == i)
        {
            for &n in &f.bytes {
                tx.send(n, now_ps, gap);
                gap = 0.0;
            }
        }
        let mut levels = parity.levels(b);
        for f in faults
            .iter()
            .filter(|f| f.kind == FaultKind::Flip && f.byte == i)
        {
            levels[f.bit] = !levels[f.bit];
        }
        tx.send_levels(&levels, now_ps, gap);
    }
}
