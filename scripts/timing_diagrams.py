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
most 400 columns: a longer transaction shows its start, and the caption
says so). The timing docs (docs/timing/*.md)
link the SVGs.
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


MAX_STEPS = 400


def read_vcd(path):
    """The 1-bit signals of the `top.line` scope: {name: [(time, level)]}."""
    codes, scope, changes = {}, [], {}
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
            elif parts[0] == "$enddefinitions":
                in_defs = False
            continue
        head = parts[0]
        if head.startswith("#"):
            t = int(head[1:])
        elif head[0] in "01xzXZ" and head[1:] in codes:
            name = codes[head[1:]]
            level = "1" if head[0] == "1" else "0" if head[0] == "0" else "x"
            if not changes[name] or changes[name][-1][1] != level:
                changes[name].append((t, level))
    order = list(dict.fromkeys(codes.values()))
    return order, changes


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
    order, changes = read_vcd(vcd)
    lead = 4 * period_ps
    t0, t1 = round(min(cycles) * period_ps - lead), round(max(cycles) * period_ps + lead)
    # One column = a short pulse of any one signal in the window, so
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
    shown = min(n, MAX_STEPS)
    cut = f"; the first {shown} of {n} columns" if shown < n else ""
    n = shown
    signals = []
    for name in order:
        wave, last = "", None
        for i in range(n):
            v = level_at(changes[name], t0 + i * step + step / 2)
            wave += "." if v == last else v
            last = v
        signals.append({"name": name, "wave": wave})
    return {
        "signal": signals,
        "head": {"text": title},
        "foot": {"text": f"{scenario}: one column = {step / 1000:.4g} ns (f_sys {transcript['f_sys_hz'] / 1e6:g} MHz){cut}; from the model's waves"},
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
        print(f"wavedrom: {len(diagrams())} diagrams current")


if __name__ == "__main__":
    main()
