#!/usr/bin/env bash
# coverage.sh: RTL line, branch and toggle coverage of every core over its
# committed vector files, checked against hdl/coverage/baseline.txt.
#
#   scripts/coverage.sh [--core CORE]... [--report-only] [--write-baseline]
#
# For each core with vectors: replays every vectors/<core>/*.hex in Verilator
# built with --coverage (scripts/sim.sh with COVERAGE=1: its own build cache
# key, one counts file per replay in build/coverage/<core>/<scenario>.dat),
# merges the counts of all its replays, whatever their parameters, with
# verilator_coverage into build/coverage/<core>.dat (and an lcov file
# <core>.info), and prints per core the figures, every uncovered RTL line
# with its code, and every output port that never changed
# (scripts/coverage_report.py). Exits 1 when a replay fails or a figure is
# below the baseline.
#
# Coverage is per module: a core's figures count every line, branch and
# bit of each module in its hierarchy once, hit when any testbench that
# instantiates that module hit it (can_controller's points in
# canopen_master's figures are merged with can_controller's own vectors;
# uart_rx's and crc_serial's with every core that has one). A run of every
# core merges all of them; with --core, the counts the other cores' last
# replays left in build/coverage/<core>/ are merged too when they are
# complete (one per vector file) and newer than every RTL file, and named
# in the report (a stale or partial set is left out, and said so: the
# figures can then only be lower).
#
#   --report-only    replay nothing: merge and report the counts files the
#                    last replays left (`COVERAGE=1 scripts/regress.sh --sim
#                    verilator` writes them, so `make test` can pay for the
#                    coverage instead of a second replay). A scenario without
#                    its counts file is an error.
#   --write-baseline store the measured figures of these cores in the baseline
#
# Environment: COVERAGE_BASELINE (default hdl/coverage/baseline.txt).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cores=() replay=1 write=()
while [ $# -gt 0 ]; do
    case "$1" in
    --core) cores+=("$2"); shift 2 ;;
    --report-only) replay=0; shift ;;
    --write-baseline) write=(--write-baseline); shift ;;
    *) echo "usage: $0 [--core CORE]... [--report-only] [--write-baseline]" >&2; exit 2 ;;
    esac
done
if [ ${#cores[@]} -eq 0 ]; then
    for d in "$root"/vectors/*/; do cores+=("$(basename "$d")"); done
fi
baseline=${COVERAGE_BASELINE:-$root/hdl/coverage/baseline.txt}
out="$root/build/coverage"
mkdir -p "$out" "$root/build/logs"

status=0 merged=()
for core in "${cores[@]}"; do
    files=("$root/vectors/$core"/*.hex)
    [ -e "${files[0]}" ] || { echo "coverage: no vectors in vectors/$core/ (run make vectors)" >&2; exit 2; }
    if [ "$replay" = 1 ]; then
        rm -rf "${out:?}/$core"
        for f in "${files[@]}"; do
            name=$(basename "$f" .hex)
            log="$root/build/logs/$name.coverage.log"
            if COVERAGE=1 "$root/scripts/sim.sh" "$core" verilator "$f" > "$log" 2>&1; then
                printf 'PASS  coverage   %-12s %s\n' "$core" "$name"
            else
                printf 'FAIL  coverage   %-12s %s (%s)\n' "$core" "$name" "$log"
                status=1
            fi
        done
    fi
    dats=()
    for f in "${files[@]}"; do
        dat="$out/$core/$(basename "$f" .hex).dat"
        if [ -f "$dat" ]; then
            dats+=("$dat")
        else
            echo "coverage: no counts for $core $(basename "$f" .hex) ($dat): replay it with COVERAGE=1" >&2
            status=1
        fi
    done
    [ ${#dats[@]} -gt 0 ] || continue
    verilator_coverage --write "$out/$core.dat" "${dats[@]}" > /dev/null
    verilator_coverage --write-info "$out/$core.info" "$out/$core.dat" > /dev/null
    merged+=("$core=$out/$core.dat")
done
[ ${#merged[@]} -gt 0 ] || { echo "coverage: nothing to report" >&2; exit 1; }
# The other cores' counts, for the modules they share with these.
lent=() unlent=()
newest_rtl=$(ls -t "$root"/hdl/rtl/*.v | head -1)
for d in "$root"/vectors/*/; do
    other=$(basename "$d")
    case " ${cores[*]} " in *" $other "*) continue ;; esac
    dats=() complete=1
    for f in "$d"*.hex; do
        dat="$out/$other/$(basename "$f" .hex).dat"
        if [ -f "$dat" ] && [ "$dat" -nt "$newest_rtl" ]; then dats+=("$dat"); else complete=0; fi
    done
    if [ "$complete" = 1 ] && [ ${#dats[@]} -gt 0 ]; then
        verilator_coverage --write "$out/$other.dat" "${dats[@]}" > /dev/null
        lent+=(--merge-with "$other=$out/$other.dat")
    elif [ ${#dats[@]} -gt 0 ] || [ -d "$out/$other" ]; then
        echo "coverage: the counts of $other in $out/$other/ are partial or older than the RTL: not merged (replay it with --core $other)"
        unlent+=("$other")
    else
        unlent+=("$other")
    fi
done
if [ ${#unlent[@]} -gt 0 ]; then
    echo "coverage: no fresh counts of ${unlent[*]}: a module these cores share with the ones reported (can_controller, uart_rx, uart_tx, crc_serial) is counted from this run's replays only and can read lower than in a run of every core"
fi
python3 "$root/scripts/coverage_report.py" --baseline "$baseline" "${write[@]}" "${lent[@]}" "${merged[@]}" || status=1
exit $status
