//! ESL fields and frame sets (seed 000, "Detailed Description of Data
//! Frames", Tables 3 to 12): what each byte means, independent of timing.
//!
//! Every field is one 10-bit character: start 0, 8 bits LSB first, stop 1.
//! The bytes below are those 8 bits (bit 0 sent first).

use crate::crc::{self, Algorithm};
use schemars::JsonSchema;

/// The non-safety CRC-8 (init 0 on both channels).
pub const CRC8: &Algorithm = &crc::ESL_CRC8;
/// The safety CRC-16 of channel 1 (init 0x0000).
pub const CRC16_CH1: &Algorithm = &crc::ESL_CRC16_CH1;
/// The safety CRC-16 of channel 2 (init 0xFFFF).
pub const CRC16_CH2: &Algorithm = &crc::ESL_CRC16_CH2;

/// Single-turn resolution of the QS35 (ENID example: `ST = 11000` = 24 bits).
pub const ST_BITS: u32 = 24;
/// Bits of the redundant single-turn RS0/RS1 of the safety answers.
pub const RS_BITS: u32 = 9;
/// Bits of the extended redundant single-turn of Data ID 6 (RS0, RS1 whole bytes).
pub const RS_EXT_BITS: u32 = 16;
/// The page register (Table 9: "7Fh Page Selection").
pub const PAGE_REGISTER: u8 = 0x7F;
/// The page after power-on (Table 9: "Default Page after power on is Page 8").
pub const DEFAULT_PAGE: u8 = 8;
/// The register page (Table 11: page 8 is "Register"); every other page is
/// EEPROM or MTP with the busy timing.
pub const REGISTER_PAGE: u8 = 8;

/// The Data IDs of Tables 3 and 12.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize, JsonSchema,
)]
pub enum DataId {
    /// 1: position read, safety, with multi-turn.
    Id1,
    /// 2: position read, safety, single-turn only.
    Id2,
    /// 4: position read, non-safety, with multi-turn.
    Id4,
    /// 5: position read, non-safety, single-turn only.
    Id5,
    /// 6: position read for calibration, extended redundant single-turn.
    Id6,
    /// 8: retrieve ENID (safety).
    Id8,
    /// 9: temperature read.
    Id9,
    /// A: alarm read, both channels.
    IdA,
    /// B: single-turn clear (sent 8 times, safety answer).
    IdB,
    /// C: clear all errors (sent 8 times).
    IdC,
    /// D: multi-turn clear (sent 8 times).
    IdD,
    /// E: memory or register read.
    IdE,
    /// F: memory or register write.
    IdF,
}

/// How a channel's CRC field is made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CrcKind {
    /// One CRC-8 field.
    Crc8,
    /// Two fields of CRC-16 (CRCx.1 = low byte first), with the channel's init.
    Crc16,
}

/// What one data field carries (Table 12).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Field {
    /// Control field (CF1, CF2).
    Cf,
    /// Status field (SF1, SF2).
    Sf,
    /// Alarm flags (ALM1 on channel 1, ALM2 on channel 2).
    Alm,
    /// Single-turn byte `n` (ABS0..2, LSB first).
    Abs(u8),
    /// Multi-turn byte `n` (ABM0..1).
    Abm(u8),
    /// Sequence counter SC1.
    Sc1,
    /// Encoder ID.
    Enid,
    /// Temperature, °C, two's complement.
    Temp,
    /// Memory address field (busy in bit 0, address in bits 1..7).
    Adf,
    /// Memory data field.
    Edf,
    /// RS0: redundant single-turn bits 8..1.
    Rs0,
    /// RS1 in bit 0, SC2 (7 bits) in bits 1..7 ("RS1, SC2").
    Rs1Sc2,
    /// 0 in bit 0, SC2 in bits 1..7 ("0, SC2", Data ID 8).
    ZeroSc2,
    /// RS1 alone in bit 0 (Data ID C).
    Rs1,
    /// Extended redundant single-turn, high byte (Data ID 6 "RS0").
    RsExtHi,
    /// Extended redundant single-turn, low byte (Data ID 6 "RS1").
    RsExtLo,
}

/// One channel of an answer: its data fields (CF first) and its CRC.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Channel {
    /// The fields before the CRC.
    pub fields: &'static [Field],
    /// The CRC that closes them.
    pub crc: CrcKind,
}

impl Channel {
    /// Fields on the line, CRC included.
    pub fn len(&self) -> usize {
        self.fields.len() + if self.crc == CrcKind::Crc16 { 2 } else { 1 }
    }

