#!/usr/bin/env bash
# check_gtkw.sh [gtkw...]: open each saved layout in GTKWave itself
# (headless, under Xvfb) from the repository root, as the command `make demo`
# prints it, and read back what GTKWave shows:
#   - every signal the layout names resolved: GTKWave silently drops a name
#     it cannot find in the VCD, so a layout that drifted from the waveform
#     would otherwise go unnoticed until an engineer opens it;
#   - the dump file resolved although the current folder is not the layout's
#     (the `[savefile]` line, see tbgen/src/gtkw.rs);
#   - the time window frames the first transaction that lasts (or the whole
#     run if none does), from the transcript (.json) next to it: the transaction fills at least half of
#     the window and lies inside it;
#   - every state register shows a name (translate filter), not a number;
#   - every trace of the `decoded` group is among the rows an 800-pixel-high
#     window shows;
#   - for the screenshot layouts (SHOTS below: one SSI, one EnDat, one CAN),
#     what GTKWave draws: a screenshot of its window (xwd) must show the
#     edges of the first transaction across at least half of the waveform
#     pane, judged from the pixels alone (an idle window draws no edge, a
#     transaction zoomed out to a sliver draws them all in a few columns).
# The window's edges are GTKWave's own answer (getWindowStartTime,
# getWindowEndTime), not worked out here from the zoom: a check that shared
# tbgen's zoom formula would pass a layout that opens on idle.
# Default: every vectors/*/*.gtkw. Prints one line per failure and a summary.
#
# Speed: GTKWave starts once per layout for all of these checks (two
# scripts with a start each cost make test about a minute more), one Xvfb
# serves every start (xvfb-run per layout started a server each time), two
# layouts are open at a time, and Python starts twice in all (the
# transcripts' spans before, the verdicts after), not twice per layout.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
# One X server for the whole check: run again under xvfb-run.
if [ -z "${CHECK_GTKW_X:-}" ]; then
    CHECK_GTKW_X=1 exec xvfb-run -a -s "-screen 0 1600x1000x24" "$0" "$@"
