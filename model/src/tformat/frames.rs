//! T-format fields and frame sets (seed 002, 6.2 and 6.3): what each byte
//! means, independent of timing.
//!
//! Every field is one 10-bit character: start 0, 8 bits LSB first, delimiter
//! 1. The bytes below are those 8 bits (bit 0 sent first).

use crate::crc::{self, Algorithm};
use schemars::JsonSchema;

/// The CRC of the frame sets: `G(X) = X^8 + 1` over every field but the CRC
/// itself, without start bits and delimiters (seed 002, 6.3.4), which is the
/// XOR of their bytes.
pub const CRC: &Algorithm = &crc::TFORMAT_CRC8;

/// Sink code in bits 0..2 of the control field. The seed's Figure 4 is lost;
/// `010` (bit 1 set) is the code public T-format material uses: Data ID 0 is
/// requested with the byte `0x02`.
pub const SINK_CODE: u8 = 0b010;

/// Encoder ID sent in ENID (seed 002, 6.3.3: "Fixed as 11H").
pub const ENID: u8 = 0x11;

/// The Data IDs of Table 1, with their uses.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize, JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum DataId {
    /// 0: single-turn data (ABS0..2).
    Id0,
    /// 1: multi-turn data (ABM0..2).
    Id1,
    /// 2: encoder ID (ENID).
    Id2,
    /// 3: everything (ABS, ENID, ABM, ALMC).
    Id3,
    /// 6: write one EEPROM byte.
    Id6,
    /// 7: reset all errors (sent 10 times).
    Id7,
    /// 8: reset single-turn data (sent 10 times).
    Id8,
    /// C: reset multi-turn data and all errors (sent 10 times).
    IdC,
    /// D: read one EEPROM byte.
    IdD,
}

impl DataId {
    /// Every Data ID of Table 1.
    pub const ALL: [DataId; 9] = [
        DataId::Id0,
        DataId::Id1,
        DataId::Id2,
        DataId::Id3,
        DataId::Id6,
        DataId::Id7,
        DataId::Id8,
        DataId::IdC,
        DataId::IdD,
    ];

    /// The 4-bit code cc0..cc3 (cc0 is bit 0).
    pub fn code(self) -> u8 {
        match self {
            DataId::Id0 => 0x0,
            DataId::Id1 => 0x1,
            DataId::Id2 => 0x2,
            DataId::Id3 => 0x3,
            DataId::Id6 => 0x6,
            DataId::Id7 => 0x7,
            DataId::Id8 => 0x8,
            DataId::IdC => 0xC,
            DataId::IdD => 0xD,
        }
    }

    /// The Data ID with code `code`, if Table 1 lists it.
    pub fn from_code(code: u8) -> Option<DataId> {
        DataId::ALL.into_iter().find(|d| d.code() == code)
    }

    /// The control field the host sends: sink code, cc0..cc3, parity cc4.
    pub fn control_field(self) -> u8 {
        control_field_for_code(self.code())
    }

    /// Whether it is an EEPROM access (6, D).
    pub fn is_eeprom(self) -> bool {
        matches!(self, DataId::Id6 | DataId::IdD)
    }

    /// Whether it is one of the resets sent ten times (7, 8, C).
    pub fn is_reset(self) -> bool {
        matches!(self, DataId::Id7 | DataId::Id8 | DataId::IdC)
    }

    /// The number of fields the encoder answers with, CRC included: Table 2
    /// for the readouts and resets, CF ADF EDF CRC for the EEPROM accesses.
    pub fn answer_fields(self) -> usize {
        match self {
            DataId::Id2 => 4,
            DataId::Id3 => 11,
            DataId::Id6 | DataId::IdD => 4,
            _ => 6,
        }
    }
}

/// The control field for a 4-bit code: parity cc4 makes the number of ones
/// in cc0..cc4 even (Table 1: Data ID 1 = 1000 with parity 1).
pub fn control_field_for_code(code: u8) -> u8 {
    let code = code & 0xF;
    let parity = (code.count_ones() & 1) as u8;
    SINK_CODE | (code << 3) | (parity << 7)
}

/// What a received control field says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ControlField {
    /// Bits 0..2 equal the sink code.
    pub sink_ok: bool,
    /// The 4-bit code cc0..cc3.
    pub code: u8,
    /// cc4 is the right parity of cc0..cc3.
    pub parity_ok: bool,
}

/// Splits a control field into its parts.
pub fn parse_control_field(byte: u8) -> ControlField {
    let code = (byte >> 3) & 0xF;
    ControlField {
        sink_ok: byte & 0b111 == SINK_CODE,
        code,
        parity_ok: (byte >> 7) == (code.count_ones() & 1) as u8,
    }
}

