//! `make test`'s stages as data: what each runs, what it must wait for, and
//! which to take first when a worker is free.
//!
//! The order is a priority list, not a sequence. Two workers (two cores)
//! take, each time one is free, the first stage in [`STAGES`] whose
//! prerequisites have all ended. So the replays (`lint`, `hdl`) start beside
//! the Rust build, which needs nothing from them; the cargo tests follow the
//! build on its worker; the closed loops, the longest of the stages that
//! need the build, come before the short checks, which fill both workers'
//! ends, and neither core idles while a stage can start.

/// One stage of `make test`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Stage {
    /// Its name: the log is `build/test/<name>.log`, the table's row is this.
    pub name: &'static str,
    /// The command, from the repository's root.
    pub argv: &'static [&'static str],
    /// The stages that must have passed before it starts.
    pub after: &'static [&'static str],
    /// What it checks, one line (`xtask test --list`).
    pub what: &'static str,
}

/// The stage every other stage waits for: the tools and `.venv/`.
pub const DEPS: Stage = Stage {
    name: "deps",
    argv: &["scripts/deps.sh"],
    after: &[],
    what: "the tools (Debian packages) and .venv/, installed when missing",
};

/// The stages after [`DEPS`], first taken first.
pub const STAGES: &[Stage] = &[
    Stage {
        name: "build",
        // One profile, one compile: the test binaries, then tbgen, the
        // emulator library (the cdylib and cosim-params) and the Python
        // module, which cargo test does not link, on the same artifacts.
        // --timings: target/cargo-timings/ shows which crate's compile costs.
        argv: &[
            "sh",
            "-c",
            "cargo test --release --workspace --locked --no-run --timings \
             && cargo build --release --locked -p tbgen -p cosim -p cosim-py",
        ],
        after: &[],
        what: "every crate compiled once, in the release profile with overflow checks",
    },
    Stage {
        name: "lint",
        argv: &["scripts/lint.sh"],
        after: &[],
        what: "Verilator -Wall on every core and wrapper; no simulator code in hdl/rtl/",
    },
    Stage {
        name: "hdl",
        // Coverage costs no second replay: the Verilator replays run on the
        // coverage-instrumented build and leave their counts behind.
        argv: &[
            "env",
            "COVERAGE=1",
            "scripts/regress.sh",
            "--icarus-budget",
            "1000000",
        ],
        after: &["lint"],
        what: "every vector file in Verilator, a representative set per core in Icarus",
    },
    Stage {
        name: "cargo-test",
        // --no-fail-fast: every failing test binary is reported, not the first.
        argv: &[
            "cargo",
            "test",
            "--release",
            "--workspace",
            "--locked",
            "--no-fail-fast",
        ],
        after: &["build"],
        what: "the model's, the flow's, the emulators' and the bad-input tests",
    },
    Stage {
        name: "coverage",
        argv: &["scripts/coverage.sh", "--report-only"],
        after: &["hdl"],
        what: "RTL line, branch and toggle coverage against hdl/coverage/baseline.txt",
    },
    Stage {
        name: "cosim",
        // Icarus on each core's cheapest configuration, Verilator on every
        // one (make soak: every configuration in Icarus too).
        argv: &[
            "scripts/cosim_regress.sh",
            "--transactions",
            "1000",
            "--quick",
            "--jobs",
            "2",
        ],
        after: &["build"],
        what: "every core closed-loop against its emulator, 1000 transactions per simulator",
    },
    Stage {
        name: "gtkw",
        argv: &["scripts/check_gtkw.sh"],
        after: &[],
        what: "every .gtkw layout opened in headless GTKWave, three judged from a screenshot",
    },
    Stage {
        name: "clippy",
        argv: &["scripts/clippy.sh"],
        after: &["build"],
        what: "clippy on every crate and target, any warning failing",
    },
    Stage {
        name: "fusesoc",
        argv: &["scripts/check_fusesoc.sh"],
        after: &[],
        what: "the FuseSoC core files current, their lint and sim targets run",
    },
    Stage {
        name: "wavedrom",
        // The diagrams' list comes from `tbgen protocols --json`.
        argv: &[".venv/bin/python", "scripts/timing_diagrams.py", "--check"],
        after: &["build"],
        what: "the WaveDrom diagrams equal to what the committed waves draw",
    },
    Stage {
        name: "vectors",
        argv: &["scripts/check_vectors.sh"],
        after: &["build"],
        what: "the committed vectors equal to what the model generates now",
    },
    Stage {
        name: "cocotb",
        argv: &["scripts/cocotb.sh"],
        after: &["build"],
        what: "the cocotb tests of our cores, the emulators from Python",
    },
    Stage {
        name: "probes",
        // Every kit's rule probes replayed through the Verilog wrappers
        // (one build per kind and simulator) and the Python module, each
        // judged by the library run's verdict (`tbgen probes --check`).
        argv: &["hdl/tb_probe/run.sh"],
        after: &["build"],
        what: "every rule probe in Icarus, Verilator, cocotb and GHDL, judged as the library's run is",
    },
    Stage {
        name: "vhdl",
        // The VHDL masters in GHDL, each 1000 reads then a planted misread.
        argv: &["scripts/vhdl_examples.sh"],
        after: &["build"],
        what: "the VHDL masters of examples/*_vhdl in GHDL with the VHDL emulators and monitors",
    },
    Stage {
        name: "formal",
        // make formal's quick part: each core's first proof, and a counter
        // one short caught with a trace GTKWave opens (make formal: all).
        argv: &[
            "sh",
            "-c",
            ".venv/bin/python scripts/formal.py --quick \
             && .venv/bin/python -m pytest -p no:cacheprovider -q hdl/formal/test_broken_rule.py -k 'prove_plain-t_cs or prove_ma-tmasl'",
        ],
        after: &[],
        what: "each core's first formal proof; a core broken on purpose fails with a trace",
    },
    Stage {
        name: "fmt",
        argv: &["cargo", "fmt", "--all", "--", "--check"],
        after: &[],
        what: "every Rust file as rustfmt writes it (cargo fmt --all fixes it)",
    },
    Stage {
        name: "sigrok",
        // Reads the committed waves and transcripts (the vectors stage
        // holds them to the model), so it needs no build: about 9 s of CPU
        // (sigrok-cli over 130 waves and six bit flips).
        argv: &[".venv/bin/python", "sigrok/check.py"],
        after: &[],
        what: "our sigrok decoders (sigrok/decoders/) agree with every transcript; an inverted bit is caught",
    },
];

/// The stages named in `only` (each with what it waits for, transitively, so
/// that `--only cosim` builds first), in [`STAGES`]' order; an unknown name
/// is an error listing the known ones.
pub fn select(only: &[String]) -> Result<Vec<Stage>, String> {
    if only.is_empty() {
        return Ok(STAGES.to_vec());
    }
    let mut wanted: Vec<&str> = Vec::new();
    let mut todo: Vec<&str> = Vec::new();
    for name in only {
        let stage = STAGES.iter().find(|s| s.name == name).ok_or_else(|| {
            let names: Vec<&str> = STAGES.iter().map(|s| s.name).collect();
            format!("no stage `{name}`; the stages are: {}", names.join(", "))
        })?;
        todo.push(stage.name);
    }
    while let Some(name) = todo.pop() {
        if wanted.contains(&name) {
            continue;
        }
        wanted.push(name);
        let stage = STAGES
            .iter()
            .find(|s| s.name == name)
            .expect("checked above");
        todo.extend(stage.after.iter().copied());
    }
    Ok(STAGES
        .iter()
        .filter(|s| wanted.contains(&s.name))
        .copied()
        .collect())
}
