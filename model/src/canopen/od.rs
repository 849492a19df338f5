//! The object dictionary of the emulated DS 406 class 2 encoder behind the
//! Leine & Linde gateway (seed 003 §1.2, §3 to §7): the DS 301
//! communication objects, the DS 406 objects the note uses and its
//! manufacturer objects 5000h, 5001h and 5500h.
//!
//! Values are stored little-endian (CANopen byte order). The EDS writer
//! (`tbgen eds`) and the SDO server read the same table, so the data sheet
//! and the emulator cannot disagree.
//!
//! Where the note is silent (it lists no object table), the objects and
//! defaults follow CiA DS 301 / DS 406 as public summaries describe them;
//! each choice is in `docs/timing/canopen.md`:
//! - TPDO communication records carry sub 1 (COB-ID) and sub 2
//!   (transmission type) only: the gateway has no inhibit time or event timer
//!   of its own; the cyclic timer 6200h times every TPDO with type FEh/FFh;
//! - PDO mappings are fixed (read-only): both TPDOs carry 6004h, 32 bits;
//! - 5500h defaults to FFFF FFFFh ("not used": the note prints "FF FF FF h",
//!   read as all ones of an Unsigned32).

use super::cob::{cob_id, TPDO1, TPDO2};
use super::encoder::{EncoderConfig, EncoderKind};

/// CiA 301 data types used here.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DataType {
    /// UNSIGNED8.
    Unsigned8,
    /// UNSIGNED16.
    Unsigned16,
    /// UNSIGNED32.
    Unsigned32,
    /// INTEGER32.
    Integer32,
    /// VISIBLE_STRING.
    VisibleString,
}

impl DataType {
    /// The CiA 301 data type index (the EDS `DataType`).
    pub fn code(self) -> u16 {
        match self {
            DataType::Integer32 => 0x0004,
            DataType::Unsigned8 => 0x0005,
            DataType::Unsigned16 => 0x0006,
            DataType::Unsigned32 => 0x0007,
            DataType::VisibleString => 0x0009,
        }
    }

    /// Size in bytes (None: variable).
    pub fn size(self) -> Option<usize> {
        match self {
            DataType::Unsigned8 => Some(1),
            DataType::Unsigned16 => Some(2),
            DataType::Unsigned32 | DataType::Integer32 => Some(4),
            DataType::VisibleString => None,
        }
    }
}

/// Access of an entry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// Read-only (may change: a measured value).
    Ro,
    /// Read-write.
    Rw,
    /// Constant.
    Const,
}

impl Access {
    /// The EDS `AccessType`.
    pub fn eds(self) -> &'static str {
        match self {
            Access::Ro => "ro",
            Access::Rw => "rw",
            Access::Const => "const",
        }
    }
}

/// CiA 301 object codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ObjectKind {
    /// A single value (sub 0).
    Var,
    /// Sub 0 is the highest sub-index; the others share a type.
    Array,
    /// Sub 0 is the highest sub-index; the others have their own types.
    Record,
}

impl ObjectKind {
    /// The EDS `ObjectType`.
    pub fn code(self) -> u8 {
        match self {
            ObjectKind::Var => 0x7,
            ObjectKind::Array => 0x8,
            ObjectKind::Record => 0x9,
        }
    }
}

/// One sub-index.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Sub {
    /// Sub-index.
    pub sub: u8,
    /// Name.
    pub name: String,
    /// Data type.
    pub dtype: DataType,
    /// Access.
    pub access: Access,
    /// Default (power-on) value, little-endian bytes.
    pub default: Vec<u8>,
    /// Mappable into a PDO.
    pub pdo: bool,
}

/// One object (index).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Object {
    /// Index.
    pub index: u16,
    /// Name.
    pub name: String,
    /// Object code.
    pub kind: ObjectKind,
    /// Sub-indices (one, sub 0, for a VAR).
    pub subs: Vec<Sub>,
}

/// The whole dictionary.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Dictionary {
    /// Objects by ascending index.
    pub objects: Vec<Object>,
}