/// The status field: information bits 0..3 are 0; then ea0, ea1, ca0, ca1.
/// The seed's Figure 5 is lost; this order is the one a public Data ID 0
/// capture (status byte `0x20` from an encoder with a battery alarm, ea1)
/// agrees with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct Status {
    /// Counting error.
    pub ea0: bool,
    /// Multi-turn error, battery error or battery alarm.
    pub ea1: bool,
    /// Parity error in the request.
    pub ca0: bool,
    /// Delimiter error in the request.
    pub ca1: bool,
}

impl Status {
    /// The status byte.
    pub fn byte(self) -> u8 {
        (self.ea0 as u8) << 4
            | (self.ea1 as u8) << 5
            | (self.ca0 as u8) << 6
            | (self.ca1 as u8) << 7
    }

    /// A status byte read back (information bits ignored).
    pub fn from_byte(b: u8) -> Status {
        Status {
            ea0: b & 0x10 != 0,
            ea1: b & 0x20 != 0,
            ca0: b & 0x40 != 0,
            ca1: b & 0x80 != 0,
        }
    }
}

/// ALMC (Table 3): the encoder's error flags, bit 0 first.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize, JsonSchema,
)]
#[serde(deny_unknown_fields, default)]
pub struct Alarms {
    /// OS: over-speed (d70).
    pub over_speed: bool,
    /// FS: full absolute status (d71).
    pub full_absolute: bool,
    /// CE: counting error (d72).
    pub counting_error: bool,
    /// OF: counter overflow (d73).
    pub counter_overflow: bool,
    /// ME: multi-turn error (d75).
    pub multi_turn_error: bool,
    /// BE: battery error (d76).
    pub battery_error: bool,
    /// BA: battery alarm (d77).
    pub battery_alarm: bool,
}

impl Alarms {
    /// The ALMC byte (bit 4 is always 0).
    pub fn byte(self) -> u8 {
        self.over_speed as u8
            | (self.full_absolute as u8) << 1
            | (self.counting_error as u8) << 2
            | (self.counter_overflow as u8) << 3
            | (self.multi_turn_error as u8) << 5
            | (self.battery_error as u8) << 6
            | (self.battery_alarm as u8) << 7
    }

    /// ea0 and ea1 of the status field (6.3.2): ea0 is the counting error,
    /// ea1 the OR of multi-turn error, battery error and battery alarm.
    pub fn status(self) -> Status {
        Status {
            ea0: self.counting_error,
            ea1: self.multi_turn_error || self.battery_error || self.battery_alarm,
            ..Status::default()
        }
    }
}

/// The fields of a frame set with its CRC appended.
pub fn with_crc(fields: &[u8]) -> Vec<u8> {
    let mut out = fields.to_vec();
    out.push(CRC.checksum_bytes(fields) as u8);
    out
}

/// Whether the last field of a frame set is the CRC of the others.
pub fn crc_ok(set: &[u8]) -> bool {
    match set.split_last() {
        Some((crc, fields)) => CRC.checksum_bytes(fields) as u8 == *crc,
        None => false,
    }
}

/// The request frame set a host sends for `id` (EEPROM address and data
/// only used by 6 and D): CF alone for readouts and resets; CF ADF EDF CRC
/// to write; CF ADF CRC to read.
pub fn request(id: DataId, address: u8, data: u8) -> Vec<u8> {
    let cf = id.control_field();
    match id {
        DataId::Id6 => with_crc(&[cf, address & 0x7F, data]),
        DataId::IdD => with_crc(&[cf, address & 0x7F]),
        _ => vec![cf],
    }
}

/// The answer frame set to a readout or reset request (Table 2): CF, SF,
/// then ABS0..2 (0, 7, 8, C), ABM0..2 (1), ENID (2), or ABS, ENID, ABM, ALMC
/// (3), then the CRC.
pub fn readout(id: DataId, status: Status, single_turn: u32, multi_turn: u16, almc: u8) -> Vec<u8> {
    let abs = le24(single_turn & 0x1_FFFF);
    let abm = le24(multi_turn as u32);
    let mut fields = vec![id.control_field(), status.byte()];
    match id {
        DataId::Id1 => fields.extend_from_slice(&abm),
        DataId::Id2 => fields.push(ENID),
        DataId::Id3 => {
            fields.extend_from_slice(&abs);
            fields.push(ENID);
            fields.extend_from_slice(&abm);
            fields.push(almc);
        }
        _ => fields.extend_from_slice(&abs),
    }
    with_crc(&fields)
}

/// The answer frame set to an accepted EEPROM request (Table 4): CF, ADF
/// (address, bit 7 busy), EDF, CRC.
pub fn eeprom_answer(id: DataId, address: u8, busy: bool, edf: u8) -> Vec<u8> {
    with_crc(&[
        id.control_field(),
        (address & 0x7F) | (busy as u8) << 7,
        edf,
    ])
}

/// Three little-endian bytes (ABS0..2, ABM0..2: "ABS0 is located to lower byte").
pub fn le24(value: u32) -> [u8; 3] {
    let b = value.to_le_bytes();
    [b[0], b[1], b[2]]
}
