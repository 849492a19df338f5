//! `tbgen decode sar`: the line at a SAR58K24 asynchronous host, captured as
//! a VCD, turned into the frames on it.
//!
//! Two scalars are read: the line at the host and the host's driver enable
//! (its bus commands; a capture of a timed or handshake mode has the enable
//! low throughout). Every character is read with its parity and stop bit
//! ([`crate::uart::line::chars`]); the host's commands (`BC AA Bx` read,
//! `BC AA Cx` zero) are the characters sent while it drives. The encoder's
//! characters go through the host's own frame finder (`model::sar58k24::Host`,
//! `host.rs`): a window of the last `L` characters (`L` = 5, 6, 7 for 16,
//! 24, 32 bits) is a frame when it starts `FF <tag>` (`81`, or `Bx` after a
//! command to encoder x) and ends with the low byte of the sum; while synced
//! (after a frame or an idle gap of `--gap-bits`) the `L`-th character must
//! close a frame, else it is flagged and the finder hunts byte by byte; a
//! parity or framing error breaks the frame; a gap with fewer than `L`
//! characters while synced is a truncated frame. Each event carries the
//! characters since the previous one, so the events together hold every
//! character on the line, and the flags have the host's names: `checksum`,
//! `parity`, `frame` (a low stop bit, a header that is not `FF <tag>`, a
//! truncated frame), `address` (`FF By` of another encoder). The host's own
//! pulses (trigger, CLR), its timeouts and stale flags are not on this
//! line; the `gen` transcript has them.

use std::path::Path;

use model::sar58k24::frames;
use model::uart::Parity;
use serde::Serialize;

use crate::capture;
use crate::uart::line::{self, Char};
use crate::Result;

/// What the decoder needs besides the file.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Dotted path of the line at the host.
    pub line: String,
    /// Dotted path of the host's driver enable.
    pub tx_en: String,
    /// Baud.
    pub baud: f64,
    /// Character format.
    pub parity: Parity,
    /// Resolution (10..32): the frame carries 2, 3 or 4 data bytes.
    pub bits: u32,
    /// Positions are sent in Gray code.
    pub gray: bool,
    /// Idle bit times that end a burst (`[sar.host] gap_bits`).
    pub gap_bits: f64,
}

/// One event on the line: a command, a frame, a flagged fault or a
/// boundary after characters that made no frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Burst {
    /// 0-based event number.
    pub index: usize,
    /// The first character's start bit, ps.
    pub start_ps: u64,
    /// `command` (the host drove it), `frame` (a position accepted), `fault`
    /// (the host flags it) or `noise` (characters that made no frame, ended
    /// by a gap without a flag).
    pub kind: &'static str,
    /// The characters since the previous event.
    pub bytes: Vec<u8>,
    /// A command: `read` or `zero`; `null` for bytes that are no command.
    pub command: Option<&'static str>,
    /// The encoder a command addresses.
    pub address: Option<u8>,
    /// The position of the frame (binary, after Gray decoding).
    pub position: Option<u32>,
    /// Its angle, `360° × a / 2^bits` cut to four decimals.
    pub angle_deg: Option<f64>,
    /// The host's flags: `checksum`, `parity`, `frame`, `address`.
    pub errors: Vec<&'static str>,
}

/// The host's frame finder over characters (`model::sar58k24::Host::step`).
struct Finder<'a> {
    options: &'a Options,
    len: usize,
    window: Vec<u8>,
    count: usize,
    synced: bool,
    pending: Vec<Char>,
    last_end_ps: Option<u64>,
    tag: u8,
    out: Vec<Burst>,
}

