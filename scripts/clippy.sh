#!/usr/bin/env bash
# clippy.sh: clippy on every crate and target of the workspace; any warning
# fails. Clippy's correctness lints are bugs (a safe public function that
# dereferences a caller's pointer was one), and its style lints keep the
# code one style across protocols.
#
# The release profile in the build's own target directory: after the
# build, clippy reuses its build scripts and proc-macros (33 s of CPU
# instead of 55 s from nothing, measured on a fresh clone), so make test
# runs it after lane 1's build. Cargo holds the directory's lock only while
# it compiles, not while tests run, so clippy and the cargo tests do not
# wait on each other.
#
# A new toolchain may bring new lints: fix what they find, or allow one
# where the code is right, as narrowly as it goes, with a comment saying
# why (cosim-py/src/lib.rs has one, for a PyO3 macro's false positive).
set -euo pipefail
cd "$(dirname "$0")/.."
exec "${CARGO:-cargo}" clippy --release --workspace --locked --all-targets -- -D warnings
