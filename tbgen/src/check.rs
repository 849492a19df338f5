//! `tbgen check <protocol> --expect FILE CAPTURE`: what a master did,
//! transaction by transaction, against what was expected.
//!
//! Both sides are transcripts: a `tbgen gen` or `tbgen decode` transcript
//! (`transactions`), a pin-level monitor's (`hdl/emu/<proto>_monitor.v`:
//! `transactions` from the same decode cores, plus its `violations`), or an
//! emulator's (`frames`, `reads`, `requests`; EnDat `transfers`, T-format
//! and ESL `answers`, read under the decoders' names by
//! `emulator_entries`). A
//! capture that is a VCD (any timescale, 1 fs included), a sigrok session
//! (`.sr`) or a logic analyser's CSV export is first decoded
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
        std::io::ErrorKind::NotFound => Error::Decode(format!(
            "{}: no such file; give the path of a transcript (JSON) or a capture (VCD, sigrok .sr, CSV)",
            path.display()
        )),
        _ => Error::io(path, e),
    })?;
    serde_json::from_str(&text).map_err(|e| Error::Decode(format!("{}: not a JSON transcript ({e}); give a `tbgen gen`/`tbgen decode` transcript, an emulator transcript or a capture (.vcd, .sr, .csv)", path.display())))
}

fn side(path: &Path, v: Value) -> Result<Side> {
    let ps_per_cycle = v.get("f_emu_hz").and_then(Value::as_f64).map(|f| 1e12 / f);
    for key in [
        "transactions",
        "frames",
        "reads",
        "requests",
        "transfers",
        "answers",
    ] {
        if let Some(Value::Array(list)) = v.get(key) {
            let list = match key {
                "transfers" | "answers" => emulator_entries(key, list),
                _ => list.clone(),
            };
            return Ok(Side {
                what: path.display().to_string(),
                list,
                ps_per_cycle,
            });
        }
    }
    Err(Error::Decode(format!(
        "{}: no list of transactions (`transactions`, `frames`, `reads`, `requests`, `transfers` or `answers`) in it; give a transcript that tbgen or an emulator wrote",
        path.display()
    )))
}

/// `(emulator's name, decoder's name)` of the fields an EnDat, T-format or
/// ESL emulator's entry shares with the transactions `tbgen decode` and the
/// pin-level monitors write (`model::<proto>::decode`); the rest of an entry
/// (`sent_bits`, `answer`, `warning`, `busy`, `comm_error`, `device`) has no
/// counterpart there and is left out.
const EMULATOR_FIELDS: [(&str, &str); 10] = [
    ("mode", "mode"),
    ("position", "position"),
    ("f1", "f1"),
    ("f2", "f2"),
    ("data_id", "data_id"),
    ("abs", "abs"),
    ("abm", "abm"),
    ("almc", "almc"),
    ("alm", "alm1"),
    ("sf", "sf"),
];

