//! `tbgen decode canopen`: the frames `tbgen decode can` finds on a
//! captured line, each read as CANopen by `model::canopen::interpret`
//! (NMT, SYNC, EMCY and the gateway's boot-up, TPDO/RPDO, SDO with the
//! object's name and abort codes by name, node guarding, heartbeat and the
//! DS 301 boot-up).

use std::path::Path;

use serde::Serialize;

use crate::can::decode::Decoded as CanFrame;
use crate::{Error, Result};

/// One frame and its CANopen meaning.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Decoded {
    /// The CAN frame (`tbgen decode can`'s fields).
    #[serde(flatten)]
    pub frame: CanFrame,
    /// The service (`nmt`, `sync`, `emcy`, `tpdo1`, `sdo_rx`, ...) and node, if the frame is intact.
    pub service: Option<serde_json::Value>,
    /// One line in words (`SDO write 6200h sub 0 (Cyclic timer) = 10 (0xA)`).
    pub meaning: String,
}

/// Decodes `line` of `file` and reads each frame as CANopen.
pub fn decode(file: &Path, line: &str, bit_rate: u64, sample_point: f64) -> Result<Vec<Decoded>> {
    let frames = crate::can::decode::decode(file, line, bit_rate, sample_point)?;
    Ok(frames
        .into_iter()
        .map(|f| {
            if let Some(e) = &f.error {
                let meaning = format!("damaged frame ({e})");
                return Decoded { frame: f, service: None, meaning };
            }
            let frame = model::can::frame::Frame { id: f.id, ide: f.ide, rtr: f.rtr, dlc: f.dlc, data: f.data.clone() };
            let m = model::canopen::interpret::interpret(&frame);
            Decoded { service: serde_json::to_value(m.service).ok(), meaning: m.text, frame: f }
        })
        .collect())
}

/// The frames as JSON.
pub fn to_json(file: &Path, line: &str, bit_rate: u64, sample_point: f64, frames: &[Decoded]) -> Result<String> {
    let doc = serde_json::json!({
        "format": crate::transcript::FORMAT,
        "source": "decode",
        "protocol": "canopen",
        "file": file.display().to_string(),
        "signals": { "can_rx": line },
        "bit_rate": bit_rate,
        "sample_point": sample_point,
        "frames": frames,
    });
    serde_json::to_string_pretty(&doc).map_err(|e| Error::Decode(e.to_string()))
}
