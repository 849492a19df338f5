#!/usr/bin/env bash
# bench.sh: speed of the model, the VCD writer, the simulators replaying the
# same vectors, the closed loop, and the corruption campaigns (`make bench`).
#
#   scripts/bench.sh [replay] [cosim] [ghdl] [campaigns] [captures]   (default: all five parts)
#   BENCH_OUT=DIR scripts/bench.sh ...              (vectors and logs; default build/bench)
#
# Every simulator model is built first, untimed (replays: SIM_BUILD_ONLY=1 of
# scripts/sim.sh; closed loop: one transaction of scripts/cosim.sh), and
# cached under build/ as `make test` leaves them; then each timed run is one
# run. The last lines give the wall time of the builds and of the whole run.
#
# Part 1, vector replay: one row per scenarios/bench/*.toml (one per core,
# sized so that each simulator takes seconds):
#   cycles      system-clock cycles of the scenario, all simulated by each replay
#               (the vector file holds fewer records: a run of unchanged
#               cycles is one record)
#   quiet       share of those cycles the model's fast-forward skips
#               (Testbench::quiet_cycles: idle, monoflop, recovery, timeouts)
#   model c/s   model cycles per second with fast-forward, recording nothing:
#               what campaigns run (`tbgen bench`: best of at least 3 runs)
#   stepped c/s the model stepped every cycle, recording nothing
#   veril. c/s  Verilator cycles per second: cycles / wall time of one replay
#               of the scenario's vectors (starting the simulator and
#               loading the vector file included, build not)
#   icarus c/s  the same for Icarus (vvp)
#   mod/veril   model c/s / Verilator c/s (mod/icar, ver/icar likewise);
#               the aim is mod/veril >= 50 on every row
#   VCD MB/s    the VCD writer alone: MB (10^6 bytes) of the scenario's VCD
#               over the time to write it from samples held in memory, no
#               model running (the file is byte for byte `tbgen gen`'s)
#
# Part 2, closed loop (scripts/cosim.sh): one row per closed loop of the
# descriptors (hdl/tb_cosim/<core>/tb_cosim_<core>.v), on its seed_*.toml
# configuration (else the first one); Icarus runs N transactions, Verilator
# 10 N (N: the loop's bench_transactions in its descriptor; each run takes seconds):
#   config      the configuration file
#   V trans/s   transactions (reads, frames, operations, PDOs) per second
#               in Verilator: transactions / wall time of the run
#   V c/s       Verilator cycles per second of the closed loop
#   I trans/s, I c/s   the same in Icarus
#   cl/replay   Verilator replay c/s of the core's bench row / closed-loop
#               c/s: how many times longer a closed-loop cycle takes than a
#               vector-replay cycle of the same core (the aim is <= 2;
#               below 1 the closed loop is the faster; `-` when part 1 did
#               not run)
#
# Part 2b, closed loop in GHDL: one row per VHDL master of examples/*_vhdl/
# against the VHDL emulator and monitor (1000 reads, as `make` there; built
# untimed): transactions and cycles (of the bench's clock) per second of one
# `ghdl -r`.
#
# Part 3, campaigns (model/examples/campaign_speed.rs, 20 000 frames, best
# of three): frames per second stepping every cycle and with fast-forward,
# and their ratio; `-` where a campaign has no such run (ESL and CAN are
# bit-level: no cycle model in the loop, so no stepped run).
#
# Part 4, logic-analyser captures (`tbgen bench --capture`, tbgen/src/bench/capture.rs):
# `tbgen decode ssi` on a capture the bench makes of the SSI seed scenario's
# lines repeated, one sample per system clock, as a sigrok session (.sr) and
# as sigrok-cli's CSV (a row per sample), at 10 M and 100 M samples:
#   samples/s   samples over the wall time of the decode
#   samples/cpu-s  the same over its CPU time (on a shared machine the wall
#               time also counts other jobs' turns)
#   peak RSS    resident memory at most during the decode; the 10 M and 100 M
#               rows side by side show whether it grows with the capture
#               (samples stream; the decoders keep each line's edges, 16
#               bytes an edge)
#
# All figures of a run come from one machine at one time: quote the ratios,
# not the absolute numbers, which depend on the machine and its load.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
tbgen="${CARGO_TARGET_DIR:-$root/target}/release/tbgen"
# The Verilator column is the -O1 model's (scripts/verilator_make_flags.sh):
# left to itself, sim.sh would build a bench file whose parameters match a
# few short committed files at -O0, compiled faster but replaying slower.
export VERILATOR_OPT=${VERILATOR_OPT:-1}
out=${BENCH_OUT:-$root/build/bench}   # logs, vectors (BENCH_OUT: another folder)
# Closed-loop binaries load libcosim from this checkout's target, also when
# their cached build (keyed by content) was copied from another checkout.
export LD_LIBRARY_PATH="${CARGO_TARGET_DIR:-$root/target}/release${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
mkdir -p "$out"
parts=("$@")
[ ${#parts[@]} -gt 0 ] || parts=(replay cosim ghdl campaigns captures)
want() { [[ " ${parts[*]} " == *" $1 "* ]]; }
for p in "${parts[@]}"; do
    case "$p" in replay|cosim|ghdl|campaigns|captures) ;; *) echo "usage: $0 [replay] [cosim] [ghdl] [campaigns] [captures]" >&2; exit 2 ;; esac
