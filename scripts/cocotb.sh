#!/usr/bin/env bash
# cocotb.sh: the cocotb examples (hdl/cocotb/test_<proto>.py) under Icarus,
# each running one of our cores against its emulator from Python, one pytest
# test per closed loop (hdl/cocotb/closed_loops_test.py).
#
#   scripts/cocotb.sh [proto ...]        (default: every example)
#   scripts/cocotb.sh [--sim icarus|ghdl] --dir DIR --top TOP --config FILE [NAME=VALUE ...]
#                                        (a master we did not write: DIR/test_<DIR's name>.py
#                                         drives TOP, DIR's .v files but tb_*.v (.vhd with --sim ghdl); an example's
#                                         `make cocotb`, examples/*/Makefile)
#
# Builds what they need when out of date, so it works on a fresh clone after
# `make deps` (which installs cocotb into .venv/): the emulator library and
# cosim-params (scripts/emu_lib.sh), and the Python module encoder_emu (the
# cdylib of cosim-py/, PyO3), which cargo builds with the rest of the
# workspace, on the same features, so nothing is compiled twice.
# Exit status 0 only when every test passed.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
venv="$root/.venv"
[ -x "$venv/bin/cocotb-config" ] || {
    echo "cocotb.sh: .venv has no cocotb; run: make deps" >&2; exit 2; }
eval "$("$root/scripts/emu_lib.sh")"
export EMU_LIB_DIR
# The module, as an editable install: build/python/ holds encoder_emu.abi3.so
# (a link to the cdylib emu_lib.sh's build leaves beside libcosim.so), and a
# .pth file puts that directory on the venv's path, for run.py and for the
# Python the simulator embeds. (`maturin develop` in cosim-py/ would compile
# the module's dependencies again: cargo resolves their features for
# cosim-py alone. Users outside this tree install it with maturin or pip.)
mkdir -p "$root/build/python"
ln -sfn "$EMU_LIB_DIR/libencoder_emu.so" "$root/build/python/encoder_emu.abi3.so"
site=$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
echo "$root/build/python" > "$site/encoder_emu_tree.pth"
# A copy installed by an earlier `maturin develop` would come first on the path.
if [ -d "$site/encoder_emu" ]; then
    rm -rf "$site/encoder_emu" "$site"/encoder_emu-*.dist-info
fi
cd "$root/hdl/cocotb"
first=${1:-}
if [ "${first#--}" = "$first" ]; then
    # The closed loops: pytest, a test per loop (-k picks the named ones);
    # -p no:cacheprovider leaves no .pytest_cache in the tree.
    select=()
    if [ $# -gt 0 ]; then
        expr=$(printf ' or %s' "$@")
        select=(-k "${expr# or }")
    fi
    exec "$venv/bin/python" -m pytest -p no:cacheprovider -rA -q closed_loops_test.py "${select[@]}"
fi
exec "$venv/bin/python" run.py "$@"
