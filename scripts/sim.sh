#!/usr/bin/env bash
# sim.sh: replay one golden vector file against its core in Icarus or Verilator.
#
#   scripts/sim.sh <core> <icarus|verilator> <vectors.hex> [waves.vcd]
#
# Reads the vector file's header (params, records, f_sys_hz), builds the
# core's testbench hdl/tb/<core>/tb_<core>.v with those parameters (cached
# under build/sim/<core>/<sim>/<parameter hash>/, so scenarios that share a
# configuration share one build), runs it, and exits with the simulator's
# status: 0 when every output matched every cycle, non-zero at the first
# mismatch. With a fourth argument the RTL waveform is dumped there.
#
# Environment (all optional; without them nothing above changes):
#   COVERAGE=1      Verilator only: build with --coverage (line, branch,
#                   toggle; its own cache key) and write the counts of this
#                   run to build/coverage/<core>/<scenario>.dat, for
#                   scripts/coverage.sh. Icarus runs ignore it.
#   RTL_DIR         directory of the *.v files to build (default hdl/rtl;
#                   scripts/mutate.py points it at a mutant)
#   SIM_BUILD_DIR   build cache root (default build/sim)
#   SIM_BUILD_ONLY=1  build (or find in the cache) and stop before the replay
#   SIM_PLUSARGS    more plusargs for the replay, space-separated
#                   (scripts/mutate.py: +mutant_id=K picks a mutant of its schema)
#   COVERAGE_FILE   with COVERAGE=1: where this run's counts go instead
#                   (tests/hdl.rs's flipped-bit replays reuse the coverage
#                   builds of make test's replays without adding to the report)
#   ENCODER_TB_MODEL_CACHE  Verilator models built on this machine, in any
#                   clone, are copied from there instead of built again
#                   (scripts/model_cache.sh; empty: off)
#   VERILATOR_OPT   0 or 1: the -O level of the Verilator model's C++. Unset,
#                   it is chosen per parameter set, the same for every caller
#                   (make test's replays, the cargo tests, make sim), so that
#                   they all share one build: -O0 when the committed vector
#                   files of this core with this file's parameters and clock
#                   add up to fewer than VERILATOR_O0_CYCLES cycles (default
#                   100000), else -O1. With coverage on, -O0 compiles about
#                   3 to 7 s faster and replays about 6 to 16 us per cycle
#                   slower: one build against one replay breaks even near
#                   400000 cycles, but ccache keeps a build for every later
#                   run on the machine, in any clone (verilator_ccache.sh),
#                   while the replays are paid on each run: at 100000 cycles
#                   -O1 pays back its compile by the fourth run.
set -euo pipefail

usage() { echo "usage: $0 <core> <icarus|verilator> <vectors.hex> [waves.vcd]" >&2; exit 2; }
[ $# -ge 3 ] || usage
core=$1 sim=$2 vectors=$3 waves=${4:-}
root=$(cd "$(dirname "$0")/.." && pwd)
# ccache, and Verilator run on paths relative to $root (in_repo): the
# same build in any clone is one ccache entry (verilator_ccache.sh).
# shellcheck source=scripts/verilator_ccache.sh
. "$root/scripts/verilator_ccache.sh"
# shellcheck source=scripts/model_cache.sh
. "$root/scripts/model_cache.sh"
tb="$root/hdl/tb/$core/tb_$core.v"
if [ ! -f "$tb" ]; then
    echo "sim.sh: no testbench $tb for core '$core'; the cores are: $(cd "$root/hdl/tb" && for d in */; do d=${d%/}; [ -f "$d/tb_$d.v" ] && printf '%s ' "$d"; done)" >&2
    exit 2
fi
case "$sim" in
icarus|verilator) ;;
*) echo "sim.sh: unknown simulator '$sim'; the supported simulators are: icarus verilator" >&2; exit 2 ;;
esac
[ -f "$vectors" ] || { echo "sim.sh: no vector file $vectors" >&2; exit 2; }

# The header, read and checked by the vector file's own reader
# (vectorfile::Replay, through `xtask vector-header`): records, f_sys_hz,
# words_per_record, params and group_cycles, or exit 2 naming the file, its
# line and the fix. Built here when missing (make test builds it first).
xtask="${CARGO_TARGET_DIR:-$root/target}/release/xtask"
[ -x "$xtask" ] || cargo build --release --quiet --manifest-path "$root/Cargo.toml" -p xtask >&2
header_vars=$("$xtask" vector-header "$core" "$vectors") || exit 2
eval "$header_vars"

