//! The whole flow from scenario to files, checked from outside: every
//! built-in scenario's four files are read back by independent readers, a
//! small scenario's outputs are pinned by snapshots, and bad input is refused
//! with a message and no output.

use std::collections::HashMap;
use std::fs;
use std::path::Path;
use std::process::Command;

use tbgen::vectors::VectorFile;
use tbgen::{builtin, generate};

fn tbgen() -> Command {
    Command::new(env!("CARGO_BIN_EXE_tbgen"))
}

/// Reads a VCD with the `vcd` crate's parser: checks that every change names a
/// declared id with a value of the declared width and that time strictly
/// increases; returns each signal's full name and width.
fn check_with_vcd_crate(path: &Path) -> HashMap<String, u32> {
    let file = std::io::BufReader::new(fs::File::open(path).unwrap());
    let mut parser = vcd::Parser::new(file);
    let header = parser.parse_header().expect("VCD header parses");
    let mut widths = HashMap::new();
    let mut names = HashMap::new();
    fn walk(
        items: &[vcd::ScopeItem],
        prefix: &str,
        widths: &mut HashMap<vcd::IdCode, u32>,
        names: &mut HashMap<String, u32>,
    ) {
        for item in items {
            match item {
                vcd::ScopeItem::Scope(s) => walk(
                    &s.items,
                    &format!("{prefix}{}.", s.identifier),
                    widths,
                    names,
                ),
                vcd::ScopeItem::Var(v) => {
                    assert!(
                        widths.insert(v.code, v.size).is_none(),
                        "id {} declared twice",
                        v.code
                    );
                    if v.size > 1 {
                        assert_eq!(
                            v.index,
                            Some(vcd::ReferenceIndex::Range(v.size as i32 - 1, 0)),
                            "{} needs [msb:lsb]",
                            v.reference
                        );
                    }
                    names.insert(format!("{prefix}{}", v.reference), v.size);
                }
                _ => {}
            }
        }
    }
    walk(&header.items, "", &mut widths, &mut names);
    let mut last_time: Option<u64> = None;
    let mut changes = 0u64;
    for command in parser {
        match command.expect("VCD body parses") {
            vcd::Command::Timestamp(t) => {
                assert!(
                    last_time.is_none_or(|l| t > l),
                    "time {t} after {last_time:?}"
                );
                last_time = Some(t);
            }
            vcd::Command::ChangeScalar(id, _) => {
                assert_eq!(
                    widths.get(&id),
                    Some(&1),
                    "scalar change of undeclared or vector id {id}"
                );
                changes += 1;
            }
            vcd::Command::ChangeVector(id, v) => {
                assert_eq!(
                    widths.get(&id).copied(),
                    Some(v.len() as u32),
                    "vector change of id {id} with the wrong width"
                );
                changes += 1;
            }
            _ => {}
        }
    }
    assert!(changes > 0 && last_time.is_some());
    names
}

