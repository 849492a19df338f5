#!/usr/bin/env bash
# regress.sh: replay every committed vector file against its core in Icarus
# and Verilator and print one line per run, then "N passed, M failed".
#
#   scripts/regress.sh [--core CORE] [--sim icarus|verilator] [--scenario NAME] [--waves] [--jobs N]
#
# With --waves, each run also dumps the RTL's waveform to build/waves/<scenario>.<sim>.vcd.
# --jobs N runs N replays at once (default: the number of cores). Runs that
# share a simulator build wait for it on sim.sh's lock, so each build is
# still made once. Lines come in the order runs finish.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cores=() sims=(icarus verilator) scenario="" waves=0 jobs=$(nproc 2>/dev/null || echo 2)
usage() { echo "usage: $0 [--core CORE] [--sim icarus|verilator] [--scenario NAME] [--waves] [--jobs N]" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
    --core) [ $# -ge 2 ] || usage; cores=("$2"); shift 2 ;;
    --sim) [ $# -ge 2 ] || usage; sims=("$2"); shift 2 ;;
    --scenario) [ $# -ge 2 ] || usage; scenario=$2; shift 2 ;;
    --waves) waves=1; shift ;;
    --jobs) [ $# -ge 2 ] || usage; jobs=$2; shift 2 ;;
    *) usage ;;
    esac
done
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || { echo "regress: --jobs takes a whole number of at least 1, not '$jobs'" >&2; exit 2; }
if [ ${#cores[@]} -eq 0 ]; then
    for d in "$root"/vectors/*/; do cores+=("$(basename "$d")"); done
fi

mkdir -p "$root/build/logs" "$root/build/waves"
results=$(mktemp -d)
trap 'rm -rf "$results"' EXIT

# One replay: prints its PASS/FAIL line and leaves a marker for the count.
replay() {
    local core=$1 sim=$2 f=$3 name log wave=()
    name=$(basename "$f" .hex)
    log="$root/build/logs/$name.$sim.log"
    [ "$waves" = 1 ] && wave=("$root/build/waves/$name.$sim.vcd")
    if "$root/scripts/sim.sh" "$core" "$sim" "$f" "${wave[@]}" > "$log" 2>&1; then
        touch "$results/pass.$core.$sim.$name"
        printf 'PASS  %-10s %-12s %s\n' "$sim" "$core" "$name"
    else
        touch "$results/fail.$core.$sim.$name"
        { printf 'FAIL  %-10s %-12s %s\n' "$sim" "$core" "$name"
          grep -E "MISMATCH|rror" "$log" | head -n 5 | sed 's/^/      /'; } | cat
    fi
}

running=0
for core in "${cores[@]}"; do
    files=("$root/vectors/$core"/*.hex)
    [ -e "${files[0]}" ] || { echo "regress: no vectors in vectors/$core/ (run make vectors)" >&2; exit 2; }
    for f in "${files[@]}"; do
        name=$(basename "$f" .hex)
        [ -n "$scenario" ] && [ "$name" != "$scenario" ] && continue
        for sim in "${sims[@]}"; do
            if [ "$running" -ge "$jobs" ]; then
                wait -n || true
                running=$((running - 1))
            fi
            replay "$core" "$sim" "$f" &
            running=$((running + 1))
        done
    done
done
wait || true
passed=$(find "$results" -name 'pass.*' | wc -l)
failed=$(find "$results" -name 'fail.*' | wc -l)
[ $((passed + failed)) -gt 0 ] || { echo "regress: no scenario matched" >&2; exit 2; }
echo "hdl: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
