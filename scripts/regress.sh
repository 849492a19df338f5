#!/usr/bin/env bash
# regress.sh: replay every committed vector file against its core in Icarus
# and Verilator and print one line per run, then "N passed, M failed".
#
#   scripts/regress.sh [--core CORE] [--sim icarus|verilator] [--scenario NAME] [--waves]
#
# With --waves, each run also dumps the RTL's waveform to build/waves/<scenario>.<sim>.vcd.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cores=() sims=(icarus verilator) scenario="" waves=0
while [ $# -gt 0 ]; do
    case "$1" in
    --core) cores=("$2"); shift 2 ;;
    --sim) sims=("$2"); shift 2 ;;
    --scenario) scenario=$2; shift 2 ;;
    --waves) waves=1; shift ;;
    *) echo "usage: $0 [--core CORE] [--sim icarus|verilator] [--scenario NAME] [--waves]" >&2; exit 2 ;;
    esac
done
if [ ${#cores[@]} -eq 0 ]; then
    for d in "$root"/vectors/*/; do cores+=("$(basename "$d")"); done
fi

passed=0 failed=0
mkdir -p "$root/build/logs" "$root/build/waves"
for core in "${cores[@]}"; do
    files=("$root/vectors/$core"/*.hex)
    [ -e "${files[0]}" ] || { echo "regress: no vectors in vectors/$core/ (run make vectors)" >&2; exit 2; }
    for f in "${files[@]}"; do
        name=$(basename "$f" .hex)
        [ -n "$scenario" ] && [ "$name" != "$scenario" ] && continue
        for sim in "${sims[@]}"; do
            log="$root/build/logs/$name.$sim.log"
            wave=()
            [ "$waves" = 1 ] && wave=("$root/build/waves/$name.$sim.vcd")
            if "$root/scripts/sim.sh" "$core" "$sim" "$f" "${wave[@]}" > "$log" 2>&1; then
                passed=$((passed + 1))
                printf 'PASS  %-10s %-12s %s\n' "$sim" "$core" "$name"
            else
                failed=$((failed + 1))
                printf 'FAIL  %-10s %-12s %s\n' "$sim" "$core" "$name"
                grep -E "MISMATCH|rror" "$log" | head -n 5 | sed 's/^/      /'
            fi
        done
    done
done
[ $((passed + failed)) -gt 0 ] || { echo "regress: no scenario matched" >&2; exit 2; }
echo "hdl: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
