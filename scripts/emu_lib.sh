#!/usr/bin/env bash
# emu_lib.sh: build the encoder emulator library (libcosim.so) and its Icarus
# VPI module (build/emu/emu.vpi) when either is out of date, then print the
# three paths a testbench's build needs, as make/shell assignments:
#
#   EMU_LIB_DIR=<dir of libcosim.so>   (Verilator: -LDFLAGS "-L$EMU_LIB_DIR -lcosim -Wl,-rpath,$EMU_LIB_DIR")
#   EMU_VPI_DIR=<dir of emu.vpi>       (Icarus: vvp -M $EMU_VPI_DIR -m emu tb.vvp)
#   EMU_HDL_DIR=<hdl/emu>              (the wrappers and emu_api.vh: -I / -y)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
target=${CARGO_TARGET_DIR:-$root/target}
# With tbgen and cosim-py (the Python module, scripts/cocotb.sh): the
# package selection of make test's build stage, so that cargo resolves the
# same features (-p cosim alone builds the proc-macros' syn without "full",
# then serde and everything above it again) and finds everything already
# built.
lib_dir="$target/release"
# The first build of a clone takes minutes: said, with cargo's own progress;
# later ones, when there is little or nothing to rebuild, quietly.
quiet=-q
if [ ! -f "$lib_dir/libcosim.so" ]; then
    echo "emu_lib.sh: building the emulator library in $root (the first time takes a few minutes)" >&2
    quiet=
fi
(cd "$root" && cargo build $quiet --release --locked -p tbgen -p cosim -p cosim-py -j 2) >&2
vpi_dir="$root/build/emu"
mkdir -p "$vpi_dir"
exec 8> "$vpi_dir/.lock"
flock 8
vpi="$vpi_dir/emu.vpi"
if [ ! -f "$vpi" ] || [ "$lib_dir/libcosim.so" -nt "$vpi" ] || [ "$root/hdl/emu/vpi/emu_vpi.c" -nt "$vpi" ]; then
    # shellcheck disable=SC2046
    gcc -shared -fPIC $(iverilog-vpi --cflags) -o "$vpi.tmp" "$root/hdl/emu/vpi/emu_vpi.c" \
        -L"$lib_dir" -lcosim -Wl,-rpath,"$lib_dir" $(iverilog-vpi --ldflags) $(iverilog-vpi --ldlibs) >&2
    mv "$vpi.tmp" "$vpi"
fi
echo "EMU_LIB_DIR=$lib_dir"
echo "EMU_VPI_DIR=$vpi_dir"
echo "EMU_HDL_DIR=$root/hdl/emu"
