#!/usr/bin/env bash
# lint.sh: Verilator --lint-only -Wall on every core in hdl/rtl/, with its
# default parameters and with the parameters of every committed vector file,
# so that width corners (1-bit, 64-bit) are linted too; no core holds code
# for one simulator or tool (an `ifdef on __ICARUS__, VERILATOR, COCOTB_SIM
# or SYNTHESIS: docs/rtl.md); then every emulator wrapper and monitor in
# hdl/emu/. Any warning fails.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
status=0 runs=0
for rtl in hdl/rtl/*.v; do
    core=$(basename "$rtl" .v)
    param_sets=("")
    if [ -d "vectors/$core" ]; then
        while IFS= read -r p; do param_sets+=("$p"); done < <(sed -n 's#^// params: ##p' vectors/"$core"/*.hex | sort -u)
    fi
    for params in "${param_sets[@]}"; do
        gargs=()
        for p in $params; do gargs+=("-G$p"); done
        runs=$((runs + 1))
        if ! out=$(verilator --lint-only -Wall -Ihdl/rtl --top-module "$core" "${gargs[@]}" "$rtl" 2>&1); then
            echo "lint FAIL $core ${params:-(defaults)}"
            echo "$out" | head -n 20
            status=1
        fi
    done
done
# Synthesizable cores are what users read and copy: no simulator's code.
if grep -nE '`(ifdef|ifndef|elsif)[[:space:]]+(__ICARUS__|VERILATOR|COCOTB_SIM|SYNTHESIS)\b' hdl/rtl/*.v; then
    echo "lint FAIL hdl/rtl/: simulator-specific code above; the cores must read the same in every tool (docs/rtl.md)"
    status=1
fi
# The emulator wrappers and monitors (hdl/emu/) go into users' testbenches,
# which may lint with -Wall: they must be clean too. They are simulation
# code (blocking assignments in clocked blocks, as in a testbench), hence
# -Wno-BLKSEQ; the DPI-C branch is the one Verilator reads.
wrappers=0
for emu in hdl/emu/*.v; do
    module=$(basename "$emu" .v)
    runs=$((runs + 1)) wrappers=$((wrappers + 1))
    if ! out=$(verilator --lint-only -Wall -Wno-BLKSEQ -Ihdl/emu --top-module "$module" "$emu" 2>&1); then
        echo "lint FAIL $emu"
        echo "$out" | head -n 20
        status=1
    fi
done
# The replay testbenches (hdl/tb/) are not held to -Wall, but the width of
# their all_outputs (vector_player.vh's change detection) is: a vector
# narrower than the outputs it concatenates would let a changed output go
# unchecked.
benches=0
for tb in hdl/tb/*/tb_*.v; do
    module=$(basename "$tb" .v)
    runs=$((runs + 1)) benches=$((benches + 1))
    out=$(verilator --lint-only --timing -Wall -Wno-fatal -Ihdl/tb/common "-I$(dirname "$tb")" -Ihdl/rtl --top-module "$module" "$tb" hdl/rtl/*.v 2>&1 || true)
    if grep -q '^%Error' <<< "$out"; then
        echo "lint FAIL $tb: does not elaborate"
        grep -A4 '^%Error' <<< "$out" | head -n 20
        status=1
    elif grep -q 'all_outputs\|outputs_checked' <<< "$out"; then
        echo "lint FAIL $tb: all_outputs"
        grep -B2 -A4 'all_outputs\|outputs_checked' <<< "$out" | head -n 20
        status=1
    fi
done
echo "lint: $runs runs over $(ls hdl/rtl/*.v | wc -l) cores, $wrappers emulator wrappers and monitors and $benches replay testbenches' output vectors, $([ $status = 0 ] && echo clean || echo WARNINGS)"
exit $status
