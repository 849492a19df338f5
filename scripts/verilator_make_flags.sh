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
# The runtime (verilated*.cpp) is compiled at -O1 too; ccache keeps it.
echo -MAKEFLAGS VM_PARALLEL_BUILDS=0 -MAKEFLAGS OPT_FAST=-O1 -MAKEFLAGS OPT_SLOW=-O1 -MAKEFLAGS OPT_GLOBAL=-O1
