//! `tbgen gtkwave-filter <protocol>`: a GTKWave Transaction Filter Process
//! that shows a protocol's decoded frames next to the lines they came from.
//!
//! GTKWave (Edit > Data Format > Transaction Filter Process) starts the
//! process once and, for each trace it filters, writes on its stdin a small
//! VCD of the trace's signals (a group made with Combine Down holds each
//! line under its own name) framed by `$comment data_start <id> $end` and
//! `$comment data_end <id> $end`; it reads back, on stdout, one trace:
//!
//! ```text
//! $name ssi (tbgen)
//! #0
//! #1000000 position=495
//! #49000000
//! $finish
//! ```
//!
//! a time (in the VCD's `$timescale` units) with the text shown from there,
//! `?color?` before a text to colour it, and a time alone for a gap. Each
//! block is decoded by the protocol's own decoder (`tbgen decode`, with the
//! options given after the protocol), so the trace shows what `tbgen decode`
//! prints; a block it cannot decode is answered with the error as the
//! trace's text, never with silence, which would hang GTKWave.

use std::io::{BufRead, Write};

use serde_json::Value;

use crate::{registry, Error, Result};

/// The marker that ends a block of GTKWave's.
const DATA_END: &str = "$comment data_end";

/// Serves GTKWave: every block of `input` answered on `output`, until
/// `input` ends. `args` are the decoder's options.
pub fn serve(
    protocol: &str,
    args: &[String],
    input: impl BufRead,
    mut output: impl Write,
) -> Result<()> {
    let entry = registry::by_table(protocol)
        .filter(|e| (e.decode_command)().is_some())
        .ok_or_else(|| Error::Decode(format!("gtkwave-filter: no decoder `{protocol}`; `tbgen protocols` lists them (decode=yes)")))?;
    let scratch = tempdir()?;
    let mut block = String::new();
    for line in input.lines() {
        let line = line.map_err(|e| Error::io("<stdin>", e))?;
        block.push_str(&line);
        block.push('\n');
        if line.trim_start().starts_with(DATA_END) {
            let trace = respond(entry, &block, args, &scratch.0);
            output
                .write_all(trace.as_bytes())
                .and_then(|_| output.flush())
                .map_err(|e| Error::io("<stdout>", e))?;
            block.clear();
        }
    }
    Ok(())
}

