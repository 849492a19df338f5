//! What both HDL test binaries share.

use std::path::Path;
use std::process::Command;

/// The options with which `scripts/sim.sh` and `scripts/cosim.sh` have
/// Verilator compile a testbench's C++ (`scripts/verilator_make_flags.sh`:
/// one translation unit at -O1, under half of Verilator's default compile
/// time and a faster model), for the benches these tests build themselves.
pub fn verilator_make_flags(root: &Path) -> Vec<String> {
    let out = Command::new(root.join("scripts/verilator_make_flags.sh")).output().expect("scripts/verilator_make_flags.sh runs");
    assert!(out.status.success(), "verilator_make_flags.sh: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).split_whitespace().map(str::to_string).collect()
}
