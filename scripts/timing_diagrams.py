#!/usr/bin/env python3
"""timing_diagrams.py: WaveDrom timing diagrams of each protocol's main transaction,
drawn from the model's own output (the committed vectors/<core>/<scenario>.vcd
and .json that tbgen writes), into docs/wavedrom/<name>.json (WaveJSON) and
docs/wavedrom/<name>.svg (rendered by the `wavedrom` package pinned in
python/requirements.txt).

    scripts/timing_diagrams.py [--out DIR] [--check]

--check regenerates into a temporary folder and fails when docs/wavedrom/
differs (make test). Each diagram shows the line signals (the VCD's
`top.line` scope) over the first transaction of the scenario, from its
earliest to its latest `*_cycle` field in the transcript, so every line edge of the
transaction is drawn (one column per tenth-percentile pulse of any one signal, at
most 140 columns (WaveDrom draws 40 px a column: under MAX_WIDTH_PX): a longer transaction shows its start, and the caption
says so). Below the line, one lane per state register the model names (the
`top.decoded` signals with a `<core>.<signal>.filter` beside the VCD, which
tbgen writes from the model's state enums): the frame's parts as the model
itself walks them (BiSS-C's ACK, START, CDS, DATA, CRC, EnDat's receive
phases ...), not a second hand-kept description; a register whose states
mostly last one column (a clock's HIGH and LOW) is left out. A stretch where
nothing changes for more than GAP columns (a timeout, an idle line) is
drawn as a gap of two columns. The timing docs (docs/timing/*.md) link the
SVGs.
"""
import argparse
import filecmp
import json
import os
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent



def diagrams():
    """(file stem, core, scenario, title with the seed document and section
    it follows) of every protocol with a diagram, from the descriptors
    (`tbgen protocols --json`)."""
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    tbgen = target / "release" / "tbgen"
    if not tbgen.is_file():
        raise SystemExit(f"timing_diagrams: no {tbgen}: build it first (make build)")
    out = subprocess.run([str(tbgen), "protocols", "--json"], check=True, capture_output=True, text=True).stdout
    return [(p["diagram"]["file"], p["core"], p["diagram"]["scenario"], p["diagram"]["title"])
            for p in json.loads(out) if p["diagram"]]


MAX_STEPS = 140
# A stretch of more unchanged columns than this is drawn as a gap.
GAP = 8


def read_filters(core):
    """{decoded signal: {value: name}} of the core's named state registers
    (vectors/<core>/<core>.<signal>.filter, "hex name" lines)."""
    named = {}
    for f in sorted((ROOT / "vectors" / core).glob(f"{core}.*.filter")):
        signal = f.name[len(core) + 1: -len(".filter")]
        named[signal] = {int(v, 16): n for v, n in (l.split() for l in f.read_text().splitlines() if l.strip())}
    return named


def read_vcd(path, named):
    """The 1-bit signals of the `top.line` scope and the `top.decoded`
    signals in `named`: (line order, named order, {name: [(time, value)]}),
    a line's value "0", "1" or "x", a named register's its state's name."""
    codes, scope, changes = {}, [], {}
    line_order, named_order = [], []
    t = 0
    in_defs = True
    for line in path.read_text().splitlines():
        parts = line.split()
        if not parts:
            continue
        if in_defs:
            if parts[0] == "$scope":
                scope.append(parts[2])
            elif parts[0] == "$upscope":
                scope.pop()
            elif parts[0] == "$var" and scope == ["top", "line"] and parts[2] == "1":
                codes[parts[3]] = parts[4]
                changes[parts[4]] = []
                line_order.append(parts[4])
            elif parts[0] == "$var" and scope == ["top", "decoded"] and parts[4] in named:
                codes[parts[3]] = parts[4]
                changes[parts[4]] = []
                named_order.append(parts[4])
            elif parts[0] == "$enddefinitions":
                in_defs = False
            continue
        head = parts[0]
        if head.startswith("#"):
            t = int(head[1:])
            continue
        if head[0] in "bB" and len(parts) == 2 and parts[1] in codes:
            name = codes[parts[1]]
            bits = head[1:]
            value = named[name].get(int(bits, 2), "x") if set(bits) <= {"0", "1"} else "x"
        elif head[0] in "01xzXZ" and head[1:] in codes:
            name = codes[head[1:]]
            value = "1" if head[0] == "1" else "0" if head[0] == "0" else "x"
        else:
            continue
        if not changes[name] or changes[name][-1][1] != value:
            changes[name].append((t, value))
    return list(dict.fromkeys(line_order)), named_order, changes


