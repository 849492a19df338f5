#!/usr/bin/env bash
# cosim_regress.sh: every closed loop of the protocol descriptors (`tbgen
# protocols`: hdl/tb_cosim/<core>/tb_cosim_<core>.v, a core against its
# encoder emulator), in each simulator, N transactions per core and simulator.
#
#   scripts/cosim_regress.sh [--transactions N] [--sim icarus|verilator] [--seed S]
#                            [--quick] [--jobs J] [--core CORE]
#
# Without --quick the N transactions of a core are split evenly over every
# configuration in hdl/tb_cosim/<core>/configs/. With --quick (`make test`)
# Verilator still runs every configuration, but Icarus runs all N on the
# core's cheapest configuration (its descriptor's `quick`: fewest Icarus
# seconds per transaction, measured), so that Icarus spends its time on
# transactions rather than on long cables, slow clocks and long idle gaps;
# `make soak` runs every configuration in Icarus.
# --jobs J runs J (core, simulator) pairs at once (default 1).
#
# `make test` runs --quick with 1000 per core and simulator; `make soak`
# 100000 in Verilator and 1000 over every configuration in Icarus. Prints
# one summary line per configuration and run (with its wall time), the ten
# slowest runs, then "cosim: N passed, M failed".
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
transactions=1000 sims=(icarus verilator) seed=1 quick=0 jobs=1 only=""
usage() { echo "usage: $0 [--transactions N] [--sim icarus|verilator] [--seed S] [--quick] [--jobs J] [--core CORE]" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
    --transactions) [ $# -ge 2 ] || usage; transactions=$2; shift 2 ;;
    --sim) [ $# -ge 2 ] || usage; sims=("$2"); shift 2 ;;
    --seed) [ $# -ge 2 ] || usage; seed=$2; shift 2 ;;
    --quick) quick=1; shift ;;
    --jobs) [ $# -ge 2 ] || usage; jobs=$2; shift 2 ;;
    --core) [ $# -ge 2 ] || usage; only=$2; shift 2 ;;
    *) usage ;;
    esac
done
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || { echo "cosim_regress: --jobs takes a whole number of at least 1, not '$jobs'" >&2; exit 2; }

# The closed loops and each one's --quick Icarus configuration (the fewest
# Icarus seconds per transaction, measured: the figures are beside each
# `quick` in model/src/<protocol>/descriptor.rs), from the descriptors.
"$root/scripts/emu_lib.sh" > /dev/null
# shellcheck source=scripts/protocols.sh
. "$root/scripts/protocols.sh"
loops=$(closed_loops)
quick_config() { awk -v c="$1" '$1 == c { print $6 }' <<< "$loops"; }

mkdir -p "$root/build/logs"
results=$(mktemp -d)
trap 'rm -rf "$results"' EXIT

# One (core, simulator) run: its summary lines, its wall time, a marker.
run() {
    local core=$1 sim=$2 log="$root/build/logs/cosim.$core.$sim.log" args=() t0 t1 secs q
    args=(--transactions "$transactions" --seed "$seed")
    if [ "$quick" = 1 ] && [ "$sim" = icarus ]; then
        q=$(quick_config "$core")
        [ -n "$q" ] && [ -f "$root/hdl/tb_cosim/$core/configs/$q.toml" ] \
            && args+=(--config "$root/hdl/tb_cosim/$core/configs/$q.toml")
    fi
    t0=$(date +%s.%N)
    if "$root/scripts/cosim.sh" "$core" "$sim" "${args[@]}" > "$log" 2>&1; then
        t1=$(date +%s.%N)
        secs=$(awk "BEGIN { printf \"%.1f\", $t1 - $t0 }")
        echo "$secs $sim $core" > "$results/pass.$core.$sim"
        { grep '^cosim: ' "$log" || true; echo "cosim: $core $sim: $secs s wall (builds included)"; } | cat
    else
        t1=$(date +%s.%N)
        secs=$(awk "BEGIN { printf \"%.1f\", $t1 - $t0 }")
        echo "$secs $sim $core" > "$results/fail.$core.$sim"
        { echo "FAIL  $sim $core (log: $log)"
          grep -iE "mismatch|error|fail" "$log" | head -n 5 | sed 's/^/      /'
          grep '^cosim: ' "$log" || true
          echo "cosim: $core $sim: $secs s wall (builds included)"; } | cat
    fi
}

# Icarus runs first (the long ones), so that no long run starts last.
running=0
for sim in "${sims[@]}"; do
    for core in $(cut -d' ' -f1 <<< "$loops"); do
        [ -z "$only" ] || [ "$only" = "$core" ] || continue
        if [ "$running" -ge "$jobs" ]; then
            wait -n || true
            running=$((running - 1))
        fi
        run "$core" "$sim" &
        running=$((running + 1))
    done
done
wait || true
passed=$(find "$results" -name 'pass.*' | wc -l)
failed=$(find "$results" -name 'fail.*' | wc -l)
[ $((passed + failed)) -gt 0 ] || { echo "cosim_regress: no closed loop${only:+ named '$only'} (tbgen protocols lists them)" >&2; exit 2; }
echo "cosim: the 10 slowest configurations (wall seconds of the run alone):"
for f in "$results"/*; do
    read -r _ sim core < "$f"
    sed -n 's/^cosim: [^ ]* [^ ]* \([^ ]*\): \([0-9]*\) transactions, .* in \([0-9.]*\) s .*/\3 \1 \2/p' "$root/build/logs/cosim.$core.$sim.log" \
        | awk -v c="$core" -v s="$sim" '{ printf "%s %s %s %s %s\n", $1, s, c, $2, $3 }'
done | sort -rn -k1,1 | awk 'NR <= 10 { printf "      %7.1f s  %-10s %-14s %s (%s transactions)\n", $1, $2, $3, $4, $5 }'
echo "cosim: the 10 slowest runs (wall seconds, builds included):"
cat "$results"/* | sort -rn -k1,1 | awk 'NR <= 10 { printf "      %7.1f s  %-10s %s\n", $1, $2, $3 }'
cat "$results"/* | awk '{ t[$2] += $1 } END { for (s in t) printf "cosim: %s: %.1f s (sum of wall times)\n", s, t[s] }' | sort
echo "cosim: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