    /// Never empty (a CF and a CRC at least).
    pub fn is_empty(&self) -> bool {
        false
    }
}

use Field::*;

impl DataId {
    /// Every Data ID of Table 12.
    pub const ALL: [DataId; 13] = [
        DataId::Id1,
        DataId::Id2,
        DataId::Id4,
        DataId::Id5,
        DataId::Id6,
        DataId::Id8,
        DataId::Id9,
        DataId::IdA,
        DataId::IdB,
        DataId::IdC,
        DataId::IdD,
        DataId::IdE,
        DataId::IdF,
    ];

    /// The 4-bit code CC0..CC3 (CC0 is bit 0; Table 3).
    pub fn code(self) -> u8 {
        match self {
            DataId::Id1 => 0x1,
            DataId::Id2 => 0x2,
            DataId::Id4 => 0x4,
            DataId::Id5 => 0x5,
            DataId::Id6 => 0x6,
            DataId::Id8 => 0x8,
            DataId::Id9 => 0x9,
            DataId::IdA => 0xA,
            DataId::IdB => 0xB,
            DataId::IdC => 0xC,
            DataId::IdD => 0xD,
            DataId::IdE => 0xE,
            DataId::IdF => 0xF,
        }
    }

    /// The Data ID with code `code`, if Table 12 lists it.
    pub fn from_code(code: u8) -> Option<DataId> {
        DataId::ALL.into_iter().find(|d| d.code() == code)
    }

    /// Memory access (E, F): point to point only.
    pub fn is_memory(self) -> bool {
        matches!(self, DataId::IdE | DataId::IdF)
    }

    /// The commands sent 8 times in a row (Table 4: B, C, D).
    pub fn is_repeated(self) -> bool {
        matches!(self, DataId::IdB | DataId::IdC | DataId::IdD)
    }

    /// Whether the answer carries the sequence counters (IDs 1, 2, 8, B).
    pub fn is_safety(self) -> bool {
        self.channel2().is_some_and(|c| c.crc == CrcKind::Crc16)
    }

    /// Channel 1 of the answer (Table 12, CF .. CRC1).
    pub fn channel1(self) -> Channel {
        let (fields, crc): (&'static [Field], CrcKind) = match self {
            DataId::Id1 => (
                &[Cf, Sf, Alm, Abs(0), Abs(1), Abs(2), Abm(0), Abm(1), Sc1],
                CrcKind::Crc16,
            ),
            DataId::Id2 | DataId::IdB => {
                (&[Cf, Sf, Alm, Abs(0), Abs(1), Abs(2), Sc1], CrcKind::Crc16)
            }
            DataId::Id4 => (
                &[Cf, Sf, Abs(0), Abs(1), Abs(2), Abm(0), Abm(1)],
                CrcKind::Crc8,
            ),
            DataId::Id5 | DataId::Id6 => (&[Cf, Sf, Abs(0), Abs(1), Abs(2)], CrcKind::Crc8),
            DataId::Id8 => (&[Cf, Sf, Enid, Sc1], CrcKind::Crc16),
            DataId::Id9 => (&[Cf, Sf, Temp], CrcKind::Crc8),
            DataId::IdA => (&[Cf, Sf, Alm], CrcKind::Crc8),
            DataId::IdC => (&[Cf, Sf, Alm, Abs(0), Abs(1), Abs(2)], CrcKind::Crc8),
            DataId::IdD => (&[Cf, Sf, Alm, Abm(0), Abm(1)], CrcKind::Crc8),
            DataId::IdE | DataId::IdF => (&[Cf, Adf, Edf], CrcKind::Crc8),
        };
        Channel { fields, crc }
    }

    /// Channel 2 of the answer, if Table 12 gives one (CF2 .. CRC2).
    pub fn channel2(self) -> Option<Channel> {
        let (fields, crc): (&'static [Field], CrcKind) = match self {
            DataId::Id1 | DataId::Id2 | DataId::IdB => {
                (&[Cf, Sf, Alm, Rs0, Rs1Sc2], CrcKind::Crc16)
            }
            DataId::Id6 => (&[Cf, Sf, RsExtHi, RsExtLo], CrcKind::Crc8),
            DataId::Id8 => (&[Cf, Sf, Enid, ZeroSc2], CrcKind::Crc16),
            DataId::IdA => (&[Cf, Sf, Alm], CrcKind::Crc8),
            DataId::IdC => (&[Cf, Sf, Alm, Rs0, Rs1], CrcKind::Crc8),
            _ => return None,
        };
        Some(Channel { fields, crc })
    }

