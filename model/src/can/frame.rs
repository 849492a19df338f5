//! CAN 2.0A/2.0B data and remote frames: the destuffed bit layout, CRC-15
//! from the catalogue (`can-crc15`), bit stuffing, and a destuffing parser
//! of a wire bit stream (for the campaign and `tbgen decode can`).
//!
//! ```text
//!  standard: SOF | ID10..ID0 | RTR | IDE=0 | r0 | DLC3..0 | data | CRC14..0 | CRC del | ACK | ACK del | EOF×7
//!  extended: SOF | ID28..ID18 | SRR=1 | IDE=1 | ID17..ID0 | RTR | r1 | r0 | DLC | data | CRC ...
//!  destuffed positions (std): 0 SOF, 1..=11 ID, 12 RTR, 13 IDE, 14 r0, 15..=18 DLC, 19.. data
//!  destuffed positions (ext): 12 SRR, 13 IDE, 14..=31 ID17..0, 32 RTR, 33 r1, 34 r0, 35..=38 DLC, 39.. data
//!  stuffing: after five equal bits from SOF to the last CRC bit, one bit of the other level
//! ```

use crate::crc::{BitSerial, CAN_CRC15};

/// A data or remote frame.
#[derive(
    Debug, Clone, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields)]
pub struct Frame {
    /// Identifier: 11 bits (standard) or 29 bits (extended).
    pub id: u32,
    /// Extended frame (CAN 2.0B).
    #[serde(default)]
    pub ide: bool,
    /// Remote frame (no data field).
    #[serde(default)]
    pub rtr: bool,
    /// Data length code, 0 to 15 (9 to 15 mean 8 bytes).
    #[serde(default)]
    pub dlc: u8,
    /// Data bytes (as many as the DLC says, at most 8; none for remote frames).
    #[serde(default)]
    pub data: Vec<u8>,
}

/// The number of data bytes a DLC means.
pub fn data_len(dlc: u8, rtr: bool) -> usize {
    if rtr {
        0
    } else {
        (dlc as usize).min(8)
    }
}

/// First destuffed data position.
pub fn data_start(ide: bool) -> u32 {
    if ide {
        39
    } else {
        19
    }
}

/// Last destuffed position of the arbitration field (ID and RTR; SRR, IDE, ID17..0 for extended).
pub fn arbitration_end(ide: bool) -> u32 {
    if ide {
        32
    } else {
        12
    }
}

/// The data bytes packed into a `u64`, byte 0 in bits 63..56 (the `o_rx_data` layout).
pub fn pack(data: &[u8]) -> u64 {
    data.iter()
        .take(8)
        .enumerate()
        .fold(0, |acc, (k, &b)| acc | (b as u64) << (56 - 8 * k))
}

/// The first `len` bytes of a packed `u64`.
pub fn unpack(data: u64, len: usize) -> Vec<u8> {
    (0..len.min(8))
        .map(|k| (data >> (56 - 8 * k)) as u8)
        .collect()
}

/// The bit a transmitter sends at destuffed position `pos` before the CRC
/// field, or `None` from the first CRC bit on.
pub fn header_bit(id: u32, ide: bool, rtr: bool, dlc: u8, data: u64, pos: u32) -> Option<bool> {
    let n = data_len(dlc, rtr) as u32;
    let ds = data_start(ide);
    let base = if ide { id >> 18 } else { id } & 0x7FF;
    let bit = match pos {
        0 => false,
        1..=11 => (base >> (11 - pos)) & 1 == 1,
        12 => {
            if ide {
                true
            } else {
                rtr
            }
        }
        13 => ide,
        _ if !ide => match pos {
            14 => false,
            15..=18 => (dlc >> (18 - pos)) & 1 == 1,
            _ => return data_bit(data, pos - ds, n),
        },
        14..=31 => (id >> (31 - pos)) & 1 == 1,
        32 => rtr,
        33 | 34 => false,
        35..=38 => (dlc >> (38 - pos)) & 1 == 1,
        _ => return data_bit(data, pos - ds, n),
    };
    Some(bit)
}

fn data_bit(data: u64, k: u32, n: u32) -> Option<bool> {
    (k < 8 * n).then(|| (data >> (63 - k)) & 1 == 1)
}

impl Frame {
    /// A standard data frame.
    pub fn data(id: u32, data: &[u8]) -> Frame {
        Frame {
            id,
            ide: false,
            rtr: false,
            dlc: data.len() as u8,
            data: data.to_vec(),
        }
    }

    /// The data as a packed `u64`.
    pub fn packed(&self) -> u64 {
        pack(&self.data)
    }

    /// Destuffed bits from SOF to the end of the data field (what CRC-15 covers).
    pub fn covered_bits(&self) -> Vec<bool> {
        let d = self.packed();
        (0..)
            .map_while(|p| header_bit(self.id, self.ide, self.rtr, self.dlc, d, p))
            .collect()
    }

    /// CRC-15 of the frame.
    pub fn crc(&self) -> u16 {
        let mut c = BitSerial::new(&CAN_CRC15);
        c.push_bits(&self.covered_bits());
        c.value() as u16
    }

    /// Destuffed bits from SOF through the last CRC bit.
    pub fn destuffed_bits(&self) -> Vec<bool> {
        let mut bits = self.covered_bits();
        let crc = self.crc();
        bits.extend((0..15).rev().map(|i| (crc >> i) & 1 == 1));
        bits
    }

