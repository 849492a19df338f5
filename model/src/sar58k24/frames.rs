//! SAR58K24 asynchronous serial position frames (seed 001, "Asynchronous
//! serial"): `FF 81 <data bytes, high first> <checksum>`, 8N1, where the data
//! is 2 bytes up to 16 bits, 3 up to 24 and 4 above, and the checksum is the
//! low byte of the sum of every byte before it; and the bus commands
//! `BC AA Bx` (read encoder x) and `BC AA Cx` (zero encoder x).

use schemars::JsonSchema;

/// The two bytes every position frame starts with (every frame table of 3.1.x to 3.3.x).
pub const HEADER: [u8; 2] = [0xFF, 0x81];

/// The first byte of every position frame.
pub const SYNC: u8 = 0xFF;

/// The second byte of a frame in the timed and handshake modes.
pub const TAG_81: u8 = 0x81;

/// The first two bytes of a bus command (3.1.5, 3.1.6).
pub const COMMAND_PREFIX: [u8; 2] = [0xBC, 0xAA];

/// The read command for encoder `address` (0..15): `BC AA Bx`.
pub fn read_command(address: u8) -> [u8; 3] {
    [0xBC, 0xAA, 0xB0 | (address & 0xF)]
}

/// The zeroing command for encoder `address` (0..15): `BC AA Cx`.
pub fn zero_command(address: u8) -> [u8; 3] {
    [0xBC, 0xAA, 0xC0 | (address & 0xF)]
}

/// The second byte of a frame: `0x81`, or in the bus modes the command
/// byte `Bx` when the encoder echoes its address (see [`AnswerTag`]).
pub fn tag_byte(tag: AnswerTag, bus: bool, address: u8) -> u8 {
    match (tag, bus) {
        (AnswerTag::Address, true) => 0xB0 | (address & 0xF),
        _ => TAG_81,
    }
}

/// What the second byte of an answer to a bus command is. The manual
/// contradicts itself (3.1.5, 3.1.6, 3.2.5, 3.2.6, 3.3.3, 3.3.4): the text
/// says the answers to `BC AA B1/B2/B3` are `FF B1 ...`, `FF B2 ...`,
/// `FF B3 ...`, "the second byte of the return data is the product address
/// number", while every frame table shows `FF 81`. The tables are the
/// timed-send table copied into every section (the one of 3.2.5 even
/// garbles its command row into `AA 81 CC DD`); the sentence is written
/// for the bus modes alone, and only an echoed address lets a host on a
/// shared line see that the wrong encoder answered. The default follows the
/// text; `fixed81` follows the tables.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize, JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum AnswerTag {
    /// Bus answers carry `Bx`, the command byte (the text's reading).
    #[default]
    Address,
    /// Bus answers carry `81` as in every other mode (the tables' reading).
    Fixed81,
}

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
    /// The frame does not start with `FF` and the expected tag (`81`).
    #[error("the frame starts with {0:02X} {1:02X}, not FF and the expected tag")]
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
    encode_tagged(value, bits, TAG_81)
}

/// Bytes in a position frame for `bits`: `FF`, tag, data, checksum.
pub fn frame_len(bits: u32) -> usize {
    data_bytes(bits) + 3
}

/// A position frame with `tag` as its second byte (`81`, or `Bx` in the bus modes).
pub fn encode_tagged(value: u32, bits: u32, tag: u8) -> Vec<u8> {
    let n = data_bytes(bits);
    let mut frame = vec![SYNC, tag];
    frame.extend_from_slice(&value.to_be_bytes()[4 - n..]);
    frame.push(checksum(&frame));
    frame
}

/// The value in a received position frame, checked.
pub fn decode(frame: &[u8], bits: u32) -> Result<u32, FrameError> {
    decode_tagged(frame, bits, TAG_81)
}

/// The value in a received frame whose second byte must be `tag`, checked.
pub fn decode_tagged(frame: &[u8], bits: u32, tag: u8) -> Result<u32, FrameError> {
    let n = data_bytes(bits);
    if frame.len() != n + 3 {
        return Err(FrameError::Length {
            bits,
            expected: n + 3,
            got: frame.len(),
        });
    }
    if frame[..2] != [SYNC, tag] {
        return Err(FrameError::Header(frame[0], frame[1]));
    }
    let expected = checksum(&frame[..frame.len() - 1]);
    let got = frame[frame.len() - 1];
    if expected != got {
        return Err(FrameError::Checksum { expected, got });
    }
    Ok(frame[2..2 + n]
        .iter()
        .fold(0u32, |v, b| (v << 8) | *b as u32))
}

/// A bus command recognised in a received byte string.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Command {
    /// `BC AA Bx`: send the position.
    Read(u8),
    /// `BC AA Cx`: zero the position.
    Zero(u8),
}

/// The command in three bytes, if they are one.
pub fn parse_command(bytes: &[u8]) -> Option<Command> {
    match bytes {
        [0xBC, 0xAA, b] if b & 0xF0 == 0xB0 => Some(Command::Read(b & 0xF)),
        [0xBC, 0xAA, b] if b & 0xF0 == 0xC0 => Some(Command::Zero(b & 0xF)),
        _ => None,
    }
}
