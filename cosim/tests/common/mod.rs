//! What both HDL test binaries share.

use std::path::Path;
use std::process::Command;

/// The options with which `scripts/sim.sh` and `scripts/cosim.sh` have
/// Verilator compile a testbench's C++ (`scripts/verilator_make_flags.sh`:
/// one translation unit at -O1, under half of Verilator's default compile
/// time and a faster model), for the benches these tests build themselves.
pub fn verilator_make_flags(root: &Path) -> Vec<String> {
    let out = Command::new(root.join("scripts/verilator_make_flags.sh"))
        .output()
        .expect("scripts/verilator_make_flags.sh runs");
    assert!(
        out.status.success(),
        "verilator_make_flags.sh: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .split_whitespace()
        .map(str::to_string)
        .collect()
}

/// `verilator`, run from the repository's root with ccache's base folder
/// there: give it the files under the root relative to it (`in_repo`), so
/// that the C++ it generates, which names them, is the same in any clone
/// and ccache finds the build made in another (scripts/verilator_ccache.sh).
pub fn verilator(root: &Path) -> Command {
    let mut cmd = Command::new("verilator");
    cmd.current_dir(root).env("CCACHE_BASEDIR", root);
    cmd
}

/// `path` relative to `root` when it lies under it, else as it is.
pub fn in_repo(root: &Path, path: &Path) -> std::path::PathBuf {
    path.strip_prefix(root).unwrap_or(path).to_path_buf()
}
