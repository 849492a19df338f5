#!/usr/bin/env bash
# check_gtkw_window.sh [gtkw...]: open each saved layout in GTKWave itself
# (headless, under Xvfb) from the repository root, as the command `make demo`
# prints it, and read back what GTKWave shows:
#   - the dump file resolved although the current folder is not the layout's
#     (the `[savefile]` line, see tbgen/src/gtkw.rs);
#   - the time window frames the first transaction that lasts (or the whole
#     run if none does), from the transcript (.json) next to it: the transaction fills at least half of
#     the window and lies inside it;
#   - the state register shows a name (translate filter), not a number;
#   - every trace of the `decoded` group is among the rows an 800-pixel-high
#     window shows.
# The window's end: under Xvfb, before the first expose, GTKWave's
# getWindowEndTime counts a 4-pixel pane; the end is therefore computed from
# what GTKWave reports as its zoom (getZoomFactor: 2^-zoom units per pixel)
# and its waveform pane's width (getWaveWidth).
# Default: every vectors/*/*.gtkw. Prints one line per failure and a summary.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
files=("$@")
[ ${#files[@]} -gt 0 ] || files=(vectors/*/*.gtkw)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0 failed=0
for gtkw in "${files[@]}"; do
    json="${gtkw%.gtkw}.json"
    # First transaction that lasts: (start ps, end ps) from the transcript.
    read -r t0 t1 < <(python3 - "$json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
ps = 10**12 // d["f_sys_hz"]
# A transaction's span, whatever the protocol calls its cycle fields
# (start_cycle/done_cycle, sent_cycle/cycle, sof_cycle/cycle): from the
# earliest to the latest of them.
spans = []
for t in d["transactions"]:
    cycles = [v for k, v in t.items() if k.endswith("cycle") and isinstance(v, int)]
    if cycles:
        spans.append((min(cycles), max(cycles)))
lasting = [s for s in spans if s[1] > s[0]] or [(0, d["cycles"])]
print(lasting[0][0] * ps, lasting[0][1] * ps)
PY
)
    mid=$(( (t0 + t1) / 2 ))
    state=$(grep -m1 '^top\.decoded\.state' "$gtkw" || true)
    cat > "$work/q.tcl" <<TCL
puts "dump: [gtkwave::getDumpFileName]"
puts "start: [gtkwave::getWindowStartTime]"
puts "zoom: [gtkwave::getZoomFactor]"
puts "width: [gtkwave::getWaveWidth]"
puts "height: [gtkwave::getWaveHeight]"
set n [gtkwave::getTotalNumTraces]
for {set i 0} {\$i < \$n} {incr i} { puts "trace \$i: [gtkwave::getTraceNameFromIndex \$i]" }
gtkwave::setMarker $mid
TCL
    [ -z "$state" ] || echo "puts \"state: [gtkwave::getTraceValueAtMarkerFromName {$state}]\"" >> "$work/q.tcl"
    echo "gtkwave::/File/Quit" >> "$work/q.tcl"
    out=$(timeout 120 xvfb-run -a -s "-screen 0 1600x1000x24" gtkwave -S "$work/q.tcl" "$gtkw" 2>&1 || true)
    why=$(T0=$t0 T1=$t1 STATE="$state" python3 - "$gtkw" "$out" <<'PY'
import os, re, sys
gtkw, out = sys.argv[1], sys.argv[2]
t0, t1 = int(os.environ["T0"]), int(os.environ["T1"])
val = lambda k: (re.search(rf"^{k}: (.*)$", out, re.M) or [None, None])[1]
problems = []
if not val("dump"):
    problems.append("GTKWave did not open the dump file from " + os.getcwd() + ": " + " ".join(out.split()[-12:]))
else:
    start, zoom, width = int(val("start")), float(val("zoom")), float(val("width"))
    px = 2 ** (-zoom)
    end = start + width * px
    # One pixel of slack: the save file gives the zoom to 6 decimals.
    if not (start <= t0 and t1 <= end + px):
        problems.append(f"window {start}..{end:.0f} ps does not hold the first transaction {t0}..{t1} ps")
    elif (t1 - t0) < 0.5 * (end - start):
        problems.append(f"the first transaction {t0}..{t1} ps fills less than half the window {start}..{end:.0f} ps")
    if os.environ["STATE"]:
        s = val("state") or ""
        if not re.fullmatch(r"[A-Z][A-Z0-9_]*", s):
            problems.append(f"state shows `{s}`, not a state name")
    # Every decoded trace must be among the rows GTKWave shows in the
    # layout's 800-pixel-high window: its waveform pane's height
    # (getWaveHeight) over a row of at most 20 pixels (GTKWave's default
    # font; getVisibleNumTraces counts every unfolded trace, shown or not).
    traces = [n for _, n in re.findall(r"^trace (\d+): (.*)$", out, re.M)]
    visible = int(val("height")) // 20
    decoded = [l.rsplit(".", 1)[1] for l in open(gtkw).read().splitlines() if l.startswith("top.decoded.")]
    group = traces.index("decoded") if "decoded" in traces else -1
    last = group + len(decoded)
    if group < 0 or last >= visible:
        problems.append(f"the decoded group (rows {group + 1} to {last}) is not within the {visible} rows the window shows")
print("; ".join(problems))
PY
)
    if [ -z "$why" ]; then
        passed=$((passed + 1))
    else
        failed=$((failed + 1))
        echo "gtkw-window FAIL $gtkw: $why"
    fi
done
echo "gtkw-window: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
