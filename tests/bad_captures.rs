//! Whatever a captured waveform holds, `tbgen decode <protocol>` answers
//! with a transcript or an error, never a panic: a capture comes from a
//! simulator, a logic analyser or a scope, and may be cut short, damaged or
//! two files joined.
//!
//! For every protocol with a decoder, the three smallest committed VCDs of
//! its core that decode with the decoder's defaults are damaged in 60 ways
//! each (deterministic: the same files every
//! run): cut at a byte, bytes overwritten, lines deleted or repeated,
//! timestamps replaced by extremes, levels flipped, every time from a point
//! on moved far forward, stray lines inserted.
//! Each is decoded in-process, as `tbgen decode <protocol> <file>` would.

use std::path::{Path, PathBuf};

#[path = "support/sweep.rs"]
mod sweep;
use sweep::{caught, quiet_panics, Rng};

const DAMAGED_PER_FILE: usize = 60;
const FILES_PER_DECODER: usize = 3;

/// One damaged copy of `vcd`, and what was done to it.
fn damage(vcd: &[u8], rng: &mut Rng) -> (Vec<u8>, &'static str) {
    let mut lines: Vec<Vec<u8>> = vcd.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
    let n = lines.len();
    let kind = rng.below(8);
    match kind {
        0 => return (vcd[..rng.below(vcd.len())].to_vec(), "cut"),
        1 => {
            let mut d = vcd.to_vec();
            for _ in 0..1 + rng.below(20) {
                let at = rng.below(d.len());
                d[at] = b"01xzXZ#b \n$r-9!"[rng.below(15)];
            }
            return (d, "bytes overwritten");
        }
        2 => {
            for _ in 0..1 + rng.below(30) {
                if !lines.is_empty() {
                    lines.remove(rng.below(lines.len()));
                }
            }
        }
        3 => {
            for _ in 0..1 + rng.below(30) {
                let line = lines[rng.below(n)].clone();
                lines.insert(rng.below(lines.len()), line);
            }
        }
        4 => {
            for line in lines.iter_mut().filter(|l| l.starts_with(b"#")) {
                if rng.below(10) == 0 {
                    let extreme = [0, 1, u64::MAX / 2, u64::MAX, rng.next() % 1_000_000_000_000]
                        [rng.below(5)];
                    *line = format!("#{extreme}").into_bytes();
                }
            }
        }
        5 => {
            for line in lines
                .iter_mut()
                .filter(|l| matches!(l.first(), Some(b'0' | b'1' | b'x' | b'z')))
            {
                if rng.below(3) == 0 {
                    line[0] = if line[0] == b'0' { b'1' } else { b'0' };
                }
            }
        }
        6 => {
            // A jump forward (the capture paused, or a clock's time wrapped):
            // every later timestamp moved by the same huge amount.
            let jump = [1u64 << 40, 1 << 50, u64::MAX / 4][rng.below(3)];
            let from = rng.below(n);
            for line in lines[from..].iter_mut().filter(|l| l.starts_with(b"#")) {
                if let Some(t) = std::str::from_utf8(&line[1..])
                    .ok()
                    .and_then(|d| d.parse::<u64>().ok())
                {
                    *line = format!("#{}", t.saturating_add(jump)).into_bytes();
                }
            }
        }
        _ => {
            for _ in 0..1 + rng.below(5) {
                let stray: &[u8] = [
                    &b"$dumpvars"[..],
                    b"$end",
                    b"#",
                    b"b101 !",
                    b"1",
                    b"$var wire 1 ! x $end",
                    b"\xff\xfe",
                ][rng.below(7)];
                lines.insert(rng.below(lines.len()), stray.to_vec());
            }
        }
    }
    (
        lines.join(&b'\n'),
        [
            "cut",
            "bytes overwritten",
            "lines deleted",
            "lines repeated",
            "extreme timestamps",
            "levels flipped",
            "a jump forward",
            "stray lines",
        ][kind],
    )
}

/// `tbgen decode <table> <path>`, in-process: Ok(transcript), Err(message), or a panic's message.
fn decode(p: &tbgen::registry::Entry, path: &Path) -> Result<Result<String, String>, String> {
    let cmd = (p.decode_command)().expect("a protocol with a decoder");
    let args = cmd
        .try_get_matches_from([p.table, path.to_str().expect("a UTF-8 path")])
        .map_err(|e| format!("arguments: {e}"))?;
    caught(|| (p.decode)(&args).map_err(|e| e.to_string()))
}

/// The core's committed VCDs, smallest first.
fn smallest_vcds(core: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../vectors")
        .join(core);
    let mut vcds: Vec<(u64, PathBuf)> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "vcd"))
        .map(|p| (std::fs::metadata(&p).expect("a file").len(), p))
        .collect();
    vcds.sort();
    vcds.into_iter().map(|(_, p)| p).collect()
}

#[test]
fn every_decoder_answers_a_damaged_capture_without_a_panic() {
    quiet_panics();
    let dir = tempfile::tempdir().expect("a temporary folder");
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    let (mut tried, mut refused, mut panics) = (0, 0, Vec::new());
    let decoders: Vec<_> = tbgen::PROTOCOLS
        .iter()
        .filter(|p| (p.decode_command)().is_some())
        .collect();
    assert!(decoders.len() >= 9, "{} decoders", decoders.len());
    for p in decoders {
        // The smallest files that decode with the decoder's defaults (some
        // need options: a chain's widths, another bit rate).
        let files: Vec<PathBuf> = smallest_vcds(p.core)
            .into_iter()
            .filter(|f| decode(p, f).is_ok_and(|r| r.is_ok()))
            .take(FILES_PER_DECODER)
            .collect();
        assert!(
            !files.is_empty(),
            "{}: no committed VCD decodes with `tbgen decode {}`'s defaults",
            p.core,
            p.table
        );
        for file in files {
            let vcd = std::fs::read(&file).expect("a committed VCD reads");
            for _ in 0..DAMAGED_PER_FILE {
                let (damaged, how) = damage(&vcd, &mut rng);
                let path = dir.path().join(format!("{}_{tried}.vcd", p.table));
                std::fs::write(&path, &damaged).expect("a temporary file");
                tried += 1;
                match decode(p, &path) {
                    Err(panic) => panics.push(format!(
                        "{} {} ({how}, kept as {}): {panic}",
                        p.table,
                        file.display(),
                        path.display()
                    )),
                    Ok(Err(_)) => refused += 1,
                    Ok(Ok(_)) => {}
                }
            }
        }
    }
    println!(
        "{tried} damaged captures decoded: {refused} refused with an error, {} read",
        tried - refused - panics.len()
    );
    if !panics.is_empty() {
        // Keep the files that panicked for whoever reads the failure.
        let kept = dir.keep();
        panic!(
            "{} panics (files in {}):\n{}",
            panics.len(),
            kept.display(),
            panics.join("\n")
        );
    }
    assert!(
        refused > tried / 10 && refused < tried,
        "the damage reaches both sides"
    );
}
