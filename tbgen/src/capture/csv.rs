//! A logic analyser's CSV export: a header row naming the columns, then one
//! row per sample or per change, each channel a `0` or `1`.
//!
//! The exports read, as their tools write them:
//!
//! - Saleae Logic 2 (digital): `Time [s],Channel 0,Channel 1` (or the names
//!   the user gave the channels), one row per change, the time in seconds
//!   (negative before the trigger).
//! - sigrok-cli `-O csv`: comment lines `; Samplerate: 50 MHz` and `;
//!   Channels (2/2): clk, data`, a header row of the channel names (or of
//!   `logic` under `label=units`, the names then from the comment), and a
//!   first column `Time` or `nanoseconds` etc. only with `time=true`; one
//!   row per sample, or per change with `dedup=true`.
//!
//! Times are made relative to the first row. The sample period, against
//! which [`super::sampled`] checks the lines' pulses, is the comment's
//! sample rate, else the time resolution of the rows (the greatest common
//! divisor of their times: a capture's times are whole samples).

use std::io::{BufRead, BufReader};
use std::path::Path;

use model::wire::Signal;

use super::{lines, open, sampled, sigrok};
use crate::{Error, Result};

/// The unit names of a time column's header, in picoseconds.
const UNITS: [(&[&str], i128); 5] = [
    (&["s", "seconds"], 1_000_000_000_000),
    (&["ms", "milliseconds"], 1_000_000_000),
    (&["us", "µs", "microseconds"], 1_000_000),
    (&["ns", "nanoseconds"], 1_000),
    (&["ps", "picoseconds"], 1),
];

/// The header row, read.
struct Header {
    /// Picoseconds per unit of the first column, if it is a time column.
    time_unit: Option<i128>,
    /// Cells in a row.
    width: usize,
}

/// Reads the lines `names` (channel name, option) of the CSV file `path`.
pub(crate) fn read(path: &Path, names: &[(&str, &str)]) -> Result<Vec<Signal>> {
    let file = path.display().to_string();
    let mut reader = BufReader::with_capacity(1 << 20, open(path)?);
    let (mut raw, mut previous) = (Vec::new(), Vec::new());
    let (mut offset, mut lineno) = (0u64, 0usize);
    let mut comment_rate: Option<f64> = None;
    let mut comment_channels: Option<Vec<String>> = None;
    let mut header: Option<Header> = None;
    let mut columns: Vec<usize> = Vec::new();
    let mut edges: Option<sampled::Edges> = None;
    let (mut first, mut last, mut resolution, mut rows) = (None::<i128>, 0i128, 0i128, 0i128);
    loop {
        raw.clear();
        let start = offset;
        let n = reader
            .read_until(b'\n', &mut raw)
            .map_err(|e| Error::io(path, e))?;
        if n == 0 {
            break;
        }
        offset += n as u64;
        lineno += 1;
        let at = |what: String| Error::Decode(format!("{file}:{lineno}: byte {start}: {what}"));
        if raw.last() != Some(&b'\n') {
            return Err(at("the last row ends without a line break: the file is cut short; export the capture again".into()));
        }
        // A row of samples without a time column that repeats the row above
        // (sigrok-cli writes one per sample): the same levels, one sample later.
        if header.as_ref().is_some_and(|h| h.time_unit.is_none()) && raw == previous {
            rows += 1;
            continue;
        }
        let text = std::str::from_utf8(&raw)
            .map_err(|_| at("not text (UTF-8): not a CSV export".into()))?;
        let text = text.trim_end_matches(['\n', '\r']);
        if text.trim().is_empty() {
            continue;
        }
        if let Some(c) = text.strip_prefix(';').or_else(|| text.strip_prefix('#')) {
            comment(c, &mut comment_rate, &mut comment_channels);
            continue;
        }
        let cells: Vec<&str> = text
            .split(',')
            .map(|c| c.trim().trim_matches('"').trim())
            .collect();
        let Some(h) = &header else {
            let time_unit = time_unit(cells[0]).map_err(at)?;
            let mut channels: Vec<String> = cells[time_unit.is_some() as usize..]
                .iter()
                .map(|c| c.to_string())
                .collect();
            if channels.iter().all(|c| c == "logic") {
                if let Some(named) = comment_channels
                    .take()
                    .filter(|n| n.len() == channels.len())
                {
                    channels = named;
                }
            }
            for &(name, option) in names {
                columns.push(
                    lines::find(&channels, name, option, &file)? + time_unit.is_some() as usize,
                );
            }
            let offset = time_unit.is_some() as usize;
            edges = Some(sampled::Edges::new(
                &columns
                    .iter()
                    .map(|&c| channels[c - offset].clone())
                    .collect::<Vec<_>>(),
            ));
            header = Some(Header {
                time_unit,
                width: cells.len(),
            });
            continue;
        };
        if cells.len() != h.width {
            return Err(at(format!(
                "{} fields, but the header row has {}: the row is cut short or damaged; export the capture again",
                cells.len(),
                h.width
            )));
        }
        let t = match h.time_unit {
            Some(unit) => time_ps(cells[0], unit)
                .ok_or_else(|| at(format!("time `{}` is not a number", cells[0])))?,
            None => {
                let rate = comment_rate.ok_or_else(|| at("no time column and no `; Samplerate:` comment to time the rows by: export with a time column (sigrok-cli -O csv:time=true)".into()))?;
                (rows as f64 * 1e12 / rate).round() as i128
            }
        };
        let t0 = *first.get_or_insert(t);
        if t < last {
            return Err(at(format!("time `{}` is before the row above it: a capture's times only increase; the file is damaged", cells[0])));
        }
        if h.time_unit.is_some() {
            resolution = gcd(resolution, t - t0);
        }
        last = t;
        rows += 1;
        let e = edges.as_mut().expect("made with the header");
        for (i, &c) in columns.iter().enumerate() {
            let level = match cells[c] {
                "0" => false,
                "1" => true,
                v => {
                    return Err(at(format!(
                        "column {}: `{v}` is not a logic level (0 or 1)",
                        c + 1
                    )))
                }
            };
            e.push(i, (t - t0) as u64, level);
        }
        std::mem::swap(&mut raw, &mut previous);
    }
    let (Some(edges), true) = (edges, rows > 0) else {
        return Err(Error::Decode(format!(
            "{file}: no rows of samples: a CSV export has a header row naming the channels, then one row per sample or change"
        )));
    };
    let period = match comment_rate {
        Some(r) => 1e12 / r,
        None => resolution as f64,
    };
    edges.finish(&file, period)
}

