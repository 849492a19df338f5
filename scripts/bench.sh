#!/usr/bin/env bash
# bench.sh: speed of the model against the simulators on the same scenario.
#
# For each scenarios/bench/*.toml: the model alone (tbgen bench), the model
# writing vectors + VCD, then Verilator and Icarus replaying those vectors
# (each simulator is built first, untimed; the timed run is the replay only).
# All figures of a row come from one run on one machine: quote the ratios,
# not the absolute numbers, which depend on the machine and its load.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tbgen="$root/target/release/tbgen"
out="$root/build/bench"
mkdir -p "$out"

now() { date +%s.%N; }
field() { sed -n "s/^$1: //p"; }
calc() { awk "BEGIN { printf \"%.6f\", $1 }"; }

printf '%-12s %10s %12s %12s %12s %10s %10s %10s %10s\n' \
    scenario cycles "model c/s" "veril. c/s" "icarus c/s" "mod/veril" "mod/icar" "ver/icar" "VCD MB/s"
for toml in "$root"/scenarios/bench/*.toml; do
    report=$("$tbgen" bench "$toml")
    name=$(echo "$report" | field scenario)
    cycles=$(echo "$report" | field cycles)
    model=$(echo "$report" | field model_cycles_per_second)
    vcd=$(echo "$report" | field vcd_bytes_per_second)
    "$tbgen" gen "$toml" --out "$out" > /dev/null
    vectors="$out/$name.hex"
    core=$(sed -n 's#^// core: ##p' "$vectors")
    declare -A rate=()
    for sim in verilator icarus; do
        "$root/scripts/sim.sh" "$core" "$sim" "$vectors" > "$out/$name.$sim.build.log" 2>&1 \
            || { echo "bench: $sim failed on $name (see $out/$name.$sim.build.log)" >&2; exit 1; }
        t0=$(now)
        "$root/scripts/sim.sh" "$core" "$sim" "$vectors" > "$out/$name.$sim.log" 2>&1
        t1=$(now)
        rate[$sim]=$(calc "$cycles / ($t1 - $t0)")
    done
    printf '%-12s %10d %12.0f %12.0f %12.0f %9.1fx %9.1fx %9.1fx %10.1f\n' \
        "$name" "$cycles" "$model" "${rate[verilator]}" "${rate[icarus]}" \
        "$(calc "$model / ${rate[verilator]}")" "$(calc "$model / ${rate[icarus]}")" \
        "$(calc "${rate[verilator]} / ${rate[icarus]}")" "$(calc "$vcd / 1000000")"
done