impl Finder<'_> {
    fn emit(&mut self, kind: &'static str, errors: Vec<&'static str>, position: Option<u32>) {
        let start_ps = self.pending.first().map_or(0, |c| c.start_ps);
        let angle_deg = position.map(|v| model::angle::angle_deg(v as u64, self.options.bits));
        let bytes = line::values(&self.pending);
        self.pending.clear();
        self.out.push(Burst { index: self.out.len(), start_ps, kind, bytes, command: None, address: None, position, angle_deg, errors });
    }

    /// An idle gap of the host's `GAP_CLOCKS`: a frame boundary.
    fn gap(&mut self) {
        if self.count != 0 {
            if self.synced && self.count < self.len {
                self.emit("fault", vec!["frame"], None);
            }
            self.count = 0;
            self.synced = true;
        }
        if !self.pending.is_empty() {
            self.emit("noise", Vec::new(), None);
        }
    }

    fn char(&mut self, c: Char, bit_ps: u64) {
        let gap_ps = (self.options.gap_bits * bit_ps as f64) as u64;
        if self.last_end_ps.is_some_and(|e| c.start_ps >= e + gap_ps) {
            self.gap();
        }
        // Idle is counted from the receiver's stop-bit sample.
        self.last_end_ps = Some(c.start_ps + (self.options.parity.frame_bits() as u64 - 1) * bit_ps + bit_ps / 2);
        self.pending.push(c);
        if c.parity_error || c.framing_error {
            let errors = [(c.parity_error, "parity"), (c.framing_error, "frame")].into_iter().filter(|f| f.0).map(|f| f.1).collect();
            self.count = 0;
            self.synced = false;
            self.emit("fault", errors, None);
            return;
        }
        let l = self.len;
        self.window.remove(0);
        self.window.push(c.value);
        self.count = (self.count + 1).min(l + 1);
        let w = &self.window;
        let header_ok = w[0] == frames::SYNC && w[1] == self.tag;
        if self.count >= l && header_ok && frames::checksum(&w[..l - 1]) == w[l - 1] {
            let data = w[2..l - 1].iter().fold(0u64, |v, &x| (v << 8) | x as u64) & ((1u64 << self.options.bits) - 1);
            let v = if self.options.gray { model::gray::from_gray(data) } else { data } as u32;
            self.count = 0;
            self.synced = true;
            self.emit("frame", Vec::new(), Some(v));
        } else if self.count == l && self.synced {
            self.synced = false;
            let error = if w[0] == frames::SYNC && w[1] & 0xF0 == 0xB0 && self.tag & 0xF0 == 0xB0 && w[1] != self.tag {
                "address"
            } else if !header_ok {
                "frame"
            } else {
                "checksum"
            };
            self.emit("fault", vec![error], None);
        }
    }
}

/// Decodes `path` with `options`.
pub fn decode(path: &Path, options: &Options) -> Result<Vec<Burst>> {
    let signals = capture::read(path, &[(&options.line, "--line"), (&options.tx_en, "--tx-en")])?;
    let (line_sig, tx_en) = (&signals[0], &signals[1]);
    let bit_ps = (1e12 / options.baud).round() as u64;
    let len = frames::frame_len(options.bits);
    let mut f = Finder { options, len, window: vec![0; len], count: 0, synced: true, pending: Vec::new(), last_end_ps: None, tag: frames::TAG_81, out: Vec::new() };
    let chars = line::chars(line_sig, Some(tx_en), bit_ps, options.parity);
    let mut k = 0;
    while k < chars.len() {
        if chars[k].from_host {
            // The host is deaf while it drives: its command is one event. Its
            // characters end at an idle gap, as the encoder's do: two commands
            // with no answer between them (the host timed out on the first)
            // are two events, not one unreadable six-byte command.
            let gap_ps = (options.gap_bits * bit_ps as f64) as u64;
            let mut n = 1;
            while chars.get(k + n).is_some_and(|c| c.from_host && c.start_ps < chars[k + n - 1].end_ps(bit_ps, options.parity) + gap_ps) {
                n += 1;
            }
            f.gap();
            let cmd = &chars[k..k + n];
            let bytes = line::values(cmd);
            let (command, address) = match frames::parse_command(&bytes) {
                Some(frames::Command::Read(a)) => (Some("read"), Some(a)),
                Some(frames::Command::Zero(a)) => (Some("zero"), Some(a)),
                None => (None, None),
            };
            if let Some(a) = address {
                f.tag = 0xB0 | a;
            }
            f.out.push(Burst { index: f.out.len(), start_ps: cmd[0].start_ps, kind: "command", bytes, command, address, position: None, angle_deg: None, errors: Vec::new() });
            k += n;
        } else {
            f.char(chars[k], bit_ps);
            k += 1;
        }
    }
    f.gap();
    Ok(f.out)
}