    /// The frame on the wire from SOF to the end of EOF, stuffed, with the
    /// ACK slot dominant when `ack`.
    pub fn wire_bits(&self, ack: bool) -> Vec<bool> {
        let mut bits = stuff(&self.destuffed_bits());
        bits.push(true); // CRC delimiter
        bits.push(!ack);
        bits.push(true); // ACK delimiter
        bits.extend([true; 7]);
        bits
    }

    /// Checks the fields; `field` names the table entry in errors.
    pub fn validate(&self, field: &str) -> crate::Result<()> {
        let limit = if self.ide { 1 << 29 } else { 1 << 11 };
        if self.id >= limit {
            return Err(crate::ConfigError::invalid(
                format!("{field}.id"),
                format!("{:#x} does not fit the identifier", self.id),
                "give an 11-bit id (29-bit with ide = true)",
            ));
        }
        if self.dlc > 15 || self.data.len() != data_len(self.dlc, self.rtr) {
            return Err(crate::ConfigError::invalid(
                format!("{field}.data"),
                format!("{} bytes with dlc {}", self.data.len(), self.dlc),
                "give min(dlc, 8) bytes (none for a remote frame), dlc 0 to 15",
            ));
        }
        Ok(())
    }
}

/// Inserts a stuff bit after every five equal bits.
pub fn stuff(bits: &[bool]) -> Vec<bool> {
    let mut out = Vec::with_capacity(bits.len() + bits.len() / 4);
    let (mut run, mut last) = (0u32, true);
    for &b in bits {
        if run == 5 {
            out.push(!last);
            run = 1;
            last = !last;
        }
        out.push(b);
        if b == last {
            run += 1;
        } else {
            run = 1;
            last = b;
        }
    }
    if run == 5 {
        out.push(!last);
    }
    out
}

/// What the parser found wrong in a wire bit stream.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FrameError {
    /// Six equal bits in the stuffed part.
    Stuff,
    /// The CRC sequence does not match.
    Crc,
    /// A dominant CRC delimiter, ACK delimiter or EOF bit.
    Form,
    /// The stream ended inside the frame.
    Truncated,
}

/// A frame parsed from the wire.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Parsed {
    /// The frame's fields as received.
    pub frame: Frame,
    /// The received CRC sequence.
    pub crc: u16,
    /// The ACK slot was dominant.
    pub ack: bool,
    /// Wire bits consumed, SOF through the last EOF bit checked.
    pub len: usize,
}

/// Parses a frame starting with SOF at `wire[0]` through EOF, as a receiver
/// checks it (the last EOF bit is not checked: a receiver ignores it).
pub fn parse(wire: &[bool]) -> Result<Parsed, (FrameError, usize)> {
    let mut i = 0usize;
    let next = |i: &mut usize| -> Result<bool, (FrameError, usize)> {
        let b = *wire.get(*i).ok_or((FrameError::Truncated, *i))?;
        *i += 1;
        Ok(b)
    };
    let (mut run, mut last) = (0u32, true);
    let mut crc = BitSerial::new(&CAN_CRC15);
    let mut f = Frame::default();
    let (mut id, mut dlc, mut data, mut rx_crc) = (0u32, 0u8, 0u64, 0u16);
    let mut pos = 0u32;
    loop {
        if run == 5 {
            let b = next(&mut i)?;
            if b == last {
                return Err((FrameError::Stuff, i - 1));
            }
            run = 1;
            last = b;
        }
        let ds = data_start(f.ide);
        let crc_start = ds + 8 * data_len(dlc, f.rtr) as u32;
        if pos >= ds && pos == crc_start + 15 {
            break;
        }
        let b = next(&mut i)?;
        if b == last {
            run += 1;
        } else {
            run = 1;
            last = b;
        }
        if pos < ds || pos < crc_start {
            crc.push(b);
        } else {
            rx_crc = rx_crc << 1 | b as u16;
        }
        match pos {
            1..=11 => id = id << 1 | b as u32,
            12 => f.rtr = b,
            13 => f.ide = b,
            14..=31 if f.ide => id = id << 1 | b as u32,
            32 if f.ide => f.rtr = b,
            15..=18 if !f.ide => dlc = dlc << 1 | b as u8,
            35..=38 if f.ide => dlc = dlc << 1 | b as u8,
            _ if pos >= ds && pos < crc_start => data |= (b as u64) << (63 - (pos - ds)),
            _ => {}
        }
        pos += 1;
    }
    f.id = id;
    f.dlc = dlc;
    f.data = unpack(data, data_len(dlc, f.rtr));
    let crc_ok = crc.value() as u16 == rx_crc;
    if !next(&mut i)? {
        return Err((FrameError::Form, i - 1));
    }
    let ack = !next(&mut i)?;
    if !next(&mut i)? {
        return Err((FrameError::Form, i - 1));
    }
    if !crc_ok {
        return Err((FrameError::Crc, i - 1));
    }
    for _ in 0..6 {
        if !next(&mut i)? {
            return Err((FrameError::Form, i - 1));
        }
    }
    Ok(Parsed {
        frame: f,
        crc: rx_crc,
        ack,
        len: i + 1,
    })
}