/// The entries of an EnDat (`transfers`), T-format or ESL (`answers`)
/// emulator transcript under the decoders' names, so that an emulator's and
/// a monitor's (or `tbgen decode`'s) transcripts compare field by field:
///
/// * a field the entry does not carry (`null`: ABM in a Data ID 0 answer, F2
///   in a type 2.1 frame) is left out, since a decoder holds the host's
///   register there (the value of an earlier answer);
/// * T-format and ESL `fields` (the answer as the encoder built it, CRC
///   last) are the decoders' `received` (what crossed the wire); ESL `sc`
///   is `sc1`, `sc2`;
/// * EnDat: a transfer the encoder answered without a frame (`answer` other
///   than `ok`: error handling, an ignored command) keeps its `mode` only,
///   as a decoder reads no position there;
/// * ESL: the runs of B, C and D requests (seed 000 Table 4: "minimum 8
///   times consecutively") are one operation of the decoder, so each run
///   of the same encoder and Data ID becomes its last answer.
fn emulator_entries(key: &str, list: &[Value]) -> Vec<Value> {
    let mut out: Vec<Value> = Vec::new();
    let mut run: Option<(Value, u64, u64)> = None; // ESL: (device, data_id, answers so far)
    for e in list {
        let Some(o) = e.as_object() else {
            out.push(e.clone());
            continue;
        };
        let mut n = serde_json::Map::new();
        for (k, v) in o {
            if timing_key(k) {
                n.insert(k.clone(), v.clone());
            }
        }
        let answered = o.get("answer").is_none_or(|a| a == "ok");
        for (from, to) in EMULATOR_FIELDS {
            match o.get(from) {
                Some(Value::Null) | None => {}
                Some(_) if !answered && from != "mode" => {}
                Some(v) => {
                    n.insert(to.to_string(), v.clone());
                }
            }
        }
        if key == "answers" {
            if let Some(f) = o.get("fields") {
                n.insert("received".into(), f.clone());
            }
            if let Some(Value::Array(sc)) = o.get("sc") {
                if let [a, b] = sc.as_slice() {
                    n.insert("sc1".into(), a.clone());
                    n.insert("sc2".into(), b.clone());
                }
            }
        }
        // ESL runs of B (0x0B), C, D: one operation of 8 answers.
        let id = o
            .get("data_id")
            .and_then(Value::as_u64)
            .filter(|d| o.contains_key("device") && (0x0B..=0x0D).contains(d));
        let continues = match (id, &run) {
            (Some(id), Some((dev, rid, count))) => {
                o.get("device") == Some(dev)
                    && *rid == id
                    && *count < u64::from(model::esl::REPEATS)
            }
            _ => false,
        };
        if continues {
            if let Some((_, _, count)) = run.as_mut() {
                *count += 1;
            }
            // The operation starts at the run's first answer; its results are the last one's.
            if let Some(Value::Object(first)) = out.pop() {
                for (k, v) in first {
                    if timing_key(&k) {
                        n.insert(k, v);
                    }
                }
            }
        } else {
            run = id.map(|id| (o.get("device").cloned().unwrap_or(Value::Null), id, 1));
        }
        out.push(Value::Object(n));
    }
    out
}

/// Refuses an expected transcript of another protocol's core (a model
/// transcript names its `core`), naming the command that reads it: a field
/// by field comparison would blame the first field the two protocols do not
/// share instead.
fn same_protocol(protocol: &str, path: &Path, doc: &Value) -> Result<()> {
    let (Some(entry), Some(core)) = (
        registry::by_table(protocol),
        doc.get("core").and_then(Value::as_str),
    ) else {
        return Ok(());
    };
    if entry.core == core {
        return Ok(());
    }
    let theirs: Vec<&str> = crate::PROTOCOLS
        .iter()
        .filter(|e| e.core == core)
        .map(|e| e.table)
        .collect();
    let fix = match theirs.first() {
        Some(t) => format!("compare it with `tbgen check {t}`, or give a {protocol} transcript"),
        None => format!("give a {protocol} transcript"),
    };
    Err(Error::Decode(format!(
        "{}: a transcript of {core}, not of {} (`{protocol}`); {fix}",
        path.display(),
        entry.core
    )))
}

/// Reads a capture: a JSON transcript, or a waveform (VCD, `.sr`, CSV)
/// decoded by `protocol`'s decoder with `decoder_args`; for a waveform,
/// also the rule verdict of its master pins.
fn capture(
    protocol: &str,
    path: &Path,
    decoder_args: &[String],
) -> Result<(Value, Option<String>)> {
    if !crate::capture::is_capture(path) {
        return Ok((read_json(path)?, None));
    }
    let entry = registry::by_table(protocol).ok_or_else(|| {
        Error::Decode(format!(
            "check: no protocol `{protocol}`; `tbgen protocols` lists them"
        ))
    })?;
    let cmd = registry::decode_command(entry).ok_or_else(|| {
        Error::Decode(format!("check {protocol}: this protocol has no decoder yet, so a capture cannot be read; give the monitor's or emulator's JSON transcript"))
    })?;
    let mut argv = vec![format!("decode {protocol}"), path.display().to_string()];
    argv.extend(decoder_args.iter().cloned());
    let m = cmd.try_get_matches_from(argv).map_err(|e| {
        Error::Decode(format!(
            "check {protocol}: the decoder's options after `--`: {}",
            e.to_string().trim()
        ))
    })?;
    let json = (entry.decode)(&m)?;
    let verdict = crate::rule_verdict::of_capture(entry, &m)?;
    let value = serde_json::from_str(&json).map_err(|e| Error::Decode(e.to_string()))?;
    Ok((value, verdict))
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
            (x.len() != y.len()).then(|| {
                (
                    format!("{path} (length)"),
                    x.len().to_string(),
                    y.len().to_string(),
                )
            })
        }
        (Value::Number(x), Value::Number(y))
            if x.as_f64()
                .zip(y.as_f64())
                .is_some_and(|(p, q)| (p - q).abs() <= 1e-9 * p.abs().max(1.0)) =>
        {
            None
        }
        _ => (a != b).then(|| (path.to_string(), a.to_string(), b.to_string())),
    }
}

