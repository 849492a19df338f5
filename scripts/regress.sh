#!/usr/bin/env bash
# regress.sh: replay every committed vector file against its core in Icarus
# and Verilator and print one line per run, then "N passed, M failed".
#
#   scripts/regress.sh [--core CORE] [--sim icarus|verilator] [--scenario S] [--waves] [--jobs N]
#                      [--icarus-budget CYCLES]
#
# --scenario S is one of:
#   - a scenario name: the committed vectors/<core>/S.hex;
#   - a scenario file, S.toml (or a name S with S.toml in the current
#     folder): tbgen generates its vectors into build/custom/<file name>/
#     and that file is replayed;
#   - a vector file, S.hex (tbgen gen's output anywhere): replayed as it is.
# For a file the core is the one its header names; --core, if given, must
# agree. An unknown core or simulator is refused with the list of known ones.
# With --waves, each run also dumps the RTL's waveform to build/waves/<scenario>.<sim>.vcd.
# --jobs N runs N replays at once (default: the number of cores). Runs that
# share a simulator build wait for it on sim.sh's lock, so each build is
# still made once. Runs start longest first; lines come in the order runs
# finish.
# --icarus-budget CYCLES replays every file in Verilator but, in Icarus, a
# representative set per core (make test): the cheapest file of each of the
# core's parameter sets, cheapest set first, while the core's Icarus cycles
# stay within CYCLES (at least one file per core). Every parameter set's
# generate branches are thus read by a second simulator as far as the budget
# allows, and every file by Verilator.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
supported_sims=(icarus verilator)
cores=() sims=("${supported_sims[@]}") scenario="" waves=0 jobs=$(nproc 2>/dev/null || echo 2) icarus_budget=""
usage() { echo "usage: $0 [--core CORE] [--sim icarus|verilator] [--scenario NAME|FILE.toml|FILE.hex] [--waves] [--jobs N] [--icarus-budget CYCLES]" >&2; exit 2; }
die() { echo "regress: $*" >&2; exit 2; }
while [ $# -gt 0 ]; do
    case "$1" in
    --core) [ $# -ge 2 ] || usage; cores=("$2"); shift 2 ;;
    --sim) [ $# -ge 2 ] || usage; sims=("$2"); shift 2 ;;
    --scenario) [ $# -ge 2 ] || usage; scenario=$2; shift 2 ;;
    --waves) waves=1; shift ;;
    --jobs) [ $# -ge 2 ] || usage; jobs=$2; shift 2 ;;
    --icarus-budget) [ $# -ge 2 ] || usage; icarus_budget=$2; shift 2 ;;
    *) usage ;;
    esac
done
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || die "--jobs takes a whole number of at least 1, not '$jobs'"
[ -z "$icarus_budget" ] || [[ "$icarus_budget" =~ ^[1-9][0-9]*$ ]] \
    || die "--icarus-budget takes a whole number of cycles of at least 1, not '$icarus_budget'"

