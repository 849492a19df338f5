//! Reading a captured waveform: the part every `tbgen decode` shares.
//!
//! A capture is a VCD file (written by `tbgen gen` or a user's own
//! simulation), a sigrok session (`.sr`, [`sigrok`]) or a logic analyser's
//! CSV export (`.csv`, [`csv`]), told apart by the file's extension. The
//! decoders only need a few lines from it, each as the list of its value
//! changes in picoseconds: this module finds them by name (a VCD's dotted
//! path, `top.line.ma_master`, or an analyser's channel, through
//! [`lines`]), converts the file's time base to picoseconds and answers
//! "what was the level at time t". It also holds the UART-style byte reader
//! that the RS-485 frame protocols (ESL, T-format) decode their lines with.
//!
//! Errors name the file and the signal, and say how to fix the call.

mod csv;
pub mod lines;
pub mod sampled;
mod sigrok;

use std::io::BufReader;
use std::path::Path;

use crate::{Error, Result};

pub use model::wire::{uart_bytes, Signal, UartByte};

/// A VCD that cannot be parsed is bad input (exit status 2), named with the
/// parser's words; a read error of the disk stays an I/O error.
fn not_vcd(path: &Path, e: std::io::Error) -> Error {
    match e.kind() {
        std::io::ErrorKind::InvalidData | std::io::ErrorKind::InvalidInput | std::io::ErrorKind::UnexpectedEof => {
            Error::Decode(format!("{}: not a readable VCD file ({e}); give a value change dump, e.g. one `tbgen gen` or a simulator wrote", path.display()))
        }
        _ => Error::io(path, e),
    }
}

/// The dotted paths of the 1-bit signals of a VCD header, for messages
/// (the first 40, then how many more).
fn scalars(header: &vcd::Header) -> String {
    fn walk(items: &[vcd::ScopeItem], prefix: &str, out: &mut Vec<String>) {
        for item in items {
            match item {
                vcd::ScopeItem::Scope(s) => {
                    walk(&s.items, &format!("{prefix}{}.", s.identifier), out)
                }
                vcd::ScopeItem::Var(v) if v.size == 1 => {
                    out.push(format!("{prefix}{}", v.reference))
                }
                _ => {}
            }
        }
    }
    let mut names = Vec::new();
    walk(&header.items, "", &mut names);
    match names.len() {
        0 => "none".into(),
        n if n > 40 => format!("{} and {} more", names[..40].join(", "), n - 40),
        _ => names.join(", "),
    }
}

/// The kinds of capture file, by extension.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Format {
    Vcd,
    Sigrok,
    Csv,
}

impl Format {
    fn of(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        [
            ("vcd", Format::Vcd),
            ("sr", Format::Sigrok),
            ("csv", Format::Csv),
        ]
        .into_iter()
        .find_map(|(e, f)| (e == ext).then_some(f))
    }
}

/// Whether `path` names a capture (`.vcd`, `.sr`, `.csv`) rather than a transcript.
pub fn is_capture(path: &Path) -> bool {
    Format::of(path).is_some()
}

/// Opens a capture file; a missing one is bad input (exit status 2), said as such.
fn open(path: &Path) -> Result<std::fs::File> {
    std::fs::File::open(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => Error::Decode(format!("{}: no such capture file; give the path to a VCD (tbgen gen or make sim WAVES=1 writes one), a sigrok session (.sr) or a logic analyser's CSV export", path.display())),
        _ => Error::io(path, e),
    })
}

/// Reads the lines of a capture the decoder names: `names` are `(name,
/// option)`, the name a VCD's dotted path or an analyser's channel, unless
/// the `--map` in force ([`lines`]) names the channel of `option`'s line.
/// The error for a missing one names the file, the name, `option` (the
/// command-line flag that sets it) and the capture's signals.
pub fn read(path: &Path, names: &[(&str, &str)]) -> Result<Vec<Signal>> {
    read_to_end(path, names).map(|(s, _)| s)
}

/// [`read`], and the capture's end in ps where the format records one (a
/// VCD's last timestamp): the lines hold their last levels until then.
pub fn read_to_end(path: &Path, names: &[(&str, &str)]) -> Result<(Vec<Signal>, Option<u64>)> {
    let resolved = lines::resolve(names)?;
    let names: Vec<(&str, &str)> = resolved
        .iter()
        .zip(names)
        .map(|(n, &(_, o))| (n.as_str(), o))
        .collect();
    match Format::of(path) {
        Some(Format::Sigrok) => sigrok::read(path, &names).map(|s| (s, None)),
        Some(Format::Csv) => csv::read(path, &names).map(|s| (s, None)),
        Some(Format::Vcd) | None => read_vcd(path, &names).map(|(s, end)| (s, Some(end))),
    }
}

