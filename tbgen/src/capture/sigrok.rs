//! A sigrok session file (`.sr`, what PulseView saves and `sigrok-cli -o`
//! writes), version 2: a zip holding `version` (`2`), `metadata` (an INI
//! file: `[device 1]` with `samplerate`, `unitsize`, `capturefile` and
//! `probe<N>` = the name of channel N) and the samples in chunks
//! `<capturefile>-1`, `-2`, ... (or one `<capturefile>`): `unitsize` bytes a
//! sample, little-endian, channel N in bit N-1.
//!
//! The chunks are inflated as a stream, a buffer at a time; only the changes
//! of the chosen channels are kept ([`super::sampled::Edges`]).

use std::io::{BufReader, Read};
use std::path::Path;

use model::wire::Signal;

use super::{lines, open, sampled};
use crate::{Error, Result};

/// What `metadata` says about the logic channels of device 1.
struct Metadata {
    capturefile: String,
    unitsize: usize,
    samplerate: f64,
    channels: Vec<String>,
}

/// Reads the lines `names` (channel name, option) of the session `path`.
pub(crate) fn read(path: &Path, names: &[(&str, &str)]) -> Result<Vec<Signal>> {
    let file = path.display().to_string();
    let len = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
    let mut zip = zip::ZipArchive::new(BufReader::new(open(path)?)).map_err(|e| {
        Error::Decode(format!(
            "{file}: byte {len} (its end): not a whole sigrok session: {e}; a session (.sr) is a zip whose directory ends the file, so the file is cut short or not a session: save or convert it again (sigrok-cli -i capture -o capture.sr)"
        ))
    })?;
    let version = entry_text(&mut zip, &file, "version")?;
    if version.trim() != "2" {
        return Err(Error::Decode(format!(
            "{file}: session format version `{}`; tbgen reads version 2 (libsigrok 0.4 and later): save it again with a current PulseView or sigrok-cli",
            version.trim()
        )));
    }
    let meta = metadata(&entry_text(&mut zip, &file, "metadata")?, &file)?;
    let mut bits = Vec::with_capacity(names.len());
    for &(name, option) in names {
        bits.push(lines::find(&meta.channels, name, option, &file)?);
    }
    let chosen: Vec<String> = bits.iter().map(|&b| meta.channels[b].clone()).collect();
    let mut edges = sampled::Edges::new(&chosen);
    let mut reader = Samples::new(&meta, bits);
    let chunks = chunk_names(&zip, &meta.capturefile);
    if chunks.is_empty() {
        return Err(Error::Decode(format!(
            "{file}: no samples: the zip holds no `{0}` or `{0}-1`; the session is empty or damaged",
            meta.capturefile
        )));
    }
    let mut buf = vec![0u8; 1 << 16];
    for name in &chunks {
        let mut chunk = zip
            .by_name(name)
            .map_err(|e| Error::Decode(format!("{file}: chunk `{name}`: {e}")))?;
        let start = chunk.data_start().unwrap_or(0);
        loop {
            let n = match chunk.read(&mut buf) {
                Ok(0) => break,
                Ok(n) => n,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(e) => {
                    return Err(Error::Decode(format!(
                        "{file}: byte {start} (chunk `{name}`, after sample {}): {e}: the session is damaged; save or convert it again",
                        reader.sample
                    )))
                }
            };
            reader.feed(&buf[..n], &mut edges);
        }
    }
    if reader.partial != 0 {
        return Err(Error::Decode(format!(
            "{file}: the last sample has {} of its {} bytes: the session is cut short; save or convert it again",
            reader.partial, meta.unitsize
        )));
    }
    edges.finish(&file, 1e12 / meta.samplerate)
}

/// The chunk names of the capture, in order: `logic-1-1`, `logic-1-2`, ...
/// up to the first missing one, or the single `logic-1` of older writers.
fn chunk_names<R: Read + std::io::Seek>(
    zip: &zip::ZipArchive<R>,
    capturefile: &str,
) -> Vec<String> {
    if zip.index_for_name(capturefile).is_some() {
        return vec![capturefile.to_string()];
    }
    (1..)
        .map(|k| format!("{capturefile}-{k}"))
        .take_while(|n| zip.index_for_name(n).is_some())
        .collect()
}

/// An entry of the zip as text, or an error naming it.
fn entry_text<R: Read + std::io::Seek>(
    zip: &mut zip::ZipArchive<R>,
    file: &str,
    name: &str,
) -> Result<String> {
    let mut text = String::new();
    zip.by_name(name)
        .map_err(|e| {
            Error::Decode(format!(
                "{file}: no `{name}` in the zip ({e}): not a sigrok session"
            ))
        })?
        .read_to_string(&mut text)
        .map_err(|e| Error::Decode(format!("{file}: `{name}`: {e}: the session is damaged")))?;
    Ok(text)
}