fi
files=("$@")
[ ${#files[@]} -gt 0 ] || files=(vectors/*/*.gtkw)
# The layouts whose window is also judged from a screenshot, by file name.
# Each is opened alone: on the one X server another GTKWave's window would
# lie over it in the picture.
SHOTS=" ssi_seed_12bit.gtkw endat_pos21_1mhz.gtkw can_rate_250k.gtkw "
is_shot() { [[ "$SHOTS" == *" $(basename "$1") "* ]]; }
work=$(mktemp -d)
trap '[ -n "${CHECK_GTKW_KEEP:-}" ] || rm -rf "$work"' EXIT

# The first transaction that lasts (start ps, end ps) of each layout, from
# the transcript (.json) next to it: "index t0 t1", one line per layout.
python3 - "${files[@]}" > "$work/spans" <<'PY'
import json, sys
for i, gtkw in enumerate(sys.argv[1:]):
    d = json.load(open(gtkw[: -len(".gtkw")] + ".json"))
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
    print(i, lasting[0][0] * ps, lasting[0][1] * ps)
PY

# query INDEX GTKW T0 T1: what GTKWave shows of one layout, to $work/out.INDEX.
query() {
    local i=$1 gtkw=$2 t0=$3 t1=$4 named
    # The screenshot of GTKWave's own window, named by its title, first:
    # the script runs once the layout is drawn, and before the marker below
    # draws a line across the pane.
    : > "$work/q.$i.tcl"
    if is_shot "$gtkw"; then
        echo "exec xwd -silent -out $work/shot.$i.xwd -name \"GTKWave - [gtkwave::getDumpFileName]\"" >> "$work/q.$i.tcl"
    fi
    cat >> "$work/q.$i.tcl" <<TCL
puts "dump: [gtkwave::getDumpFileName]"
puts "start: [gtkwave::getWindowStartTime]"
puts "window_end: [gtkwave::getWindowEndTime]"
puts "width: [gtkwave::getWaveWidth]"
puts "height: [gtkwave::getWaveHeight]"
set n [gtkwave::getTotalNumTraces]
for {set i 0} {\$i < \$n} {incr i} { puts "trace \$i: [gtkwave::getTraceNameFromIndex \$i]" }
gtkwave::setMarker $(( (t0 + t1) / 2 ))
TCL
    # Every trace shown through a translate filter (the line after `^1 file`).
    # (Answers are labelled by position: a name's [msb:lsb] inside a Tcl
    # string would be a command.)
    local k=0
    for named in $(awk 'shown { print; shown = 0 } /^\^1 / { shown = 1 }' "$gtkw"); do
        echo "puts \"named $k: [gtkwave::getTraceValueAtMarkerFromName {$named}]\"" >> "$work/q.$i.tcl"
        k=$((k + 1))
    done
    # The last line says GTKWave answered every query: one that died under
    # load said too little to judge the layout by.
    echo 'puts "end: answered"' >> "$work/q.$i.tcl"
    echo "gtkwave::/File/Quit" >> "$work/q.$i.tcl"
    timeout 120 gtkwave -S "$work/q.$i.tcl" "$gtkw" > "$work/out.$i" 2>&1 || true
}

# Two at a time, a screenshot layout alone; `wait` names the queries.
pids=()
while read -r i t0 t1; do
    if is_shot "${files[$i]}"; then
        for pid in "${pids[@]}"; do wait "$pid" || true; done
        pids=()
        query "$i" "${files[$i]}" "$t0" "$t1"
        continue
    fi
    if [ ${#pids[@]} -ge 2 ]; then wait "${pids[0]}" || true; pids=("${pids[@]:1}"); fi
    query "$i" "${files[$i]}" "$t0" "$t1" &
    pids+=($!)
done < "$work/spans"
for pid in "${pids[@]}"; do wait "$pid" || true; done
# A GTKWave that died under load (two at a time on a busy machine) did not
# answer every query: such a layout is queried once more, alone. A layout
# that drifted fails on the answers, not for want of them.
while read -r i t0 t1; do
    grep -q '^end: answered' "$work/out.$i" || query "$i" "${files[$i]}" "$t0" "$t1"
done < "$work/spans"

# The verdicts: one line per failing layout, then the summary.
export SHOTS
python3 - "$work" "${files[@]}" <<'PY'
import os, re, struct, sys
work, files = sys.argv[1], sys.argv[2:]

def read_xwd(path):
    """(width, height, pixel(x, y) -> 0xRRGGBB) of a 24/32-bit xwd dump."""
    b = open(path, "rb").read()
    h = struct.unpack(">25I", b[:100])
    size, w, ht, lsb_first, bpl, ncolors = h[0], h[4], h[5], h[7] == 0, h[12], h[19]
    if bpl < 4 * w:
        raise ValueError(f"{bpl} bytes a row for {w} pixels: not a 32-bit dump")
    px = b[size + 12 * ncolors:]
    order = "little" if lsb_first else "big"
    return w, ht, lambda x, y: int.from_bytes(px[y * bpl + 4 * x: y * bpl + 4 * x + 4], order) & 0xFFFFFF

def edges_on_screen(path):
    """(pane_left, pane_width, edge columns) of a GTKWave window's picture.
    The waveform pane is where the picture is black: the columns, and in
    them the rows, of which at least a quarter of the pixels are black
    (the window's frame, bars and other panes are light; the pane's own
    grid and marker lines cross it, so first to last, not the longest run).
    An edge is a vertical stroke of bright pixels in the pane between 10
    and 60 pixels long in one column, with nothing bright two columns either
    side of it: a one-bit trace's rising or falling edge (its rows are about
    20 pixels, its strokes 15), longer than a glyph of a bus value (8),
    shorter than the lines that cross the whole pane, and not the fill a
    bus draws where it changes at every pixel (a free-running counter)."""
    w, ht, at = read_xwd(path)
    bright = lambda p: max(p >> 16, (p >> 8) & 255, p & 255) >= 0x90
    cols = [x for x in range(w) if sum(at(x, y) == 0 for y in range(0, ht, 2)) * 8 >= ht]
    if not cols:
        return 0, 0, []
    left, width = cols[0], cols[-1] + 1 - cols[0]
    rows = [y for y in range(ht) if sum(at(x, y) == 0 for x in range(left, left + width, 2)) * 8 >= width]
    top, height = rows[0], rows[-1] + 1 - rows[0]
    edges = []
    for x in range(left, left + width):
        run = 0
        for y in range(top, top + height + 1):
            if y < top + height and bright(at(x, y)):
                run += 1
                continue
            # Alone in its rows two pixels either side, but for the level
            # lines at its ends: not the fill of a bus changing every pixel.
            inner = range(y - run + 2, y - 2)
            if 10 <= run <= 60 and not any(bright(at(x + d, v)) for d in (-2, 2) for v in inner if 0 <= x + d < w):
                edges.append(x)
                break
            run = 0
    return left, width, edges

spans = {int(i): (int(t0), int(t1)) for i, t0, t1 in (l.split() for l in open(os.path.join(work, "spans")))}
passed = failed = 0
for i, gtkw in enumerate(files):
    t0, t1 = spans[i]
    out = open(os.path.join(work, f"out.{i}"), errors="replace").read()
    lines = open(gtkw).read().splitlines()
    val = lambda k: (re.search(rf"^{k}: (.*)$", out, re.M) or [None, None])[1]
    problems = []
    if not val("end"):
        problems.append("GTKWave did not answer every query (twice): " + " ".join(out.split()[-12:]))
    elif not val("dump"):
        problems.append("GTKWave did not open the dump file from " + os.getcwd() + ": " + " ".join(out.split()[-12:]))
    else:
        start, end = int(val("start")), int(val("window_end"))
        # One pixel of GTKWave's own (its window over its pane's width) of
        # slack at the end: a run shown whole ends on its last pixel.
        px = (end - start) / max(1, int(val("width")))
        if not (start <= t0 and t1 <= end + px):
            problems.append(f"window {start}..{end} ps does not hold the first transaction {t0}..{t1} ps")
        elif (t1 - t0) < 0.5 * (end - start):
            problems.append(f"the first transaction {t0}..{t1} ps fills less than half the window {start}..{end} ps")
        # Every trace with a translate filter shows a name, not a number.
        filtered = [lines[k + 1] for k, l in enumerate(lines[:-1]) if l.startswith("^1 ")]
        unnamed = [l for l in lines if l.startswith("top.decoded.") and "state" in l and l not in filtered]
        if unnamed:
            problems.append(f"state registers shown as numbers (no translate filter): {', '.join(unnamed)}")
        for k, name in enumerate(filtered):
            shown_value = (re.search(rf"^named {k}: (.*)$", out, re.M) or [None, ""])[1]
            if not re.fullmatch(r"[A-Z][A-Z0-9_]*", shown_value):
                problems.append(f"{name} shows `{shown_value}`, not a state name")
        traces = [n for _, n in re.findall(r"^trace (\d+): (.*)$", out, re.M)]
        # The signals: those the layout names (top.scope.name[msb:lsb] ->
        # name[msb:lsb]) are exactly those GTKWave shows, less the group
        # labels (the layout's `-label` lines).
        labels = {l[1:] for l in lines if l.startswith("-")}
        named = sorted(l.rsplit(".", 1)[1] for l in lines if l.startswith("top."))
        shown = sorted(t for t in traces if t not in labels)
        if named != shown:
            dropped = sorted(set(named) - set(shown))
            extra = sorted(set(shown) - set(named))
            problems.append(f"GTKWave shows other signals than the layout names (not resolved: {', '.join(dropped[:8]) or 'none'}; not named: {', '.join(extra[:8]) or 'none'})")
        # Every decoded trace must be among the rows GTKWave shows in the
        # layout's 800-pixel-high window: its waveform pane's height
        # (getWaveHeight) over a row of at most 20 pixels (GTKWave's default
        # font; getVisibleNumTraces counts every unfolded trace, shown or not).
        visible = int(val("height")) // 20
        decoded = [l.rsplit(".", 1)[1] for l in lines if l.startswith("top.decoded.")]
        group = traces.index("decoded") if "decoded" in traces else -1
        last = group + len(decoded)
        if group < 0 or last >= visible:
            problems.append(f"the decoded group (rows {group + 1} to {last}) is not within the {visible} rows the window shows")
        shot = os.path.join(work, f"shot.{i}.xwd")
        if f" {os.path.basename(gtkw)} " in os.environ["SHOTS"]:
            if not os.path.exists(shot):
                problems.append("no screenshot of GTKWave's window (xwd, from x11-apps)")
            else:
                left, width, edges = edges_on_screen(shot)
                if len(edges) < 4:
                    problems.append(f"the screenshot shows {len(edges)} edges in the {width}-pixel waveform pane: the window is idle")
                elif edges[-1] - edges[0] < 0.5 * width:
                    problems.append(f"the screenshot shows the edges in pixels {edges[0] - left} to {edges[-1] - left} of the {width}-pixel waveform pane: less than half of it")
                else:
                    # Zoomed out over several transactions, the edges come
                    # in bunches with idle line between them.
                    gap, at = max((b - a, a) for a, b in zip(edges, edges[1:]))
                    if gap > 0.25 * width:
                        problems.append(f"the screenshot shows no edge in pixels {at - left} to {at - left + gap} of the {width}-pixel waveform pane: bunches of edges, not one transaction across it")
    if problems:
        failed += 1
        print(f"gtkw FAIL {gtkw}: " + "; ".join(problems))
    else:
        passed += 1
print(f"gtkw: {passed} passed, {failed} failed")
sys.exit(0 if failed == 0 and passed > 0 else 1)
PY
