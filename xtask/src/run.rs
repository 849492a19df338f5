//! Running the stages: each on a thread of its own, its output to
//! `build/test/<name>.log`, printed whole when it ends (one stage at a
//! time, so two stages' lines never interleave), with its wall time, its
//! CPU seconds and the load; then the table of every stage and the verdict.

use std::fs::{self, File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::mpsc;
use std::thread;
use std::time::Instant;

use crate::plan::Stage;
use crate::schedule::{Board, Next};

/// How one stage ended.
#[derive(Debug, Clone)]
pub struct Ended {
    /// Wall seconds.
    pub wall_s: f64,
    /// User + system seconds of the stage and of every process it waited for.
    pub cpu_s: Option<f64>,
    /// Its exit status (128 + the signal when a signal ended it).
    pub status: i32,
}

impl Ended {
    fn passed(&self) -> bool {
        self.status == 0
    }
}

/// Where the logs and the table go.
pub struct Logs {
    dir: PathBuf,
}

impl Logs {
    /// `dir`, emptied.
    pub fn fresh(dir: &Path) -> io::Result<Self> {
        if dir.exists() {
            fs::remove_dir_all(dir)?;
        }
        fs::create_dir_all(dir)?;
        File::create(dir.join("times.txt"))?;
        Ok(Logs {
            dir: dir.to_path_buf(),
        })
    }

    fn log(&self, name: &str) -> PathBuf {
        self.dir.join(format!("{name}.log"))
    }

    /// Prints the stage's header and log, and adds its row to `times.txt`.
    fn report(&self, name: &str, ended: &Ended) -> io::Result<()> {
        let cpu = ended.cpu_s.map_or("-".to_string(), |c| format!("{c:.1}"));
        let verdict = if ended.passed() {
            "passed".to_string()
        } else {
            format!("FAILED, exit {}", ended.status)
        };
        let text = fs::read_to_string(self.log(name)).unwrap_or_default();
        let mut out = io::stdout().lock();
        writeln!(
            out,
            "==== stage {name} ({:.1} s, cpu {cpu} s, {verdict})",
            ended.wall_s
        )?;
        out.write_all(text.as_bytes())?;
        out.flush()?;
        let mut times = OpenOptions::new()
            .append(true)
            .open(self.dir.join("times.txt"))?;
        writeln!(
            times,
            "{name:<12} {:>8.1} s  cpu {cpu:>8} s  load {:>5}  {}",
            ended.wall_s,
            load(),
            if ended.passed() { "passed" } else { "FAILED" }
        )
    }
}

/// The 1-minute load average, as /proc/loadavg says it.
fn load() -> String {
    fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|l| l.split_whitespace().next().map(str::to_string))
        .unwrap_or_else(|| "-".to_string())
}

/// Runs `argv` from `root` with its output in `log`; waits for it with
/// wait4(2), whose resource usage is the stage's own CPU time even while
/// other stages run beside it.
pub fn run_stage(root: &Path, argv: &[&str], log: &Path) -> Ended {
    let started = Instant::now();
    let failed = |msg: String| {
        let _ = fs::write(log, format!("{msg}\n"));
        Ended {
            wall_s: started.elapsed().as_secs_f64(),
            cpu_s: None,
            status: 127,
        }
    };
    let out = match File::create(log) {
        Ok(f) => f,
        Err(e) => return failed(format!("cannot write {}: {e}", log.display())),
    };
    let err = match out.try_clone() {
        Ok(f) => f,
        Err(e) => return failed(format!("cannot write {}: {e}", log.display())),
    };
    let child = Command::new(argv[0])
        .args(&argv[1..])
        .current_dir(root)
        .stdout(out)
        .stderr(err)
        .spawn();
    let child = match child {
        Ok(c) => c,
        Err(e) => return failed(format!("cannot start `{}`: {e}", argv.join(" "))),
    };
    let pid = child.id() as libc::pid_t;
    let mut status: libc::c_int = 0;
    // SAFETY: rusage is plain data that wait4 fills in; it is zeroed first.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let waited = loop {
        // SAFETY: pid is our own child, not yet reaped (std's Child is never
        // waited on); status and usage are valid for writing.
        let r = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
        if r == -1 && io::Error::last_os_error().kind() == io::ErrorKind::Interrupted {
            continue;
        }
        break r;
    };
    let wall_s = started.elapsed().as_secs_f64();
    if waited != pid {
        return Ended {
            wall_s,
            cpu_s: None,
            status: 127,
        };
    }
    let secs = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 / 1e6;
    let status = if libc::WIFEXITED(status) {
        libc::WEXITSTATUS(status)
    } else if libc::WIFSIGNALED(status) {
        128 + libc::WTERMSIG(status)
    } else {
        1
    };
    Ended {
        wall_s,
        cpu_s: Some(secs(usage.ru_utime) + secs(usage.ru_stime)),
        status,
    }
}

