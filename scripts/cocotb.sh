#!/usr/bin/env bash
# cocotb.sh: the cocotb examples (hdl/cocotb/test_<proto>.py) under Icarus,
# each running one of our cores against its emulator from Python.
#
#   scripts/cocotb.sh [proto ...]        (default: every example)
#   scripts/cocotb.sh --dir DIR --top TOP --config FILE [NAME=VALUE ...]
#                                        (a master we did not write: DIR/test_<DIR's name>.py
#                                         drives TOP, DIR's .v files but tb_*.v; an example's
#                                         `make cocotb`, examples/*/Makefile)
#
# Builds what they need when out of date, so it works on a fresh clone after
# `make deps` (which installs cocotb and maturin into .venv/): the emulator
# library and cosim-params (scripts/emu_lib.sh), and the Python module
# encoder_emu from cosim-py/ (PyO3), installed into .venv/ by maturin.
# Exit status 0 only when every test passed.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
venv="$root/.venv"
[ -x "$venv/bin/maturin" ] && [ -x "$venv/bin/cocotb-config" ] || {
    echo "cocotb.sh: .venv has no cocotb or maturin; run: make deps" >&2; exit 2; }
eval "$("$root/scripts/emu_lib.sh")"
export EMU_LIB_DIR
# The module, rebuilt when the crate or the cosim sources are newer than the stamp.
stamp="$venv/.encoder_emu.stamp"
if [ ! -f "$stamp" ] || [ -n "$(find "$root/cosim-py" "$root/cosim/src" "$root/model/src" -newer "$stamp" -name '*.rs' -o -newer "$stamp" -name 'Cargo.toml' | head -n 1)" ]; then
    (cd "$root/cosim-py" && VIRTUAL_ENV="$venv" PATH="$venv/bin:$PATH" CARGO_TARGET_DIR="$root/target" \
        "$venv/bin/maturin" develop --release --locked -q) >&2
    touch "$stamp"
fi
cd "$root/hdl/cocotb"
exec "$venv/bin/python" run.py "$@"