done

now() { date +%s.%N; }
field() { sed -n "s/^$1: //p"; }
calc() { awk "BEGIN { printf \"%.6f\", $1 }"; }
started=$(now)
build_s=0
timed_build() { local t0; t0=$(now); "$@"; build_s=$(calc "$build_s + $(now) - $t0"); }

# The closed loops and each one's transactions in Icarus (Verilator runs 10
# times as many): about 100 000 cycles of the core's bench configuration
# (its descriptor's bench_transactions, tbgen protocols).
# shellcheck source=scripts/protocols.sh
. "$root/scripts/protocols.sh"
loops=$(closed_loops)
declare -A cosim_n=()
while read -r name _ _ _ _ _ n; do cosim_n[$name]=$n; done <<< "$loops"

# The Verilator replay rate of each core's bench row (for cl/replay).
declare -A replay_rate=()

if want replay; then
    # Vectors, then every replay build, untimed.
    declare -A core_of=()
    for toml in "$root"/scenarios/bench/*.toml; do
        name=$(basename "$toml" .toml)
        "$tbgen" gen "$toml" --out "$out" > /dev/null
        core_of[$name]=$(sed -n 's#^// core: ##p' "$out/$name.hex")
        for sim in verilator icarus; do
            timed_build env SIM_BUILD_ONLY=1 "$root/scripts/sim.sh" "${core_of[$name]}" "$sim" "$out/$name.hex" \
                > "$out/$name.$sim.build.log" 2>&1 \
                || { echo "bench: building $sim for $name failed (see $out/$name.$sim.build.log)" >&2; exit 1; }
        done
    done
fi

if want replay; then
    echo "Part 1: vector replay (scenarios/bench/*.toml)"
    printf '%-14s %-15s %8s %6s %10s %11s %10s %10s %9s %8s %8s %8s\n' \
        scenario core cycles quiet "model c/s" "stepped c/s" "veril. c/s" "icarus c/s" "mod/veril" "mod/icar" "ver/icar" "VCD MB/s"
    for toml in "$root"/scenarios/bench/*.toml; do
        report=$("$tbgen" bench "$toml")
        name=$(echo "$report" | field scenario)
        core=${core_of[$name]}
        cycles=$(echo "$report" | field cycles)
        quiet=$(echo "$report" | field quiet_share)
        [ -n "$quiet" ] || { echo "bench: '$tbgen bench' gave no quiet_share: its Bench command must call tbgen::bench::report" >&2; exit 1; }
        model=$(echo "$report" | field model_cycles_per_second)
        stepped=$(echo "$report" | field model_stepped_cycles_per_second)
        vcd=$(echo "$report" | field vcd_writer_bytes_per_second)
        declare -A rate=()
        for sim in verilator icarus; do
            t0=$(now)
            "$root/scripts/sim.sh" "$core" "$sim" "$out/$name.hex" > "$out/$name.$sim.log" 2>&1 \
                || { echo "bench: $sim failed on $name (see $out/$name.$sim.log)" >&2; exit 1; }
            t1=$(now)
            rate[$sim]=$(calc "$cycles / ($t1 - $t0)")
        done
        replay_rate[$core]=${rate[verilator]}
        printf '%-14s %-15s %8d %5.1f%% %10.3g %11.3g %10.3g %10.3g %8.0fx %7.0fx %7.1fx %8.1f\n' \
            "$name" "$core" "$cycles" "$(calc "100 * $quiet")" "$model" "$stepped" "${rate[verilator]}" "${rate[icarus]}" \
            "$(calc "$model / ${rate[verilator]}")" "$(calc "$model / ${rate[icarus]}")" \
            "$(calc "${rate[verilator]} / ${rate[icarus]}")" "$(calc "$vcd / 1000000")"
    done
    echo
fi

if want cosim; then
    # One cosim.sh run: "<transactions> <cycles> <seconds>" from its summary line.
    cosim_run() {
        local log=$1; shift
        "$root/scripts/cosim.sh" "$@" > "$log" 2>&1 || { echo "bench: closed loop failed: $* (see $log)" >&2; exit 1; }
        sed -n 's/^cosim: .*\.toml: \([0-9]*\) transactions, \([0-9]*\) cycles in \([0-9.]*\) s.*/\1 \2 \3/p' "$log" | head -n 1
    }
    read -ra cores <<< "$(cut -d' ' -f1 <<< "$loops" | paste -sd' ')"
    declare -A cfg_of=()
    for core in "${cores[@]}"; do
        cfg=$( (ls "$root"/hdl/tb_cosim/"$core"/configs/seed_*.toml 2> /dev/null || true) | head -n 1)
        [ -n "$cfg" ] || cfg=$(ls "$root"/hdl/tb_cosim/"$core"/configs/*.toml | head -n 1)
        cfg_of[$core]=$cfg
        for sim in verilator icarus; do
            timed_build cosim_run "$out/cosim.$core.$sim.build.log" "$core" "$sim" --config "$cfg" --transactions 1 > /dev/null
        done
    done
    echo "Part 2: closed loop (scripts/cosim.sh; Icarus N transactions, Verilator 10 N)"
    printf '%-15s %-28s %5s %9s %10s %9s %10s %9s\n' core config N "V trans/s" "V c/s" "I trans/s" "I c/s" cl/replay
    for core in "${cores[@]}"; do
        n=${cosim_n[$core]}
        read -r vt vc vs < <(cosim_run "$out/cosim.$core.verilator.log" "$core" verilator --config "${cfg_of[$core]}" --transactions $((10 * n)))
        read -r it ic is < <(cosim_run "$out/cosim.$core.icarus.log" "$core" icarus --config "${cfg_of[$core]}" --transactions "$n")
        vrate=$(calc "$vc / $vs")
        ratio=-
        [ -n "${replay_rate[$core]:-}" ] && ratio=$(printf '%.2fx' "$(calc "${replay_rate[$core]} / $vrate")")
        printf '%-15s %-28s %5d %9.0f %10.3g %9.1f %10.3g %9s\n' "$core" "$(basename "${cfg_of[$core]}")" "$n" \
            "$(calc "$vt / $vs")" "$vrate" "$(calc "$it / $is")" "$(calc "$ic / $is")" "$ratio"
    done
    echo
fi

if want ghdl; then
    echo "Part 2b: closed loop in GHDL (examples/*_vhdl: a VHDL master, the VHDL emulator and monitor)"
    printf '%-22s %5s %10s %10s %10s\n' example N trans/s c/s cycles
    for dir in "$root"/examples/*_vhdl; do
        name=$(basename "$dir")
        top=$(sed -n 's/^TOP := //p' "$dir/Makefile")
        timed_build make -s -C "$dir" "build/$top.stamp"
        t0=$(now)
        (cd "$dir" && ghdl -r --std=08 --workdir=build "$top") > "$out/ghdl.$name.log" 2>&1 \
            || { echo "bench: GHDL failed on $name (see $out/ghdl.$name.log)" >&2; exit 1; }
        t1=$(now)
        # "PASS <master>: <N> reads ... decoded, <C> cycles"
        read -r reads cycles < <(sed -n 's/.*PASS [a-z0-9_]*: \([0-9]*\) .*, \([0-9]*\) cycles$/\1 \2/p' "$out/ghdl.$name.log")
        printf '%-22s %5d %10.0f %10.3g %10d\n' "$name" "$reads" "$(calc "$reads / ($t1 - $t0)")" \
            "$(calc "$cycles / ($t1 - $t0)")" "$cycles"
    done
    echo
fi

if want campaigns; then
    timed_build bash -c "cd '$root' && cargo build -q --release -p model --example campaign_speed -j 2"
    echo "Part 3: corruption campaigns (frames/s, best of three runs of 20000 frames)"
    printf '%-10s %-12s %12s %12s %8s\n' campaign kind stepped fast-fwd ratio
    "${CARGO_TARGET_DIR:-$root/target}/release/examples/campaign_speed" 20000 |
        while read -r _ name kind _ stepped fast; do
            ratio=-
            [ "$stepped" != - ] && [ "$fast" != - ] && ratio=$(printf '%.2fx' "$(calc "$fast / $stepped")")
            printf '%-10s %-12s %12s %12s %8s\n' "$name" "$kind" "$stepped" "$fast" "$ratio"
        done
    echo
fi

if want captures; then
    echo "Part 4: tbgen decode on logic-analyser captures (the SSI seed scenario's lines, repeated)"
    printf '%-6s %11s %12s %6s %12s %14s %10s\n' format samples "file MB" reads samples/s samples/cpu-s "peak RSS MB"
    for format in sr csv; do
        for samples in 10000000 100000000; do
            report=$(TMPDIR="$out" "$tbgen" bench --capture "$format" --samples "$samples")
            rss=$(echo "$report" | field peak_rss_bytes)
            [ "$rss" = - ] || rss=$(printf '%.1f' "$(calc "$rss / 1000000")")
            cpu=$(echo "$report" | field samples_per_cpu_second)
            [ "$cpu" = - ] || cpu=$(printf '%.3g' "$cpu")
            printf '%-6s %11d %12.1f %6d %12.3g %14s %10s\n' "$format" "$samples" \
                "$(calc "$(echo "$report" | field file_bytes) / 1000000")" "$(echo "$report" | field reads)" \
                "$(echo "$report" | field samples_per_second)" "$cpu" "$rss"
        done
    done
    echo
fi

total=$(calc "$(now) - $started")
printf 'bench.sh: %.0f s in all, of which %.0f s building simulator models and examples (untimed); load average at the end: %s\n' \
    "$total" "$build_s" "$(cut -d' ' -f1-3 /proc/loadavg)"
