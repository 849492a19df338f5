#!/usr/bin/env bash
# test.sh: what `make test` runs, stage by stage, with the wall time of each.
#
#   scripts/test.sh
#
# Stages, in two lanes that run side by side on a 2-core machine once the
# tools are checked:
#
#   deps                               tools, .venv
#   lane 1: build                      one cargo profile (release, with
#                                      overflow checks in the workspace's
#                                      crates: Cargo.toml): the tests, tbgen,
#                                      the emulator library, cosim-params and
#                                      the Python module (cosim-py), every
#                                      crate compiled once
#           cargo-test                 model, flow, HDL flip, sigrok, cosim
#                                      tests (cargo test --release)
#   lane 2: lint, hdl, coverage        Verilator lint, every vector file in
#                                      Icarus and Verilator (the Verilator
#                                      replays on the coverage build, which
#                                      the cargo tests' flipped-bit replays
#                                      reuse), RTL coverage against its
#                                      baseline
#   either: gtkw, clippy,              every .gtkw in GTKWave (signals, and
#           fusesoc, wavedrom,         the window each opens on), clippy
#           vectors, cosim, cocotb     on every crate (any warning fails),
#                                      the FuseSoC core files, the timing
#                                      diagrams, committed vectors == fresh
#                                      ones, every core closed-loop against
#                                      its emulator (1000 transactions per
#                                      core and simulator), the cocotb
#                                      examples in Icarus (the emulators
#                                      from Python, PyO3); clippy and the
#                                      last three after lane 1's build. Whichever lane is free first
#                                      takes the next of these, so neither
#                                      core idles while the other lane still
#                                      has work: lane 2 is free first, and
#                                      runs the closed loops beside the cargo
#                                      tests, which keep about one core busy.
#
# The replays need nothing from cargo, so lane 2 starts with lane 1's
# compile: rustc's long single-threaded stretches (one crate, one link at
# a time) leave a core the simulators use.
#
# Each stage's output goes to build/test/<stage>.log and is printed whole
# when the stage ends, so the two lanes never interleave lines. The last
# lines are a table of stage times (also in build/test/times.txt) and the
# verdict. Exit status 0 only if every stage passed.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
logs="$root/build/test"
# Every Verilator build of every stage through ccache (make deps installs
# it), not only those of sim.sh and cosim.sh: the cargo tests' own benches
# (monitor rules, error benches), the examples and cocotb. Each build
# compiles Verilator's runtime (verilated*.cpp) again, which ccache makes
# one compile per run, and a rerun on the same machine reuses the rest.
command -v ccache > /dev/null 2>&1 && export OBJCACHE=${OBJCACHE:-ccache}
rm -rf "$logs"
mkdir -p "$logs"
: > "$logs/times.txt"
started=$(date +%s.%N)

# stage NAME COMMAND...: run COMMAND, log it, print its log, its wall time
# and its CPU time (user + system of the stage and everything it started,
# from /usr/bin/time when it is there): on a shared machine the CPU seconds
# compare from run to run, the wall times only under the same load.
have_time=0
[ -x /usr/bin/time ] && have_time=1
stage() {
    local name=$1; shift
    local t0 t1 status cpu="-"
    t0=$(date +%s.%N)
    if [ "$have_time" = 1 ]; then
        /usr/bin/time -f '%U %S' -o "$logs/.$name.cpu" "$@" > "$logs/$name.log" 2>&1
        status=$?
        cpu=$(awk 'NF == 2 && $1 ~ /^[0-9.]+$/ { printf "%.1f", $1 + $2 }' "$logs/.$name.cpu" 2> /dev/null)
        [ -n "$cpu" ] || cpu="-"
    else
        "$@" > "$logs/$name.log" 2>&1
        status=$?
    fi
    t1=$(date +%s.%N)
    local secs
    secs=$(awk "BEGIN { printf \"%.1f\", $t1 - $t0 }")
    # One stage's output at a time, whole, whichever lane it comes from.
    {
        flock 9
        echo "==== stage $name ($secs s, cpu $cpu s, $([ $status = 0 ] && echo passed || echo FAILED, exit $status))"
        cat "$logs/$name.log"
        printf '%-12s %8s s  cpu %8s s  load %5s  %s\n' "$name" "$secs" "$cpu" "$(cut -d' ' -f1 /proc/loadavg 2> /dev/null)" \
            "$([ $status = 0 ] && echo passed || echo FAILED)" >> "$logs/times.txt"
    } 9> "$logs/.print.lock"
    return $status
}