/// A transaction's start in picoseconds, if its transcript says.
fn start_ps(t: &Value, ps_per_cycle: Option<f64>) -> Option<f64> {
    let o = t.as_object()?;
    for (k, scale) in [
        ("start_ps", 1.0),
        ("sof_ps", 1.0),
        ("time_ps", 1.0),
        ("time_ns", 1e3),
        ("start_ns", 1e3),
    ] {
        if let Some(v) = o.get(k).and_then(Value::as_f64) {
            return Some(v * scale);
        }
    }
    let cycle = ["cycle", "start_cycle", "sof_cycle"]
        .iter()
        .find_map(|k| o.get(*k).and_then(Value::as_f64))?;
    ps_per_cycle.map(|p| cycle * p)
}

fn at(t: &Value, side: &Side) -> String {
    match start_ps(t, side.ps_per_cycle) {
        Some(ps) => format!(" at {:.3} us", ps / 1e6),
        None => String::new(),
    }
}

/// Compares `capture` against `expect`; `timeout_us` bounds the time between transactions.
pub fn check(
    protocol: &str,
    expect: &Path,
    capture_path: &Path,
    decoder_args: &[String],
    timeout_us: Option<f64>,
) -> Result<Report> {
    if let Some(t) = timeout_us {
        if !(t > 0.0 && t.is_finite()) {
            return Err(Error::Decode(format!(
                "--timeout-us {t}: give a positive time in microseconds"
            )));
        }
    }
    let expected = read_json(expect)?;
    same_protocol(protocol, expect, &expected)?;
    let want = side(expect, expected)?;
    let (captured, verdict) = capture(protocol, capture_path, decoder_args)?;
    let got = side(capture_path, captured)?;
    let mut report = compare(protocol, &want, &got, timeout_us)?;
    // The rule verdict of a VCD's master pins, a section of its own: it
    // leaves the exit status alone, as the comparison leaves timing out
    // ("another latency or clock rate passes") unless --timeout-us asks.
    if let Some(v) = verdict {
        report.text = format!("{}\n{}", report.text, v.trim_end());
    }
    Ok(report)
}