    /// Fields of the whole answer on the line (Table 12 "Frame Size").
    pub fn answer_fields(self) -> usize {
        self.channel1().len() + self.channel2().map_or(0, |c| c.len())
    }

    /// The control field the host sends to `address` (0..7).
    pub fn control_field(self, address: u8) -> u8 {
        control_field_for_code(address, self.code())
    }
}

/// The control field for encoder address `address` and a 4-bit code:
/// EAD0..2 in bits 0..2, CC0..CC3 in bits 3..6, parity in bit 7 making the
/// number of ones in CC0..CC3 and the parity bit odd (Table 3 `<odd>`,
/// "Parity check bit for Command ID").
pub fn control_field_for_code(address: u8, code: u8) -> u8 {
    let code = code & 0xF;
    let parity = (code.count_ones() & 1 == 0) as u8;
    (address & 0b111) | (code << 3) | (parity << 7)
}

/// What a received control field says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ControlField {
    /// EAD0..2.
    pub address: u8,
    /// CC0..CC3.
    pub code: u8,
    /// The parity bit makes CC0..CC3 and itself odd.
    pub parity_ok: bool,
}

/// Splits a control field into its parts.
pub fn parse_control_field(byte: u8) -> ControlField {
    let code = (byte >> 3) & 0xF;
    ControlField {
        address: byte & 0b111,
        code,
        parity_ok: (byte & 0xF8).count_ones() & 1 == 1,
    }
}

/// The status field (Figure 8 is lost; the bits in the order Table 5 lists
/// them, bit 0 first): CA0, CA1, EA0, EA1, DD0..DD3.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct Status {
    /// Wrong parity bit in the request.
    pub ca0: bool,
    /// Wrong stop bit in the request.
    pub ca1: bool,
    /// Safety error (ST, MEM, OV, UV, LED).
    pub ea0: bool,
    /// Non-safety error (MT, XC, LIS, OVSP).
    pub ea1: bool,
    /// DD0: temperature warning.
    pub temp_warning: bool,
    /// DD1: this is channel 2.
    pub ch2: bool,
    /// DD2: encoder ready.
    pub ready: bool,
    /// DD3: forced test passed.
    pub forced_test: bool,
}

impl Status {
    /// The status byte.
    pub fn byte(self) -> u8 {
        [
            self.ca0,
            self.ca1,
            self.ea0,
            self.ea1,
            self.temp_warning,
            self.ch2,
            self.ready,
            self.forced_test,
        ]
        .iter()
        .enumerate()
        .fold(0, |acc, (i, &b)| acc | (b as u8) << i)
    }

    /// A status byte read back.
    pub fn from_byte(b: u8) -> Status {
        let bit = |i: u8| b >> i & 1 == 1;
        Status {
            ca0: bit(0),
            ca1: bit(1),
            ea0: bit(2),
            ea1: bit(3),
            temp_warning: bit(4),
            ch2: bit(5),
            ready: bit(6),
            forced_test: bit(7),
        }
    }
}

/// Status bits CA0 | CA1: the encoder saw a bad request.
pub const STATUS_CA_MASK: u8 = 0b11;
/// Status bit DD1: the field belongs to channel 2.
pub const STATUS_CH2: u8 = 1 << 5;

/// Encoder error flags (Table 7, ALM bit 0 first; Table 8 for how each is cleared).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize, JsonSchema,
)]
#[serde(deny_unknown_fields, default)]
pub struct Alarms {
    /// XC: multi-turn miss count (bit 0; cleared by C).
    pub xc: bool,
    /// MT: multi-turn counting error (bit 1; cleared by C).
    pub mt: bool,
    /// LED current out of range (bit 2; power cycle).
    pub led: bool,
    /// Lissajous out of specification (bit 2; power cycle).
    pub lis: bool,
    /// Over-speed (bit 3; power cycle).
    pub overspeed: bool,
    /// Memory load failure (bit 4; power cycle).
    pub mem: bool,
    /// Single-turn error (bit 5; power cycle).
    pub st: bool,
    /// Under-voltage (bit 6; clears itself).
    pub uv: bool,
    /// Over-voltage (bit 7; clears itself).
    pub ov: bool,
}