/// Reads the named scalars of a VCD file, and its last timestamp.
fn read_vcd(path: &Path, names: &[(&str, &str)]) -> Result<(Vec<Signal>, u64)> {
    let file = open(path)?;
    let mut parser = vcd::Parser::new(BufReader::new(file));
    let header = parser.parse_header().map_err(|e| not_vcd(path, e))?;
    let mut ids = Vec::with_capacity(names.len());
    for &(name, option) in names {
        let parts: Vec<&str> = name.split('.').collect();
        let var = header.find_var(&parts).ok_or_else(|| {
            Error::Decode(format!("{}: no signal `{name}`; give its dotted path with {option}; the capture's 1-bit signals: {}", path.display(), scalars(&header)))
        })?;
        if var.size != 1 {
            return Err(Error::Decode(format!(
                "{}: `{name}` is {} bits wide; {option} needs a 1-bit line signal",
                path.display(),
                var.size
            )));
        }
        ids.push(var.code);
    }
    let scale = tracefile::capture::timescale_ps(&header);
    let wanted: Vec<(&str, vcd::IdCode)> = names.iter().map(|&(n, _)| n).zip(ids).collect();
    tracefile::capture::read_scalars_to_end(parser, &wanted, scale).map_err(|e| match e {
        tracefile::capture::ScanError::Io(e) => not_vcd(path, e),
        tracefile::capture::ScanError::TimestampOverflow(ts) => Error::Decode(format!(
            "{}: timestamp #{ts} is beyond 2^62 ps (about 53 days), the longest capture the decoders read; cut the capture before it",
            path.display()
        )),
        tracefile::capture::ScanError::TimeGoesBack { later, earlier } => Error::Decode(format!(
            "{}:{}: timestamp #{earlier} after #{later}: a VCD's times only increase; the file is damaged or two captures were joined: cut it at that line or capture again",
            path.display(),
            backward_line(path, later, earlier).map_or_else(|| "?".into(), |l| l.to_string())
        )),
    })
}

