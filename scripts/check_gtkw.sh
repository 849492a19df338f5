#!/usr/bin/env bash
# check_gtkw.sh: open every committed .gtkw in GTKWave (headless, under Xvfb)
# and require that GTKWave resolved every signal it names. GTKWave silently
# drops a name it cannot find in the VCD, so a layout that drifted from the
# waveform would otherwise go unnoticed until an engineer opens it.
#
# One Xvfb server serves every GTKWave start (xvfb-run per layout spent most
# of its second starting a server), and two layouts are checked at a time.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
script="$work/list.tcl"
cat > "$script" <<'TCL'
set n [gtkwave::getTotalNumTraces]
for {set i 0} {$i < $n} {incr i} { puts "trace: [gtkwave::getTraceNameFromIndex $i]" }
gtkwave::/File/Quit
TCL

# A display of our own: the first free number from 90 up.
display=90
while [ -e "/tmp/.X$display-lock" ] || [ -e "/tmp/.X11-unix/X$display" ]; do display=$((display + 1)); done
Xvfb ":$display" -screen 0 1280x1024x24 -nolisten tcp > "$work/xvfb.log" 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; wait $xvfb 2>/dev/null; rm -rf "$work"' EXIT
for _ in $(seq 50); do [ -e "/tmp/.X11-unix/X$display" ] && break; sleep 0.1; done
[ -e "/tmp/.X11-unix/X$display" ] || { echo "check_gtkw: Xvfb did not start:"; cat "$work/xvfb.log"; exit 1; }
export DISPLAY=":$display"

# check ONE.gtkw [ATTEMPT]: writes pass/fail, the difference and GTKWave's
# own messages under $work.
check() {
    local gtkw=$1 attempt=${2:-1} dir base expected got status
    dir=$(dirname "$gtkw") base=$(basename "$gtkw" .gtkw)
    # Names as the save file gives them: top.scope.name[msb:lsb] -> name[msb:lsb].
    expected=$(grep '^top\.' "$gtkw" | sed 's/.*\.//' | sort)
    status=0
    (cd "$dir" && timeout 120 gtkwave -S "$script" "$(basename "$gtkw")") \
        > "$work/out.$base" 2> "$work/err.$base" || status=$?
    got=$(sed -n 's/^trace: //p' "$work/out.$base" | grep -vxF -f <(sed -n 's/^-//p' "$gtkw") | sort || true)
    if [ "$expected" = "$got" ]; then
        touch "$work/pass.$base"
        rm -f "$work/fail.$base"
        [ "$attempt" = 1 ] || echo "gtkw: $base.gtkw passed on attempt $attempt (attempt 1 failed: $(head -c 300 "$work/first.$base"))"
    else
        { echo "gtkw FAIL $base.gtkw (attempt $attempt, GTKWave exit $status): GTKWave shows other signals than the layout names"
          diff <(echo "$expected") <(echo "$got") | head -n 10 | sed 's/^/      /' || true
          grep -v -e '^$' -e 'GTKWave Analyzer' -e 'start time' -e 'end time' -e 'Executing Tcl' "$work/err.$base" | head -n 5 | sed 's/^/      gtkwave: /' || true; } > "$work/fail.$base"
        tr '\n' ' ' < "$work/fail.$base" > "$work/first.$base"
    fi
}

# Two at a time; `wait` names the checks so that it never waits for Xvfb.
pids=()
for gtkw in "$root"/vectors/*/*.gtkw; do
    if [ ${#pids[@]} -ge 2 ]; then wait "${pids[0]}" || true; pids=("${pids[@]:1}"); fi
    check "$gtkw" &
    pids+=($!)
done
for pid in "${pids[@]}"; do wait "$pid" || true; done
# A GTKWave that dies under load (two at a time, on a busy machine) is not a
# layout that drifted: check each failure once more, alone. A real drift
# fails both times and is reported with both attempts' messages.
for fail in "$work"/fail.*; do
    [ -e "$fail" ] || continue
    base=${fail##*/fail.}
    for gtkw in "$root"/vectors/*/"$base".gtkw; do check "$gtkw" 2; done
done
cat "$work"/fail.* 2>/dev/null || true
passed=$(find "$work" -name 'pass.*' | wc -l)
failed=$(find "$work" -name 'fail.*' | wc -l)
echo "gtkw: $passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
