//! `tbgen check <protocol> --expect FILE CAPTURE`: what a master did,
//! transaction by transaction, against what was expected.
//!
//! Both sides are transcripts: a `tbgen gen` or `tbgen decode` transcript
//! (`transactions`), a pin-level monitor's (`hdl/emu/<proto>_monitor.v`:
//! `transactions` from the same decode cores, plus its `violations`), or an
//! emulator's (`frames`, `reads`, `requests`). A
//! capture that is a VCD (any timescale, 1 fs included) is first decoded
//! with the protocol's own decoder (`tbgen decode <protocol>`), whose
//! options (the port names) follow `--`, so the check does not care what
//! the master calls its pins.
//!
//! The comparison walks the transactions in order and, in each, every field
//! the two sides both have, recursively (positions, error and warning bits,
//! CRC verdicts, commands, register accesses, bytes), leaving out the fields
//! that say when or how fast (`index`, `*_ps`, `*_ns`, `*_us`, `*cycle*`,
//! `delay*`, `clocks`): a master with another latency or line clock passes
//! when it did the same things. The first difference is printed with the
//! capture's time of the transaction. `--timeout-us T` also holds the
//! capture to a deadline: a transaction that starts more than `T` after the
//! previous one (a late frame a master's timeout would break on) is a
//! difference.

use std::path::Path;

use serde_json::Value;

use crate::error::{Error, Result};
use crate::registry;

/// What `tbgen check` found.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// No difference.
    pub ok: bool,
    /// The text to print.
    pub text: String,
}

/// A transcript's transactions and the picoseconds of one of its cycles.
struct Side {
    what: String,
    list: Vec<Value>,
    ps_per_cycle: Option<f64>,
}

/// Keys that say when or how fast, not what.
fn timing_key(k: &str) -> bool {
    k == "index"
        || k == "clocks"
        || k.ends_with("_ps")
        || k.ends_with("_ns")
        || k.ends_with("_us")
        || k.contains("cycle")
        || k.starts_with("delay")
}

fn read_json(path: &Path) -> Result<Value> {
    let text = std::fs::read_to_string(path).map_err(|e| match e.kind() {
        // Bad input (exit 2), as every missing file of tbgen's command line.
        std::io::ErrorKind::NotFound => Error::Decode(format!("{}: no such file; give the path of a transcript (JSON) or a capture (VCD)", path.display())),
        _ => Error::io(path, e),
    })?;
    serde_json::from_str(&text).map_err(|e| Error::Decode(format!("{}: not a JSON transcript ({e}); give a `tbgen gen`/`tbgen decode` transcript, an emulator transcript or a VCD", path.display())))
}

fn side(path: &Path, v: Value) -> Result<Side> {
    let ps_per_cycle = v.get("f_emu_hz").and_then(Value::as_f64).map(|f| 1e12 / f);
    for key in ["transactions", "frames", "reads", "requests"] {
        if let Some(Value::Array(list)) = v.get(key) {
            return Ok(Side { what: path.display().to_string(), list: list.clone(), ps_per_cycle });
        }
    }
    Err(Error::Decode(format!(
        "{}: no list of transactions (`transactions`, `frames`, `reads` or `requests`) in it; give a transcript that tbgen or an emulator wrote",
        path.display()
    )))
}

/// Reads a capture: a JSON transcript, or a VCD decoded by `protocol`'s decoder with `decoder_args`.
fn capture(protocol: &str, path: &Path, decoder_args: &[String]) -> Result<Value> {
    let is_vcd = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("vcd"));
    if !is_vcd {
        return read_json(path);
    }
    let entry = registry::by_table(protocol).ok_or_else(|| Error::Decode(format!("check: no protocol `{protocol}`; `tbgen protocols` lists them")))?;
    let cmd = (entry.decode_command)().ok_or_else(|| {
        Error::Decode(format!("check {protocol}: this protocol has no decoder yet, so a VCD cannot be read; give the monitor's or emulator's JSON transcript"))
    })?;
    let mut argv = vec![format!("decode {protocol}"), path.display().to_string()];
    argv.extend(decoder_args.iter().cloned());
    let m = cmd.try_get_matches_from(argv).map_err(|e| Error::Decode(format!("check {protocol}: the decoder's options after `--`: {}", e.to_string().trim())))?;
    let json = (entry.decode)(&m)?;
    serde_json::from_str(&json).map_err(|e| Error::Decode(e.to_string()))
}

