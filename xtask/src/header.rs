//! `xtask vector-header <core> <file.hex>`: a vector file's header, read
//! and checked by [`vectorfile::Replay`] (the reader beside the writer), as
//! shell variables for `scripts/sim.sh`, which builds and runs the
//! simulator from them:
//!
//! ```text
//! records=225
//! f_sys_hz=50000000
//! words_per_record=17
//! params='BITS=12 CLOCKS_PER_BIT=200 ...'
//! group_cycles=122316
//! ```
//!
//! `group_cycles` is the cycles of the committed files of the core
//! (`vectors/<core>/*.hex`) that share the file's parameters and clock, and
//! so one Verilator build (the file's own cycles when none do): sim.sh
//! chooses that build's optimisation level by it.
//!
//! Exit status 2, with the file, its line and the fix on stderr, for a file
//! a replay cannot take.

use std::path::Path;
use std::process::ExitCode;

use vectorfile::{Replay, Summary};

/// The cycles of the committed files of `core` that share `replay`'s build.
fn group_cycles(root: &Path, replay: &Replay) -> u64 {
    let key = replay.build_key();
    let dir = root.join("vectors").join(&replay.core);
    let group: u64 = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "hex"))
        .filter_map(|p| Summary::read(&p))
        .filter(|s| s.build_key() == key)
        .map(|s| s.cycles)
        .sum();
    if group > 0 {
        group
    } else {
        replay.cycles
    }
}

/// `xtask vector-headers <file.hex>...`: one line per file, `<core>
/// <cycles> <build> <file>` (`<build>`: the parameters and clock, spaces as
/// `_`), for `scripts/regress.sh`'s plan.
pub fn summaries(files: &[String]) -> ExitCode {
    for f in files {
        let Some(s) = Summary::read(Path::new(f)).filter(|s| !s.core.is_empty()) else {
            eprintln!("regress: {f} has no tbgen header (// core: ...)");
            return ExitCode::from(2);
        };
        println!(
            "{} {} {}@{} {f}",
            s.core,
            s.cycles,
            s.params.replace(' ', "_"),
            s.f_sys_hz
        );
    }
    ExitCode::SUCCESS
}

pub fn main(root: &Path, args: &[String]) -> ExitCode {
    let [core, file] = args else {
        eprintln!("xtask: usage: xtask vector-header <core> <file.hex>");
        return ExitCode::from(2);
    };
    match Replay::read(Path::new(file), core) {
        Ok(r) => {
            println!("records={}", r.records);
            println!("f_sys_hz={}", r.f_sys_hz);
            println!("words_per_record={}", r.words_per_record);
            // Checked NAME=digits words: safe inside single quotes.
            println!("params='{}'", vectorfile::params_text(&r.params));
            println!("group_cycles={}", group_cycles(root, &r));
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("sim.sh: {e}");
            ExitCode::from(2)
        }
    }
}