/// Little-endian bytes of a value of a fixed-size type.
pub fn le(dtype: DataType, v: u32) -> Vec<u8> {
    v.to_le_bytes()[..dtype.size().unwrap_or(4)].to_vec()
}

/// The value of little-endian bytes (up to 4).
pub fn value(bytes: &[u8]) -> u32 {
    bytes
        .iter()
        .take(4)
        .enumerate()
        .fold(0, |a, (k, &b)| a | (b as u32) << (8 * k))
}

fn var(index: u16, name: &str, dtype: DataType, access: Access, default: u32, pdo: bool) -> Object {
    Object {
        index,
        name: name.into(),
        kind: ObjectKind::Var,
        subs: vec![Sub {
            sub: 0,
            name: name.into(),
            dtype,
            access,
            default: le(dtype, default),
            pdo,
        }],
    }
}

fn string(index: u16, name: &str, text: &str) -> Object {
    Object {
        index,
        name: name.into(),
        kind: ObjectKind::Var,
        subs: vec![Sub {
            sub: 0,
            name: name.into(),
            dtype: DataType::VisibleString,
            access: Access::Const,
            default: text.as_bytes().to_vec(),
            pdo: false,
        }],
    }
}

fn record(index: u16, name: &str, subs: &[(&str, DataType, Access, u32)]) -> Object {
    let mut v = vec![Sub {
        sub: 0,
        name: "Highest sub-index supported".into(),
        dtype: DataType::Unsigned8,
        access: Access::Const,
        default: vec![subs.len() as u8],
        pdo: false,
    }];
    v.extend(subs.iter().enumerate().map(|(k, &(n, t, a, d))| Sub {
        sub: k as u8 + 1,
        name: n.into(),
        dtype: t,
        access: a,
        default: le(t, d),
        pdo: false,
    }));
    Object {
        index,
        name: name.into(),
        kind: ObjectKind::Record,
        subs: v,
    }
}

use Access::{Const, Ro, Rw};
use DataType::{Integer32 as I32, Unsigned16 as U16, Unsigned32 as U32, Unsigned8 as U8};

/// Name of the device (1008h).
pub const DEVICE_NAME: &str = "CANopen Encoder Gateway DS406";
/// Hardware version (1009h).
pub const HARDWARE_VERSION: &str = "1.0";
/// Software version (100Ah): the note's revision.
pub const SOFTWARE_VERSION: &str = "1.3";
/// Mapping entry of the position value: 6004h sub 0, 32 bits.
pub const MAP_POSITION: u32 = 0x6004_0020;