/// Runs every stage of `board` on `jobs` workers; true when all passed.
pub fn run_all(root: &Path, logs: &Logs, mut board: Board, jobs: usize) -> io::Result<bool> {
    let (tx, rx) = mpsc::channel::<(usize, Ended)>();
    let mut running = 0;
    let mut all_passed = true;
    loop {
        while running < jobs {
            match board.next() {
                Some(Next::Run(i)) => {
                    let stage: Stage = board.stages()[i];
                    let (root, log, tx) = (root.to_path_buf(), logs.log(stage.name), tx.clone());
                    thread::spawn(move || {
                        let ended = run_stage(&root, stage.argv, &log);
                        // The receiver lives until every stage has ended.
                        let _ = tx.send((i, ended));
                    });
                    running += 1;
                }
                Some(Next::Skip(i, before)) => {
                    let name = board.stages()[i].name;
                    fs::write(
                        logs.log(name),
                        format!("{name}: not run, the {before} stage failed\n"),
                    )?;
                    logs.report(
                        name,
                        &Ended {
                            wall_s: 0.0,
                            cpu_s: None,
                            status: 1,
                        },
                    )?;
                    all_passed = false;
                }
                None => break,
            }
        }
        if running == 0 {
            break;
        }
        let (i, ended) = rx.recv().expect("a stage thread ended without reporting");
        running -= 1;
        board.end(i, ended.passed());
        all_passed &= ended.passed();
        logs.report(board.stages()[i].name, &ended)?;
    }
    debug_assert!(board.finished());
    Ok(all_passed)
}

/// The lines of a failed stage's log worth repeating at the end.
pub fn failure_lines(log: &str) -> Vec<&str> {
    const MARKS: &[&str] = &[
        "FAIL",
        "panicked",
        "assertion",
        "left:",
        "right:",
        "error",
        "below",
        "MISMATCH",
    ];
    log.lines()
        .filter(|l| MARKS.iter().any(|m| l.contains(m)))
        .take(20)
        .collect()
}

/// Prints the table of stage times, the total and the verdict; repeats the
/// end of each failed stage's log last, so that a reader who sees only the
/// tail of the output (a CI summary) still sees the cause.
pub fn summary(logs: &Logs, total_s: f64, passed: bool) -> io::Result<()> {
    let times = fs::read_to_string(logs.dir.join("times.txt"))?;
    let mut out = io::stdout().lock();
    writeln!(out)?;
    writeln!(out, "==== stage times (wall clock, stages overlap; CPU seconds; the 1-minute load average at the stage's end)")?;
    out.write_all(times.as_bytes())?;
    let loads = fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let loads: Vec<&str> = loads.split_whitespace().take(3).collect();
    writeln!(
        out,
        "{:<12} {total_s:>8.1} s  load {}",
        "total",
        loads.join(" ")
    )?;
    let failed = times.lines().filter(|r| r.ends_with("FAILED")).count();
    let ran = times.lines().count();
    if passed {
        writeln!(out, "make test: all checks passed")?;
        // The plain closing line CI reads: stages, not tests.
        writeln!(out, "stages: {ran} passed, 0 failed")?;
        return Ok(());
    }
    for row in times.lines().filter(|r| r.ends_with("FAILED")) {
        let name = row.split_whitespace().next().unwrap_or_default();
        let log = fs::read_to_string(logs.log(name)).unwrap_or_default();
        writeln!(out, "==== the failed stage {name}: its failure lines, then its last lines (whole log: build/test/{name}.log)")?;
        for l in failure_lines(&log) {
            writeln!(out, "{l}")?;
        }
        writeln!(out, "----")?;
        let lines: Vec<&str> = log.lines().collect();
        for l in &lines[lines.len().saturating_sub(8)..] {
            writeln!(out, "{l}")?;
        }
    }
    writeln!(out, "stages: {} passed, {failed} failed", ran - failed)?;
    out.flush()?;
    eprintln!("make test: FAILED (see the stages marked FAILED above; logs in build/test/)");
    Ok(())
}