#[test]
fn every_builtin_scenario_writes_four_files_that_independent_readers_accept() {
    let dir = tempfile::tempdir().unwrap();
    for scenario in builtin::all().unwrap() {
        let summary = generate::generate(&scenario, dir.path()).unwrap();
        assert_eq!(summary.files.len(), 4);
        for f in &summary.files {
            assert!(f.exists(), "{} missing", f.display());
        }

        // Vectors: the header agrees with the body.
        let text = fs::read_to_string(&summary.files[0]).unwrap();
        let v = VectorFile::parse(&text).unwrap();
        assert_eq!(
            v.get("records").unwrap().parse::<usize>().unwrap(),
            v.records.len()
        );
        let words: usize = v.get("words_per_record").unwrap().parse().unwrap();
        assert!(v.records.iter().all(|r| r.len() == words));
        assert_eq!(v.records[0][0], 0, "first record at cycle 0");
        let cycles: u64 = v.get("cycles").unwrap().parse().unwrap();
        assert_eq!(
            v.records.last().unwrap()[0],
            cycles - 1,
            "last record at the last cycle"
        );
        assert!(
            v.records.windows(2).all(|w| w[0][0] < w[1][0]),
            "cycle stamps increase"
        );

        // Waveform, reader 1: the vcd crate.
        let declared = check_with_vcd_crate(&summary.files[1]);

        // Waveform, reader 2: wellen, an independent parser (the one Surfer uses).
        let mut wave = wellen::simple::read(&summary.files[1]).expect("wellen reads the VCD");
        let h = wave.hierarchy();
        let mut seen = 0;
        let (pulse_names, value_name, value_field) = tbgen::registry::by_core(scenario.core())
            .expect("a registered core")
            .transaction_signals;
        let mut pulse_refs = Vec::new();
        let mut value_ref = None;
        for var_ref in h.all_vars() {
            let var = &h[var_ref];
            let name = var.full_name(h);
            let width = var.length(h).expect("bit vector");
            assert_eq!(
                declared.get(&name),
                Some(&width),
                "{name}: wellen and vcd disagree on width"
            );
            if width > 1 {
                let index = var.index().expect("vectors carry [msb:lsb]");
                assert_eq!((index.msb(), index.lsb()), (width as i64 - 1, 0), "{name}");
            }
            if pulse_names
                .iter()
                .any(|p| name == format!("top.{}.{p}", scenario.core()))
            {
                pulse_refs.push(var.signal_ref());
            }
            if name == format!("top.{}.{value_name}", scenario.core()) {
                value_ref = Some(var.signal_ref());
            }
            seen += 1;
        }
        assert_eq!(seen, declared.len());
        assert!(
            wave.time_table().windows(2).all(|w| w[0] < w[1]),
            "wellen: time strictly increasing"
        );

        // The transcript and the waveform tell the same story: one result
        // pulse per transaction, and the result port at each pulse holds the
        // transcript's value.
        let transcript: serde_json::Value =
            serde_json::from_str(&fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
        let transactions = transcript["transactions"].as_array().unwrap();
        assert_eq!(
            pulse_refs.len(),
            pulse_names.len(),
            "{}: result pulses not all in the VCD",
            scenario.name
        );
        let value_ref = value_ref.expect("result port in the VCD");
        let mut load = pulse_refs.clone();
        load.push(value_ref);
        wave.load_signals(&load);
        let mut rises: Vec<_> = pulse_refs
            .iter()
            .flat_map(|r| {
                let signal = wave.get_signal(*r).unwrap();
                signal
                    .iter_changes()
                    .filter(|(_, v)| v.to_bit_string().as_deref() == Some("1"))
                    .map(|(t, _)| t)
                    .collect::<Vec<_>>()
            })
            .collect();
        rises.sort();
        assert_eq!(
            rises.len(),
            transactions.len(),
            "{}: result pulses vs transactions",
            scenario.name
        );
        let value = wave.get_signal(value_ref).unwrap();
        for (t, tr) in rises.iter().zip(transactions) {
            if let Some(expected) = tr[value_field].as_u64() {
                let offset = value.get_offset(*t).unwrap();
                let bits = value.get_value_at(&offset, 0).to_bit_string().unwrap();
                assert_eq!(
                    u64::from_str_radix(&bits, 2).unwrap(),
                    expected,
                    "{}",
                    scenario.name
                );
            }
        }
    }
}

#[test]
fn a_small_scenarios_vectors_transcript_and_layout_are_pinned() {
    // A change here means the model, the vector format or the layout changed:
    // review the new snapshot and regenerate vectors/ with `make vectors`.
    let dir = tempfile::tempdir().unwrap();
    let scenario = builtin::find("ssi_monoflop_violation").unwrap();
    let summary = generate::generate(&scenario, dir.path()).unwrap();
    insta::assert_snapshot!(
        "ssi_monoflop_violation.hex",
        fs::read_to_string(&summary.files[0]).unwrap()
    );
    insta::assert_snapshot!(
        "ssi_monoflop_violation.json",
        fs::read_to_string(&summary.files[2]).unwrap()
    );
    insta::assert_snapshot!(
        "ssi_monoflop_violation.gtkw",
        fs::read_to_string(&summary.files[3]).unwrap()
    );
}

const GOOD: &str =
    "name = \"bad\"\n[ssi]\npositions = [1]\n[ssi.master]\nbits = 12\nclock_khz = 250\n";

fn gen_file(text: &str) -> (std::process::Output, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("bad.toml");
    fs::write(&file, text).unwrap();
    let out = dir.path().join("out");
    fs::create_dir(&out).unwrap();
    // A file from an earlier run that a failed run must not touch.
    fs::write(out.join("bad.hex"), "earlier run\n").unwrap();
    let result = tbgen()
        .args([
            "gen",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    (result, dir)
}

#[test]
fn a_bad_scenario_file_is_refused_with_file_line_and_field_exit_2_and_nothing_written() {
    for (broken, line, field) in [
        (GOOD.replace("250", "300"), 6, "master.clock_khz"),
        (GOOD.replace("clock_khz", "clock_hz"), 6, "clock_hz"),
        (GOOD.replace("bits = 12", "bits = \"twelve\""), 5, "bits"),
        (
            GOOD.replace("positions = [1]", "positions = [9999]"),
            3,
            "positions[0]",
        ),
    ] {
        let (result, dir) = gen_file(&broken);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(2), "{stderr}");
        assert!(
            stderr.contains(&format!("bad.toml:{line}")),
            "no line {line} in: {stderr}"
        );
        assert!(stderr.contains(field), "no field {field} in: {stderr}");
        let out = dir.path().join("out");
        let left: Vec<_> = fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(left, vec![std::ffi::OsString::from("bad.hex")], "{stderr}");
        assert_eq!(
            fs::read_to_string(out.join("bad.hex")).unwrap(),
            "earlier run\n"
        );
    }
}

#[test]
fn a_good_scenario_file_replaces_earlier_outputs() {
    let (result, dir) = gen_file(GOOD);
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    let out = dir.path().join("out");
    assert!(fs::read_to_string(out.join("bad.hex"))
        .unwrap()
        .starts_with("// tbgen-vectors 1"));
    for ext in ["vcd", "json", "gtkw"] {
        assert!(out.join(format!("bad.{ext}")).exists());
    }
    assert!(fs::read_dir(&out).unwrap().all(|e| !e
        .unwrap()
        .file_name()
        .to_string_lossy()
        .ends_with(".partial")));
}

#[test]
fn tbgen_crc_prints_the_seed_biss_example_and_its_wire_bits() {
    // Seed 001, BiSS-C: data 1000101011100011, nE 1, nW 0 -> CRC 110101, sent inverted 001010.
    let out = tbgen()
        .args(["crc", "biss-crc6", "100010101110001110"])
        .output()
        .unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(out.status.success());
    assert!(text.contains("crc:       0x35 (110101)"), "{text}");
    assert!(text.contains("wire:      001010"), "{text}");
}

#[test]
fn tbgen_refuses_unknown_names_with_status_2() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().to_str().unwrap();
    let missing = dir.path().join("missing.vcd");
    for (args, says) in [
        (vec!["crc", "crc-99", "0101"], "no CRC algorithm `crc-99`"),
        (vec!["crc", "biss-crc6", "01x1"], "bits `01x1`"),
        (
            vec!["gen", "no_such_scenario", "--out", "x"],
            "no scenario `no_such_scenario`",
        ),
        (
            vec!["list", "no_such_protocol"],
            "list: no protocol `no_such_protocol`; give one of: ssi,",
        ),
        // A path that is a folder, or missing: bad input like the rest, in words.
        (vec!["decode", "ssi", folder], "is a folder; give a file"),
        (
            vec!["decode", "ssi", missing.to_str().unwrap()],
            "no such capture file",
        ),
    ] {
        let out = tbgen().args(&args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}

#[test]
fn tbgen_list_takes_a_protocol() {
    let out = tbgen().args(["list", "endat"]).output().unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(out.status.success());
    assert!(text.lines().count() > 10, "{text}");
    assert!(text.lines().all(|l| l.contains("endat_master")), "{text}");
}

#[test]
fn a_scenario_without_a_name_is_told_where_the_name_goes() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("noname.toml");
    let text = fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenarios/endat/pos22_ad_8mhz_100m.toml"
    ))
    .unwrap();
    fs::write(
        &file,
        text.lines()
            .filter(|l| !l.starts_with("name"))
            .collect::<Vec<_>>()
            .join("\n"),
    )
    .unwrap();
    let out = tbgen()
        .args(["gen", file.to_str().unwrap(), "--out"])
        .arg(dir.path().join("out"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains(
            "missing field `name`; add `name = \"my_scenario\"` above the protocol's table"
        ),
        "{err}"
    );
    assert!(
        !err.contains("field `#"),
        "the comment line is named as a field: {err}"
    );
}

#[test]
fn every_subcommand_help_shows_an_example() {
    for sub in ["list", "gen", "crc", "bench"] {
        let out = tbgen().args([sub, "--help"]).output().unwrap();
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(text.contains("Example"), "tbgen {sub} --help: {text}");
    }
}

#[test]
fn output_into_a_closed_pipe_ends_quietly_without_a_panic() {
    use std::process::Stdio;
    // The reader closes its end before tbgen writes: every write fails with
    // a broken pipe, as it does under `tbgen decode ... | head -1`.
    let mut child = tbgen()
        .args([
            "decode",
            "endat",
            concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../vectors/endat_master/endat_pos22_ad_8mhz_100m.vcd"
            ),
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !stderr.contains("panicked"),
        "tbgen panicked on a closed pipe: {stderr}"
    );
    assert!(
        out.status.success(),
        "status {:?}, stderr {stderr}",
        out.status
    );
}