/// Takes what a comment line says about the capture: sigrok's
/// `Samplerate: 50 MHz` and `Channels (2/2): clk, data`.
fn comment(c: &str, rate: &mut Option<f64>, channels: &mut Option<Vec<String>>) {
    let c = c.trim();
    if let Some(r) = c.strip_prefix("Samplerate:") {
        *rate = sigrok::rate(r).filter(|&r| r > 0.0);
    } else if let Some((_, names)) = c.strip_prefix("Channels").and_then(|r| r.split_once(':')) {
        *channels = Some(names.split(',').map(|n| n.trim().to_string()).collect());
    }
}

/// The picoseconds per unit of a time column's header (`Time [s]`,
/// `Time[ns]`, or sigrok's `nanoseconds`), `Ok(None)` for a channel's
/// column, and an error for a time column without a unit (sigrok's `Time`
/// under `label=channel`, whose unit depends on the sample rate).
fn time_unit(cell: &str) -> std::result::Result<Option<i128>, String> {
    let lower = cell.to_lowercase();
    let unit = match lower.strip_prefix("time") {
        Some(rest) => rest
            .trim()
            .trim_start_matches('[')
            .trim_end_matches(']')
            .trim()
            .to_string(),
        None => lower.clone(),
    };
    match UNITS.iter().find(|(names, _)| names.contains(&unit.as_str())) {
        Some(&(_, ps)) => Ok(Some(ps)),
        None if lower.starts_with("time") => Err(format!(
            "time column `{cell}` has no unit: name it `Time [s]` (or ms, us, ns), or export with sigrok-cli -O csv:time=true, whose header names the unit"
        )),
        None => Ok(None),
    }
}

/// `text` (a decimal, perhaps with an exponent: `0.000010000`, `1.5e-6`)
/// times `unit` picoseconds, to the nearest picosecond, without rounding
/// through a float.
fn time_ps(text: &str, unit: i128) -> Option<i128> {
    let (mantissa, exp) = match text.find(['e', 'E']) {
        Some(i) => (&text[..i], text[i + 1..].parse::<i32>().ok()?),
        None => (text, 0),
    };
    let (neg, mantissa) = match mantissa.strip_prefix('-') {
        Some(m) => (true, m),
        None => (false, mantissa.strip_prefix('+').unwrap_or(mantissa)),
    };
    let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    if int.is_empty() && frac.is_empty()
        || !int.chars().chain(frac.chars()).all(|c| c.is_ascii_digit())
        || int.len() + frac.len() > 30
    {
        return None;
    }
    let digits: i128 = format!("{int}{frac}").parse().ok()?;
    let mut value = digits.checked_mul(unit)?;
    let shift = exp - frac.len() as i32;
    if shift >= 0 {
        value = value.checked_mul(10i128.checked_pow(shift as u32)?)?;
    } else {
        let d = 10i128.checked_pow(shift.unsigned_abs())?;
        value = (value + d / 2) / d;
    }
    Some(if neg { -value } else { value })
}

fn gcd(a: i128, b: i128) -> i128 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_read_exactly_in_every_unit_an_export_uses() {
        assert_eq!(time_ps("0.000010000", 1_000_000_000_000), Some(10_000_000));
        assert_eq!(time_ps("-0.5", 1_000_000_000_000), Some(-500_000_000_000));
        assert_eq!(time_ps("1.5e-6", 1_000_000_000_000), Some(1_500_000));
        assert_eq!(time_ps("11", 1_000), Some(11_000));
        assert_eq!(time_ps("abc", 1), None);
        assert_eq!(time_ps(".", 1), None);
        assert_eq!(time_unit("Time [s]"), Ok(Some(1_000_000_000_000)));
        assert_eq!(time_unit("Time[us]"), Ok(Some(1_000_000)));
        assert_eq!(time_unit("nanoseconds"), Ok(Some(1_000)));
        assert!(time_unit("Time").unwrap_err().contains("has no unit"));
        assert_eq!(time_unit("Channel 0"), Ok(None));
    }
}