impl Alarms {
    /// The ALM byte (LED and LIS share bit 2).
    pub fn byte(self) -> u8 {
        [
            self.xc,
            self.mt,
            self.led || self.lis,
            self.overspeed,
            self.mem,
            self.st,
            self.uv,
            self.ov,
        ]
        .iter()
        .enumerate()
        .fold(0, |acc, (i, &b)| acc | (b as u8) << i)
    }

    /// EA0 (safety error: ST, MEM, OV, UV, LED) and EA1 (non-safety: MT,
    /// XC, LIS, OVSP) of Table 5.
    pub fn ea(self) -> (bool, bool) {
        (
            self.st || self.mem || self.ov || self.uv || self.led,
            self.mt || self.xc || self.lis || self.overspeed,
        )
    }

    /// What "clear all errors" (Data ID C) leaves: XC and MT are the latched
    /// errors Table 8 resets by "Perform all error clear".
    pub fn after_clear(self) -> Alarms {
        Alarms {
            xc: false,
            mt: false,
            ..self
        }
    }
}

/// ENID (Table 6): `{1'b<safety>, 2'b<MT-#-byte>, 5'b<ST-#-bit>}`, safety in bit 7.
pub fn enid(safety: bool, mt_bytes: u8, st_bits: u8) -> u8 {
    (safety as u8) << 7 | (mt_bytes & 0b11) << 5 | (st_bits & 0x1F)
}

/// The bytes of one channel with its CRC appended (`ch2` picks the CRC-16 init).
pub fn with_crc(data: &[u8], crc: CrcKind, ch2: bool) -> Vec<u8> {
    let mut out = data.to_vec();
    match crc {
        CrcKind::Crc8 => out.push(CRC8.checksum_bytes(data) as u8),
        CrcKind::Crc16 => {
            let alg = if ch2 { CRC16_CH2 } else { CRC16_CH1 };
            let v = crc16(alg, data);
            out.extend_from_slice(&[v as u8, (v >> 8) as u8]);
        }
    }
    out
}

/// A CRC-16 over fields: their data bits LSB first, padded to whole 16 bits.
pub fn crc16(alg: &Algorithm, data: &[u8]) -> u16 {
    let bits: Vec<bool> = data
        .iter()
        .flat_map(|&b| (0..8).map(move |i| b >> i & 1 == 1))
        .collect();
    alg.checksum_frame_bits(&bits) as u16
}

/// Whether a channel's received bytes (data then CRC) carry a good CRC.
pub fn channel_crc_ok(bytes: &[u8], crc: CrcKind, ch2: bool) -> bool {
    let n = match crc {
        CrcKind::Crc8 => 1,
        CrcKind::Crc16 => 2,
    };
    bytes.len() > n && with_crc(&bytes[..bytes.len() - n], crc, ch2) == bytes
}

/// The request frame set: CF and its CRC-8; memory read CF ADF CRC; write
/// CF ADF EDF CRC (ADF = address in bits 1..7, busy bit 0 = 0).
pub fn request(address: u8, code: u8, mem_address: u8, data: u8) -> Vec<u8> {
    let cf = control_field_for_code(address, code);
    let fields = match DataId::from_code(code & 0xF) {
        Some(DataId::IdE) => vec![cf, adf(mem_address, false)],
        Some(DataId::IdF) => vec![cf, adf(mem_address, false), data],
        _ => vec![cf],
    };
    with_crc(&fields, CrcKind::Crc8, false)
}

/// An address field: busy in bit 0, Add0..Add6 in bits 1..7 (Figure 12 lists
/// Busy before Add0).
pub fn adf(mem_address: u8, busy: bool) -> u8 {
    (mem_address & 0x7F) << 1 | busy as u8
}

/// The values an answer is built from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AnswerData {
    /// CF (the request's control field, echoed).
    pub cf: u8,
    /// Channel-1 status.
    pub status: Status,
    /// ALM1.
    pub alm1: u8,
    /// ALM2.
    pub alm2: u8,
    /// Single-turn, 24 bits.
    pub abs: u32,
    /// Multi-turn, 16 bits.
    pub abm: u16,
    /// Redundant single-turn of channel 2 (9 bits, or 16 for Data ID 6).
    pub rs: u16,
    /// SC1.
    pub sc1: u8,
    /// SC2 (7 bits on the line).
    pub sc2: u8,
    /// ENID.
    pub enid: u8,
    /// Temperature.
    pub temp: u8,
    /// ADF.
    pub adf: u8,
    /// EDF.
    pub edf: u8,
}

