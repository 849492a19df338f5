#!/usr/bin/env bash
# verilator_make_flags.sh: the Verilator options with which scripts/sim.sh
# and scripts/cosim.sh compile a testbench's C++, printed on one line.
#
# Measured on endat_master with coverage (one build, ccache off, 2-core
# machine; CPU seconds of the C++ compile of the model, the runtime aside):
#   Verilator's default (a dozen translation units, -Os)   28.8 s, replay 0.49 s
#   one translation unit (VM_PARALLEL_BUILDS=0), -Os       19.2 s
#   one translation unit, -O1                              12.8 s, replay 0.19 s
#   one translation unit, -O0                               6.2 s, replay 1.03 s
# (replay: endat_params_22_2mhz, 52105 cycles). Each of the ~80 parameter
# sets of `make test` is its own build, most replays are short, so the
# compile is what costs: one unit (every header parsed once) at -O1.
# The runtime (verilated*.cpp) is compiled at -O1 always; ccache keeps it.
#
# VERILATOR_OPT=0 (environment; default 1) compiles the model at -O0:
# scripts/regress.sh asks for it for a build whose files are short (the
# compile saved is worth more than the slower replay; see the break-even
# there). Measured on the endat_master coverage build above (a loaded
# machine, CPU seconds): model -O0 6.3 s, -O1 13.5 s.
opt=${VERILATOR_OPT:-1}
case "$opt" in
0|1|2) ;;
*) echo "verilator_make_flags.sh: VERILATOR_OPT is 0, 1 or 2, not '$opt'" >&2; exit 2 ;;
esac
echo -MAKEFLAGS VM_PARALLEL_BUILDS=0 -MAKEFLAGS OPT_FAST=-O$opt -MAKEFLAGS OPT_SLOW=-O$opt -MAKEFLAGS OPT_GLOBAL=-O1