/// The 1-based line of the first timestamp `#earlier` that follows `#later`
/// (the parser counts no lines; this runs only on that error).
fn backward_line(path: &Path, later: u64, earlier: u64) -> Option<usize> {
    let text = std::fs::read(path).ok()?;
    let mut seen_later = false;
    for (i, line) in text.split(|&b| b == b'\n').enumerate() {
        let Some(ts) = line
            .trim_ascii()
            .strip_prefix(b"#")
            .and_then(|d| std::str::from_utf8(d).ok())
            .and_then(|d| d.parse::<u64>().ok())
        else {
            continue;
        };
        if ts == later {
            seen_later = true;
        } else if seen_later && ts == earlier {
            return Some(i + 1);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line_of(bits: &[bool], bit_ps: u64, idle_before: u64) -> Signal {
        let mut changes = vec![(0, true)];
        for (i, &b) in bits.iter().enumerate() {
            let t = idle_before + i as u64 * bit_ps;
            if changes.last().unwrap().1 != b {
                changes.push((t, b));
            }
        }
        if !changes.last().unwrap().1 {
            changes.push((idle_before + bits.len() as u64 * bit_ps, true));
        }
        Signal {
            name: "line".into(),
            changes,
        }
    }

    fn character(value: u8, stop: bool) -> Vec<bool> {
        let mut bits = vec![false];
        bits.extend((0..8).map(|k| value >> k & 1 == 1));
        bits.push(stop);
        bits
    }

    #[test]
    fn every_byte_value_reads_back_at_10_mbps() {
        let bit_ps = 100_000;
        let mut bits = Vec::new();
        for v in 0..=255u8 {
            bits.extend(character(v, true));
        }
        let got = uart_bytes(&line_of(&bits, bit_ps, 1_000_000), bit_ps);
        assert_eq!(got.len(), 256);
        for (v, b) in got.iter().enumerate() {
            assert_eq!((b.value, b.framing_error), (v as u8, false));
            assert_eq!(b.start_ps, 1_000_000 + v as u64 * 10 * bit_ps);
        }
    }

    #[test]
    fn a_low_stop_bit_is_flagged_and_the_next_byte_still_reads() {
        let bit_ps = 400_000;
        let mut bits = character(0x5A, false);
        bits.extend([true, true]);
        bits.extend(character(0xC3, true));
        let got = uart_bytes(&line_of(&bits, bit_ps, 0), bit_ps);
        assert_eq!(
            got.iter()
                .map(|b| (b.value, b.framing_error))
                .collect::<Vec<_>>(),
            vec![(0x5A, true), (0xC3, false)]
        );
    }

    #[test]
    fn a_missing_signal_lists_the_captures_signals_and_a_bad_file_is_bad_input() {
        let s = crate::builtin::find("ssi_seed_12bit").unwrap();
        let dir = tempfile::tempdir().unwrap();
        let summary = crate::generate::generate(&s, dir.path()).unwrap();
        let msg = read(&summary.files[1], &[("top.x", "--clk")])
            .unwrap_err()
            .to_string();
        assert!(msg.contains("ssi_seed_12bit.vcd: no signal `top.x`; give its dotted path with --clk; the capture's 1-bit signals: top."), "{msg}");
        assert!(msg.contains("top.line.ssi_clk_master"), "{msg}");
        let bad = dir.path().join("g.vcd");
        std::fs::write(&bad, "garbage\n").unwrap();
        let e = read(&bad, &[("top.x", "--clk")]).unwrap_err();
        assert!(
            e.to_string().contains("g.vcd: not a readable VCD file"),
            "{e}"
        );
        assert_eq!(e.exit_code(), 2);
    }

    /// Found by mutating committed captures: a timestamp smaller than the
    /// one before it (two captures joined, lines repeated) put edges out of
    /// order, and the decoders subtracted past zero. It is refused, with
    /// the line.
    #[test]
    fn a_timestamp_that_goes_back_is_refused_with_its_line() {
        let dir = tempfile::tempdir().unwrap();
        let vcd = dir.path().join("back.vcd");
        std::fs::write(&vcd, "$timescale 1ns $end\n$scope module top $end\n$var wire 1 ! clk $end\n$upscope $end\n$enddefinitions $end\n#0\n1!\n#100\n0!\n#100\n1!\n#50\n0!\n").unwrap();
        let e = read(&vcd, &[("top.clk", "--clk")]).unwrap_err();
        assert!(
            e.to_string()
                .contains("back.vcd:12: timestamp #50 after #100: a VCD's times only increase"),
            "{e}"
        );
        assert_eq!(e.exit_code(), 2);
    }

    #[test]
    fn or_is_high_whenever_either_signal_is() {
        let line = Signal {
            name: "line".into(),
            changes: vec![(0, true), (100, false), (300, true), (500, false)],
        };
        let en = Signal {
            name: "en".into(),
            changes: vec![(0, false), (50, true), (200, false)],
        };
        let heard = line.or(&en);
        assert_eq!(
            heard.changes,
            vec![(0, true), (200, false), (300, true), (500, false)]
        );
        assert_eq!(heard.name, "line | en");
    }

    #[test]
    fn a_short_glitch_is_not_a_start_bit() {
        let bit_ps = 100_000;
        let line = Signal {
            name: "l".into(),
            changes: vec![(0, true), (500_000, false), (520_000, true)],
        };
        assert!(uart_bytes(&line, bit_ps).is_empty());
    }

    #[test]
    fn a_femtosecond_capture_reads_in_picoseconds() {
        // What Icarus and Verilator write with `timescale 1fs / 1fs: refused before, read now.
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("fs.vcd");
        let text = "$timescale 1fs $end\n$scope module tb $end\n$var wire 1 ! clk $end\n$upscope $end\n$enddefinitions $end\n\
                    #0\n1!\n#10000000\n0!\n#20000499\n1!\n#30000500\n0!\n";
        std::fs::write(&path, text).unwrap();
        let sig = read(&path, &[("tb.clk", "--clk")]).unwrap();
        assert_eq!(
            sig[0].changes,
            vec![(0, true), (10_000, false), (20_000, true), (30_001, false)]
        );
        let path10 = dir.path().join("fs10.vcd");
        std::fs::write(&path10, text.replace("1fs", "10fs")).unwrap();
        let sig = read(&path10, &[("tb.clk", "--clk")]).unwrap();
        assert_eq!(sig[0].changes[1], (100_000, false));
    }
}