/// Parses `metadata`: the `[device 1]` section (a session of several
/// devices keeps the first's logic channels).
fn metadata(text: &str, file: &str) -> Result<Metadata> {
    let mut section = String::new();
    let mut capturefile = None;
    let mut unitsize = None;
    let mut samplerate = None;
    let mut channels: Vec<String> = Vec::new();
    for line in text.lines().map(str::trim) {
        if let Some(s) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            section = s.to_string();
            continue;
        }
        let Some((key, value)) = line.split_once('=') else {
            continue;
        };
        if section != "device 1" {
            continue;
        }
        let (key, value) = (key.trim(), value.trim());
        match key {
            "capturefile" => capturefile = Some(value.to_string()),
            "unitsize" => {
                unitsize = value
                    .parse::<usize>()
                    .ok()
                    .filter(|&u| (1..=8).contains(&u))
            }
            "samplerate" => {
                samplerate = Some(rate(value).ok_or_else(|| {
                    Error::Decode(format!(
                        "{file}: metadata: samplerate `{value}` is no rate (e.g. 50 MHz)"
                    ))
                })?)
            }
            k => {
                if let Some(n) = k
                    .strip_prefix("probe")
                    .and_then(|n| n.parse::<usize>().ok())
                    .filter(|&n| n >= 1)
                {
                    if channels.len() < n {
                        channels.resize(n, String::new());
                    }
                    channels[n - 1] = value.to_string();
                }
            }
        }
    }
    let missing = |what: &str| {
        Error::Decode(format!("{file}: metadata: no {what} in [device 1]: not a session of a logic analyser, or a damaged one"))
    };
    Ok(Metadata {
        capturefile: capturefile.ok_or_else(|| missing("capturefile"))?,
        unitsize: unitsize.ok_or_else(|| missing("unitsize of 1 to 8"))?,
        samplerate: samplerate
            .filter(|&r| r > 0.0)
            .ok_or_else(|| missing("samplerate"))?,
        channels,
    })
}

/// A rate as libsigrok writes it: `50 MHz`, `1.5 kHz`, `1 GHz`, `20000`.
pub(crate) fn rate(text: &str) -> Option<f64> {
    let t = text.trim();
    let (num, scale) = [("GHz", 1e9), ("MHz", 1e6), ("kHz", 1e3), ("Hz", 1.0)]
        .iter()
        .find_map(|&(u, s)| t.strip_suffix(u).map(|n| (n.trim(), s)))
        .unwrap_or((t, 1.0));
    num.parse::<f64>()
        .ok()
        .map(|v| v * scale)
        .filter(|v| v.is_finite())
}

/// The sample stream: bytes in, the chosen channels' levels out.
struct Samples {
    unitsize: usize,
    samplerate: f64,
    bits: Vec<usize>,
    mask: u64,
    /// Index of the next sample.
    sample: u64,
    /// The chosen bits of the last sample (none yet: `u64::MAX`).
    last: u64,
    /// Bytes of a sample split across two buffers.
    carry: [u8; 8],
    partial: usize,
}

impl Samples {
    fn new(meta: &Metadata, bits: Vec<usize>) -> Samples {
        let mask = bits.iter().fold(0u64, |m, &b| m | 1 << b);
        Samples {
            unitsize: meta.unitsize,
            samplerate: meta.samplerate,
            bits,
            mask,
            sample: 0,
            last: u64::MAX,
            carry: [0; 8],
            partial: 0,
        }
    }

    fn feed(&mut self, mut bytes: &[u8], edges: &mut sampled::Edges) {
        if self.partial > 0 {
            let take = (self.unitsize - self.partial).min(bytes.len());
            self.carry[self.partial..self.partial + take].copy_from_slice(&bytes[..take]);
            self.partial += take;
            bytes = &bytes[take..];
            if self.partial < self.unitsize {
                return;
            }
            let mut word = [0u8; 8];
            word[..self.unitsize].copy_from_slice(&self.carry[..self.unitsize]);
            self.partial = 0;
            self.one(u64::from_le_bytes(word), edges);
        }
        if self.unitsize == 1 {
            // The common case (up to 8 channels): from change to change,
            // the run of samples between them skipped in one search.
            let mask = self.mask as u8;
            while let Some((&b, rest)) = bytes.split_first() {
                if self.last != u64::MAX {
                    let last = self.last as u8;
                    match bytes.iter().position(|&b| b & mask != last) {
                        Some(i) if i > 0 => {
                            self.sample += i as u64;
                            bytes = &bytes[i..];
                            continue;
                        }
                        Some(_) => {}
                        None => {
                            self.sample += bytes.len() as u64;
                            return;
                        }
                    }
                }
                self.one(b as u64, edges);
                bytes = rest;
            }
            return;
        }
        let mut units = bytes.chunks_exact(self.unitsize);
        {
            for u in units.by_ref() {
                let mut word = [0u8; 8];
                word[..self.unitsize].copy_from_slice(u);
                self.one(u64::from_le_bytes(word), edges);
            }
        }
        let rest = units.remainder();
        self.carry[..rest.len()].copy_from_slice(rest);
        self.partial = rest.len();
    }

    fn one(&mut self, word: u64, edges: &mut sampled::Edges) {
        let v = word & self.mask;
        if v != self.last {
            let t = (self.sample as f64 * 1e12 / self.samplerate).round() as u64;
            for (i, &b) in self.bits.iter().enumerate() {
                if self.last == u64::MAX || (v ^ self.last) >> b & 1 == 1 {
                    edges.push(i, t, v >> b & 1 == 1);
                }
            }
            self.last = v;
        }
        self.sample += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rates_read_as_libsigrok_writes_them() {
        assert_eq!(rate("50 MHz"), Some(50e6));
        assert_eq!(rate("1 GHz"), Some(1e9));
        assert_eq!(rate("1.5 kHz"), Some(1500.0));
        assert_eq!(rate("20000"), Some(20000.0));
        assert_eq!(rate("fast"), None);
    }
}
