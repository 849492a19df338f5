//! `tbgen bench --capture sr|csv --samples N`: how fast `tbgen decode`
//! reads a logic analyser's capture, and how much memory it needs.
//!
//! The capture is made here, not committed: the SSI seed scenario's clock
//! and data at the master, one sample per system clock, repeated until `N`
//! samples, written as a sigrok session (`.sr`, the zip sigrok-cli and
//! PulseView write: 4 MiB chunks, deflated) or as sigrok-cli's CSV (one row
//! per sample). Then `tbgen decode ssi` runs on it in this process, timed;
//! its peak memory is the process's resident high-water mark (Linux's
//! `VmHWM`), reset just before the decode (`/proc/self/clear_refs`), so the
//! making of the capture is not in it.
//!
//! | key | what it is |
//! |---|---|
//! | `format`, `samples` | the capture |
//! | `file_bytes` | its size on disk |
//! | `reads` | SSI reads decoded (every repetition's: checked) |
//! | `decode_seconds` | wall time of the decode |
//! | `samples_per_second` | `samples / decode_seconds` |
//! | `decode_cpu_seconds`, `samples_per_cpu_second` | the same in CPU time of the decoding thread (`-` where the system cannot say): on a shared machine the wall time also counts other jobs' turns |
//! | `peak_rss_bytes` | resident memory at most during the decode (`-` where the system cannot say) |

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;
use std::time::Instant;

use crate::{builtin, capture, generate, registry, Error, Result};

/// The scenario whose lines the capture repeats.
const SCENARIO: &str = "ssi_seed_12bit";
/// Bytes of samples per `.sr` chunk (what libsigrok's srzip writer uses).
const CHUNK: usize = 4 << 20;

/// The bench's capture formats (`--capture`).
pub const FORMATS: [&str; 2] = ["sr", "csv"];

/// One repetition of the scenario's lines, a byte a sample (bit 0 the
/// clock, bit 1 the data), and the reads it holds.
struct Tile {
    samples: Vec<u8>,
    rate_hz: u64,
    reads: usize,
    names: [String; 2],
}

fn tile(scratch: &Path) -> Result<Tile> {
    let s = builtin::resolve(SCENARIO)?;
    let summary = generate::generate(&s, scratch)?;
    let vcd = &summary.files[1];
    let (clk, data) = ("top.line.ssi_clk_master", "top.line.ssi_data_master");
    let lines = capture::read(vcd, &[(clk, "--clk"), (data, "--data")])?;
    let grid = lines
        .iter()
        .flat_map(|l| &l.changes)
        .fold(0, |g, &(t, _)| gcd(g, t));
    let end = lines
        .iter()
        .flat_map(|l| l.changes.last())
        .map(|&(t, _)| t)
        .max()
        .unwrap_or(0);
    // The scenario's whole run: its last read's monoflop pause included.
    let n = (end / grid + 1).max(summary.cycles);
    let samples = (0..n)
        .map(|k| {
            lines
                .iter()
                .enumerate()
                .fold(0u8, |b, (i, l)| b | (l.level_at(k * grid) as u8) << i)
        })
        .collect();
    let names = [clk, data].map(|n| n.rsplit('.').next().unwrap_or(n).to_string());
    Ok(Tile {
        samples,
        rate_hz: 1_000_000_000_000 / grid,
        reads: summary.transactions,
        names,
    })
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// Writes `samples` samples of repeated `tile` to `out` as `format`.
fn write(out: &Path, format: &str, tile: &Tile, samples: u64) -> Result<()> {
    let io = |e: std::io::Error| Error::io(out, e);
    let file = BufWriter::with_capacity(1 << 20, File::create(out).map_err(io)?);
    let mut chunks = Repeat {
        tile: &tile.samples,
        at: 0,
        left: samples,
    };
    match format {
        "sr" => {
            let zip_err =
                |e: zip::result::ZipError| Error::Decode(format!("{}: {e}", out.display()));
            let mut zip = zip::ZipWriter::new(file);
            let opts = zip::write::SimpleFileOptions::default()
                .compression_method(zip::CompressionMethod::Deflated);
            zip.start_file("version", opts).map_err(zip_err)?;
            zip.write_all(b"2").map_err(io)?;
            zip.start_file("metadata", opts).map_err(zip_err)?;
            let meta = format!(
                "[global]\nsigrok version=0.5.2\n\n[device 1]\ncapturefile=logic-1\ntotal probes=2\nsamplerate={} MHz\ntotal analog=0\nprobe1={}\nprobe2={}\nunitsize=1\n",
                tile.rate_hz / 1_000_000,
                tile.names[0],
                tile.names[1]
            );
            zip.write_all(meta.as_bytes()).map_err(io)?;
            let mut buf = Vec::with_capacity(CHUNK);
            let mut k = 0;
            loop {
                buf.clear();
                while buf.len() < CHUNK {
                    match chunks.next_slice(CHUNK - buf.len()) {
                        Some(s) => buf.extend_from_slice(s),
                        None => break,
                    }
                }
                if buf.is_empty() {
                    break;
                }
                k += 1;
                zip.start_file(format!("logic-1-{k}"), opts)
                    .map_err(zip_err)?;
                zip.write_all(&buf).map_err(io)?;
            }
            zip.finish().map_err(zip_err)?.flush().map_err(io)
        }
        _ => {
            let mut w = file;
            write!(
                w,
                "; CSV generated by tbgen bench\n; Channels (2/2): {0}, {1}\n; Samplerate: {2} Hz\n{0},{1}\n",
                tile.names[0], tile.names[1], tile.rate_hz
            )
            .map_err(io)?;
            const ROWS: [&[u8; 4]; 4] = [b"0,0\n", b"1,0\n", b"0,1\n", b"1,1\n"];
            let mut line = Vec::with_capacity(1 << 16);
            while let Some(s) = chunks.next_slice(1 << 14) {
                line.clear();
                for &b in s {
                    line.extend_from_slice(ROWS[b as usize & 3]);
                }
                w.write_all(&line).map_err(io)?;
            }
            w.flush().map_err(io)
        }
    }
}

/// The tile's samples over and over, `left` of them in all.
struct Repeat<'a> {
    tile: &'a [u8],
    at: usize,
    left: u64,
}