/// The JSON `tbgen decode sar` prints.
pub fn to_json(path: &Path, options: &Options, bursts: &[Burst]) -> Result<String> {
    line::to_json("sar", path, &options.line, &options.tx_en, bursts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builtin;
    use crate::scenario::Setup;
    use crate::uart::line::generated;

    fn options(cfg: &model::sar58k24::BenchConfig) -> Options {
        Options {
            line: "top.line.line_at_host".into(),
            tx_en: "top.line.tx_en_host".into(),
            baud: cfg.baud,
            parity: cfg.parity,
            bits: cfg.encoders[0].bits,
            gray: cfg.encoders[0].code == model::sar58k24::OutputCode::Gray,
            gap_bits: cfg.host.gap_bits,
        }
    }

    /// Every character on the line, in order, equals the transcript's wire
    /// bytes; the positions of the frames equal, in order, every position
    /// the host accepted; the flags equal, in order, every line flag the
    /// host pulsed (its timeouts and stale flags are not on the line).
    #[test]
    fn decoding_the_line_of_every_sar_scenario_gives_back_the_wire_and_every_accepted_position() {
        let dir = tempfile::tempdir().unwrap();
        let (mut scenarios, mut positions, mut faulty) = (0, 0, 0);
        for name in builtin::all().unwrap().into_iter().filter(|s| s.core() == "sar_async_host").map(|s| s.name) {
            let (s, vcd, gen) = generated(&name, dir.path());
            let Setup::Sar(cfg) = &s.setup else { unreachable!("{} runs sar_async_host", s.name) };
            let decoded = decode(&vcd, &options(cfg)).unwrap();
            let wire: Vec<u64> = decoded.iter().flat_map(|b| b.bytes.iter().map(|&x| x as u64)).collect();
            let flags: Vec<&str> = decoded.iter().flat_map(|b| b.errors.iter().copied()).collect();
            let want_flags: Vec<&str> = gen["transactions"].as_array().unwrap().iter().flat_map(|t| t["errors"].as_array().unwrap().iter().map(|e| e.as_str().unwrap())).filter(|e| !["timeout", "stale"].contains(e)).collect();
            assert_eq!(flags, want_flags, "{}: the host's flags", s.name);
            assert_eq!(wire, crate::transcript::wire_bytes(&gen).unwrap(), "{}: the wire", s.name);
            let got: Vec<u64> = decoded.iter().filter_map(|b| b.position.map(u64::from)).collect();
            let want: Vec<u64> = gen["transactions"].as_array().unwrap().iter().flat_map(|t| t["positions"].as_array().unwrap().iter().map(|p| p.as_u64().unwrap())).collect();
            assert_eq!(got, want, "{}: accepted positions", s.name);
            faulty += decoded.iter().filter(|b| !b.errors.is_empty()).count();
            positions += got.len();
            scenarios += 1;
        }
        assert!(scenarios >= 4 && positions >= 25 && faulty >= 3, "{scenarios} scenarios, {positions} positions, {faulty} faulty bursts");
    }

    #[test]
    fn the_seed_frame_ff_81_01_7f_00_decodes_to_383_and_8_4155_degrees() {
        // Seed 001, "Product communication": FF 81 01 7F 00 = 383 = 8.4155° at 14 bits.
        let dir = tempfile::tempdir().unwrap();
        let (s, vcd, _) = generated("sar_seed_timed_14bit", dir.path());
        let Setup::Sar(cfg) = &s.setup else { unreachable!() };
        let d = decode(&vcd, &options(cfg)).unwrap();
        assert_eq!(d[0].bytes, [0xFF, 0x81, 0x01, 0x7F, 0x00]);
        assert_eq!((d[0].position, d[0].angle_deg), (Some(383), Some(8.4155)));
    }

    #[test]
    fn a_capture_without_the_named_line_lists_the_captures_signals() {
        let dir = tempfile::tempdir().unwrap();
        let (s, vcd, _) = generated("sar_seed_timed_14bit", dir.path());
        let Setup::Sar(cfg) = &s.setup else { unreachable!() };
        let e = decode(&vcd, &Options { tx_en: "top.de".into(), ..options(cfg) }).unwrap_err().to_string();
        assert!(e.contains("top.de") && e.contains("--tx-en") && e.contains("sar_seed_timed_14bit.vcd") && e.contains("line.line_at_host"), "{e}");
    }
}
