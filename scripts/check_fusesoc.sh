#!/usr/bin/env bash
# check_fusesoc.sh: the FuseSoC core files (fusesoc/*.core) are current and
# work in FuseSoC itself (pinned in python/requirements.txt, .venv/):
#   1. scripts/fusesoc_cores.py writes exactly the committed files;
#   2. `fusesoc core list` finds every one, and `core show` reads each;
#   3. per core, `fusesoc run --target=lint` (Verilator -Wall) passes, and
#      for every core with a testbench `--target=sim` (Icarus) replays its
#      committed vector file and prints PASS.
#
#   scripts/check_fusesoc.sh [CORE...]     (default: every core)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
fusesoc=.venv/bin/fusesoc
[ -x "$fusesoc" ] || { echo "check_fusesoc: no $fusesoc (run make deps)" >&2; exit 2; }
py=.venv/bin/python
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$py" scripts/fusesoc_cores.py --out "$tmp/fresh" > /dev/null
if ! diff -r -q fusesoc "$tmp/fresh" > "$tmp/diff"; then
    echo "check_fusesoc: fusesoc/ is not what scripts/fusesoc_cores.py writes:"
    sed 's/^/  /' "$tmp/diff"
    echo "  regenerate: scripts/fusesoc_cores.py, review and commit fusesoc/"
    exit 1
fi

fs() { "$fusesoc" --cores-root fusesoc "$@"; }
cores=("$@")
if [ ${#cores[@]} -eq 0 ]; then
    for f in fusesoc/*.core; do cores+=("$(basename "$f" .core)"); done
fi
listed=$(fs core list 2>&1)
status=0 runs=0
for core in "${cores[@]}"; do
    vlnv="encoder-tb:rtl:$core"
    grep -q "$vlnv:" <<< "$listed" || { echo "FAIL  fusesoc core list has no $vlnv"; echo "$listed" | tail -n 5; status=1; continue; }
    fs core show "$vlnv" > /dev/null 2>&1 || { echo "FAIL  fusesoc core show $vlnv"; status=1; }
    targets=(lint)
    grep -q '^  sim:' "fusesoc/$core.core" && targets+=(sim)
    for t in "${targets[@]}"; do
        runs=$((runs + 1))
        log="$tmp/$core.$t.log"
        if fs run --build-root "build/fusesoc/$core" --target "$t" "$vlnv" > "$log" 2>&1 \
           && { [ "$t" = lint ] || grep -q '^PASS:' "$log"; }; then
            printf 'PASS  %-5s %s\n' "$t" "$core"
        else
            printf 'FAIL  %-5s %s\n' "$t" "$core"
            tail -n 15 "$log" | sed 's/^/      /'
            status=1
        fi
    done
done
echo "fusesoc: ${#cores[@]} cores listed, $runs runs, $([ $status = 0 ] && echo all passed || echo FAILURES)"
exit $status
