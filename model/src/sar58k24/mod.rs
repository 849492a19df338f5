//! SAR58K24 asynchronous serial position frames (seed 001, "Asynchronous
//! serial"): `FF 81 <data bytes, high first> <checksum>`, 8N1, where the data
//! is 2 bytes up to 16 bits, 3 up to 24 and 4 above, and the checksum is the
//! low byte of the sum of every byte before it.
//!
//! Only the frame layer is here so far; the timed-send, handshake and bus
//! modes, Modbus RTU and the receiver core are later work.

/// The two bytes every position frame starts with.
pub const HEADER: [u8; 2] = [0xFF, 0x81];

/// Why a received frame is not a position frame.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum FrameError {
    /// Fewer or more bytes than `2 + data + 1`.
    #[error("a position frame for {bits} bits is {expected} bytes, not {got}")]
    Length {
        /// Resolution the frame was decoded for.
        bits: u32,
        /// Bytes expected.
        expected: usize,
        /// Bytes received.
        got: usize,
    },
    /// The frame does not start with `FF 81`.
    #[error("the frame starts with {0:02X} {1:02X}, not FF 81")]
    Header(u8, u8),
    /// The checksum byte is not the low byte of the sum of the others.
    #[error("checksum {got:02X}, expected {expected:02X}")]
    Checksum {
        /// The checksum the bytes before it give.
        expected: u8,
        /// The checksum byte received.
        got: u8,
    },
}

/// Data bytes in a frame for an encoder of `bits` resolution.
pub fn data_bytes(bits: u32) -> usize {
    match bits {
        0..=16 => 2,
        17..=24 => 3,
        _ => 4,
    }
}

/// The low byte of the sum of `bytes`.
pub fn checksum(bytes: &[u8]) -> u8 {
    bytes.iter().fold(0u8, |sum, b| sum.wrapping_add(*b))
}

/// The position frame an encoder of `bits` resolution sends for `value`.
pub fn encode(value: u32, bits: u32) -> Vec<u8> {
    let n = data_bytes(bits);
    let mut frame = HEADER.to_vec();
    frame.extend_from_slice(&value.to_be_bytes()[4 - n..]);
    frame.push(checksum(&frame));
    frame
}

/// The value in a received position frame, checked.
pub fn decode(frame: &[u8], bits: u32) -> Result<u32, FrameError> {
    let n = data_bytes(bits);
    if frame.len() != n + 3 {
        return Err(FrameError::Length { bits, expected: n + 3, got: frame.len() });
    }
    if frame[..2] != HEADER {
        return Err(FrameError::Header(frame[0], frame[1]));
    }
    let expected = checksum(&frame[..frame.len() - 1]);
    let got = frame[frame.len() - 1];
    if expected != got {
        return Err(FrameError::Checksum { expected, got });
    }
    Ok(frame[2..2 + n].iter().fold(0u32, |v, b| (v << 8) | *b as u32))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::angle::angle_deg;

    #[test]
    fn seed_001_frame_ff_81_01_7f_00_is_383_and_8_4155_degrees_for_14_bits() {
        // Seed 001, "Asynchronous serial": FF 81 01 7F 00, checksum 00 = low byte of FF+81+01+7F.
        let frame = [0xFF, 0x81, 0x01, 0x7F, 0x00];
        assert_eq!(checksum(&frame[..4]), 0x00);
        assert_eq!(decode(&frame, 14), Ok(383));
        assert_eq!(encode(383, 14), frame);
        assert_eq!(angle_deg(383, 14), 8.4155);
    }

    #[test]
    fn frames_grow_with_resolution_as_the_seed_lists() {
        assert_eq!(encode(0x12_3456, 24).len(), 6);
        assert_eq!(encode(0x0123_4567, 25).len(), 7);
        assert_eq!(decode(&encode(0x0123_4567, 25), 25), Ok(0x0123_4567));
    }

    #[test]
    fn a_corrupted_byte_is_caught_by_the_checksum() {
        let mut frame = encode(383, 14);
        frame[3] ^= 0x10;
        assert!(matches!(decode(&frame, 14), Err(FrameError::Checksum { .. })));
        assert_eq!(decode(&frame[..4], 14), Err(FrameError::Length { bits: 14, expected: 5, got: 4 }));
        assert_eq!(decode(&[0xFE, 0x81, 1, 0x7F, 0], 14), Err(FrameError::Header(0xFE, 0x81)));
    }
}