/// The transactions of `got` against `want`, in order.
fn compare(protocol: &str, want: &Side, got: &Side, timeout_us: Option<f64>) -> Result<Report> {
    let fail = |text: String| Ok(Report { ok: false, text });
    for (k, (a, b)) in want.list.iter().zip(&got.list).enumerate() {
        if let Some((path, va, vb)) = differ("", a, b) {
            return fail(format!(
                "DIFFERENCE in transaction {k}{}: {} expected {va}, captured {vb} ({} vs {})",
                at(b, got),
                path.trim_start_matches('.'),
                want.what,
                got.what
            ));
        }
        if let (Some(limit), Some(prev)) = (timeout_us, k.checked_sub(1)) {
            let (t0, t1) = (
                start_ps(&got.list[prev], got.ps_per_cycle),
                start_ps(b, got.ps_per_cycle),
            );
            if let (Some(t0), Some(t1)) = (t0, t1) {
                let gap = (t1 - t0) / 1e6;
                if gap > limit {
                    return fail(format!(
                        "DIFFERENCE in transaction {k}{}: it starts {gap:.3} us after transaction {prev}, beyond the timeout of {limit} us",
                        at(b, got)
                    ));
                }
            }
        }
    }
    if want.list.len() != got.list.len() {
        let k = want.list.len().min(got.list.len());
        let when = got.list.get(k).map(|t| at(t, got)).unwrap_or_default();
        return fail(format!(
            "DIFFERENCE in transaction {k}{when}: {} expected {} transactions, {} captured {}",
            want.what,
            want.list.len(),
            got.what,
            got.list.len()
        ));
    }
    Ok(Report {
        ok: true,
        text: format!(
            "PASS: {} transactions of {protocol} equal, in order ({} vs {})",
            got.list.len(),
            want.what,
            got.what
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decoded_seed(dir: &Path) -> (std::path::PathBuf, std::path::PathBuf) {
        let s = crate::builtin::find("biss_seed_16bit").unwrap();
        let summary = crate::generate::generate(&s, dir).unwrap();
        let vcd = summary
            .files
            .iter()
            .find(|f| f.extension().is_some_and(|e| e == "vcd"))
            .unwrap()
            .clone();
        let json = summary
            .files
            .iter()
            .find(|f| f.extension().is_some_and(|e| e == "json"))
            .unwrap()
            .clone();
        (vcd, json)
    }

    fn args() -> Vec<String> {
        vec!["--bits".into(), "16".into()]
    }

    /// A capture that opens with the master's power-on delay measurement,
    /// checked without --meas-khz: its 000111 frames at 200 kHz were read as
    /// four pos21 reads of position 0 and the check failed on "f1 expected
    /// null"; they are the measurement, found at their clock.
    #[test]
    fn a_capture_opening_with_a_delay_measurement_passes_without_meas_khz() {
        let dir = tempfile::tempdir().unwrap();
        let s = crate::builtin::find("endat_clock_4mhz").unwrap();
        let summary = crate::generate::generate(&s, dir.path()).unwrap();
        let file = |ext: &str| {
            summary
                .files
                .iter()
                .find(|f| f.extension().is_some_and(|e| e == ext))
                .unwrap()
                .clone()
        };
        let r = check("endat", &file("json"), &file("vcd"), &[], None).unwrap();
        assert!(r.ok, "{}", r.text);
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
        assert!(std::fs::read_to_string(&fs)
            .unwrap()
            .contains("$timescale 1 fs $end"));
        let mut v: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        let p = &mut v["transactions"][1]["slaves"][0]["position"];
        *p = Value::from(p.as_u64().unwrap() ^ 4);
        let planted = dir.path().join("planted.json");
        std::fs::write(&planted, v.to_string()).unwrap();
        let r = check("biss", &planted, &fs, &args(), None).unwrap();
        assert!(!r.ok);
        assert!(
            r.text.starts_with(
                "DIFFERENCE in transaction 1 at 21.212 us: slaves[0].position expected"
            ),
            "{}",
            r.text
        );
        // The same capture in fs passes against the untouched transcript.
        assert!(check("biss", &json, &fs, &args(), None).unwrap().ok);
    }

    #[test]
    fn a_transcript_of_another_protocol_is_refused_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let (vcd, json) = decoded_seed(dir.path());
        let e = check("endat", &json, &vcd, &[], None).unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("a transcript of biss_master, not of endat_master (`endat`); compare it with `tbgen check biss`"),
            "{text}"
        );
        assert_eq!(e.exit_code(), 2);
    }

    #[test]
    fn a_late_frame_breaks_the_timeout_and_a_missing_one_is_counted() {
        let dir = tempfile::tempdir().unwrap();
        let (vcd, json) = decoded_seed(dir.path());
        let decoded = dir.path().join("decoded.json");
        std::fs::write(
            &decoded,
            capture("biss", &vcd, &args()).unwrap().0.to_string(),
        )
        .unwrap();
        // The seed's frames are 20.2 us apart: a 15 us timeout is broken by the second.
        let r = check("biss", &json, &decoded, &[], Some(15.0)).unwrap();
        assert!(!r.ok);
        assert!(r.text.starts_with("DIFFERENCE in transaction 1 at 21.212 us: it starts 20.212 us after transaction 0, beyond the timeout of 15 us"), "{}", r.text);
        assert!(check("biss", &json, &decoded, &[], Some(25.0)).unwrap().ok);
        let mut v: Value =
            serde_json::from_str(&std::fs::read_to_string(&decoded).unwrap()).unwrap();
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
        let e = check("biss", &bad, &bad, &[], None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("x.json: no list of transactions"), "{e}");
        let e = check("biss", &dir.path().join("none.json"), &bad, &[], None).unwrap_err();
        assert!(e.to_string().contains("none.json: no such file"), "{e}");
        assert_eq!(e.exit_code(), 2);
        let (vcd, json) = decoded_seed(dir.path());
        let e = check("biss", &json, &vcd, &["--nope".into()], None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("the decoder's options after `--`"), "{e}");
    }

    /// A closed loop's two transcripts of one run (`tests/check/`): the
    /// emulator's (its `TRANSCRIPT`) and the pin-level monitor's, as files in
    /// `dir`. EnDat and T-format: 12 reads of the masters we did not write
    /// (`make -C examples/<proto>_reader_other READS=12`, `build/transcript.json`
    /// and `build/monitor.json`); ESL: 12 operations of `esl_host`'s closed
    /// loop (`hdl/tb_cosim/esl_host`, `readout_0m.toml`, Icarus, with the
    /// emulator's `TRANSCRIPT` set and `+esl_monitor_transcript`).
    fn closed_loop(proto: &str, dir: &Path) -> (std::path::PathBuf, std::path::PathBuf, Value) {
        let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/check");
        let read = |f: &str| std::fs::read_to_string(fixtures.join(f)).unwrap();
        let (emu, mon) = (
            dir.join(format!("{proto}_emulator.json")),
            dir.join(format!("{proto}_monitor.json")),
        );
        std::fs::write(&emu, read(&format!("{proto}_emulator.json"))).unwrap();
        let text = read(&format!("{proto}_monitor.json"));
        std::fs::write(&mon, &text).unwrap();
        (emu, mon, serde_json::from_str(&text).unwrap())
    }

    /// The field a T-format or ESL monitor names the single-turn position, EnDat's `position`.
    fn position_field(proto: &str) -> &'static str {
        if proto == "endat" {
            "position"
        } else {
            "abs"
        }
    }

    #[test]
    fn an_emulators_and_a_monitors_transcript_of_a_clean_closed_loop_agree() {
        for proto in ["endat", "tformat", "esl"] {
            let dir = tempfile::tempdir().unwrap();
            let (emu, mon, v) = closed_loop(proto, dir.path());
            let n = v["transactions"].as_array().unwrap().len();
            assert!(n >= 10, "{proto}: {n} transactions");
            for (a, b) in [(&emu, &mon), (&mon, &emu), (&emu, &emu), (&mon, &mon)] {
                let r = check(proto, a, b, &[], None).unwrap();
                assert!(r.ok, "{proto}: {}", r.text);
                assert!(
                    r.text
                        .starts_with(&format!("PASS: {n} transactions of {proto} equal")),
                    "{}",
                    r.text
                );
            }
            // The emulator's entries under the decoders' names: the position is compared.
            let want = side(&emu, read_json(&emu).unwrap()).unwrap();
            let carried = want
                .list
                .iter()
                .filter(|t| t.get(position_field(proto)).is_some_and(Value::is_u64))
                .count();
            assert!(
                carried * 2 > n && want.list[3].get(position_field(proto)).is_some(),
                "{proto}: {:?}",
                want.list
            );
        }
    }

    #[test]
    fn a_flipped_position_bit_in_a_monitors_transcript_is_found_with_its_transaction_and_time() {
        for proto in ["endat", "tformat", "esl"] {
            let dir = tempfile::tempdir().unwrap();
            let (emu, mon, mut v) = closed_loop(proto, dir.path());
            let t = &mut v["transactions"][3];
            let field = position_field(proto);
            let clean = t[field].as_u64().unwrap();
            t[field] = Value::from(clean ^ 4);
            let when = t["start_ps"].as_f64().unwrap() / 1e6;
            std::fs::write(&mon, v.to_string()).unwrap();
            for (a, b, want, got) in [
                (&emu, &mon, clean, clean ^ 4),
                (&mon, &emu, clean ^ 4, clean),
            ] {
                let r = check(proto, a, b, &[], None).unwrap();
                assert!(!r.ok, "{proto}: {}", r.text);
                // The capture's time of the transaction: the monitor's start, or the emulator's cycle.
                let head = if b == &mon {
                    format!("DIFFERENCE in transaction 3 at {when:.3} us: ")
                } else {
                    "DIFFERENCE in transaction 3 at ".to_string()
                };
                assert!(
                    r.text.starts_with(&head),
                    "{proto}: {} (want {head})",
                    r.text
                );
                assert!(
                    r.text
                        .contains(&format!("{field} expected {want}, captured {got}")),
                    "{proto}: {}",
                    r.text
                );
            }
        }
    }

    #[test]
    fn a_late_transaction_in_a_monitors_transcript_breaks_the_timeout() {
        for proto in ["endat", "tformat", "esl"] {
            let dir = tempfile::tempdir().unwrap();
            let (emu, mon, mut v) = closed_loop(proto, dir.path());
            let list = v["transactions"].as_array_mut().unwrap();
            let starts: Vec<f64> = list
                .iter()
                .map(|t| t["start_ps"].as_f64().unwrap())
                .collect();
            let gap = starts
                .windows(2)
                .map(|w| (w[1] - w[0]) / 1e6)
                .fold(0.0, f64::max);
            let limit = (gap * 1.5).ceil();
            assert!(
                check(proto, &emu, &mon, &[], Some(limit)).unwrap().ok,
                "{proto}: the clean run within {limit} us"
            );
            // Transaction 5 and every later one a whole timeout late.
            for t in list.iter_mut().skip(5) {
                t["start_ps"] = Value::from(t["start_ps"].as_f64().unwrap() + limit * 1e6);
            }
            let late = (starts[5] - starts[4]) / 1e6 + limit;
            std::fs::write(&mon, v.to_string()).unwrap();
            let r = check(proto, &emu, &mon, &[], Some(limit)).unwrap();
            assert!(!r.ok, "{proto}: {}", r.text);
            let want = format!(
                "DIFFERENCE in transaction 5 at {:.3} us: it starts {late:.3} us after transaction 4, beyond the timeout of {limit} us",
                starts[5] / 1e6 + limit
            );
            assert_eq!(r.text, want, "{proto}");
            // Without the timeout the values still agree.
            assert!(check(proto, &emu, &mon, &[], None).unwrap().ok, "{proto}");
        }
    }

    #[test]
    fn an_esl_run_of_eight_b_c_or_d_answers_is_one_operation_as_the_decoder_groups_it() {
        let answer = |i: u64, id: u64, abs: u64| {
            serde_json::json!({"index": i, "device": 0, "cycle": 100 * i, "data_id": id, "fields": [i], "comm_error": false,
                               "abs": abs, "abm": null, "alm": 1, "sf": 0, "sc": [i, i + 1]})
        };
        let mut list: Vec<Value> = (0..8).map(|i| answer(i, 0x0C, 10 + i)).collect();
        list.push(answer(8, 0x0C, 30)); // a ninth C begins the next operation
        list.push(answer(9, 1, 40));
        let out = emulator_entries("answers", &list);
        assert_eq!(out.len(), 3, "{out:?}");
        // The first operation: its start (index, cycle) from the first answer, its results from the eighth.
        assert_eq!(
            (out[0]["index"].as_u64(), out[0]["cycle"].as_u64()),
            (Some(0), Some(0))
        );
        assert_eq!(
            (
                out[0]["abs"].as_u64(),
                out[0]["sc1"].as_u64(),
                out[0]["sc2"].as_u64()
            ),
            (Some(17), Some(7), Some(8))
        );
        assert_eq!(out[0]["alm1"].as_u64(), Some(1));
        assert_eq!(out[0]["received"], serde_json::json!([7]));
        assert!(
            out[0].get("abm").is_none()
                && out[0].get("alm").is_none()
                && out[0].get("device").is_none()
        );
        assert_eq!(
            (out[1]["index"].as_u64(), out[1]["abs"].as_u64()),
            (Some(8), Some(30))
        );
        assert_eq!(
            (out[2]["data_id"].as_u64(), out[2]["abs"].as_u64()),
            (Some(1), Some(40))
        );
    }
}