impl Repeat<'_> {
    fn next_slice(&mut self, most: usize) -> Option<&[u8]> {
        if self.left == 0 {
            return None;
        }
        if self.at == self.tile.len() {
            self.at = 0;
        }
        let n = most
            .min(self.tile.len() - self.at)
            .min(self.left.min(usize::MAX as u64) as usize);
        let s = &self.tile[self.at..self.at + n];
        self.at += n;
        self.left -= n as u64;
        Some(s)
    }
}

/// CPU time this thread has run, seconds (Linux's schedstat, in ns): on a
/// machine shared with other jobs the wall time also counts their turns.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    Some(stat.split_whitespace().next()?.parse::<f64>().ok()? / 1e9)
}

/// The process's resident high-water mark, bytes (Linux).
fn peak_rss() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let kb = status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))?
        .trim()
        .strip_suffix("kB")?
        .trim()
        .parse::<u64>()
        .ok()?;
    Some(kb * 1024)
}

/// `tbgen bench --capture <format> --samples <n>`: the figures of the module docs as `key: value` lines.
pub fn report(format: &str, samples: u64) -> Result<String> {
    if !FORMATS.contains(&format) {
        return Err(Error::Decode(format!(
            "bench --capture {format}: give one of {}",
            FORMATS.join(", ")
        )));
    }
    let scratch = std::env::temp_dir().join(format!("tbgen-bench-capture-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).map_err(|e| Error::io(&scratch, e))?;
    let result = measure(&scratch, format, samples);
    let _ = std::fs::remove_dir_all(&scratch);
    result
}

fn measure(scratch: &Path, format: &str, samples: u64) -> Result<String> {
    let tile = tile(scratch)?;
    let path = scratch.join(format!("capture.{format}"));
    write(&path, format, &tile, samples)?;
    let file_bytes = std::fs::metadata(&path)
        .map_err(|e| Error::io(&path, e))?
        .len();
    let entry = registry::by_table("ssi").expect("SSI has a decoder");
    let cmd = (entry.decode_command)().expect("SSI has a decoder");
    let args = cmd
        .try_get_matches_from(["ssi", &path.display().to_string()])
        .map_err(|e| Error::Decode(e.to_string()))?;
    // The high-water mark from here on (writing "5" resets it, Linux 4.0 and later).
    let reset = std::fs::write("/proc/self/clear_refs", "5").is_ok();
    let (t0, cpu0) = (Instant::now(), cpu_seconds());
    let json = (entry.decode)(&args)?;
    let seconds = t0.elapsed().as_secs_f64();
    let cpu = cpu0.zip(cpu_seconds()).map(|(a, b)| b - a);
    let peak = peak_rss().filter(|_| reset);
    let decoded: serde_json::Value =
        serde_json::from_str(&json).map_err(|e| Error::Decode(e.to_string()))?;
    let reads = decoded["transactions"].as_array().map_or(0, Vec::len);
    // Every whole repetition's reads, and perhaps the cut last one's.
    let whole = (samples / tile.samples.len() as u64) as usize * tile.reads;
    if reads < whole || reads > whole + tile.reads {
        return Err(Error::Decode(format!(
            "bench --capture {format}: {reads} reads decoded, {whole} expected"
        )));
    }
    Ok(format!(
        "format: {format}\nsamples: {samples}\nfile_bytes: {file_bytes}\nreads: {reads}\ndecode_seconds: {seconds:.3}\nsamples_per_second: {:.0}\n\
         decode_cpu_seconds: {}\nsamples_per_cpu_second: {}\npeak_rss_bytes: {}\n",
        samples as f64 / seconds,
        cpu.map_or("-".to_string(), |c| format!("{c:.3}")),
        cpu.map_or("-".to_string(), |c| format!("{:.0}", samples as f64 / c)),
        peak.map_or("-".to_string(), |p| p.to_string())
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A few repetitions in both formats: every read decoded (the report
    /// refuses a count short of the repetitions'), a figure for each key.
    #[test]
    fn a_small_bench_capture_decodes_every_read_in_both_formats() {
        for format in FORMATS {
            let r = report(format, 400_000).unwrap();
            assert!(
                r.contains(&format!("format: {format}\nsamples: 400000\n")),
                "{r}"
            );
            let reads: usize = r
                .lines()
                .find_map(|l| l.strip_prefix("reads: "))
                .unwrap()
                .parse()
                .unwrap();
            assert!(reads >= 12, "{r}");
            assert!(
                r.contains("samples_per_second: ") && r.contains("peak_rss_bytes: "),
                "{r}"
            );
        }
    }
}
