#!/usr/bin/env bash
# vhdl_examples.sh: every VHDL master in examples/*_vhdl/ closed-loop in GHDL
# against its emulator with its monitor (`make`: 1000 random reads, must
# pass), then with a planted misread (`make FLIP_BIT=3`: the bench flips bit
# 3 of read 500, and must fail there), and from cocotb on GHDL where the
# example has a cocotb test (`make cocotb`, the same two ways). make test's
# `vhdl` stage. First,
# emu_random_pkg.vhd must draw what emu_random.vh draws (both print the same
# draws: GHDL's and Icarus's outputs compared).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
failed=0

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
tb=$root/hdl/emu/vhdl/tb
iverilog -g2005 -I "$root/hdl/emu" -o "$tmp/r.vvp" "$tb/tb_emu_random.v"
vvp -n "$tmp/r.vvp" | tr a-f A-F > "$tmp/verilog.txt"
(cd "$tmp" && ghdl -a --std=08 "$root/hdl/emu/vhdl/emu_random_pkg.vhd" "$tb/tb_emu_random.vhd" \
    && ghdl --elab-run --std=08 tb_emu_random) > "$tmp/vhdl.txt"
if [ -s "$tmp/vhdl.txt" ] && cmp -s "$tmp/verilog.txt" "$tmp/vhdl.txt"; then
    echo "vhdl: emu_random_pkg draws what emu_random.vh draws ($(wc -l < "$tmp/vhdl.txt") draws)"
else
    diff "$tmp/verilog.txt" "$tmp/vhdl.txt" || true
    echo "vhdl: FAIL emu_random_pkg.vhd and emu_random.vh draw different numbers (left Verilog, right VHDL)"
    failed=1
fi

