#!/usr/bin/env bash
# cosim_regress.sh: every core that has a closed-loop testbench
# (hdl/tb_cosim/<core>/tb_cosim_<core>.v) run against its encoder emulator,
# in each simulator, N transactions per core and simulator.
#
#   scripts/cosim_regress.sh [--transactions N] [--sim icarus|verilator] [--seed S]
#                            [--quick] [--jobs J] [--core CORE]
#
# Without --quick the N transactions of a core are split evenly over every
# configuration in hdl/tb_cosim/<core>/configs/. With --quick (`make test`)
# Verilator still runs every configuration, but Icarus runs all N on the
# core's cheapest configuration (the table below: fewest Icarus seconds
# per transaction, measured), so that Icarus spends its time on
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

# --quick: each core's cheapest configuration in Icarus. Icarus seconds per
# transaction (60 transactions on each configuration, start-up included,
# 2-core machine loaded about 3, after the cores' counters moved out of
# their state machines' always @* blocks), the chosen one first:
#   biss_master     chain_2500khz_100m 0.026, seed_10mhz_10m 0.021, wide_1mhz_50m 0.031
#                   (the chain is kept: two slaves over 100 m, 0.005 s dearer)
#   can_controller  one_node_500k_10tq 0.021, one_node_125k 0.045, two_nodes_1000k 0.053
#   canopen_master  cyclic_250k_10tq 0.057, cyclic_250k 0.072, sync_1000k 0.081
#   endat_master    pos22_1mhz_20m 0.018, pos22_500khz_50m 0.031, pos22_4mhz_100m_short 0.063
#   esl_host        readout_0m 0.032, readout_50m_fast 0.032, readout_100m_slow 0.053
#   modbus_master   read16_31250_8_clocks 0.023, read16_31250_fixed_t35 0.040, read32_15625_even_100m 0.052
#                   (measured later, unloaded, after the register banks: docs/rtl.md)
#   sar58k24_can    factory_250k_10tq 0.075, factory_250k 0.090, mixed_500k 0.087, node7f_1000k 0.102
#                   (the three 10tq configurations, ten clock cycles per CAN bit, and
#                   the rows they were set against re-measured on 300 transactions,
#                   unloaded, 2026-11-24; their gain is smaller than their 1.6x to 3.2x
#                   fewer cycles, since the emulator's work is per bit, not per cycle)
#   sar_async_host  handshake_gray_31250_100m 0.013, bus_32bit_15625_10m 0.019, timed_16bit_115200 0.053
#   ssi_master      fast_1mhz_50m 0.006, gray_100khz_100m 0.008, seed_250khz_10m 0.014
#   tformat_host    readout_50m_fast 0.013, readout_0m 0.013, readout_100m_slow 0.023
# A core not in the table (a new closed loop) runs every configuration.
quick_config() {
    case "$1" in
    biss_master) echo chain_2500khz_100m ;;
    can_controller) echo one_node_500k_10tq ;;
    canopen_master) echo cyclic_250k_10tq ;;
    endat_master) echo pos22_1mhz_20m ;;
    esl_host) echo readout_0m ;;
    modbus_master) echo read16_31250_8_clocks ;;
    sar58k24_can) echo factory_250k_10tq ;;
    sar_async_host) echo handshake_gray_31250_100m ;;
    ssi_master) echo fast_1mhz_50m ;;
    tformat_host) echo readout_50m_fast ;;
    esac
}

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
    for dir in "$root"/hdl/tb_cosim/*/; do
        core=$(basename "$dir")
        [ -f "$dir/tb_cosim_$core.v" ] || continue
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
[ $((passed + failed)) -gt 0 ] || { echo "cosim_regress: no closed-loop testbench found in hdl/tb_cosim/" >&2; exit 2; }
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