impl Dictionary {
    /// The dictionary of an encoder of configuration `cfg` at `node`
    /// (the COB-ID defaults depend on the node).
    pub fn encoder(cfg: &EncoderConfig, node: u8) -> Dictionary {
        let k = cfg.kind;
        let mut o = vec![
            var(0x1000, "Device type", U32, Const, k.device_type(), false),
            var(0x1001, "Error register", U8, Ro, 0, false),
            var(0x1005, "COB-ID SYNC", U32, Rw, 0x80, false),
            string(0x1008, "Manufacturer device name", DEVICE_NAME),
            string(0x1009, "Manufacturer hardware version", HARDWARE_VERSION),
            string(0x100A, "Manufacturer software version", SOFTWARE_VERSION),
            var(0x100C, "Guard time", U16, Rw, 0, false),
            var(0x100D, "Life time factor", U8, Rw, 0, false),
            var(0x1017, "Producer heartbeat time", U16, Rw, 0, false),
            record(
                0x1018,
                "Identity object",
                &[
                    ("Vendor-ID", U32, Ro, cfg.vendor_id),
                    ("Product code", U32, Ro, 0x0000_0406),
                    ("Revision number", U32, Ro, 0x0001_0003),
                    ("Serial number", U32, Ro, cfg.serial_number),
                ],
            ),
            record(
                0x1800,
                "TPDO1 communication parameter",
                &[
                    ("COB-ID used by TPDO", U32, Rw, cob_id(TPDO1, node) as u32),
                    ("Transmission type", U8, Rw, 0xFE),
                ],
            ),
            record(
                0x1801,
                "TPDO2 communication parameter",
                &[
                    ("COB-ID used by TPDO", U32, Rw, cob_id(TPDO2, node) as u32),
                    ("Transmission type", U8, Rw, 0x01),
                ],
            ),
            record(
                0x1A00,
                "TPDO1 mapping parameter",
                &[("Application object 1", U32, Const, MAP_POSITION)],
            ),
            record(
                0x1A01,
                "TPDO2 mapping parameter",
                &[("Application object 1", U32, Const, MAP_POSITION)],
            ),
            var(0x5000, "Transmission rate", U8, Rw, 0xFF, false),
            var(0x5001, "Node number", U8, Rw, 0xFF, false),
            var(
                0x5500,
                "Gateway Serial number",
                U32,
                Ro,
                cfg.serial_number,
                false,
            ),
            var(0x6000, "Operating parameters", U16, Rw, 0, false),
        ];
        if k != EncoderKind::Linear {
            o.push(var(
                0x6001,
                "Measuring units per revolution",
                U32,
                Rw,
                k.singleturn_resolution(),
                false,
            ));
            o.push(var(
                0x6002,
                "Total measuring range in measuring units",
                U32,
                Rw,
                k.total_resolution() as u32,
                false,
            ));
        }
        o.extend([
            var(0x6003, "Preset value", U32, Rw, 0, false),
            var(0x6004, "Position value", U32, Ro, 0, true),
            var(0x6200, "Cyclic timer", U16, Rw, 0, false),
            var(0x6500, "Operating status", U16, Ro, 0, false),
            var(
                0x6501,
                if k == EncoderKind::Linear {
                    "Measuring step"
                } else {
                    "Singleturn resolution"
                },
                U32,
                Const,
                if k == EncoderKind::Linear {
                    cfg.linear_step_nm
                } else {
                    k.singleturn_resolution()
                },
                false,
            ),
        ]);
        if k != EncoderKind::Linear {
            o.push(var(
                0x6502,
                "Number of distinguishable revolutions",
                U16,
                Const,
                k.revolutions(),
                false,
            ));
        }
        o.extend([
            var(0x6503, "Alarms", U16, Ro, 0, false),
            var(
                0x6504,
                "Supported alarms",
                U16,
                Const,
                SUPPORTED_ALARMS as u32,
                false,
            ),
            var(0x6505, "Warnings", U16, Ro, 0, false),
            var(0x6506, "Supported warnings", U16, Const, 0, false),
            var(
                0x6507,
                "Profile and software version",
                U32,
                Const,
                0x0103_0201,
                false,
            ),
            var(0x6508, "Operating time", U32, Ro, 0, false),
            var(0x6509, "Offset value", I32, Ro, 0, false),
            var(
                0x650B,
                "Serial number",
                U32,
                Const,
                cfg.encoder_serial,
                false,
            ),
        ]);
        Dictionary { objects: o }
    }

    /// The object at `index`.
    pub fn object(&self, index: u16) -> Option<&Object> {
        self.objects.iter().find(|o| o.index == index)
    }

    /// The entry at `index`/`sub`, or the SDO abort code saying which part is missing.
    pub fn entry(&self, index: u16, sub: u8) -> Result<&Sub, u32> {
        let o = self.object(index).ok_or(super::sdo::abort::NO_OBJECT)?;
        o.subs
            .iter()
            .find(|s| s.sub == sub)
            .ok_or(super::sdo::abort::NO_SUBINDEX)
    }

    /// Every entry, in index then sub-index order.
    pub fn entries(&self) -> impl Iterator<Item = (u16, &Sub)> {
        self.objects
            .iter()
            .flat_map(|o| o.subs.iter().map(move |s| (o.index, s)))
    }
}

/// 6503h/6504h bit 0: position error (the one alarm the gateway can see: the
/// EnDat encoder's error bit).
pub const ALARM_POSITION_ERROR: u16 = 0x0001;
/// Supported alarms (6504h).
pub const SUPPORTED_ALARMS: u16 = ALARM_POSITION_ERROR;
