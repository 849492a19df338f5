//! The decode core of `tbgen decode can` and the CAN pin-level monitors
//! (`cosim::monitor::can`): a line turned into frames. A frame starts at a
//! falling edge after at least 10.5 recessive bits (bus idle, after EOF and
//! intermission, or after an error delimiter and intermission); each bit is
//! sampled a bit time after the last sample, moved towards the falling edge
//! that starts it (a receiver resynchronising on recessive-to-dominant
//! edges, so a transmitter at the oscillator tolerance is read on its own
//! grid), and read by the destuffing parser [`super::frame::parse`].

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

/// The first 200 bits of a frame whose SOF falls at `sof`: each read at the
/// sample point, a bit time after the last, moved towards the falling edge
/// that starts the bit when there is one (a receiver resynchronising on
/// recessive-to-dominant edges, Bosch CAN 2.0 part A §9.1 [4]) by at most
/// half the time from the sample point to the bit's end: enough to follow a
/// transmitter at the oscillator tolerance (0.5 % drifts 0.05 bit between
/// two stuff edges), while an acknowledgement that comes late by the bus's
/// round trip cannot push the sample point out of the bit.
fn sampled(line: &Signal, sof: u64, bit_ps: u64, sample_point: f64) -> Vec<bool> {
    let into = (sample_point * bit_ps as f64) as u64;
    let most = ((1.0 - sample_point) * bit_ps as f64 / 2.0) as i64;
    let mut at = sof + into;
    let mut bits = vec![line.level_at(at)];
    while bits.len() < 200 {
        let previous = bits[bits.len() - 1];
        let next = at + bit_ps;
        // A falling edge between the last sample point and the next one:
        // the next bit's start, expected `bit - into` after the last sample.
        at = match line.next_level(at + 1, false) {
            Some(e) if previous && e <= next => {
                let phase = e as i64 - (next - into) as i64;
                (next as i64 + phase.clamp(-most, most)) as u64
            }
            _ => next,
        };
        bits.push(line.level_at(at));
    }
    bits
}

/// The frames of `line` at `bit_ps` per bit, sampled at `sample_point` of
/// each bit (resynchronised as [`sampled`] says).
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
        let bits = sampled(line, t, bit_ps, sample_point);
        // A falling edge whose bit is recessive at its sample point is a
        // glitch, not a start of frame: a bit's level is the bus level at
        // its sample point (Bosch CAN 2.0, bit timing), so a node that
        // synchronised on the edge reads no dominant SOF and stays idle.
        if bits[0] {
            continue;
        }
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
