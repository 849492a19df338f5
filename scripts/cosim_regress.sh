#!/usr/bin/env bash
# cosim_regress.sh: every core that has a closed-loop testbench
# (hdl/tb_cosim/<core>/tb_cosim_<core>.v) run against its encoder emulator,
# in each simulator, N transactions per core and simulator.
#
#   scripts/cosim_regress.sh [--transactions N] [--sim icarus|verilator] [--seed S]
#
# `make test` runs 1000 per core and simulator; `make soak` 100000 in
# Verilator. Prints one summary line per run, then "cosim: N passed, M failed".
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
transactions=1000 sims=(icarus verilator) seed=1
usage() { echo "usage: $0 [--transactions N] [--sim icarus|verilator] [--seed S]" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
    --transactions) [ $# -ge 2 ] || usage; transactions=$2; shift 2 ;;
    --sim) [ $# -ge 2 ] || usage; sims=("$2"); shift 2 ;;
    --seed) [ $# -ge 2 ] || usage; seed=$2; shift 2 ;;
    *) usage ;;
    esac
done
mkdir -p "$root/build/logs"
passed=0 failed=0
for dir in "$root"/hdl/tb_cosim/*/; do
    core=$(basename "$dir")
    [ -f "$dir/tb_cosim_$core.v" ] || continue
    for sim in "${sims[@]}"; do
        log="$root/build/logs/cosim.$core.$sim.log"
        if "$root/scripts/cosim.sh" "$core" "$sim" --transactions "$transactions" --seed "$seed" > "$log" 2>&1; then
            passed=$((passed + 1))
        else
            failed=$((failed + 1))
            echo "FAIL  $sim $core (log: $log)"
            grep -iE "mismatch|error|fail" "$log" | head -n 5 | sed 's/^/      /'
        fi
        grep '^cosim: ' "$log" || true
    done
done
[ $((passed + failed)) -gt 0 ] || { echo "cosim_regress: no closed-loop testbench found in hdl/tb_cosim/" >&2; exit 2; }
echo "cosim: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
