//! `tbgen decode can`: a captured CAN line turned into frames. A frame
//! starts at a falling edge after at least 11 recessive bits (bus idle,
//! after EOF and intermission, or after an error delimiter and
//! intermission); its bits are sampled at `(k + sample point)` bit times
//! after that edge (hard synchronisation at SOF only: enough for captures
//! from one clock domain and for short frames at a few hundred ppm), and
//! read by the model's destuffing parser.

use std::path::Path;

use serde::Serialize;

use crate::capture;
use crate::{Error, Result};

/// One frame found on the line.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Decoded {
    /// SOF edge, ps.
    pub sof_ps: u64,
    /// Identifier.
    pub id: u32,
    /// Extended.
    pub ide: bool,
    /// Remote.
    pub rtr: bool,
    /// DLC.
    pub dlc: u8,
    /// Data bytes.
    pub data: Vec<u8>,
    /// CRC sequence received.
    pub crc: Option<u16>,
    /// ACK slot dominant.
    pub ack: bool,
    /// What the parser found wrong (`stuff`, `crc`, `form`, `truncated`).
    pub error: Option<String>,
}

/// Decodes `line` of `file`.
pub fn decode(file: &Path, line: &str, bit_rate: u64, sample_point: f64) -> Result<Vec<Decoded>> {
    let sig = capture::read(file, &[(line, "--line")])?.remove(0);
    let bit_ps = 1_000_000_000_000 / bit_rate;
    let mut frames = Vec::new();
    let mut idle_since = 0u64;
    let mut after = 0u64;
    for (t, level) in sig.edges() {
        if level {
            idle_since = t;
            continue;
        }
        if t < after || t - idle_since < 11 * bit_ps - bit_ps / 2 {
            continue;
        }
        let bits: Vec<bool> = (0..200u64).map(|k| sig.level_at(t + k * bit_ps + (sample_point * bit_ps as f64) as u64)).collect();
        let d = match model::can::frame::parse(&bits) {
            Ok(p) => {
                after = t + p.len as u64 * bit_ps;
                Decoded { sof_ps: t, id: p.frame.id, ide: p.frame.ide, rtr: p.frame.rtr, dlc: p.frame.dlc, data: p.frame.data, crc: Some(p.crc), ack: p.ack, error: None }
            }
            Err((e, at)) => {
                after = t + at as u64 * bit_ps;
                let name = serde_json::to_value(e).ok().and_then(|v| v.as_str().map(str::to_string)).unwrap_or_default();
                Decoded { sof_ps: t, id: 0, ide: false, rtr: false, dlc: 0, data: Vec::new(), crc: None, ack: false, error: Some(name) }
            }
        };
        frames.push(d);
    }
    Ok(frames)
}

/// The frames as JSON.
pub fn to_json(file: &Path, bit_rate: u64, sample_point: f64, frames: &[Decoded]) -> Result<String> {
    let doc = serde_json::json!({ "file": file.display().to_string(), "bit_rate": bit_rate, "sample_point": sample_point, "frames": frames });
    serde_json::to_string_pretty(&doc).map_err(|e| Error::Decode(e.to_string()))
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
}
