//! The plan is sound and the scheduler keeps both cores busy in the order
//! the plan means.

use super::*;
use plan::{Stage, DEPS, STAGES};
use schedule::Next;

fn names(stages: &[Stage]) -> Vec<&'static str> {
    stages.iter().map(|s| s.name).collect()
}

#[test]
fn every_prerequisite_is_a_stage_taken_before_it() {
    for (i, s) in STAGES.iter().enumerate() {
        for before in s.after {
            let at = STAGES.iter().position(|t| t.name == *before);
            assert!(
                matches!(at, Some(j) if j < i),
                "{} waits for {before}, which is not an earlier stage",
                s.name
            );
        }
    }
    let mut all = names(STAGES);
    all.push(DEPS.name);
    all.sort();
    all.dedup();
    assert_eq!(all.len(), STAGES.len() + 1, "two stages share a name");
}

#[test]
fn every_stage_command_exists() {
    let root = root();
    for s in std::iter::once(&DEPS).chain(STAGES) {
        let cmd = s
            .argv
            .iter()
            .find(|a| a.starts_with("scripts/") || a.starts_with(".venv/"))
            .unwrap_or(&s.argv[0]);
        if cmd.contains('/') && !cmd.starts_with(".venv/") {
            assert!(
                root.join(cmd).is_file(),
                "stage {}: {cmd} is not a file",
                s.name
            );
        }
    }
}

/// Runs the plan's scheduler on `jobs` simulated workers with the given
/// durations; returns each stage's (name, start time), in start order.
fn simulate(
    stages: Vec<Stage>,
    jobs: usize,
    secs: impl Fn(&str) -> u32,
    fails: &[&str],
) -> Vec<(&'static str, u32)> {
    let mut board = Board::new(stages);
    let mut now = 0;
    let mut running: Vec<(u32, usize)> = Vec::new();
    let mut started = Vec::new();
    loop {
        while running.len() < jobs {
            match board.next() {
                Some(Next::Run(i)) => {
                    let s = board.stages()[i];
                    started.push((s.name, now));
                    running.push((now + secs(s.name), i));
                }
                Some(Next::Skip(..)) => {}
                None => break,
            }
        }
        if running.is_empty() {
            break;
        }
        running.sort();
        let (t, i) = running.remove(0);
        now = t;
        let name = board.stages()[i].name;
        board.end(i, !fails.contains(&name));
    }
    assert!(board.finished());
    started
}

#[test]
fn the_replays_run_beside_the_build_and_the_cargo_tests_follow_it() {
    // Durations of a typical run, seconds.
    let secs = |n: &str| match n {
        "build" => 300,
        "cargo-test" => 200,
        "hdl" => 250,
        "cosim" => 150,
        "lint" => 20,
        _ => 20,
    };
    let started = simulate(STAGES.to_vec(), 2, secs, &[]);
    let at = |n: &str| started.iter().find(|(s, _)| *s == n).unwrap().1;
    assert_eq!(at("build"), 0);
    assert_eq!(at("lint"), 0, "lint starts beside the build");
    assert_eq!(at("hdl"), 20, "the replays follow lint on the other core");
    assert_eq!(
        at("cargo-test"),
        300,
        "the cargo tests start as soon as the build ends"
    );
    assert!(at("cosim") >= 300, "the closed loops need the build");
    // No core idles while a stage could start: the short checks that need
    // nothing fill the gap between the replays' end and the build's.
    assert_eq!(at("coverage"), 270);
    assert_eq!(at("gtkw"), 290, "{started:?}");
    assert_eq!(started.len(), STAGES.len());
}

#[test]
fn a_failed_prerequisite_stops_what_waits_for_it_and_nothing_else() {
    let started = simulate(STAGES.to_vec(), 2, |_| 10, &["build"]);
    let ran: Vec<&str> = started.iter().map(|(n, _)| *n).collect();
    for s in STAGES {
        let needs_build = s.after.contains(&"build");
        assert_eq!(ran.contains(&s.name), !needs_build, "{}", s.name);
    }
}

#[test]
fn only_takes_a_stage_with_what_it_waits_for() {
    let got = plan::select(&["coverage".to_string()]).unwrap();
    assert_eq!(names(&got), ["lint", "hdl", "coverage"]);
    let got = plan::select(&["cosim".to_string(), "fmt".to_string()]).unwrap();
    assert_eq!(names(&got), ["build", "cosim", "fmt"]);
    let err = plan::select(&["lnit".to_string()]).unwrap_err();
    assert!(
        err.contains("no stage `lnit`") && err.contains("lint, hdl"),
        "{err}"
    );
}

#[test]
fn the_command_line_is_read_or_refused_with_the_fix() {
    let a = |v: &[&str]| parse(&v.iter().map(|s| s.to_string()).collect::<Vec<_>>());
    assert_eq!(a(&["test"]).unwrap(), Args::default());
    assert_eq!(
        a(&["test", "--jobs", "3", "--only", "lint,hdl"]).unwrap(),
        Args {
            jobs: Some(3),
            only: vec!["lint".into(), "hdl".into()],
            list: false
        }
    );
    assert!(a(&["test", "--jobs", "0"])
        .unwrap_err()
        .contains("at least 1"));
    assert!(a(&["test", "--jobs"]).unwrap_err().contains("--jobs takes"));
    assert!(a(&["tset"]).unwrap_err().contains("unknown command `tset`"));
    assert!(a(&["test", "--fast"])
        .unwrap_err()
        .contains("unknown option `--fast`"));
}

#[test]
fn a_stage_reports_its_exit_status_and_cpu_seconds() {
    let dir = std::env::temp_dir().join(format!("xtask-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let log = dir.join("s.log");
    let ended = run::run_stage(
        &dir,
        &["sh", "-c", "echo hello; echo oops >&2; exit 3"],
        &log,
    );
    assert_eq!(ended.status, 3);
    assert!(ended.cpu_s.is_some());
    assert_eq!(std::fs::read_to_string(&log).unwrap(), "hello\noops\n");
    // A busy loop of about 0.3 s of CPU is counted as the stage's own.
    let ended = run::run_stage(
        &dir,
        &[
            "sh",
            "-c",
            "i=0; while [ $i -lt 200000 ]; do i=$((i+1)); done",
        ],
        &log,
    );
    assert_eq!(ended.status, 0);
    assert!(ended.cpu_s.unwrap() > 0.05, "{ended:?}");
    let ended = run::run_stage(&dir, &["no-such-command-here"], &log);
    assert_eq!(ended.status, 127);
    assert!(std::fs::read_to_string(&log)
        .unwrap()
        .contains("cannot start `no-such-command-here`"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn failure_lines_pick_the_cause() {
    let log = "compiling\ntest a ... ok\nthread 'x' panicked at y\nMISMATCH cycle 4\nok\n";
    assert_eq!(
        run::failure_lines(log),
        ["thread 'x' panicked at y", "MISMATCH cycle 4"]
    );
}