# The stages either lane may run: each lane, when its own stages are done,
# takes the first one in this order that nobody took yet and that can start
# (cosim, clippy, vectors and cocotb need lane 1's build), waiting only when none can.
# The closed loops come first: the longest, they then run beside the cargo
# tests, and the short checks fill both lanes' ends.
shared_stages=(cosim gtkw clippy fusesoc wavedrom vectors cocotb fmt)
needs_build=" cosim clippy vectors cocotb "
# after_build NAME COMMAND...: stage NAME once lane 1's build is done (tbgen,
# the emulator library, the Python module), or a failed NAME if it failed.
after_build() {
    local name=$1; shift
    while [ ! -f "$logs/.build.status" ]; do sleep 2; done
    if [ "$(cat "$logs/.build.status")" = 0 ]; then
        stage "$name" "$@"
    else
        stage "$name" sh -c "echo \"$name: not run, the build stage failed\" >&2; exit 1"
    fi
}
run_shared() {
    case "$1" in
    gtkw) stage gtkw scripts/check_gtkw.sh ;;
    clippy) after_build clippy scripts/clippy.sh ;;
    fusesoc) stage fusesoc scripts/check_fusesoc.sh ;;
    wavedrom) stage wavedrom .venv/bin/python scripts/timing_diagrams.py --check ;;
    vectors) after_build vectors scripts/check_vectors.sh ;;
    # Icarus on each core's cheapest configuration, Verilator on every
    # one (make soak: every configuration in Icarus too).
    cosim) after_build cosim scripts/cosim_regress.sh --transactions 1000 --quick --jobs 2 ;;
    cocotb) after_build cocotb scripts/cocotb.sh ;;
    # Every Rust file as rustfmt writes it (cargo fmt --all fixes it).
    fmt) stage fmt cargo fmt --all -- --check ;;
    esac
}
# take_shared: print the next shared stage that can start and claim it
# (waiting while only stages that need the build are left and it is not
# done), or fail when none is left.
take_shared() {
    local name left
    while :; do
        left=0
        {
            flock 8
            for name in "${shared_stages[@]}"; do
                [ -f "$logs/.taken.$name" ] && continue
                left=1
                if [[ "$needs_build" == *" $name "* ]] && [ ! -f "$logs/.build.status" ]; then
                    continue
                fi
                : > "$logs/.taken.$name"
                echo "$name"
                return 0
            done
        } 8> "$logs/.shared.lock"
        [ "$left" = 1 ] || return 1
        sleep 2
    done
}
shared_lane() {
    local next lane_fail=0
    while next=$(take_shared); do
        run_shared "$next" || lane_fail=1
    done
    return $lane_fail
}

fail=0
stage deps scripts/deps.sh || fail=1
if [ $fail = 0 ]; then
    (
        lane_fail=0
        # One profile, one compile: the test binaries, then tbgen, the
        # emulator library (the cdylib and cosim-params) and the Python
        # module (cosim-py's cdylib), which cargo test does not link, on the
        # artifacts already built. --timings:
        # target/cargo-timings/ shows which crate's compile costs.
        stage build sh -c 'cargo test --release --workspace --locked --no-run --timings && cargo build --release --locked -p tbgen -p cosim -p cosim-py' || lane_fail=1
        # The shared stages vectors, cosim and cocotb need the build: tell
        # them how it went.
        echo "$lane_fail" > "$logs/.build.status"
        if [ $lane_fail = 0 ]; then
            # --no-fail-fast: every failing test binary is reported, not the
            # first. Release with overflow checks and debug assertions in the
            # workspace's crates (Cargo.toml), so that arithmetic overflow
            # panics in tests instead of wrapping.
            stage cargo-test cargo test --release --workspace --locked --no-fail-fast || lane_fail=1
        fi
        shared_lane || lane_fail=1
        exit $lane_fail
    ) &
    lane1=$!
    (
        lane_fail=0
        stage lint scripts/lint.sh || lane_fail=1
        # Coverage costs no second replay: the Verilator replays run on
        # the coverage-instrumented build and leave their counts behind.
        stage hdl env COVERAGE=1 scripts/regress.sh --icarus-budget 1000000 || lane_fail=1
        stage coverage scripts/coverage.sh --report-only || lane_fail=1
        shared_lane || lane_fail=1
        exit $lane_fail
    ) &
    lane2=$!
    wait $lane1 || fail=1
    wait $lane2 || fail=1
fi

total=$(awk "BEGIN { printf \"%.1f\", $(date +%s.%N) - $started }")
echo
echo "==== stage times (wall clock, lanes 1 and 2 overlap; CPU seconds; the 1-minute load average at the stage's end)"
cat "$logs/times.txt"
printf '%-12s %8s s  load %s\n' total "$total" "$(cut -d' ' -f1-3 /proc/loadavg 2> /dev/null)"
if [ $fail = 0 ]; then
    echo "make test: all checks passed"
else
    # Repeat the end of each failed stage's log last, so that a reader who
    # sees only the tail of the output (a CI summary) still sees the cause.
    for name in $(awk '$NF == "FAILED" { print $1 }' "$logs/times.txt"); do
        echo "==== the failed stage $name: its failure lines, then its last lines (whole log: build/test/$name.log)"
        grep -E 'FAIL|panicked|assertion|left:|right:|error|below|MISMATCH' "$logs/$name.log" | head -n 20
        echo "----"
        tail -n 8 "$logs/$name.log"
    done
    echo "make test: FAILED (see the stages marked FAILED above; logs in build/test/)" >&2
    exit 1
fi
