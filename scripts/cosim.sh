#!/usr/bin/env bash
# cosim.sh: run one of our cores closed-loop against its encoder emulator
# (libcosim through hdl/emu/), no vectors.
#
#   scripts/cosim.sh <core> <icarus|verilator> [--transactions N] [--config FILE]
#                    [--seed S] [--flip-bit K] [--transcript FILE]
#
# Every configuration in hdl/tb_cosim/<core>/configs/*.toml (or the one given)
# is a scenario file: cosim-params derives the core's parameters from its
# [master] table, the emulator reads its device, cable and fault tables. N
# transactions (default 1000) are split evenly over the configurations. The
# testbench is built once per parameter set (cached under
# build/cosim/<core>/<sim>/<hash>/, like scripts/sim.sh). --flip-bit plants a
# misread (the testbench flips bit K of the core's output before comparing):
# the run must then fail. Exit status 0 only when every configuration passed.
set -euo pipefail

usage() { echo "usage: $0 <core> <icarus|verilator> [--transactions N] [--config FILE] [--seed S] [--flip-bit K] [--transcript FILE]" >&2; exit 2; }
[ $# -ge 2 ] || usage
core=$1 sim=$2
shift 2
transactions=1000 config="" seed=1 flip="" transcript=""
while [ $# -gt 0 ]; do
    case "$1" in
    --transactions) transactions=$2; shift 2 ;;
    --config) config=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --flip-bit) flip=$2; shift 2 ;;
    --transcript) transcript=$2; shift 2 ;;
    *) usage ;;
    esac
done
root=$(cd "$(dirname "$0")/.." && pwd)
# ccache, and Verilator run on paths relative to $root (in_repo): the
# same build in any clone is one ccache entry (verilator_ccache.sh).
# shellcheck source=scripts/verilator_ccache.sh
. "$root/scripts/verilator_ccache.sh"
case "$sim" in icarus|verilator) ;; *) usage ;; esac
tb="$root/hdl/tb_cosim/$core/tb_cosim_$core.v"
if [ -n "$config" ]; then configs=("$config"); else configs=("$root"/hdl/tb_cosim/"$core"/configs/*.toml); fi

# The library, its VPI module and the parameter tool.
eval "$("$root/scripts/emu_lib.sh")"
params_tool="$EMU_LIB_DIR/cosim-params"
# The loop's emulator (its kind names the wrapper's plusarg) from the
# descriptors (tbgen protocols).
# shellcheck source=scripts/protocols.sh
. "$root/scripts/protocols.sh"
loops=$(closed_loops)
read -r _ _ _ kind emu _ < <(awk -v c="$core" '$1 == c' <<< "$loops") || {
    echo "cosim.sh: no closed-loop testbench for core '$core' ($(cut -d' ' -f1 <<< "$loops" | paste -sd' '))" >&2; exit 2; }
# The simulators load the library emu_lib.sh just built: under `cargo test`,
# LD_LIBRARY_PATH names target/debug first, where an older libcosim.so may
# lie (it would win over the Verilator binary's rpath and Icarus's search).
export LD_LIBRARY_PATH="$EMU_LIB_DIR${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

# How Verilator's C++ is compiled (one translation unit at -O1): part of the key,
# with every file a testbench can pull in (the monitors come by `include).
vflags=()
[ "$sim" = verilator ] && read -ra vflags <<< "$("$root/scripts/verilator_make_flags.sh")"

per=$(( (transactions + ${#configs[@]} - 1) / ${#configs[@]} ))
rtl=("$root"/hdl/rtl/*.v)
status=0 total=0
for cfg in "${configs[@]}"; do
    params=$("$params_tool" "$core" "$cfg") || { status=1; continue; }
    f_sys_hz=$(sed -n 's/^F_SYS_HZ=//p' <<< "$params")
    half_fs=$(( 500000000000000 / f_sys_hz ))
    key=$(printf '%s\n' "$params" "${vflags[@]}" | cat - "$tb" "$root/hdl/emu/$emu.v" "$root"/hdl/emu/*.vh "$root"/hdl/emu/*_monitor.v "${rtl[@]}" | sha1sum | cut -c1-12)
    build="$root/build/cosim/$core/$sim/$key"
    mkdir -p "$build"
    exec 9> "$build/.lock"
    flock 9
    plusargs=("+${kind}_emu_config=$cfg" "+transactions=$per" "+seed=$seed")
    [ -n "$flip" ] && plusargs+=("+flip_bit=$flip")
    [ -n "$transcript" ] && plusargs+=("+transcript=$transcript")
    case "$sim" in
    icarus)
        if [ ! -f "$build/tb.vvp" ]; then
            pargs=()
            for p in $params; do pargs+=("-Ptb_cosim_$core.$p"); done
            iverilog -g2005 -Wall -Wno-timescale -s "tb_cosim_$core" -I "$root/hdl/emu" \
                "${pargs[@]}" "-Ptb_cosim_$core.HALF_PERIOD_FS=$half_fs" \
                -o "$build/tb.vvp.tmp" "$tb" "$root/hdl/emu/$emu.v" "${rtl[@]}" > "$build/build.log" 2>&1 \
                || { cat "$build/build.log" >&2; exit 1; }
            mv "$build/tb.vvp.tmp" "$build/tb.vvp"
        fi
        flock -u 9
        start=$(date +%s.%N)
        vvp -n -M "$EMU_VPI_DIR" -m emu "$build/tb.vvp" "${plusargs[@]}" > "$build/run.log" 2>&1 || status=1
        ;;
    verilator)
        if [ ! -x "$build/Vtb" ]; then
            gargs=()
            for p in $params; do gargs+=("-G$p"); done
            rel_rtl=()
            for f in "${rtl[@]}"; do rel_rtl+=("$(in_repo "$f")"); done
            # From $root, on names relative to it (verilator_ccache.sh: why).
            (cd "$root" && verilator --binary --timing -j 2 -Wno-fatal -Wno-lint -Wno-style "${vflags[@]}" \
                --top-module "tb_cosim_$core" -Ihdl/emu \
                "${gargs[@]}" "-GHALF_PERIOD_FS=$half_fs" \
                -LDFLAGS "-L$EMU_LIB_DIR -lcosim -Wl,-rpath,$EMU_LIB_DIR" \
                --Mdir "$build/obj" -o Vtb "$(in_repo "$tb")" "hdl/emu/$emu.v" "${rel_rtl[@]}") > "$build/build.log" 2>&1 \
                || { cat "$build/build.log" >&2; exit 1; }
            mv "$build/obj/Vtb" "$build/Vtb"
        fi
        flock -u 9
        start=$(date +%s.%N)
        "$build/Vtb" "${plusargs[@]}" > "$build/run.log" 2>&1 || status=1
        ;;
    esac
    end=$(date +%s.%N)
    grep -v '^cycles ' "$build/run.log" || true
    total=$(( total + per ))
    cycles=$(sed -n 's/^cycles //p' "$build/run.log")
    seconds=$(awk "BEGIN { printf \"%.3f\", $end - $start }")
    rate=$(awk "BEGIN { if (\"$cycles\" != \"\") printf \"%.0f\", ${cycles:-0} / $seconds; else printf \"-\" }")
    echo "cosim: $core $sim $(basename "$cfg"): $per transactions, ${cycles:-?} cycles in $seconds s ($rate cycles/s)"
done
echo "cosim: $core $sim: $total transactions over ${#configs[@]} configuration(s), $([ $status = 0 ] && echo pass || echo FAIL)"
exit $status
