//! The decode core of `tbgen decode can` and the CAN pin-level monitors
//! (`cosim::monitor::can`): a line turned into frames. A frame starts at a
//! falling edge after at least 10.5 recessive bits (bus idle, after EOF and
//! intermission, or after an error delimiter and intermission); its bits are
//! sampled at `(k + sample point)` bit times after that edge (hard
//! synchronisation at SOF only: enough for captures from one clock domain
//! and for frames at a few hundred ppm), and read by the destuffing parser
//! [`super::frame::parse`].

use serde::Serialize;

use super::frame::FrameError;
use crate::wire::Signal;

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
    /// Wire bits read: SOF through the last EOF bit, or through the bit in error.
    #[serde(skip)]
    pub bits: usize,
}

impl Decoded {
    /// The frame's fields (for an intact frame).
    pub fn frame(&self) -> super::frame::Frame {
        super::frame::Frame {
            id: self.id,
            ide: self.ide,
            rtr: self.rtr,
            dlc: self.dlc,
            data: self.data.clone(),
        }
    }
}

/// The frames of `line` at `bit_ps` per bit, sampled at `sample_point` of each bit.
pub fn frames(line: &Signal, bit_ps: u64, sample_point: f64) -> Vec<Decoded> {
    let mut frames = Vec::new();
    let mut idle_since = 0u64;
    let mut after = 0u64;
    for (t, level) in line.edges() {
        if level {
            idle_since = t;
            continue;
        }
        if t < after || t - idle_since < 11 * bit_ps - bit_ps / 2 {
            continue;
        }
        let bits: Vec<bool> = (0..200u64)
            .map(|k| line.level_at(t + k * bit_ps + (sample_point * bit_ps as f64) as u64))
            .collect();
        let d = match super::frame::parse(&bits) {
            Ok(p) => {
                after = t + p.len as u64 * bit_ps;
                Decoded {
                    sof_ps: t,
                    id: p.frame.id,
                    ide: p.frame.ide,
                    rtr: p.frame.rtr,
                    dlc: p.frame.dlc,
                    data: p.frame.data,
                    crc: Some(p.crc),
                    ack: p.ack,
                    error: None,
                    bits: p.len,
                }
            }
            Err((e, at)) => {
                after = t + at as u64 * bit_ps;
                let name = match e {
                    FrameError::Stuff => "stuff",
                    FrameError::Crc => "crc",
                    FrameError::Form => "form",
                    FrameError::Truncated => "truncated",
                };
                Decoded {
                    sof_ps: t,
                    id: 0,
                    ide: false,
                    rtr: false,
                    dlc: 0,
                    data: Vec::new(),
                    crc: None,
                    ack: false,
                    error: Some(name.to_string()),
                    bits: at + 1,
                }
            }
        };
        frames.push(d);
    }
    frames
}
