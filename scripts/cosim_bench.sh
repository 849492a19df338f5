#!/usr/bin/env bash
# cosim_bench.sh: closed-loop speed against vector replay, per core and simulator.
#
#   scripts/cosim_bench.sh [N] [CORE...]   (N transactions, default 1000;
#                                          cores: default ssi_master biss_master endat_master tformat_host)
#
# For each core: the seed (or, where there is none, the first) configuration of the closed loop
# (hdl/tb_cosim/<core>/configs/seed_*.toml) is also a scenario file; tbgen
# turns it, with N reads/frames of moving positions, into golden vectors, and
# the same N transactions are run (a) as a vector replay (scripts/sim.sh) and
# (b) closed-loop against the emulator (scripts/cosim.sh). Builds are untimed.
# Quote the ratios: the absolute rates depend on the machine and its load.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
n=${1:-1000}
shift $(( $# > 0 ? 1 : 0 ))
cores=("$@")
[ ${#cores[@]} -gt 0 ] || cores=(ssi_master biss_master endat_master tformat_host)
out="$root/build/cosim_bench"
mkdir -p "$out"
(cd "$root" && cargo build -q --release -p tbgen -p cosim -j 2)
tbgen="${CARGO_TARGET_DIR:-$root/target}/release/tbgen"
now() { date +%s.%N; }
calc() { awk "BEGIN { printf \"%.3f\", $1 }"; }

printf '%-12s %-9s %6s %10s %10s %12s %12s %8s\n' core sim N "replay s" "cosim s" "replay c/s" "cosim c/s" "cosim/replay"
for core in "${cores[@]}"; do
    cfg=$( (ls "$root"/hdl/tb_cosim/$core/configs/seed_*.toml 2> /dev/null || true) | head -n 1)
    [ -n "$cfg" ] || cfg=$(ls "$root"/hdl/tb_cosim/$core/configs/*.toml | head -n 1)
    scenario="$out/$core.toml"
    case "$core" in
    ssi_master) sed "s/^\[ssi\]$/[ssi]\nreads = $n\nstep = 7919/" "$cfg" > "$scenario" ;;
    biss_master) sed "s/^\[\[biss.slaves\]\]$/[[biss.slaves]]\nstep = 7919/" "$cfg" > "$scenario"
                 printf '\n[biss.host]\nframes = %d\n' "$n" >> "$scenario" ;;
    # EnDat: the same number of 2.2 position reads (the closed loop mixes in a few 2.1 reads and faults).
    endat_master) sed -e '/^\[endat.emulator\]$/,/^$/d' -e "s/^\[endat\]$/[endat]\nstep = 7919/" "$cfg" > "$scenario"
                  printf '\n[[endat.commands]]\ncommand = "pos22"\nrepeat = %d\n' "$n" >> "$scenario" ;;
    # T-format: N Data ID 3 readouts.
    tformat_host) cp "$cfg" "$scenario"
                  for _ in $(seq "$n"); do printf '\n[[tformat.ops]]\ndata_id = 3\n'; done >> "$scenario" ;;
    esac
    "$tbgen" gen "$scenario" --out "$out" > /dev/null
    name=$(sed -n 's/^name = "\(.*\)"/\1/p' "$scenario")
    vectors="$out/$name.hex"
    cycles=$(sed -n 's#^// cycles: ##p' "$vectors")
    for sim in verilator icarus; do
        "$root/scripts/sim.sh" "$core" "$sim" "$vectors" > "$out/$core.$sim.replay.log" 2>&1 \
            || { echo "cosim_bench: replay failed ($out/$core.$sim.replay.log)" >&2; exit 1; }
        t0=$(now)
        "$root/scripts/sim.sh" "$core" "$sim" "$vectors" > /dev/null 2>&1
        t1=$(now)
        replay=$(calc "$t1 - $t0")
        "$root/scripts/cosim.sh" "$core" "$sim" --config "$cfg" --transactions 1 > /dev/null 2>&1
        line=$("$root/scripts/cosim.sh" "$core" "$sim" --config "$cfg" --transactions "$n" | grep "cycles/s" | head -n 1)
        cosim_s=$(sed -n 's/.* cycles in \([0-9.]*\) s.*/\1/p' <<< "$line")
        cosim_rate=$(sed -n 's/.*(\([0-9]*\) cycles\/s).*/\1/p' <<< "$line")
        printf '%-12s %-9s %6d %10.2f %10.2f %12.0f %12s %8.2fx\n' "$core" "$sim" "$n" "$replay" "$cosim_s" \
            "$(calc "$cycles / $replay")" "$cosim_rate" "$(calc "$cosim_s / $replay")"
    done
done