/// The first difference between `a` (expected) and `b` (captured), as a path and the two values.
fn differ(path: &str, a: &Value, b: &Value) -> Option<(String, String, String)> {
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            for (k, va) in x {
                if timing_key(k) {
                    continue;
                }
                if let Some(vb) = y.get(k) {
                    if let Some(d) = differ(&format!("{path}.{k}"), va, vb) {
                        return Some(d);
                    }
                }
            }
            None
        }
        (Value::Array(x), Value::Array(y)) => {
            for (i, (va, vb)) in x.iter().zip(y).enumerate() {
                if let Some(d) = differ(&format!("{path}[{i}]"), va, vb) {
                    return Some(d);
                }
            }
            (x.len() != y.len()).then(|| (format!("{path} (length)"), x.len().to_string(), y.len().to_string()))
        }
        (Value::Number(x), Value::Number(y)) if x.as_f64().zip(y.as_f64()).is_some_and(|(p, q)| (p - q).abs() <= 1e-9 * p.abs().max(1.0)) => None,
        _ => (a != b).then(|| (path.to_string(), a.to_string(), b.to_string())),
    }
}

/// A transaction's start in picoseconds, if its transcript says.
fn start_ps(t: &Value, ps_per_cycle: Option<f64>) -> Option<f64> {
    let o = t.as_object()?;
    for (k, scale) in [("start_ps", 1.0), ("sof_ps", 1.0), ("time_ps", 1.0), ("time_ns", 1e3), ("start_ns", 1e3)] {
        if let Some(v) = o.get(k).and_then(Value::as_f64) {
            return Some(v * scale);
        }
    }
    let cycle = ["cycle", "start_cycle", "sof_cycle"].iter().find_map(|k| o.get(*k).and_then(Value::as_f64))?;
    ps_per_cycle.map(|p| cycle * p)
}

fn at(t: &Value, side: &Side) -> String {
    match start_ps(t, side.ps_per_cycle) {
        Some(ps) => format!(" at {:.3} us", ps / 1e6),
        None => String::new(),
    }
}

