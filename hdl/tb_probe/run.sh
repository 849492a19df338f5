#!/usr/bin/env bash
# run.sh: every rule probe of every kit (cosim/src/probe/) in Icarus, in
# Verilator, from cocotb and in GHDL (the VHDL wrappers), each run judged by
# `tbgen probes --check`, the verdict of the library's own run
# (cosim/tests/unit/rules.rs).
#
#   hdl/tb_probe/run.sh [--out DIR] [icarus] [verilator] [cocotb] [ghdl]   (default: all four)
#
# `tbgen probes --out DIR` (default build/probes) writes the probes; the
# testbench hdl/tb_probe/tb_probe.v is built once per kind and emulator
# clock for each simulator (the kit's wrappers come from DIR/<kind>/
# probe_wiring.vh) and run in each probe's folder DIR/<kind>/<probe>/<sim>/;
# hdl/cocotb/rule_probes.py runs each kit's probes in one cocotb simulation;
# GHDL analyses hdl/tb_probe/tb_probe.vhd with the kit's probe_wiring.vhd
# and the VHDL wrappers once per kind, and runs each probe with its clock.
# Exit status 0 only when every probe passed in every simulator asked for.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out="$root/build/probes"
sims=()
while [ $# -gt 0 ]; do
    case "$1" in
    --out) out=$(realpath -m "$2"); shift 2 ;;
    icarus|verilator|cocotb|ghdl) sims+=("$1"); shift ;;
    *) echo "usage: $0 [--out DIR] [icarus] [verilator] [cocotb] [ghdl]" >&2; exit 2 ;;
    esac
