#!/usr/bin/env bash
# vhdl_examples.sh: every VHDL master in examples/*_vhdl/ closed-loop in GHDL
# against its emulator with its monitor (`make`: 1000 random reads, must
# pass), then with a planted misread (`make FLIP_BIT=3`: the bench flips bit
# 3 of read 500, and must fail there). make test's `vhdl` stage. First,
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
exit $failed