# The cores: every core with a testbench (hdl/tb/<core>/tb_<core>.v).
known_cores=()
for tb in "$root"/hdl/tb/*/tb_*.v; do
    c=$(basename "$(dirname "$tb")")
    [ "$(basename "$tb")" = "tb_$c.v" ] && known_cores+=("$c")
done
for sim in "${sims[@]}"; do
    case " ${supported_sims[*]} " in
    *" $sim "*) ;;
    *) die "unknown simulator '$sim'; the supported simulators are: ${supported_sims[*]} (SIM=icarus or SIM=verilator)" ;;
    esac
done
for core in "${cores[@]}"; do
    case " ${known_cores[*]} " in
    *" $core "*) ;;
    *)  near=()
        for c in "${known_cores[@]}"; do [[ "$c" == *"$core"* || "$core" == *"$c"* ]] && near+=("$c"); done
        hint=""
        [ ${#near[@]} -gt 0 ] && hint=" Did you mean ${near[*]}?"
        die "unknown core '$core'. The cores are: ${known_cores[*]}.$hint" ;;
    esac
done

# The vector files' headers, read by the files' own reader (vectorfile,
# through `xtask vector-headers`): "<core> <cycles> <params@f_sys> <file>"
# per file. Built here when missing (make test builds it first).
xtask="${CARGO_TARGET_DIR:-$root/target}/release/xtask"
[ -x "$xtask" ] || (cd "$root" && ${CARGO:-cargo} build --release --locked -q -p xtask) || die "could not build xtask"
headers() { "$xtask" vector-headers "$@" || exit 2; }

# A scenario given as a file: generate (.toml) or take (.hex) one vector file.
file=""
if [ -n "$scenario" ]; then
    case "$scenario" in
    *.hex) [ -f "$scenario" ] || die "no vector file '$scenario' (give a path to a .hex that tbgen gen wrote)"
           file=$(cd "$(dirname "$scenario")" && pwd)/$(basename "$scenario") ;;
    *.toml) [ -f "$scenario" ] || die "no scenario file '$scenario'"
           file=$scenario ;;
    *)     # A name: a committed scenario, or NAME.toml beside the user.
           found=0 elsewhere=""
           search=("${known_cores[@]}")
           [ ${#cores[@]} -gt 0 ] && search=("${cores[@]}")
           for c in "${search[@]}"; do
               [ -f "$root/vectors/$c/$scenario.hex" ] && found=1
           done
           for c in "${known_cores[@]}"; do
               [ -f "$root/vectors/$c/$scenario.hex" ] && elsewhere=" It is a scenario of core '$c' (CORE=$c)."
           done
           if [ "$found" = 0 ]; then
               if [ -f "$scenario.toml" ]; then
                   file=$scenario.toml
               else
                   where="vectors/${cores[0]:-*}/"
                   listed=""
                   if [ ${#cores[@]} -eq 1 ] && [ -d "$root/vectors/${cores[0]}" ]; then
                       listed=" Its scenarios: $(cd "$root/vectors/${cores[0]}" && ls -- *.hex | sed 's/\.hex$//' | tr '\n' ' ')"
                   fi
                   die "no scenario named '$scenario' in $where and no file $scenario.toml in $PWD. Give a scenario file (SCENARIO=path/to/$scenario.toml) or a vector file (SCENARIO=path/to/$scenario.hex).$elsewhere$listed"
               fi
           fi ;;
    esac
    if [[ "$file" == *.toml ]]; then
        stem=$(basename "$file" .toml)
        out="$root/build/custom/$stem"
        rm -rf "$out"
        mkdir -p "$root/build/custom"
        (cd "$root" && ${CARGO:-cargo} build --release --locked -q -p tbgen) || die "could not build tbgen"
        "$root/target/release/tbgen" gen "$file" --out "$out" || exit 2
        hexes=("$out"/*.hex)
        [ -e "${hexes[0]}" ] || die "tbgen wrote no vector file for $file"
        file=${hexes[0]}
    fi
    if [ -n "$file" ]; then
        read -r fcore _ < <(headers "$file")
        [ -n "$fcore" ] || exit 2
        if [ ${#cores[@]} -gt 0 ] && [ "${cores[0]}" != "$fcore" ]; then
            die "$scenario is a scenario of core '$fcore', not '${cores[0]}' (leave CORE out, or CORE=$fcore)"
        fi
        cores=("$fcore")
    fi
fi
if [ ${#cores[@]} -eq 0 ]; then
    for d in "$root"/vectors/*/; do cores+=("$(basename "$d")"); done
fi

mkdir -p "$root/build/logs" "$root/build/waves"
results=$(mktemp -d)
trap 'rm -rf "$results"' EXIT

# One replay: prints its PASS/FAIL line with its wall time (the build, or
# the wait for a build another run makes, apart from the replay itself) and
# leaves a marker holding the times for the count and the summary.
replay() {
    local core=$1 sim=$2 f=$3 name log wave=() t0 t1 t2 status=0 build_s run_s
    name=$(basename "$f" .hex)
    log="$root/build/logs/$name.$sim.log"
    [ "$waves" = 1 ] && wave=("$root/build/waves/$name.$sim.vcd")
    t0=$(date +%s.%N)
    SIM_BUILD_ONLY=1 "$root/scripts/sim.sh" "$core" "$sim" "$f" "${wave[@]}" > "$log" 2>&1 || status=1
    t1=$(date +%s.%N)
    if [ "$status" = 0 ]; then
        "$root/scripts/sim.sh" "$core" "$sim" "$f" "${wave[@]}" >> "$log" 2>&1 || status=1
    fi
    t2=$(date +%s.%N)
    build_s=$(awk "BEGIN { printf \"%.1f\", $t1 - $t0 }")
    run_s=$(awk "BEGIN { printf \"%.1f\", $t2 - $t1 }")
    echo "$run_s $build_s $sim $core $name" > "$results/$([ $status = 0 ] && echo pass || echo fail).$core.$sim.$name"
    if [ "$status" = 0 ]; then
        printf 'PASS  %-10s %-12s %-40s replay %6s s  build %5s s\n' "$sim" "$core" "$name" "$run_s" "$build_s"
    else
        { printf 'FAIL  %-10s %-12s %-40s replay %6s s  build %5s s\n' "$sim" "$core" "$name" "$run_s" "$build_s"
          grep -E "MISMATCH|rror" "$log" | head -n 5 | sed 's/^/      /'; } | cat
    fi
}