# Bad input stops the run at time 0 with the file, the field and the fix; X
# on an input is reported with its time and pin: tb_emu_errors, one case a
# run, each run's exit status and the message it must print.
export LD_LIBRARY_PATH=$root/target/release${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
vhdl=$root/hdl/emu/vhdl
(cd "$tmp" && ghdl -a --std=08 "$vhdl/emu_ffi.vhd" "$vhdl/emu_pkg.vhd" "$vhdl/emu_core.vhd" "$vhdl/ssi_encoder_emu.vhd" "$tb/tb_emu_errors.vhd" \
    && ghdl -e --std=08 tb_emu_errors)
printf '[encoder]\nbits = 12\n' > "$tmp/ok.toml"
printf '[encoder]\nbitz = 12\n' > "$tmp/bad.toml"
bad_input() {   # expected exit status ("fail" or "pass"), the text the output must hold, ghdl -r arguments...
    local want=$1 text=$2 out rc=0
    shift 2
    out=$(cd "$tmp" && ghdl -r --std=08 tb_emu_errors "$@" 2>&1) || rc=1
    if { [ "$want" = fail ] && [ $rc -eq 0 ]; } || { [ "$want" = pass ] && [ $rc -ne 0 ]; } || ! grep -qF -- "$text" <<<"$out"; then
        echo "$out"
        echo "vhdl: FAIL bad input ($*): wanted a $want with '$text'"
        failed=1
    else
        echo "vhdl: bad input ($*): $(grep -m1 -oF -- "$text" <<<"$out")"
    fi
}
bad_input fail "@0ms:(assertion failure): ERROR: :tb_emu_errors:u_emu: opening the ssi emulator library failed: no configuration file"
bad_input fail "@0ms:(assertion failure): ERROR: :tb_emu_errors:u_emu: opening the ssi emulator library failed: nope.toml: cannot read" +ssi_emu_config=nope.toml
bad_input fail 'bad.toml:1: unknown field `bitz`, expected one of `bits`' +ssi_emu_config=bad.toml
bad_input fail "emulator input i_ssi_clk is X or Z (STOP_ON_X = 1)" +ssi_emu_config=ok.toml -gX_AT_NS=1000
bad_input pass "ERROR: :tb_emu_errors:u_emu: X or Z ('X') on emulator input i_ssi_clk at 1062.5 ns, emulator cycle 8 (held at '1', not read as data)" +ssi_emu_config=ok.toml -gX_AT_NS=1000 -gSTOP_ON_X=0
bad_input fail "no emulator or monitor instance is named u_enc" +ssi_emu_config=ok.toml -gCALL_NAME=u_enc
bad_input fail "cannot find in top entity generic 'x_at_nz'" +ssi_emu_config=ok.toml -gX_AT_NZ=1

# Every emulator and monitor opens its kind and steps on idle lines.
if out=$(cd "$tmp" && ghdl -a --std=08 "$vhdl"/*_emu.vhd "$vhdl"/*_monitor.vhd "$tb/tb_emu_all.vhd" \
        && ghdl --elab-run --std=08 tb_emu_all -gCONFIGS="$root/hdl/cocotb/configs" 2>&1) && grep -q 'PASS tb_emu_all' <<<"$out"; then
    echo "vhdl: $(grep -o 'PASS tb_emu_all.*' <<<"$out")"
else
    echo "$out"
    echo "vhdl: FAIL tb_emu_all"
    failed=1
fi

# The FuseSoC cores of the VHDL emulators (fusesoc/emu_vhdl/, written by
# scripts/fusesoc_cores.py, whose output the fusesoc stage compares): each
# one's `lint` target analyses, elaborates and opens it in GHDL.
n=0
for core in "$root"/fusesoc/emu_vhdl/*.core; do
    name=$(basename "$core" .core)
    grep -q '^  lint:' "$core" || continue
    if out=$(cd "$root" && .venv/bin/fusesoc --cores-root fusesoc run --build-root "$tmp/fusesoc/$name" \
            --target lint "encoder-tb:emu-vhdl:$name" 2>&1); then
        n=$((n + 1))
    else
        echo "$out" | tail -n 15
        echo "vhdl: FAIL fusesoc run --target lint encoder-tb:emu-vhdl:$name"
        failed=1
    fi
done
echo "vhdl: $n FuseSoC cores of fusesoc/emu_vhdl/ pass their lint target in GHDL"

for dir in "$root"/examples/*_vhdl; do
    name=$(basename "$dir")
    if out=$(make -s -C "$dir" 2>&1) && grep -q '^.*PASS ' <<<"$out"; then
        echo "vhdl: $name: $(grep -o 'PASS .*' <<<"$out")"
    else
        echo "$out"
        echo "vhdl: FAIL $name: the clean run did not pass"
        failed=1
    fi
    if out=$(make -s -C "$dir" FLIP_BIT=3 2>&1); then
        echo "$out"
        echo "vhdl: FAIL $name: a planted misread (FLIP_BIT=3) passed"
        failed=1
    elif grep -q 'read 500' <<<"$out"; then
        echo "vhdl: $name: the planted misread fails at read 500, as it must"
    else
        echo "$out"
        echo "vhdl: FAIL $name: the planted misread failed elsewhere than at read 500"
        failed=1
    fi
done

# cocotb on GHDL: each example with a cocotb test (`make cocotb`) passes, and
# fails with a planted misread (COSIM_FLIP_BIT=3).
for test in "$root"/examples/*_vhdl/test_*.py; do
    dir=$(dirname "$test")
    name=$(basename "$dir")
    if out=$(make -s -C "$dir" cocotb 2>&1) && grep -q '^cocotb: pass' <<<"$out"; then
        echo "vhdl: $name: $(grep -o 'cocotb: .* passed' <<<"$out")"
    else
        echo "$out"
        echo "vhdl: FAIL $name: cocotb on GHDL did not pass"
        failed=1
    fi
    if out=$(COSIM_FLIP_BIT=3 make -s -C "$dir" cocotb 2>&1); then
        echo "$out"
        echo "vhdl: FAIL $name: a planted misread (COSIM_FLIP_BIT=3) passed cocotb"
        failed=1
    elif grep -q 'AssertionError: read 0: reader' <<<"$out"; then
        echo "vhdl: $name: cocotb on GHDL fails on the planted misread, as it must"
    else
        echo "$out"
        echo "vhdl: FAIL $name: the planted misread failed cocotb elsewhere than at read 0"
        failed=1
    fi
done
exit $failed
