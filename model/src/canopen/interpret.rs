//! A CAN frame read as CANopen (pre-defined connection set): NMT, SYNC,
//! EMCY or boot-up, PDO, SDO with object names, node guarding and heartbeat.
//! The building block of `tbgen decode canopen`.

use serde::Serialize;

use super::cob::{classify, NmtCommand, NmtState, Service};
use super::encoder::EncoderConfig;
use super::od::Dictionary;
use super::sdo::abort_name;
use crate::can::frame::Frame;

/// What a frame means.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Meaning {
    /// The service and node (`service`, `node`).
    #[serde(flatten)]
    pub service: Service,
    /// One line in words.
    pub text: String,
}

fn name(index: u16, sub: u8) -> String {
    let d = Dictionary::encoder(&EncoderConfig::default(), 1);
    match d.object(index) {
        Some(o) if o.subs.len() > 1 => format!(
            "{index:04X}h sub {sub} ({}: {})",
            o.name,
            o.subs
                .iter()
                .find(|s| s.sub == sub)
                .map(|s| s.name.as_str())
                .unwrap_or("?")
        ),
        Some(o) => format!("{index:04X}h sub {sub} ({})", o.name),
        None => format!("{index:04X}h sub {sub}"),
    }
}

fn le32(d: &[u8]) -> u32 {
    d.iter()
        .take(4)
        .enumerate()
        .fold(0, |a, (k, &b)| a | (b as u32) << (8 * k))
}

fn sdo(d: &[u8], request: bool) -> String {
    if d.len() < 8 {
        return format!("SDO, {} bytes (not 8)", d.len());
    }
    let (index, sub) = (d[1] as u16 | (d[2] as u16) << 8, d[3]);
    let cs = d[0] >> 5;
    let value = || {
        let n = if d[0] & 1 != 0 {
            4 - ((d[0] >> 2) & 3) as usize
        } else {
            4
        };
        le32(&d[4..4 + n])
    };
    match (request, cs) {
        (_, 4) => format!(
            "SDO abort {}: {:08X}h {}",
            name(index, sub),
            le32(&d[4..]),
            abort_name(le32(&d[4..]))
        ),
        (true, 1) if d[0] & 2 != 0 => format!(
            "SDO write {} = {} (0x{:X})",
            name(index, sub),
            value(),
            value()
        ),
        (true, 1) => format!(
            "SDO write {}, segmented, {} bytes",
            name(index, sub),
            le32(&d[4..])
        ),
        (true, 0) => format!(
            "SDO download segment, toggle {}, {} bytes{}",
            (d[0] >> 4) & 1,
            7 - ((d[0] >> 1) & 7),
            if d[0] & 1 != 0 { ", last" } else { "" }
        ),
        (true, 2) => format!("SDO read {}", name(index, sub)),
        (true, 3) => format!("SDO upload segment request, toggle {}", (d[0] >> 4) & 1),
        (false, 3) if d[0] == 0x60 => format!("SDO write confirmed {}", name(index, sub)),
        (false, 2) if d[0] & 2 != 0 => format!(
            "SDO read {} = {} (0x{:X})",
            name(index, sub),
            value(),
            value()
        ),
        (false, 2) => format!(
            "SDO read {}, segmented, {} bytes",
            name(index, sub),
            le32(&d[4..])
        ),
        (false, 1) => format!("SDO download segment confirmed, toggle {}", (d[0] >> 4) & 1),
        (false, 0) => format!(
            "SDO upload segment, toggle {}, {} bytes{}",
            (d[0] >> 4) & 1,
            7 - ((d[0] >> 1) & 7),
            if d[0] & 1 != 0 { ", last" } else { "" }
        ),
        _ => format!("SDO, command byte {:02X}h unknown", d[0]),
    }
}

/// The meaning of `f`.
pub fn interpret(f: &Frame) -> Meaning {
    let s = if f.ide {
        Service::Other
    } else {
        classify(f.id as u16)
    };
    let d = &f.data;
    let text = match s {
        Service::Nmt if d.len() >= 2 => match NmtCommand::from_byte(d[0]) {
            Some(c) => format!(
                "NMT {} to {}",
                c.name(),
                if d[1] == 0 {
                    "all nodes".into()
                } else {
                    format!("node {}", d[1])
                }
            ),
            None => format!("NMT, command {:02X}h unknown", d[0]),
        },
        Service::Sync => "SYNC".into(),
        Service::Emcy(n) if d.is_empty() && !f.rtr => format!("boot-up of node {n} (gateway form)"),
        // DS 301 lays an EMCY over 8 bytes (error code, error register,
        // 5 manufacturer bytes); the master takes only those (DLC 8).
        Service::Emcy(_) if d.len() == 8 && !f.rtr => format!(
            "EMCY code {:04X}h, error register {:02X}h",
            d[0] as u16 | (d[1] as u16) << 8,
            d[2]
        ),
        Service::Emcy(n) => format!(
            "not an EMCY: {} bytes on node {n}'s EMCY identifier (an EMCY has 8)",
            d.len()
        ),
        Service::Tpdo1(_) | Service::Tpdo2(_) if d.len() >= 4 => format!("position {}", le32(d)),
        Service::Rpdo1(n) => format!("RPDO1 to node {n}, {} bytes", d.len()),
        Service::SdoRx(_) => sdo(d, true),
        Service::SdoTx(_) => sdo(d, false),
        Service::NmtErr(n) if f.rtr => format!("node guarding request to node {n}"),
        Service::NmtErr(_) if d.len() == 1 => match (d[0], NmtState::from_byte(d[0])) {
            (0, _) => "boot-up (DS 301 form)".into(),
            (b, Some(st)) => format!(
                "state {st:?}{}",
                if b & 0x80 != 0 { ", toggle 1" } else { "" }
            ),
            (b, None) => format!("error control, state byte {b:02X}h unknown"),
        },
        _ => format!("not a pre-defined CANopen frame ({} bytes)", d.len()),
    };
    Meaning { service: s, text }
}