fn field_byte(f: Field, d: &AnswerData, ch2: bool) -> u8 {
    match f {
        Cf => d.cf,
        Sf => Status { ch2, ..d.status }.byte(),
        Alm => {
            if ch2 {
                d.alm2
            } else {
                d.alm1
            }
        }
        Abs(n) => (d.abs >> (8 * n)) as u8,
        Abm(n) => (d.abm >> (8 * n)) as u8,
        Sc1 => d.sc1,
        Enid => d.enid,
        Temp => d.temp,
        Adf => d.adf,
        Edf => d.edf,
        Rs0 => (d.rs >> 1) as u8,
        Rs1Sc2 => (d.rs & 1) as u8 | (d.sc2 << 1),
        ZeroSc2 => d.sc2 << 1,
        Rs1 => (d.rs & 1) as u8,
        RsExtHi => (d.rs >> 8) as u8,
        RsExtLo => d.rs as u8,
    }
}

/// The answer frame set of `id` (Table 12), CRCs included.
pub fn answer(id: DataId, d: &AnswerData) -> Vec<u8> {
    let c1 = id.channel1();
    let mut out = with_crc(
        &c1.fields
            .iter()
            .map(|&f| field_byte(f, d, false))
            .collect::<Vec<_>>(),
        c1.crc,
        false,
    );
    if let Some(c2) = id.channel2() {
        out.extend(with_crc(
            &c2.fields
                .iter()
                .map(|&f| field_byte(f, d, true))
                .collect::<Vec<_>>(),
            c2.crc,
            true,
        ));
    }
    out
}

/// The short answer to a request with a bad parity or stop bit: CF as
/// received, SF with CA0/CA1, CRC-8. Nothing is executed (seed: "the command
/// request will not be acknowledged and executed"; Table 5 says how CA0/CA1
/// report it). The format is this model's decision: a bad request's Data ID
/// cannot be trusted to select one of Table 12.
pub fn comm_error_answer(cf: u8, status: Status) -> Vec<u8> {
    with_crc(&[cf, status.byte()], CrcKind::Crc8, false)
}

/// Fields of [`comm_error_answer`].
pub const COMM_ERROR_FIELDS: usize = 3;

/// What the host reads out of a received answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct Decoded {
    /// CF1.
    pub cf: u8,
    /// SF1 (or the ADF for memory access).
    pub sf: u8,
    /// SF2.
    pub sf2: u8,
    /// ALM1.
    pub alm1: u8,
    /// ALM2.
    pub alm2: u8,
    /// Single-turn (24 bits).
    pub abs: u32,
    /// Multi-turn (16 bits).
    pub abm: u16,
    /// Redundant single-turn (9 bits; 16 for Data ID 6).
    pub rs: u16,
    /// SC1.
    pub sc1: u8,
    /// SC2 (7 bits).
    pub sc2: u8,
    /// ENID.
    pub enid: u8,
    /// Temperature.
    pub temp: u8,
    /// ADF.
    pub adf: u8,
    /// EDF.
    pub edf: u8,
}

/// Reads the fields of `id`'s layout out of `bytes` (as many as there are).
pub fn decode(id: DataId, bytes: &[u8]) -> Decoded {
    let mut d = Decoded::default();
    let c1 = id.channel1();
    let mut put = |f: Field, b: u8, ch2: bool| match f {
        Cf if !ch2 => d.cf = b,
        Sf if ch2 => d.sf2 = b,
        Sf => d.sf = b,
        Alm if ch2 => d.alm2 = b,
        Alm => d.alm1 = b,
        Abs(n) => d.abs |= u32::from(b) << (8 * n),
        Abm(n) => d.abm |= u16::from(b) << (8 * n),
        Sc1 => d.sc1 = b,
        Enid if !ch2 => d.enid = b,
        Temp => d.temp = b,
        Adf => d.adf = b,
        Edf => d.edf = b,
        Rs0 => d.rs |= u16::from(b) << 1,
        Rs1Sc2 => {
            d.rs |= u16::from(b & 1);
            d.sc2 = b >> 1;
        }
        ZeroSc2 => d.sc2 = b >> 1,
        Rs1 => d.rs |= u16::from(b & 1),
        RsExtHi => d.rs |= u16::from(b) << 8,
        RsExtLo => d.rs |= u16::from(b),
        Cf | Enid => {}
    };
    for (i, &f) in c1.fields.iter().enumerate() {
        if let Some(&b) = bytes.get(i) {
            put(f, b, false);
        }
    }
    if let Some(c2) = id.channel2() {
        for (i, &f) in c2.fields.iter().enumerate() {
            if let Some(&b) = bytes.get(c1.len() + i) {
                put(f, b, true);
            }
        }
    }
    d
}