done
[ ${#sims[@]} -gt 0 ] || sims=(icarus verilator cocotb ghdl)
# shellcheck source=scripts/verilator_ccache.sh
. "$root/scripts/verilator_ccache.sh"
eval "$("$root/scripts/emu_lib.sh")"
export EMU_LIB_DIR
export LD_LIBRARY_PATH="$EMU_LIB_DIR${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
tbgen="$EMU_LIB_DIR/tbgen"
(cd "$root" && "$tbgen" probes --out "$out")
tb="$root/hdl/tb_probe/tb_probe.v"
status=0

# The builds: one per kind, emulator clock and stimulus depth.
groups=$(awk -F'\t' '!/^#/ { print $1, $2, $3 }' "$out/probes.tsv" | sort -u)

run_hdl() {
    local sim=$1 kind f depth build key
    local vflags=()
    # The model at -O0 unless asked otherwise: the probes are short (a few
    # thousand cycles each, the library's work), the compile is what costs
    # (scripts/verilator_make_flags.sh: the measures).
    [ "$sim" = verilator ] && read -ra vflags <<< "$(VERILATOR_OPT=${VERILATOR_OPT:-0} "$root/scripts/verilator_make_flags.sh")"
    while read -r kind f depth; do
        key=$(printf '%s\n' "$kind" "$f" "$depth" "${vflags[@]}" \
            | cat - "$tb" "$out/$kind/probe_wiring.vh" "$root"/hdl/emu/*.vh "$root"/hdl/emu/*.v | sha1sum | cut -c1-12)
        build="$root/build/tb_probe/$sim/$kind-$key"
        mkdir -p "$build"
        case "$sim" in
        icarus)
            if [ ! -f "$build/tb.vvp" ]; then
                iverilog -g2005 -Wall -Wno-timescale -Wno-implicit-dimensions -s tb_probe \
                    -I "$out/$kind" -I "$root/hdl/emu" -y "$root/hdl/emu" \
                    -Ptb_probe.F_HZ="$f" -Ptb_probe.STIM_DEPTH="$depth" \
                    -o "$build/tb.vvp.tmp" "$tb" > "$build/build.log" 2>&1 \
                    || { cat "$build/build.log" >&2; return 1; }
                mv "$build/tb.vvp.tmp" "$build/tb.vvp"
            fi
            ;;
        verilator)
            if [ ! -x "$build/Vtb" ]; then
                # --x-assign 0: the X the testbench drives on an unknown pin
                # is 0, as the library reads it (two-state: tb_probe.v).
                (cd "$root" && verilator --binary --timing -j 2 -Wno-fatal -Wno-lint -Wno-style "${vflags[@]}" \
                    --x-assign 0 --x-initial 0 --top-module tb_probe \
                    -I"$out/$kind" -Ihdl/emu -y hdl/emu \
                    -GF_HZ="$f" -GSTIM_DEPTH="$depth" \
                    -LDFLAGS "-L$EMU_LIB_DIR -lcosim -Wl,-rpath,$EMU_LIB_DIR" \
                    --Mdir "$build/obj" -o Vtb "$(in_repo "$tb")") > "$build/build.log" 2>&1 \
                    || { cat "$build/build.log" >&2; return 1; }
                mv "$build/obj/Vtb" "$build/Vtb"
            fi
            ;;
        esac
        awk -F'\t' -v k="$kind" -v f="$f" -v d="$depth" '$1 == k && $2 == f && $3 == d { print $4 }' "$out/probes.tsv" \
        | while read -r probe; do
            mkdir -p "$out/$probe/$sim"
            cd "$out/$probe/$sim"
            rm -f emulator.json monitor.json
            case "$sim" in
            icarus) vvp -n -M "$EMU_VPI_DIR" -m emu "$build/tb.vvp" > sim.log 2>&1 || true ;;
            verilator) "$build/Vtb" > sim.log 2>&1 || true ;;
            esac
        done
    done <<< "$groups"
}

# GHDL: one analysis per kind (the emulator clock is a generic of the run).
run_ghdl() {
    local kind build vhdl="$root/hdl/emu/vhdl"
    for kind in $(awk -F'\t' '!/^#/ { print $1 }' "$out/probes.tsv" | sort -u); do
        build="$root/build/tb_probe/ghdl/$kind"
        rm -rf "$build"
        mkdir -p "$build"
        (cd "$build" && ghdl -a --std=08 "$vhdl/emu_ffi.vhd" "$vhdl/emu_pkg.vhd" "$vhdl/emu_core.vhd" \
            "$vhdl"/*_emu.vhd "$vhdl"/*_monitor.vhd "$out/$kind/probe_wiring.vhd" "$root/hdl/tb_probe/tb_probe.vhd" \
            && ghdl -e --std=08 tb_probe) > "$build/build.log" 2>&1 || { cat "$build/build.log" >&2; return 1; }
        awk -F'\t' -v k="$kind" '$1 == k { print $2, $4 }' "$out/probes.tsv" \
        | while read -r f probe; do
            mkdir -p "$out/$probe/ghdl"
            rm -f "$out/$probe/ghdl/emulator.json" "$out/$probe/ghdl/monitor.json"
            (cd "$out/$probe/ghdl" && ghdl -r --std=08 --workdir="$build" tb_probe -gF_HZ="$f" > sim.log 2>&1) || true
        done
    done
}

for sim in "${sims[@]}"; do
    start=$(date +%s.%N)
    case "$sim" in
    icarus|verilator) run_hdl "$sim" || { status=1; continue; } ;;
    ghdl) run_ghdl || { status=1; continue; } ;;
    cocotb)
        [ -x "$root/.venv/bin/python" ] || { echo "run.sh: .venv has no Python; run: make deps" >&2; exit 2; }
        "$root/.venv/bin/python" "$root/hdl/cocotb/rule_probes.py" "$out" > "$out/cocotb.log" 2>&1 || true
        ;;
    esac
    end=$(date +%s.%N)
    (cd "$root" && "$tbgen" probes --check "$out" --sim "$sim") > "$out/$sim.txt" || status=1
    grep -v ': pass, ' "$out/$sim.txt" || true
    echo "probes $sim: $(awk "BEGIN { printf \"%.1f\", $end - $start }") s (wall), details in $out/$sim.txt"
done
exit $status
