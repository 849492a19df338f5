//! A long `tbgen gen` as a user meets it: interrupted with Ctrl-C it leaves
//! nothing behind in `--out` (no hidden `.partial` file, no folder it made)
//! and dies of the signal as interrupted tools do; asked with `--progress`
//! it says how far it is, how big the waveform will be and how long is
//! left; not asked, with stderr not a terminal, it says nothing there.

use std::fs;
use std::io::{BufRead, BufReader};
use std::os::unix::process::ExitStatusExt;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// EnDat position reads at the slowest clock the seed allows (100 kHz),
/// `repeat` times: about 92,000 cycles of a 64 MHz system clock a read.
fn long_scenario(dir: &Path, repeat: u32) -> std::path::PathBuf {
    let path = dir.join("long.toml");
    fs::write(
        &path,
        format!(
            "name = \"long_100khz\"\n[endat]\nf_sys_mhz = 64\n[endat.master]\nclock_khz = 100\n\
             [[endat.commands]]\ncommand = \"pos21\"\nrepeat = {repeat}\n"
        ),
    )
    .unwrap();
    path
}

fn gen(scenario: &Path, out: &Path, extra: &[&str]) -> Child {
    Command::new(env!("CARGO_BIN_EXE_tbgen"))
        .arg("gen")
        .arg(scenario)
        .arg("--out")
        .arg(out)
        .args(extra)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("tbgen starts")
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .map(|d| {
            d.map(|e| e.unwrap().file_name().into_string().unwrap())
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

fn interrupt(child: &Child, signal: &str) {
    let ok = Command::new("kill")
        .arg(format!("-{signal}"))
        .arg(child.id().to_string())
        .status()
        .unwrap()
        .success();
    assert!(ok, "kill -{signal} {}", child.id());
}

/// Ctrl-C (SIGINT) and SIGTERM halfway through writing: the folder the user
/// gave holds what it held before, the folder tbgen made inside it is gone,
/// and the process ended by the signal (the shell's 130 and 143).
#[test]
fn an_interrupted_gen_leaves_nothing_in_out_and_dies_of_the_signal() {
    for (signal, number) in [("INT", 2), ("TERM", 15)] {
        let dir = tempfile::tempdir().unwrap();
        let scenario = long_scenario(dir.path(), 99_999);
        let users = dir.path().join("out");
        fs::create_dir(&users).unwrap();
        fs::write(users.join("notes.txt"), "mine").unwrap();
        let out = users.join("new");
        let mut child = gen(&scenario, &out, &[]);
        // Interrupted while the waveform is being written: its hidden
        // temporary file is there.
        let started = Instant::now();
        let partial = out.join(".long_100khz.vcd.partial");
        while !partial.exists() {
            assert!(
                started.elapsed() < Duration::from_secs(60),
                "no {} after a minute",
                partial.display()
            );
            assert!(child.try_wait().unwrap().is_none(), "tbgen ended early");
            std::thread::sleep(Duration::from_millis(20));
        }
        std::thread::sleep(Duration::from_millis(300));
        interrupt(&child, signal);
        let status = child.wait().unwrap();
        assert_eq!(
            status.signal(),
            Some(number),
            "SIG{signal}: tbgen ended with {status}, not by the signal"
        );
        assert_eq!(
            names(&users),
            vec!["notes.txt"],
            "SIG{signal}: left behind in --out's folder"
        );
    }
}

/// `--progress` with stderr piped (a log): a line with the share done, the
/// waveform's size at the end and the time left, once the run's length is
/// counted. Without it, stderr stays empty.
#[test]
fn progress_is_shown_when_asked_and_only_then() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = long_scenario(dir.path(), 600);
    let mut child = gen(&scenario, &dir.path().join("a"), &["--progress"]);
    let lines: Vec<String> = BufReader::new(child.stderr.take().unwrap())
        .lines()
        .map(Result::unwrap)
        .collect();
    assert!(child.wait().unwrap().success());
    let estimate = lines.iter().find(|l| {
        l.contains(" % (") && l.contains("VCD") && l.contains("of about") && l.ends_with(" left")
    });
    assert!(
        estimate.is_some_and(|l| l.starts_with("tbgen: long_100khz: ")),
        "no progress line with an estimate in {lines:?}"
    );

    let quiet = gen(&scenario, &dir.path().join("b"), &[])
        .wait_with_output()
        .unwrap();
    assert!(quiet.status.success());
    assert_eq!(String::from_utf8_lossy(&quiet.stderr), "");
}