# The files to replay, with their cycle counts and build groups (the files
# of a core that share parameters and clock share one simulator build).
entries=()
declare -A group_cycles=() group_files=() icarus_files=()
for core in "${cores[@]}"; do
    if [ -n "$file" ]; then
        files=("$file")
    else
        files=("$root/vectors/$core"/*.hex)
        [ -e "${files[0]}" ] || { echo "regress: no vectors in vectors/$core/ (run make vectors)" >&2; exit 2; }
    fi
    summary=$(headers "${files[@]}") || exit 2
    while read -r _ cycles build f; do
        name=$(basename "$f" .hex)
        [ -z "$file" ] && [ -n "$scenario" ] && [ "$name" != "$scenario" ] && continue
        group="$core.$(printf '%s' "$build" | sha1sum | cut -c1-12)"
        group_cycles[$group]=$(( ${group_cycles[$group]:-0} + cycles ))
        group_files[$group]=$(( ${group_files[$group]:-0} + 1 ))
        entries+=("$cycles $core $group $f")
    done <<< "$summary"
    # The core's representative Icarus set (--icarus-budget): the cheapest
    # file of each parameter set, cheapest set first, within the budget.
    if [ -n "$icarus_budget" ]; then
        spent=0
        while read -r _ cycles f; do
            [ -n "$f" ] || continue
            if [ "$spent" -gt 0 ] && [ $((spent + cycles)) -gt "$icarus_budget" ]; then break; fi
            icarus_files[$f]=1
            spent=$((spent + cycles))
        done < <(awk '{ split($3, b, "@"); print b[1], $2, $4 }' <<< "$summary" \
                 | sort -k1,1 -k2,2n | awk '!seen[$1]++' | sort -n -k2,2)
    fi
done

# How each Verilator build is optimised (scripts/verilator_make_flags.sh)
# is scripts/sim.sh's choice, the same for every caller (so that the cargo
# tests' flipped-bit replays reuse these builds): -O0 compiles the model in
# half the CPU time of -O1 (about 7 s less per build) but replays about five
# times slower (about 16 us more per cycle, coverage on), so a build whose
# committed files add up to fewer than VERILATOR_O0_CYCLES cycles (default
# 100000: sim.sh says why) is made at -O0: 52 of the 130 parameter sets.
# The same rule here only estimates each run's cost.
o0_cycles=${VERILATOR_O0_CYCLES:-100000}

# The runs, longest first, so that no long replay starts last and keeps one
# core busy while the other has nothing left to do. The cost is in
# microseconds of one core: an Icarus cycle about 25 us; a Verilator cycle
# about 4 us at -O1 and 20 us at -O0, plus the build (about 14 s at -O1, 7 s
# at -O0) shared by the files of its group.
runs=()
for e in "${entries[@]}"; do
    read -r cycles core group f <<< "$e"
    for sim in "${sims[@]}"; do
        if [ "$sim" = icarus ] && [ -n "$icarus_budget" ] && [ -z "${icarus_files[$f]:-}" ]; then
            continue
        fi
        if [ "$sim" = icarus ]; then
            cost=$(( cycles * 25 ))
        elif [ "${group_cycles[$group]}" -lt "$o0_cycles" ]; then
            cost=$(( cycles * 20 + 7000000 / ${group_files[$group]} ))
        else
            cost=$(( cycles * 4 + 14000000 / ${group_files[$group]} ))
        fi
        runs+=("$cost $core $sim $f")
    done
done
running=0
while read -r _ core sim f; do
    [ -n "$core" ] || continue
    if [ "$running" -ge "$jobs" ]; then
        wait -n || true
        running=$((running - 1))
    fi
    replay "$core" "$sim" "$f" &
    running=$((running + 1))
done < <(printf '%s\n' "${runs[@]}" | sort -rn -k1,1)
wait || true
passed=$(find "$results" -name 'pass.*' | wc -l)
failed=$(find "$results" -name 'fail.*' | wc -l)
[ $((passed + failed)) -gt 0 ] || { echo "regress: no scenario matched" >&2; exit 2; }
# Where the time went: the ten slowest replays and builds, and the sums.
echo "hdl: the 10 slowest replays (wall seconds; replay, then build or wait for it):"
cat "$results"/* | sort -rn -k1,1 \
    | awk 'NR <= 10 { printf "      %7.1f s  build %6.1f s  %-10s %-14s %s\n", $1, $2, $3, $4, $5 }'
echo "hdl: the 10 slowest builds (wall seconds, waits for another run's build included):"
cat "$results"/* | sort -rn -k2,2 \
    | awk 'NR <= 10 { printf "      %7.1f s  %-10s %-14s %s\n", $2, $3, $4, $5 }'
cat "$results"/* \
    | awk '{ r[$3] += $1; b[$3] += $2 } END { for (s in r) printf "hdl: %s: replays %.1f s, builds and waits %.1f s (sums of wall times)\n", s, r[s], b[s] }' | sort
if [ -n "$icarus_budget" ]; then
    echo "hdl: icarus: ${#icarus_files[@]} of ${#entries[@]} files, the representative set of each core within $icarus_budget cycles (--icarus-budget); verilator: every file"
fi
echo "hdl: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
