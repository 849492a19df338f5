#!/usr/bin/env bash
# clippy.sh: clippy on every crate and target of the workspace; any warning
# fails. Clippy's correctness lints are bugs (a safe public function that
# dereferences a caller's pointer was one), and its style lints keep the
# code one style across protocols.
#
# Its own target directory (target/clippy): clippy's check artifacts are
# not the release build's, and a separate directory never waits on the
# lock of the cargo build and tests that make test runs beside it.
#
# A new toolchain may bring new lints: fix what they find, or allow one
# where the code is right, at the item, with a comment saying why
# (cosim-py/src/lib.rs has one, for a PyO3 macro's false positive).
set -euo pipefail
cd "$(dirname "$0")/.."
CARGO_TARGET_DIR=${CLIPPY_TARGET_DIR:-target/clippy} \
    exec "${CARGO:-cargo}" clippy --release --workspace --locked --all-targets -- -D warnings
