//! `tbgen decode can`: a captured CAN line turned into frames by the
//! model's decode core ([`model::can::decode`], which the CAN and CANopen
//! pin-level monitors of `cosim` share).

use std::path::Path;

use crate::capture;
use crate::{Error, Result};

/// One frame found on the line (the model's decode core, shared with the CAN monitors).
pub use model::can::decode::Decoded;

/// Decodes `line` of `file`.
pub fn decode(file: &Path, line: &str, bit_rate: u64, sample_point: f64) -> Result<Vec<Decoded>> {
    let sig = capture::read(file, &[(line, "--line")])?.remove(0);
    Ok(model::can::decode::frames(&sig, 1_000_000_000_000 / bit_rate, sample_point))
}

/// The frames as JSON, the identifier, data and CRC in hex as CAN tools
/// and datasheets write them (`"id": "0x123"`, an extended one in 8 digits;
/// `"data": "DE AD BE EF"`; `"crc": "0x1A2B"`). The transcripts and the
/// monitors keep numbers (`tbgen check` compares those).
pub fn to_json(file: &Path, bit_rate: u64, sample_point: f64, frames: &[Decoded]) -> Result<String> {
    let frames: Vec<serde_json::Value> = frames.iter().map(in_hex).collect::<Result<_>>()?;
    let doc = serde_json::json!({ "file": file.display().to_string(), "bit_rate": bit_rate, "sample_point": sample_point, "frames": frames });
    serde_json::to_string_pretty(&doc).map_err(|e| Error::Decode(e.to_string()))
}

/// One frame's JSON with its identifier, data and CRC in hex.
fn in_hex(f: &Decoded) -> Result<serde_json::Value> {
    let mut v = serde_json::to_value(f).map_err(|e| Error::Decode(e.to_string()))?;
    let id = if f.ide { format!("0x{:08X}", f.id) } else { format!("0x{:03X}", f.id) };
    let data: Vec<String> = f.data.iter().map(|b| format!("{b:02X}")).collect();
    v["id"] = id.into();
    v["data"] = data.join(" ").into();
    v["crc"] = f.crc.map(|c| format!("0x{c:04X}")).into();
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Setup;
    use crate::{builtin, generate};

    #[test]
    fn decoding_the_line_of_error_free_can_scenarios_gives_back_the_transcripts_frames() {
        let dir = tempfile::tempdir().unwrap();
        let mut compared = 0;
        for name in ["can_arbitration_3_nodes", "can_extended_frames", "can_rate_1000k", "can_bus_longest"] {
            let s = builtin::find(name).unwrap();
            let Setup::Can(cfg) = &s.setup else { unreachable!("{name} is a CAN scenario") };
            let t = cfg.bit_timing().unwrap();
            let rate = (cfg.f_sys_mhz * 1e6) as u64 / t.clocks_per_bit();
            let summary = generate::generate(&s, dir.path()).unwrap();
            let gen: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
            let decoded = decode(&summary.files[1], "top.line.can_rx", rate, t.sample_point()).unwrap();
            let gen = gen["transactions"].as_array().unwrap();
            assert_eq!(decoded.len(), gen.len(), "{name}: frames");
            for (d, g) in decoded.iter().zip(gen) {
                assert_eq!(d.error, None, "{name}");
                for key in ["id", "ide", "rtr", "dlc", "data", "crc", "ack"] {
                    assert_eq!(serde_json::to_value(d).unwrap()[key], g[key], "{name}: `{key}` decoded vs gen");
                    compared += 1;
                }
            }
        }
        assert!(compared >= 70, "{compared}");
    }

    #[test]
    fn identifiers_data_and_crc_are_printed_in_hex() {
        let f = Decoded {
            sof_ps: 0,
            id: 0x1AB,
            ide: false,
            rtr: false,
            dlc: 2,
            data: vec![0xDE, 0x0A],
            crc: Some(0x145B),
            ack: true,
            error: None,
            bits: 0,
        };
        let ext = Decoded { id: 0x1ABCDEF, ide: true, crc: None, ..f.clone() };
        let text = to_json(Path::new("x.vcd"), 250_000, 0.875, &[f, ext]).unwrap();
        let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
        let frames = doc["frames"].as_array().unwrap();
        assert_eq!(frames[0]["id"], "0x1AB");
        assert_eq!(frames[0]["data"], "DE 0A");
        assert_eq!(frames[0]["crc"], "0x145B");
        assert_eq!(frames[1]["id"], "0x01ABCDEF");
        assert!(frames[1]["crc"].is_null());
        assert_eq!(frames[0]["dlc"], 2);
    }
}
