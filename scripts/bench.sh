#!/usr/bin/env bash
# bench.sh: speed of the model against the simulators on the same vectors.
#
# For each scenarios/bench/*.toml (sized so that each simulator takes
# seconds): `tbgen bench` times the model and the VCD writer (best of
# several runs, see tbgen/src/bench.rs); `tbgen gen` writes the vectors
# (untimed); each simulator is built without replaying (SIM_BUILD_ONLY=1,
# untimed, cached under build/sim/), then replays the vectors once, timed.
#
# Columns:
#   cycles      system-clock cycles of the scenario (= vector records replayed)
#   quiet       share of those cycles the model's fast-forward skips
#               (Testbench::quiet_cycles: idle, monoflop, recovery, timeouts)
#   model c/s   model cycles per second with fast-forward, recording nothing:
#               what campaigns run (cycles / best run time)
#   stepped c/s the model stepped every cycle, recording nothing
#   veril. c/s  Verilator cycles per second: cycles / wall time of one replay
#               of the same vectors (loading the vector file included, build not)
#   icarus c/s  the same for Icarus (vvp)
#   mod/veril   model c/s / Verilator c/s (mod/icar, ver/icar likewise)
#   VCD MB/s    the VCD writer alone: MB (10^6 bytes) of the scenario's VCD
#               over the time to write it from samples held in memory, no
#               model running (the file is byte for byte `tbgen gen`'s)
#   (to come with co-simulation: closed-loop cycles per second per core)
#
# All figures of a row come from one run on one machine: quote the ratios,
# not the absolute numbers, which depend on the machine and its load. The
# last line is the wall time of the whole script.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tbgen="$root/target/release/tbgen"
out="$root/build/bench"
mkdir -p "$out"

now() { date +%s.%N; }
field() { sed -n "s/^$1: //p"; }
calc() { awk "BEGIN { printf \"%.6f\", $1 }"; }

started=$(now)
printf '%-12s %9s %6s %12s %12s %11s %11s %10s %9s %9s %9s\n' \
    scenario cycles quiet "model c/s" "stepped c/s" "veril. c/s" "icarus c/s" "mod/veril" "mod/icar" "ver/icar" "VCD MB/s"
for toml in "$root"/scenarios/bench/*.toml; do
    report=$("$tbgen" bench "$toml")
    name=$(echo "$report" | field scenario)
    cycles=$(echo "$report" | field cycles)
    quiet=$(echo "$report" | field quiet_share)
    [ -n "$quiet" ] || { echo "bench: '$tbgen bench' gave no quiet_share: its Bench command must call tbgen::bench::report" >&2; exit 1; }
    model=$(echo "$report" | field model_cycles_per_second)
    stepped=$(echo "$report" | field model_stepped_cycles_per_second)
    vcd=$(echo "$report" | field vcd_writer_bytes_per_second)
    "$tbgen" gen "$toml" --out "$out" > /dev/null
    vectors="$out/$name.hex"
    core=$(sed -n 's#^// core: ##p' "$vectors")
    declare -A rate=()
    for sim in verilator icarus; do
        SIM_BUILD_ONLY=1 "$root/scripts/sim.sh" "$core" "$sim" "$vectors" > "$out/$name.$sim.build.log" 2>&1 \
            || { echo "bench: building $sim for $name failed (see $out/$name.$sim.build.log)" >&2; exit 1; }
        t0=$(now)
        "$root/scripts/sim.sh" "$core" "$sim" "$vectors" > "$out/$name.$sim.log" 2>&1 \
            || { echo "bench: $sim failed on $name (see $out/$name.$sim.log)" >&2; exit 1; }
        t1=$(now)
        rate[$sim]=$(calc "$cycles / ($t1 - $t0)")
    done
    printf '%-12s %9d %5.1f%% %12.3g %12.3g %11.3g %11.3g %9.0fx %8.0fx %8.1fx %9.1f\n' \
        "$name" "$cycles" "$(calc "100 * $quiet")" "$model" "$stepped" "${rate[verilator]}" "${rate[icarus]}" \
        "$(calc "$model / ${rate[verilator]}")" "$(calc "$model / ${rate[icarus]}")" \
        "$(calc "${rate[verilator]} / ${rate[icarus]}")" "$(calc "$vcd / 1000000")"
done
printf 'bench.sh: %.0f s in all\n' "$(calc "$(now) - $started")"