def level_at(changes, t):
    level = "x"
    for (ct, v) in changes:
        if ct > t:
            break
        level = v
    return level


def diagram(core, scenario, title):
    vcd = ROOT / "vectors" / core / f"{scenario}.vcd"
    transcript = json.loads((ROOT / "vectors" / core / f"{scenario}.json").read_text())
    period_ps = 10**12 / transcript["f_sys_hz"]
    first = transcript["transactions"][0]
    cycles = [v for k, v in first.items() if (k.endswith("_cycle") or k == "cycle") and isinstance(v, int)]
    if not cycles:
        raise SystemExit(f"{core}/{scenario}: the first transaction has no *_cycle field")
    named = read_filters(core)
    order, lanes, changes = read_vcd(vcd, named)
    lead = 4 * period_ps
    t0, t1 = round(min(cycles) * period_ps - lead), round(max(cycles) * period_ps + lead)
    # One column = a short pulse of any one line signal in the window, so
    # nearly every pulse gets a column (offsets between signals, such as a cable's
    # delay, do not shrink it).
    pulses = []
    for name in order:
        ts = [t for (t, _) in changes[name] if t0 <= t <= t1]
        # Pulses of one or two system cycles (a driver-enable turn-around)
        # are not bits: they would make the columns too fine to read.
        pulses += [b - a for a, b in zip(ts, ts[1:]) if b - a > 2.5 * period_ps]
    # The tenth percentile: a stray short pulse does not set the scale.
    step = sorted(pulses)[len(pulses) // 10] if pulses else (t1 - t0) / 40
    n = int((t1 - t0) / step) + 1
    # Every column's values, line signals then named registers.
    columns = [[level_at(changes[name], t0 + i * step + step / 2) for name in order + lanes] for i in range(n)]
    # Long unchanged stretches become gaps: two columns kept, a gap mark
    # after the first of them.
    kept, gaps, i = [], set(), 0
    while i < n:
        j = i
        while j + 1 < n and columns[j + 1] == columns[i]:
            j += 1
        if j - i + 1 > GAP:
            kept += [i, j]
            gaps.add(len(kept) - 1)
        else:
            kept += range(i, j + 1)
        i = j + 1
    shown = min(len(kept), MAX_STEPS)
    cut = f"; the first {shown} of {len(kept)} columns" if shown < len(kept) else ""
    compressed = f"; {len(gaps)} idle stretch{'es' if len(gaps) != 1 else ''} of more than {GAP} columns cut short (~)" if gaps else ""
    kept = kept[:shown]
    signals = []
    for k, name in enumerate(order):
        wave, last = "", None
        for c, i in enumerate(kept):
            v = columns[i][k]
            wave += ("|" if c in gaps else "") + ("." if v == last else v)
            last = v
        signals.append({"name": name, "wave": wave})
    # The named registers: one data lane each, a segment per state, its
    # name written in when it spans at least two columns.
    for k, name in enumerate(lanes, start=len(order)):
        wave, data, last = "", [], None
        for c, i in enumerate(kept):
            v = columns[i][k]
            mark = "|" if c in gaps else ""
            if v == last:
                wave += mark + "."
            elif v == "x":
                wave += mark + "x"
            else:
                wave += mark + "="
                data.append(v)
            last = v
        # A one-column segment's name would overprint its neighbours'.
        marks = [ch for ch in wave if ch != "|"]
        starts = [c for c, ch in enumerate(marks) if ch == "="]
        widths = [next((e for e in range(c + 1, len(marks)) if marks[e] != "."), len(marks)) - c for c in starts]
        data = [d if w >= 2 else "" for d, w in zip(data, widths)]
        # A register that changes at every column names the clock's half
        # periods (HIGH, LOW), not the frame's parts: left out.
        if 3 * sum(1 for d in data if d) >= len(data):
            signals.append({"name": name, "wave": wave, "data": data})
    return {
        "signal": signals,
        "head": {"text": title},
        "foot": {"text": f"{scenario}: one column = {step / 1000:.4g} ns (f_sys {transcript['f_sys_hz'] / 1e6:g} MHz){compressed}{cut}; from the model's waves"},
        "config": {"hscale": 1},
    }


def generate(out):
    import wavedrom  # the pinned renderer (python/requirements.txt)
    out.mkdir(parents=True, exist_ok=True)
    index = ["# Timing diagrams", "",
             "Drawn by `scripts/timing_diagrams.py` from the model's own waves (the committed",
             "`vectors/<core>/<scenario>.vcd`), rendered with WaveDrom (`wavedrom` in",
             "`python/requirements.txt`); `make test` checks they are current. Do not edit: change",
             "the model, regenerate the vectors, then run `.venv/bin/python scripts/timing_diagrams.py`.", ""]
    all_diagrams = diagrams()
    for stem, core, scenario, title in all_diagrams:
        index += [f"## {title}", "", f"Scenario `{scenario}`, core `{core}` ([WaveJSON]({stem}.json)).", "", f"![{title}]({stem}.svg)", ""]
    (out / "README.md").write_text("\n".join(index))
    for stem, core, scenario, title in all_diagrams:
        if not (ROOT / "vectors" / core / f"{scenario}.vcd").is_file():
            raise SystemExit(f"wavedrom: no vectors/{core}/{scenario}.vcd (rename it in the protocol's descriptor, model/src/<protocol>/descriptor.rs)")
        d = diagram(core, scenario, title)
        text = json.dumps(d, indent=1) + "\n"
        (out / f"{stem}.json").write_text(text)
        wavedrom.render(text).saveas(str(out / f"{stem}.svg"))


# The widest diagram that a reader sees whole: WaveDrom centres the title
# on the drawing, which a wider one pushes off the screen.
MAX_WIDTH_PX = 6000

# The BiSS-C frame's parts in the order the seed lists them (seed 001,
# SAR58K24 user's manual, BiSS-C: Ack, Start, CDS, data, error, warning,
# CRC): the labels the model's own states must show in its diagram.
BISS_FRAME = ["ACK", "START", "CDS", "DATA", "ERR", "WARN", "CRC"]


def readable(folder):
    """What makes a drawn diagram unreadable: too wide for its title, or,
    for BiSS-C, labels that are not the frame's parts in the seed's order."""
    import re
    problems = []
    for stem, core, scenario, title in diagrams():
        m = re.search(r'<svg[^>]*\swidth="(\d+)"', (folder / f"{stem}.svg").read_text())
        if not m or int(m.group(1)) > MAX_WIDTH_PX:
            problems.append(f"{stem}.svg is {m.group(1) if m else 'of no'} px wide (at most {MAX_WIDTH_PX}, or its title is off screen)")
        if core == "biss_master":
            labels = [d for s in json.loads((folder / f"{stem}.json").read_text())["signal"] for d in s.get("data", []) if d]
            seen = [d for d in labels if d in BISS_FRAME]
            if seen[:len(BISS_FRAME)] != BISS_FRAME:
                problems.append(f"{stem}: the labels {labels} do not name the BiSS-C frame's parts {BISS_FRAME}")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(ROOT / "docs" / "wavedrom"))
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    if not args.check:
        generate(pathlib.Path(args.out))
        print(f"wavedrom: {len(diagrams())} diagrams in {args.out}")
        return
    with tempfile.TemporaryDirectory() as tmp:
        generate(pathlib.Path(tmp))
        committed = ROOT / "docs" / "wavedrom"
        cmp = filecmp.dircmp(committed, tmp)
        bad = cmp.diff_files + cmp.left_only + cmp.right_only
        # dircmp compares shallowly; compare every file's bytes.
        bad += [f.name for f in pathlib.Path(tmp).iterdir() if (committed / f.name).is_file() and (committed / f.name).read_bytes() != f.read_bytes() and f.name not in bad]
        if bad:
            print(f"wavedrom: docs/wavedrom/ is not what scripts/timing_diagrams.py draws from the vectors: {', '.join(sorted(set(bad)))}; run scripts/timing_diagrams.py and commit")
            sys.exit(1)
        problems = readable(pathlib.Path(tmp))
        if problems:
            print("wavedrom: " + "; ".join(problems))
            sys.exit(1)
        print(f"wavedrom: {len(diagrams())} diagrams current")


if __name__ == "__main__":
    main()