/// Compares `capture` against `expect`; `timeout_us` bounds the time between transactions.
pub fn check(protocol: &str, expect: &Path, capture_path: &Path, decoder_args: &[String], timeout_us: Option<f64>) -> Result<Report> {
    if let Some(t) = timeout_us {
        if !(t > 0.0 && t.is_finite()) {
            return Err(Error::Decode(format!("--timeout-us {t}: give a positive time in microseconds")));
        }
    }
    let want = side(expect, read_json(expect)?)?;
    let got = side(capture_path, capture(protocol, capture_path, decoder_args)?)?;
    let fail = |text: String| Ok(Report { ok: false, text });
    for (k, (a, b)) in want.list.iter().zip(&got.list).enumerate() {
        if let Some((path, va, vb)) = differ("", a, b) {
            return fail(format!(
                "DIFFERENCE in transaction {k}{}: {} expected {va}, captured {vb} ({} vs {})",
                at(b, &got),
                path.trim_start_matches('.'),
                want.what,
                got.what
            ));
        }
        if let (Some(limit), Some(prev)) = (timeout_us, k.checked_sub(1)) {
            let (t0, t1) = (start_ps(&got.list[prev], got.ps_per_cycle), start_ps(b, got.ps_per_cycle));
            if let (Some(t0), Some(t1)) = (t0, t1) {
                let gap = (t1 - t0) / 1e6;
                if gap > limit {
                    return fail(format!(
                        "DIFFERENCE in transaction {k}{}: it starts {gap:.3} us after transaction {prev}, beyond the timeout of {limit} us",
                        at(b, &got)
                    ));
                }
            }
        }
    }
    if want.list.len() != got.list.len() {
        let k = want.list.len().min(got.list.len());
        let when = got.list.get(k).map(|t| at(t, &got)).unwrap_or_default();
        return fail(format!(
            "DIFFERENCE in transaction {k}{when}: {} expected {} transactions, {} captured {}",
            want.what,
            want.list.len(),
            got.what,
            got.list.len()
        ));
    }
    Ok(Report { ok: true, text: format!("PASS: {} transactions of {protocol} equal, in order ({} vs {})", got.list.len(), want.what, got.what) })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decoded_seed(dir: &Path) -> (std::path::PathBuf, std::path::PathBuf) {
        let s = crate::builtin::find("biss_seed_16bit").unwrap();
        let summary = crate::generate::generate(&s, dir).unwrap();
        let vcd = summary.files.iter().find(|f| f.extension().is_some_and(|e| e == "vcd")).unwrap().clone();
        let json = summary.files.iter().find(|f| f.extension().is_some_and(|e| e == "json")).unwrap().clone();
        (vcd, json)
    }

    fn args() -> Vec<String> {
        vec!["--bits".into(), "16".into()]
    }

    #[test]
    fn a_clean_capture_passes_against_the_models_transcript() {
        let dir = tempfile::tempdir().unwrap();
        let (vcd, json) = decoded_seed(dir.path());
        let r = check("biss", &json, &vcd, &args(), None).unwrap();
        assert!(r.ok, "{}", r.text);
        assert!(r.text.starts_with("PASS: "), "{}", r.text);
    }

    /// The seed capture with every timestamp scaled to 1 fs units (as Icarus writes).
    fn femto(vcd: &Path, out: &Path) {
        let text = std::fs::read_to_string(vcd).unwrap();
        let mut lines = Vec::new();
        for l in text.lines() {
            if let Some(t) = l.strip_prefix('#') {
                lines.push(format!("#{}", t.parse::<u64>().unwrap() * 1000));
            } else {
                lines.push(l.replace("$timescale 1 ps $end", "$timescale 1 fs $end"));
            }
        }
        std::fs::write(out, lines.join("\n") + "\n").unwrap();
    }

    #[test]
    fn a_flipped_position_bit_is_the_first_difference_with_its_time() {
        let dir = tempfile::tempdir().unwrap();
        let (vcd, json) = decoded_seed(dir.path());
        let fs = dir.path().join("fs.vcd");
        femto(&vcd, &fs);
        assert!(std::fs::read_to_string(&fs).unwrap().contains("$timescale 1 fs $end"));
        let mut v: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        let p = &mut v["transactions"][1]["slaves"][0]["position"];
        *p = Value::from(p.as_u64().unwrap() ^ 4);
        let planted = dir.path().join("planted.json");
        std::fs::write(&planted, v.to_string()).unwrap();
        let r = check("biss", &planted, &fs, &args(), None).unwrap();
        assert!(!r.ok);
        assert!(r.text.starts_with("DIFFERENCE in transaction 1 at 21.212 us: slaves[0].position expected"), "{}", r.text);
        // The same capture in fs passes against the untouched transcript.
        assert!(check("biss", &json, &fs, &args(), None).unwrap().ok);
    }

    #[test]
    fn a_late_frame_breaks_the_timeout_and_a_missing_one_is_counted() {
        let dir = tempfile::tempdir().unwrap();
        let (vcd, json) = decoded_seed(dir.path());
        let decoded = dir.path().join("decoded.json");
        std::fs::write(&decoded, capture("biss", &vcd, &args()).unwrap().to_string()).unwrap();
        // The seed's frames are 20.2 us apart: a 15 us timeout is broken by the second.
        let r = check("biss", &json, &decoded, &[], Some(15.0)).unwrap();
        assert!(!r.ok);
        assert!(r.text.starts_with("DIFFERENCE in transaction 1 at 21.212 us: it starts 20.212 us after transaction 0, beyond the timeout of 15 us"), "{}", r.text);
        assert!(check("biss", &json, &decoded, &[], Some(25.0)).unwrap().ok);
        let mut v: Value = serde_json::from_str(&std::fs::read_to_string(&decoded).unwrap()).unwrap();
        v["transactions"].as_array_mut().unwrap().pop();
        std::fs::write(&decoded, v.to_string()).unwrap();
        let r = check("biss", &json, &decoded, &[], None).unwrap();
        assert!(!r.ok && r.text.contains("transactions, "), "{}", r.text);
    }

    #[test]
    fn bad_input_names_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let bad = dir.path().join("x.json");
        std::fs::write(&bad, "{\"a\": 1}").unwrap();
        let e = check("biss", &bad, &bad, &[], None).unwrap_err().to_string();
        assert!(e.contains("x.json: no list of transactions"), "{e}");
        let e = check("biss", &dir.path().join("none.json"), &bad, &[], None).unwrap_err();
        assert!(e.to_string().contains("none.json: no such file"), "{e}");
        assert_eq!(e.exit_code(), 2);
        let (vcd, json) = decoded_seed(dir.path());
        let e = check("biss", &json, &vcd, &["--nope".into()], None).unwrap_err().to_string();
        assert!(e.contains("the decoder's options after `--`"), "{e}");
    }
}
