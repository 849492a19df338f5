#!/usr/bin/env bash
# vhdl_examples.sh: every VHDL master in examples/*_vhdl/ closed-loop in GHDL
# against its emulator with its monitor (`make`: 1000 random reads, must
# pass), then with a planted misread (`make FLIP_BIT=3`: the bench flips bit
# 3 of read 500, and must fail there). make test's `vhdl` stage.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
failed=0
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
