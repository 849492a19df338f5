#!/usr/bin/env bash
# soak.sh: the long closed-loop run of `make soak`: at least N transactions
# (default 100000) per core that has a closed-loop testbench
# (hdl/tb_cosim/<core>/tb_cosim_<core>.v), in Verilator, over every one of
# the core's configurations, then a count per core.
#
#   scripts/soak.sh [--transactions N] [--jobs J] [--seed S] [CORE...]
#
# Spread: every configuration (long cables, slow line clocks, clock offsets)
# runs at least N/10 transactions (--floor-share changes the 10); the rest go
# to the configuration with the fewest cycles per transaction, measured by a
# probe of 200 transactions per configuration (the probe also builds the
# simulator model; its transactions are not counted). So each core's total is
# N, every configuration is soaked, and the run takes as little simulated
# time as that allows. J cores run at once (default 2, the machine's cores).
#
# Prints, per core, the transactions and cycles of each configuration and the
# core's total, then "soak: K cores, T transactions, pass" (exit 0) or the
# failing cores (exit 1). Logs: build/soak/<core>.<config>.log.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
n=100000 jobs=2 seed=1 share=10
usage() { echo "usage: $0 [--transactions N] [--jobs J] [--seed S] [--floor-share D] [CORE...]" >&2; exit 2; }
cores=()
while [ $# -gt 0 ]; do
    case "$1" in
    --transactions) [ $# -ge 2 ] || usage; n=$2; shift 2 ;;
    --jobs) [ $# -ge 2 ] || usage; jobs=$2; shift 2 ;;
    --seed) [ $# -ge 2 ] || usage; seed=$2; shift 2 ;;
    --floor-share) [ $# -ge 2 ] || usage; share=$2; shift 2 ;;
    -*) usage ;;
    *) cores+=("$1"); shift ;;
    esac
done
if [ ${#cores[@]} -eq 0 ]; then
    for dir in "$root"/hdl/tb_cosim/*/; do
        core=$(basename "$dir")
        [ -f "$dir/tb_cosim_$core.v" ] && cores+=("$core")
    done
fi
out="$root/build/soak"
# Closed-loop binaries load libcosim from this checkout's target, also when
# their cached build (keyed by content) was copied from another checkout.
export LD_LIBRARY_PATH="${CARGO_TARGET_DIR:-$root/target}/release${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
mkdir -p "$out"
# The library and tools once, before the jobs share them.
"$root/scripts/emu_lib.sh" > /dev/null

# "<transactions> <cycles> <seconds>" of a cosim.sh log's configuration line.
figures() { sed -n 's/^cosim: .*\.toml: \([0-9]*\) transactions, \([0-9]*\) cycles in \([0-9.]*\) s.*/\1 \2 \3/p' "$1" | head -n 1; }

# One core: probe, plan, soak; writes $out/<core>.summary.
soak_core() {
    local core=$1 cfg name best='' best_cpt='' status=0 total=0 cycles=0 seconds=0
    local floor=$(( (n + share - 1) / share ))
    local -a cfgs=("$root"/hdl/tb_cosim/"$core"/configs/*.toml)
    local -A count=()
    for cfg in "${cfgs[@]}"; do
        name=$(basename "$cfg" .toml)
        "$root/scripts/cosim.sh" "$core" verilator --config "$cfg" --transactions 200 --seed "$seed" \
            > "$out/$core.$name.probe.log" 2>&1 || { echo "FAIL $core $name (probe; log: $out/$core.$name.probe.log)" > "$out/$core.summary"; return 0; }
        read -r t c _ < <(figures "$out/$core.$name.probe.log")
        cpt=$(( c / t ))
        if [ -z "$best" ] || [ "$cpt" -lt "$best_cpt" ]; then best=$cfg best_cpt=$cpt; fi
        count[$cfg]=$floor
    done
    local rest=$(( n - floor * ${#cfgs[@]} ))
    [ "$rest" -gt 0 ] && count[$best]=$(( floor + rest ))
    {
        for cfg in "${cfgs[@]}"; do
            name=$(basename "$cfg" .toml)
            log="$out/$core.$name.log"
            if "$root/scripts/cosim.sh" "$core" verilator --config "$cfg" --transactions "${count[$cfg]}" --seed "$seed" > "$log" 2>&1; then
                verdict=pass
            else
                verdict=FAIL status=1
            fi
            read -r t c s < <(figures "$log") || { t=0 c=0 s=0; }
            total=$(( total + t )) cycles=$(( cycles + c ))
            seconds=$(awk "BEGIN { print $seconds + $s }")
            printf '  %-15s %-32s %7d transactions %12d cycles %8.1f s  %s\n' "$core" "$name" "$t" "$c" "$s" "$verdict"
            [ "$verdict" = pass ] || grep -iE "mismatch|error|fail" "$log" | head -n 5 | sed 's/^/      /'
        done
        printf 'soak: %-15s %7d transactions over %d configuration(s), %d cycles in %.0f s: %s\n' \
            "$core" "$total" "${#cfgs[@]}" "$cycles" "$seconds" "$([ $status = 0 ] && echo pass || echo FAIL)"
    } > "$out/$core.summary"
}
export -f soak_core figures
export root n seed share out

started=$(date +%s)
printf '%s\n' "${cores[@]}" | xargs -P "$jobs" -I{} bash -c 'soak_core "$1"' _ {}
failed=0 grand=0
for core in "${cores[@]}"; do
    cat "$out/$core.summary"
    grep -q '^soak: .*: pass$' "$out/$core.summary" || failed=$((failed + 1))
    t=$(sed -n 's/^soak: *[a-z0-9_]* *\([0-9]*\) transactions.*/\1/p' "$out/$core.summary")
    grand=$(( grand + ${t:-0} ))
done
echo "soak: ${#cores[@]} cores, $grand transactions in Verilator, $(( $(date +%s) - started )) s: $([ $failed = 0 ] && echo pass || echo "$failed FAILED")"
[ "$failed" -eq 0 ]
