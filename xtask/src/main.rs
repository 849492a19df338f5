//! The project's build as code. `make test` runs `xtask test`: the stages
//! of [`plan::STAGES`] after [`plan::DEPS`], two at a time (one per core),
//! each stage's log printed whole when it ends, then a table of every
//! stage's wall and CPU seconds (`build/test/times.txt`) and the verdict.
//!
//! ```text
//! xtask test [--jobs N] [--only STAGE[,STAGE...]]   run the stages (and what they wait for)
//! xtask test --list                                 the stages, in the order they are taken
//! xtask vector-header <core> <file.hex>             a vector file's header, checked, as shell variables
//! xtask vector-headers <file.hex>...                core, cycles and build of each file, one line each
//! ```
//!
//! Exit status: 0 when every stage passed, 1 when one failed, 2 for a bad
//! command line.

mod header;
mod plan;
mod run;
mod schedule;

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use schedule::Board;

const USAGE: &str = "usage: xtask test [--jobs N] [--only STAGE[,STAGE...]] | xtask test --list | xtask vector-header <core> <file.hex>";

/// The command line of `xtask test`.
#[derive(Debug, Default, PartialEq)]
struct Args {
    jobs: Option<usize>,
    only: Vec<String>,
    list: bool,
}

fn parse(args: &[String]) -> Result<Args, String> {
    let mut it = args.iter();
    match it.next().map(String::as_str) {
        Some("test") => {}
        Some(other) => return Err(format!("unknown command `{other}`; {USAGE}")),
        None => return Err(USAGE.to_string()),
    }
    let mut out = Args::default();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--list" => out.list = true,
            "--jobs" => {
                let v = it
                    .next()
                    .ok_or("--jobs takes a number of workers, e.g. --jobs 2")?;
                match v.parse::<usize>() {
                    Ok(n) if n >= 1 => out.jobs = Some(n),
                    _ => {
                        return Err(format!(
                            "--jobs takes a whole number of at least 1, not `{v}`"
                        ))
                    }
                }
            }
            "--only" => {
                let v = it
                    .next()
                    .ok_or("--only takes stage names, e.g. --only lint,hdl")?;
                out.only
                    .extend(v.split(',').filter(|s| !s.is_empty()).map(str::to_string));
            }
            other => return Err(format!("unknown option `{other}`; {USAGE}")),
        }
    }
    Ok(out)
}

/// The repository's root: this crate's parent folder.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the repository")
        .to_path_buf()
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("vector-header") => return header::main(&root(), &args[1..]),
        Some("vector-headers") => return header::summaries(&args[1..]),
        _ => {}
    }
    let args = match parse(&args) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("xtask: {e}");
            return ExitCode::from(2);
        }
    };
    let stages = match plan::select(&args.only) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("xtask: {e}");
            return ExitCode::from(2);
        }
    };
    if args.list {
        for s in std::iter::once(&plan::DEPS).chain(&stages) {
            let after = if s.after.is_empty() {
                String::new()
            } else {
                format!(" (after {})", s.after.join(", "))
            };
            println!("{:<12} {}{after}", s.name, s.what);
        }
        return ExitCode::SUCCESS;
    }
    match test(&root(), stages, args.jobs) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("xtask: {e}");
            ExitCode::from(1)
        }
    }
}

fn test(root: &Path, stages: Vec<plan::Stage>, jobs: Option<usize>) -> std::io::Result<bool> {
    // Every Verilator build of every stage through ccache (make deps
    // installs it): each build compiles Verilator's runtime again, which
    // ccache makes one compile per run, and a rerun reuses the rest.
    if std::env::var_os("OBJCACHE").is_none() && on_path("ccache") {
        std::env::set_var("OBJCACHE", "ccache");
    }
    let jobs = jobs.unwrap_or_else(|| std::thread::available_parallelism().map_or(2, |n| n.get()));
    let started = Instant::now();
    let logs = run::Logs::fresh(&root.join("build/test"))?;
    // The tools first, alone: every other stage needs them.
    let passed = run::run_all(root, &logs, Board::new(vec![plan::DEPS]), 1)?
        && run::run_all(root, &logs, Board::new(stages), jobs)?;
    run::summary(&logs, started.elapsed().as_secs_f64(), passed)?;
    Ok(passed)
}

fn on_path(tool: &str) -> bool {
    std::env::var_os("PATH")
        .map(|p| std::env::split_paths(&p).any(|d| d.join(tool).is_file()))
        .unwrap_or(false)
}

#[cfg(test)]
mod tests;
