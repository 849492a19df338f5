//! `tbgen decode sar`: the line at a SAR58K24 asynchronous host, captured as
//! a VCD, turned into the frames on it. The decode core is
//! [`model::sar58k24::decode`] (shared with the co-simulation monitor
//! `sar58k24_monitor`); this module reads the capture's two scalars.
//!
//! Two scalars are read: the line at the host and the host's driver enable
//! (its bus commands; a capture of a timed or handshake mode has the enable
//! low throughout). Every character is read with its parity and stop bit
//! ([`crate::uart::line::chars`]); the host's commands (`BC AA Bx` read,
//! `BC AA Cx` zero) are the characters sent while it drives. The encoder's
//! characters go through the host's own frame finder (`model::sar58k24::Host`,
//! `host.rs`): a window of the last `L` characters (`L` = 5, 6, 7 for 16,
//! 24, 32 bits) is a frame when it starts `FF <tag>` (`81`, or `Bx` after a
//! command to encoder x unless `--answer-tag fixed81`) and ends with the low byte of the sum; while synced
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

use model::sar58k24::AnswerTag;
use model::uart::Parity;

use crate::capture;
use crate::uart::line;
use crate::Result;

pub use model::sar58k24::decode::Burst;

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
    /// The second byte of a bus answer (`--answer-tag`, the encoders'
    /// `answer_tag`, the host's `TAG_ADDRESS`).
    pub answer_tag: AnswerTag,
}

/// Decodes `path` with `options`.
pub fn decode(path: &Path, options: &Options) -> Result<Vec<Burst>> {
    let signals = capture::read(path, &[(&options.line, "--line"), (&options.tx_en, "--tx-en")])?;
    let o = model::sar58k24::decode::Options { baud: options.baud, parity: options.parity, bits: options.bits, gray: options.gray, gap_bits: options.gap_bits, answer_tag: options.answer_tag };
    Ok(model::sar58k24::decode::decode(&signals[0], &signals[1], &o))
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
            answer_tag: cfg.encoders[0].answer_tag,
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
    fn bus_answers_tagged_81_decode_with_answer_tag_fixed81_and_are_flagged_without() {
        // Seed 001, 3.1.5/3.1.6 as the tables read it: BC AA B2 answered FF 81 ...
        // (scenario sar_bus_fixed81, host built with TAG_ADDRESS = 0).
        let dir = tempfile::tempdir().unwrap();
        let (s, vcd, _) = generated("sar_bus_fixed81", dir.path());
        let Setup::Sar(cfg) = &s.setup else { unreachable!() };
        assert_eq!(cfg.encoders[0].answer_tag, AnswerTag::Fixed81);
        let d = decode(&vcd, &options(cfg)).unwrap();
        let frames: Vec<_> = d.iter().filter(|b| b.kind == "frame").map(|b| (b.bytes[..2].to_vec(), b.position)).collect();
        assert_eq!(frames, [(vec![0xFF, 0x81], Some(8738)), (vec![0xFF, 0x81], Some(0)), (vec![0xFF, 0x81], Some(12))]);
        assert!(d.iter().all(|b| b.errors.is_empty()), "{d:?}");
        // Read as address-tagged answers (the default), every answer is a header fault.
        let d = decode(&vcd, &Options { answer_tag: AnswerTag::Address, ..options(cfg) }).unwrap();
        assert_eq!(d.iter().filter(|b| b.errors == ["frame"]).count(), 3, "{d:?}");
        assert!(d.iter().all(|b| b.position.is_none()), "{d:?}");
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
