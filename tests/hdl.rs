//! The testbenches can fail: vectors with one expected bit flipped must stop
//! the replay with a mismatch in Icarus and in Verilator, a masked bit must
//! not, and a truncated vector file is refused. Needs the simulators that
//! `make deps` installs.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use tbgen::vectors::VectorFile;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap().to_path_buf()
}

/// Runs scripts/sim.sh and returns (passed, output).
fn simulate(core: &str, sim: &str, vectors: &Path) -> (bool, String) {
    let out = Command::new(root().join("scripts/sim.sh"))
        .args([core, sim, vectors.to_str().unwrap()])
        .output()
        .expect("scripts/sim.sh runs (make deps installs the simulators)");
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
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
    v.records.iter().position(|r| r[3 + 2 * 2] == 1).expect("a done record")
}

#[test]
fn golden_vectors_pass_and_one_flipped_expected_bit_fails_in_both_simulators() {
    let dir = tempfile::tempdir().unwrap();
    let text = golden();
    let done = done_record(&text);
    let cases = [
        ("golden", text.clone(), true),
        ("o_ssi_clk flipped", edit(&text, 40, O_SSI_CLK, |v| v ^ 1), false),
        ("o_position bit 0 flipped", edit(&text, done, O_POSITION, |v| v ^ 1), false),
        ("o_position bit 0 flipped but masked", edit(&edit(&text, done, O_POSITION, |v| v ^ 1), done, O_POSITION + 1, |m| m & !1), true),
    ];
    for sim in ["icarus", "verilator"] {
        for (i, (what, vectors, should_pass)) in cases.iter().enumerate() {
            let path = dir.path().join(format!("{SCENARIO}_{i}.hex"));
            fs::write(&path, vectors).unwrap();
            let (passed, output) = simulate(CORE, sim, &path);
            assert_eq!(passed, *should_pass, "{sim}, {what}:\n{output}");
            if !should_pass {
                assert!(output.contains("MISMATCH at cycle"), "{sim}, {what}: no mismatch report:\n{output}");
                assert!(output.contains("expected") && output.contains("actual"), "{output}");
            }
        }
    }
}

#[test]
fn a_vector_file_shorter_than_its_record_count_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let text = golden();
    let cut: String = text.lines().take(text.lines().count() - 5).map(|l| format!("{l}\n")).collect();
    let path = dir.path().join("short.hex");
    fs::write(&path, cut).unwrap();
    for sim in ["icarus", "verilator"] {
        let (passed, output) = simulate(CORE, sim, &path);
        assert!(!passed, "{sim} accepted a truncated file:\n{output}");
        assert!(output.contains("fewer than"), "{sim}: {output}");
    }
}