/// The redundant single-turn channel 2 reports for a 24-bit single-turn
/// position: its top `RS_BITS` (16 for Data ID 6).
pub fn redundant(abs: u32, id: DataId) -> u16 {
    let bits = if id == DataId::Id6 {
        RS_EXT_BITS
    } else {
        RS_BITS
    };
    ((abs & 0xFF_FFFF) >> (ST_BITS - bits)) as u16
}

/// Whether channel 2's redundant single-turn agrees with channel 1's
/// position within `tolerance` LSBs of the redundant resolution (modulo one
/// turn): the two channels quantise the same angle independently.
pub fn channels_agree(abs: u32, rs: u16, id: DataId, tolerance: u16) -> bool {
    let bits = if id == DataId::Id6 {
        RS_EXT_BITS
    } else {
        RS_BITS
    };
    let modulus = 1u32 << bits;
    let diff = (u32::from(rs) + modulus - u32::from(redundant(abs, id))) % modulus;
    diff <= u32::from(tolerance) || diff >= modulus - u32::from(tolerance)
}

/// The checks a host makes on one answer frame set (everything but timing).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Checks {
    /// Channel 1's CRC is wrong.
    pub crc1: bool,
    /// Channel 2's CRC is wrong.
    pub crc2: bool,
    /// A field had a bad stop bit, or the answer has not the number of
    /// fields the request asks for.
    pub frame: bool,
    /// CF1 (or CF2) is not the request's control field.
    pub cf: bool,
    /// CA0 or CA1 set: the encoder saw a bad request.
    pub comm: bool,
    /// Channel 2's redundant single-turn disagrees with channel 1.
    pub rs: bool,
}

impl Checks {
    /// Any of them.
    pub fn any(self) -> bool {
        self.crc1 || self.crc2 || self.frame || self.cf || self.comm || self.rs
    }
}

/// Checks one received answer to a request with control field `request_cf`
/// (`id` its Data ID) against Table 12; `framing_error` is whether any field
/// had a bad stop bit. A [`comm_error_answer`] is recognised by its length
/// and reported as `comm` alone if its CRC holds.
pub fn check(
    id: DataId,
    request_cf: u8,
    bytes: &[u8],
    framing_error: bool,
    rs_tolerance: u16,
) -> Checks {
    let mut c = Checks {
        frame: framing_error,
        ..Checks::default()
    };
    let c1 = id.channel1();
    if bytes.len() == COMM_ERROR_FIELDS && bytes.len() != id.answer_fields() {
        c.crc1 = !channel_crc_ok(bytes, CrcKind::Crc8, false);
        c.comm = !c.crc1 && bytes[1] & STATUS_CA_MASK != 0;
        c.frame |= !c.comm;
        // The CF is echoed as received: its parity bit may be the one that broke.
        c.cf = bytes[0] & 0x7F != request_cf & 0x7F;
        return c;
    }
    c.frame |= bytes.len() != id.answer_fields();
    c.crc1 = bytes.len() < c1.len() || !channel_crc_ok(&bytes[..c1.len()], c1.crc, false);
    c.cf = bytes.first() != Some(&request_cf);
    if let Some(c2) = id.channel2() {
        let ch2 = bytes
            .get(c1.len()..(c1.len() + c2.len()).min(bytes.len()))
            .unwrap_or(&[]);
        c.crc2 = ch2.len() < c2.len() || !channel_crc_ok(ch2, c2.crc, true);
        c.cf |= ch2.first().is_some_and(|&b| b != request_cf);
    }
    let d = decode(id, bytes);
    if !id.is_memory() {
        c.comm =
            d.sf & STATUS_CA_MASK != 0 || (id.channel2().is_some() && d.sf2 & STATUS_CA_MASK != 0);
    }
    let has_rs = id.channel2().is_some_and(|c2| {
        c2.fields
            .iter()
            .any(|f| matches!(f, Rs0 | Rs1 | Rs1Sc2 | RsExtHi))
    });
    c.rs =
        has_rs && !c.crc1 && !c.crc2 && !c.frame && !channels_agree(d.abs, d.rs, id, rs_tolerance);
    c
}