# Half a system-clock period in femtoseconds (the testbench timescale is 1 fs).
half_fs=$(( 500000000000000 / f_sys_hz ))
# The vector memory, in 64-bit words. Verilator: 4 Mi words, doubled until
# the file fits, so that ordinary files share one (costly) build and long
# benches still fit. Icarus builds in a second but allocates the whole
# memory at every start (4 Mi words: 170 MB, about 1 s of a short replay on
# a loaded machine): the smallest power of two from 4 Ki words that fits.
words=$words_per_record
max_words=$(( 1 << 22 ))
[ "$sim" = icarus ] && max_words=$(( 1 << 12 ))
while [ $(( records * words )) -gt "$max_words" ]; do max_words=$(( max_words * 2 )); done
# Absolute, since Verilator runs from $root: a relative RTL_DIR is the caller's.
rtl_dir=${RTL_DIR:-$root/hdl/rtl}
[[ "$rtl_dir" = /* ]] || rtl_dir="$PWD/$rtl_dir"
rtl=("$rtl_dir"/*.v)
trace=0
[ -n "$waves" ] && trace=1
coverage=0 cov_main="$root/hdl/tb/common/coverage_main.cpp"
[ "${COVERAGE:-0}" = 1 ] && [ "$sim" = verilator ] && coverage=1
# A coverage build is another binary: its key adds a line (and the main it
# is built with), so plain builds keep their keys.
cov_key=() cov_files=()
[ "$coverage" = 1 ] && cov_key=(coverage) cov_files=("$cov_main")
# How Verilator's C++ is compiled (scripts/verilator_make_flags.sh: one
# translation unit at -O1, a third of the default build's compile time and
# a faster model); part of the key, so a build made otherwise is not reused.
vflags=()
if [ "$sim" = verilator ]; then
    if [ -z "${VERILATOR_OPT:-}" ]; then
        # group_cycles: the cycles of the committed files that share this
        # build (xtask vector-header reads their headers).
        export VERILATOR_OPT=1
        [ "$group_cycles" -lt "${VERILATOR_O0_CYCLES:-100000}" ] && VERILATOR_OPT=0
    fi
    read -ra vflags <<< "$("$root/scripts/verilator_make_flags.sh")"
fi
# The testbench's port half, written from the model (tbgen/src/testbench_ports.rs).
ports_vh="$root/hdl/tb/$core/tb_${core}_ports.vh"
key=$(printf '%s\n' "$params" "$half_fs" "$trace" "$max_words" "${cov_key[@]}" "${vflags[@]}" | cat - "$tb" "$ports_vh" "$root/hdl/tb/common/vector_player.vh" "${rtl[@]}" "${cov_files[@]}" | sha1sum | cut -c1-12)
build="${SIM_BUILD_DIR:-$root/build/sim}/$core/$sim/$key"
# Absolute, since Verilator runs from $root: a relative SIM_BUILD_DIR is the caller's.
[[ "$build" = /* ]] || build="$PWD/$build"
mkdir -p "$build"
# Parallel runs (cargo's test threads, make -j) may want the same build:
# one builds while the others wait on the lock, then all reuse it.
exec 9> "$build/.lock"
flock 9

plusargs=("+vectors=$vectors" "+records=$records")
[ -n "$waves" ] && plusargs+=("+waves=$waves")
if [ -n "${SIM_PLUSARGS:-}" ]; then read -ra extra <<< "$SIM_PLUSARGS"; plusargs+=("${extra[@]}"); fi
if [ "$coverage" = 1 ]; then
    cov_file=${COVERAGE_FILE:-$root/build/coverage/$core/$(basename "$vectors" .hex).dat}
    mkdir -p "$(dirname "$cov_file")"
    rm -f "$cov_file"
    plusargs+=("+coverage_file=$cov_file")
fi

case "$sim" in
icarus)
    if [ ! -f "$build/tb.vvp" ]; then
        pargs=()
        for p in $params; do pargs+=("-Ptb_$core.$p"); done
        iverilog -g2005 -Wall -Wno-timescale -s "tb_$core" -I "$root/hdl/tb/common" -I "$root/hdl/tb/$core" \
            "${pargs[@]}" "-Ptb_$core.HALF_PERIOD_FS=$half_fs" "-Ptb_$core.MAX_WORDS=$max_words" \
            -o "$build/tb.vvp.tmp" "$tb" "${rtl[@]}" > "$build/build.log" 2>&1 \
            || { cat "$build/build.log" >&2; exit 1; }
        mv "$build/tb.vvp.tmp" "$build/tb.vvp"
    fi
    flock -u 9
    [ "${SIM_BUILD_ONLY:-0}" = 1 ] && exit 0
    exec vvp -n "$build/tb.vvp" "${plusargs[@]}"
    ;;
verilator)
    if [ ! -x "$build/Vtb" ]; then
        gargs=()
        for p in $params; do gargs+=("-G$p"); done
        targs=(--binary)
        [ "$trace" = 1 ] && targs+=(--trace)
        # Verilator 5.006's --binary main never writes coverage: its own main does.
        [ "$coverage" = 1 ] && targs=(--cc --exe --build --coverage --prefix Vtb "$cov_main")
        [ "$coverage" = 1 ] && [ "$trace" = 1 ] && targs+=(--trace)
        # From $root, on names relative to it (verilator_ccache.sh: why).
        rel_rtl=()
        for f in "${rtl[@]}"; do rel_rtl+=("$(in_repo "$f")"); done
        # Built on this machine before, in any clone (model_cache.sh: why):
        # a copy. The names are part of the entry: Verilator writes them in.
        mkey=$(model_cache_key "$core" "$key" "$(in_repo "$tb")" "${rel_rtl[@]}" "$(in_repo "$cov_main")")
        if ! model_cache_get "$mkey" "$build/Vtb"; then
            (cd "$root" && verilator --timing -j 2 -Wno-fatal -Wno-lint -Wno-style "${vflags[@]}" "${targs[@]}" \
                --top-module "tb_$core" -Ihdl/tb/common "-Ihdl/tb/$core" \
                "${gargs[@]}" "-GHALF_PERIOD_FS=$half_fs" "-GMAX_WORDS=$max_words" \
                --Mdir "$build/obj" -o Vtb "$(in_repo "$tb")" "${rel_rtl[@]}") > "$build/build.log" 2>&1 \
                || { cat "$build/build.log" >&2; exit 1; }
            mv "$build/obj/Vtb" "$build/Vtb"
            model_cache_put "$mkey" "$build/Vtb"
        fi
    fi
    flock -u 9
    [ "${SIM_BUILD_ONLY:-0}" = 1 ] && exit 0
    exec "$build/Vtb" "${plusargs[@]}"
    ;;
*)
    usage
    ;;
esac
