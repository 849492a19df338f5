//! The testbenches can fail: vectors with one expected bit flipped must stop
//! the replay with a mismatch in Icarus and in Verilator, a masked bit must
//! not, an output change the file does not expect stops it at its cycle,
//! and a truncated vector file is refused. Needs the simulators that
//! `make deps` installs.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use tbgen::vectors::VectorFile;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// Runs scripts/sim.sh and returns (passed, output). Verilator runs on the
/// coverage build of the file's parameter set, the one `make test`'s
/// replays (`COVERAGE=1 scripts/regress.sh`) build and reuse, so that these
/// replays cost no build of their own; their counts go beside the vector
/// file (every one here is a copy in a temporary folder), not into
/// build/coverage/, so the coverage report stays that of the committed files.
fn simulate(core: &str, sim: &str, vectors: &Path) -> (bool, String) {
    let out = Command::new(root().join("scripts/sim.sh"))
        .args([core, sim, vectors.to_str().unwrap()])
        .env("COVERAGE", "1")
        .env("COVERAGE_FILE", vectors.with_extension("dat"))
        .output()
        .expect("scripts/sim.sh runs (make deps installs the simulators)");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.success(), text)
}

/// Rewrites word `word` of record `record` with `f`.
fn edit(text: &str, record: usize, word: usize, f: impl Fn(u64) -> u64) -> String {
    let mut seen = 0;
    let mut out = String::new();
    for line in text.lines() {
        if !line.starts_with("//") {
            if seen == record {
                let mut words: Vec<String> = line.split_whitespace().map(String::from).collect();
                let width = words[word].len();
                let value = u64::from_str_radix(&words[word], 16).unwrap();
                words[word] = format!("{:0width$x}", f(value));
                out.push_str(&words.join(" "));
                out.push('\n');
                seen += 1;
                continue;
            }
            seen += 1;
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}

const CORE: &str = "ssi_master";
const SCENARIO: &str = "ssi_seed_12bit";
/// Word layout of an ssi_master record: cycle, 2 inputs, then (expected, mask) per output.
const O_SSI_CLK: usize = 3;
const O_POSITION: usize = 3 + 2 * 3;

fn golden() -> String {
    fs::read_to_string(root().join(format!("vectors/{CORE}/{SCENARIO}.hex"))).unwrap()
}

/// The first record with o_done set: the one whose o_position is checked.
fn done_record(text: &str) -> usize {
    let v = VectorFile::parse(text).unwrap();
    v.records
        .iter()
        .position(|r| r[3 + 2 * 2] == 1)
        .expect("a done record")
}

#[test]
fn golden_vectors_pass_and_one_flipped_expected_bit_fails_in_both_simulators() {
    let dir = tempfile::tempdir().unwrap();
    let text = golden();
    let done = done_record(&text);
    let cases = [
        ("golden", text.clone(), true),
        (
            "o_ssi_clk flipped",
            edit(&text, 40, O_SSI_CLK, |v| v ^ 1),
            false,
        ),
        (
            "o_position bit 0 flipped",
            edit(&text, done, O_POSITION, |v| v ^ 1),
            false,
        ),
        (
            "o_position bit 0 flipped but masked",
            edit(
                &edit(&text, done, O_POSITION, |v| v ^ 1),
                done,
                O_POSITION + 1,
                |m| m & !1,
            ),
            true,
        ),
    ];
    for sim in ["icarus", "verilator"] {
        for (i, (what, vectors, should_pass)) in cases.iter().enumerate() {
            let path = dir.path().join(format!("{SCENARIO}_{i}.hex"));
            fs::write(&path, vectors).unwrap();
            let (passed, output) = simulate(CORE, sim, &path);
            assert_eq!(passed, *should_pass, "{sim}, {what}:\n{output}");
            if !should_pass {
                assert!(
                    output.contains("MISMATCH at cycle"),
                    "{sim}, {what}: no mismatch report:\n{output}"
                );
                assert!(
                    output.contains("expected") && output.contains("actual"),
                    "{output}"
                );
            }
        }
    }
}

/// Removes record `record` (its cycle's expectation becomes the record
/// before it) and returns the file, with its `records:` header one lower.
fn drop_record(text: &str, record: usize) -> String {
    let mut seen = 0;
    let mut out = String::new();
    for line in text.lines() {
        if let Some(n) = line.strip_prefix("// records: ") {
            out.push_str(&format!(
                "// records: {}\n",
                n.trim().parse::<usize>().unwrap() - 1
            ));
            continue;
        }
        if !line.starts_with("//") {
            seen += 1;
            if seen - 1 == record {
                continue;
            }
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}

/// The player compares a cycle only when an output or the record changed
/// (vector_player.vh; Icarus sleeps until then, Verilator looks at each
/// falling edge). With a record removed whose inputs are the record
/// before's, the core's output changes in a cycle where the file expects
/// the old value: both simulators must stop at exactly that cycle.
#[test]
fn an_output_change_the_file_does_not_expect_fails_at_its_cycle_in_both_simulators() {
    let dir = tempfile::tempdir().unwrap();
    let text = golden();
    let v = VectorFile::parse(&text).unwrap();
    const N_IN: usize = 2;
    // Records well inside the file (the core counting through a frame)
    // where only expected outputs change.
    let dropped: Vec<usize> = (20..v.records.len() - 1)
        .filter(|&r| v.records[r][1..=N_IN] == v.records[r - 1][1..=N_IN])
        .step_by(7)
        .take(3)
        .collect();
    assert_eq!(
        dropped.len(),
        3,
        "{SCENARIO} has records where only outputs change"
    );
    for sim in ["icarus", "verilator"] {
        for &r in &dropped {
            let path = dir.path().join(format!("{SCENARIO}_drop{r}.hex"));
            fs::write(&path, drop_record(&text, r)).unwrap();
            let (passed, output) = simulate(CORE, sim, &path);
            assert!(!passed, "{sim} passed with record {r} removed:\n{output}");
            let want = format!("MISMATCH at cycle {} ", v.records[r][0]);
            assert!(
                output.contains(&want),
                "{sim}, record {r} removed: no '{want}':\n{output}"
            );
        }
    }
}

/// A file cut short or out of order is refused: five records gone, by
/// sim.sh against the header's count; the last record's last words gone
/// (Verilator would read them as 0, a mask comparing nothing), by sim.sh
/// with the record's line; a record repeated in place of the last (the
/// count still right), by the player, whose cycle stamps must increase.
#[test]
fn a_vector_file_shorter_than_its_record_count_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let text = golden();
    let lines: Vec<&str> = text.lines().collect();
    let joined = |ls: &[&str]| ls.iter().map(|l| format!("{l}\n")).collect::<String>();
    let records_cut = joined(&lines[..lines.len() - 5]);
    let (last, rest) = lines.split_last().unwrap();
    let words_cut = joined(rest) + &last.split(' ').take(10).collect::<Vec<_>>().join(" ") + "\n";
    let first_record = lines.iter().position(|l| !l.starts_with("//")).unwrap();
    let repeated = joined(
        &[
            &lines[..first_record + 3],
            &lines[first_record + 2..lines.len() - 1],
        ]
        .concat(),
    );
    let cases = [
        ("records_cut", records_cut, "but the file holds".to_string()),
        (
            "words_cut",
            words_cut,
            format!("words_cut.hex:{}: a record of 10 words", lines.len()),
        ),
        (
            "repeated",
            repeated,
            "do not increase at record 3".to_string(),
        ),
    ];
    for (name, cut, says) in cases {
        refused_in_both_simulators(dir.path(), name, &cut, &[&says]);
    }
}

/// Writes `text` as `<name>.hex` in `dir` and replays it in Icarus and in
/// Verilator: each must fail with every one of `says` in its output.
fn refused_in_both_simulators(dir: &Path, name: &str, text: &str, says: &[&str]) {
    let path = dir.join(format!("{name}.hex"));
    fs::write(&path, text).unwrap();
    for sim in ["icarus", "verilator"] {
        let (passed, output) = simulate(CORE, sim, &path);
        assert!(!passed, "{sim} accepted {name}.hex:\n{output}");
        for s in says {
            assert!(
                output.contains(s),
                "{sim} ({name}.hex): no '{s}':\n{output}"
            );
        }
    }
}

/// Found by damaging a vector file's header: a huge `records:` made Icarus
/// abort on an array it could not size, a zero `f_sys_hz:` made sim.sh
/// divide by zero, and a parameter `BITS=x` reached the simulator. A damaged
/// header is refused before any simulator starts, naming the file, the
/// line and the fix.
#[test]
fn a_damaged_vector_header_is_refused_with_its_line_before_a_simulator_starts() {
    let dir = tempfile::tempdir().unwrap();
    let text = golden();
    let header = |key: &str| {
        text.lines()
            .position(|l| l.starts_with(&format!("// {key}: ")))
            .unwrap()
            + 1
    };
    let with = |key: &str, value: &str| {
        text.lines()
            .map(|l| {
                if l.starts_with(&format!("// {key}: ")) {
                    format!("// {key}: {value}\n")
                } else {
                    format!("{l}\n")
                }
            })
            .collect::<String>()
    };
    let cases = [
        ("records", with("records", "4000000000"), "the file holds"),
        ("f_sys_hz", with("f_sys_hz", "0"), "is not a clock"),
        (
            "words_per_record",
            with("words_per_record", "x"),
            "is not a word count",
        ),
        (
            "params",
            text.replace("BITS=12 ", "BITS=x "),
            "is not NAME=number",
        ),
    ];
    for (key, damaged, says) in cases {
        let want = format!(
            "{}:{}: {key}: ",
            dir.path().join(format!("{key}.hex")).display(),
            header(key)
        );
        refused_in_both_simulators(dir.path(), key, &damaged, &[&want, says]);
    }
}

/// The output columns of a vector file: (name, word index of its expected
/// value), read from the `record:` header (each output is followed by `mask`).
fn output_columns(v: &VectorFile) -> Vec<(String, usize)> {
    let layout: Vec<&str> = v
        .get("record")
        .unwrap()
        .split_whitespace()
        .filter(|w| *w != "|")
        .collect();
    layout
        .windows(2)
        .enumerate()
        .filter(|(_, pair)| pair[1] == "mask" && pair[0] != "mask")
        .map(|(i, pair)| (pair[0].split('[').next().unwrap().to_string(), i))
        .collect()
}

#[test]
fn every_testbench_checks_every_output_port_in_both_simulators() {
    // A testbench that forgot to compare one port would pass whatever that
    // port did. For each core, the smallest committed vector file is
    // replayed once per output port with bit 0 of that port's expected
    // value flipped in the earliest record after the first (cycle 0) in
    // which that bit is compared: both simulators must stop with a mismatch that names
    // that port. (The replay stops at the mismatch, so an early record keeps
    // these ~200 replays short: the middle record of a 19200-baud Modbus
    // file is 160 000 cycles in.)
    let dir = tempfile::tempdir().unwrap();
    let (mut cores, mut flips) = (0, 0);
    let mut core_dirs: Vec<PathBuf> = fs::read_dir(root().join("vectors"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .collect();
    core_dirs.sort();
    for core_dir in core_dirs {
        let core = core_dir.file_name().unwrap().to_str().unwrap().to_string();
        let smallest = fs::read_dir(&core_dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "hex"))
            .min_by_key(|p| fs::metadata(p).unwrap().len())
            .unwrap();
        let text = fs::read_to_string(&smallest).unwrap();
        let v = VectorFile::parse(&text).unwrap();
        let outputs = output_columns(&v);
        assert!(
            !outputs.is_empty(),
            "{core}: no outputs in {}",
            smallest.display()
        );
        for (name, word) in &outputs {
            let record = (1..v.records.len())
                .find(|&r| v.records[r][word + 1] & 1 == 1)
                .unwrap_or_else(|| {
                    panic!(
                        "{core}: {name} is masked in every record of {}",
                        smallest.display()
                    )
                });
            let path = dir.path().join(format!("{core}_{name}.hex"));
            fs::write(&path, edit(&text, record, *word, |x| x ^ 1)).unwrap();
            for sim in ["icarus", "verilator"] {
                let (passed, output) = simulate(&core, sim, &path);
                assert!(
                    !passed,
                    "{core} in {sim} passed with {name} flipped:\n{output}"
                );
                assert!(
                    output.contains(&format!("signal {name} ")),
                    "{core} in {sim}: the mismatch does not name {name}:\n{output}"
                );
                flips += 1;
            }
        }
        cores += 1;
    }
    println!("{cores} cores, {flips} flipped-bit replays, every one stopped by a mismatch naming its port");
    assert!(cores >= 6 && flips >= 200, "{cores} cores, {flips} replays");
}