/// A folder removed when dropped.
struct Scratch(std::path::PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn tempdir() -> Result<Scratch> {
    let dir = std::env::temp_dir().join(format!("tbgen-gtkwave-filter-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
    Ok(Scratch(dir))
}

/// The trace for one block.
fn respond(
    entry: &registry::Entry,
    block: &str,
    args: &[String],
    scratch: &std::path::Path,
) -> String {
    let name = format!("$name {} (tbgen)\n", entry.table);
    let result = timescale_fs(block).and_then(|unit_fs| {
        let vcd = scratch.join("block.vcd");
        std::fs::write(&vcd, block).map_err(|e| Error::io(&vcd, e))?;
        let argv = [entry.table.to_string(), vcd.display().to_string()]
            .into_iter()
            .chain(args.iter().cloned());
        let m = (entry.decode_command)()
            .expect("a decoder")
            .try_get_matches_from(argv)
            .map_err(|e| {
                Error::Decode(format!(
                    "gtkwave-filter {}: the decoder's options: {}",
                    entry.table,
                    e.to_string().trim()
                ))
            })?;
        let decoded: Value =
            serde_json::from_str(&(entry.decode)(&m)?).map_err(|e| Error::Decode(e.to_string()))?;
        Ok(trace(&decoded, unit_fs))
    });
    match result {
        Ok(body) => format!("{name}#0\n{body}$finish\n"),
        Err(e) => format!("{name}#0 ?red?{}\n$finish\n", one_line(&e.to_string())),
    }
}

/// The block's `$timescale` in femtoseconds (`1ps` → 1000).
fn timescale_fs(block: &str) -> Result<u128> {
    let text = block
        .split("$timescale")
        .nth(1)
        .and_then(|r| r.split("$end").next())
        .map(|t| t.split_whitespace().collect::<String>())
        .ok_or_else(|| Error::Decode("gtkwave-filter: the block has no $timescale".into()))?;
    let digits = text.trim_end_matches(|c: char| c.is_ascii_alphabetic());
    let unit = &text[digits.len()..];
    let scale: u128 = match unit {
        "s" => 1_000_000_000_000_000,
        "ms" => 1_000_000_000_000,
        "us" => 1_000_000_000,
        "ns" => 1_000_000,
        "ps" => 1_000,
        "fs" => 1,
        _ => {
            return Err(Error::Decode(format!(
                "gtkwave-filter: $timescale `{text}`: no unit s, ms, us, ns, ps or fs"
            )))
        }
    };
    let n: u128 = digits.parse().map_err(|_| {
        Error::Decode(format!(
            "gtkwave-filter: $timescale `{text}` is no number and unit"
        ))
    })?;
    Ok(n.max(1) * scale)
}

/// A message on one line (GTKWave shows one line a time).
fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The transactions (CAN's `frames`) as trace lines: each from its start
/// (`start_ps`, CAN's `sof_ps`) with its fields, red when it has errors,
/// and a gap from its `end_ps` where it has one.
fn trace(decoded: &Value, unit_fs: u128) -> String {
    let units = |ps: u64| ps as u128 * 1000 / unit_fs;
    let empty = Vec::new();
    let all = decoded
        .get("transactions")
        .or_else(|| decoded.get("frames"))
        .and_then(Value::as_array)
        .unwrap_or(&empty);
    let mut out = String::new();
    let mut last = 0u128;
    for t in all {
        let Some(start) = t
            .get("start_ps")
            .or_else(|| t.get("sof_ps"))
            .and_then(Value::as_u64)
        else {
            continue;
        };
        // GTKWave takes the times in order: a transaction starting where the
        // last ended (rounded to the unit) starts one unit later.
        let start = units(start).max(last);
        out += &format!("#{start} {}\n", label(t));
        last = start + 1;
        if let Some(end) = t.get("end_ps").and_then(Value::as_u64) {
            let end = units(end).max(last);
            out += &format!("#{end}\n");
            last = end + 1;
        }
    }
    out
}

/// What a transaction shows: its fields other than times and index, as
/// `key=value`, its errors first and in red.
fn label(t: &Value) -> String {
    let Some(fields) = t.as_object() else {
        return t.to_string();
    };
    let errors: Vec<String> = ["errors", "error"]
        .iter()
        .filter_map(|k| fields.get(*k))
        .flat_map(|e| match e {
            Value::Array(a) => a
                .iter()
                .map(|x| x.as_str().map_or_else(|| x.to_string(), str::to_string))
                .collect(),
            Value::String(s) => vec![s.clone()],
            _ => Vec::new(),
        })
        .collect();
    let shown: Vec<String> = fields
        .iter()
        .filter(|(k, v)| {
            !(k.ends_with("_ps") || *k == "index" || *k == "errors" || *k == "error" || v.is_null())
        })
        .map(|(k, v)| {
            format!(
                "{k}={}",
                v.as_str().map_or_else(|| v.to_string(), str::to_string)
            )
        })
        .collect();
    let text = one_line(&shown.join(" "));
    match errors.is_empty() {
        true => text,
        false => format!("?red?{}: {text}", errors.join(",")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timescales_read_in_femtoseconds() {
        assert_eq!(timescale_fs("$timescale 1ps $end").unwrap(), 1_000);
        assert_eq!(
            timescale_fs("$timescale\n 10 ns\n$end").unwrap(),
            10_000_000
        );
        assert!(timescale_fs("$timescale 1 parsec $end").is_err());
    }
}
