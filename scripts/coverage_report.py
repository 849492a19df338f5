#!/usr/bin/env python3
"""coverage_report.py: per-core RTL coverage from Verilator coverage files.

    scripts/coverage_report.py [--baseline FILE] [--write-baseline]
                               [--merge-with CORE=MERGED.dat]... CORE=MERGED.dat ...

Each CORE=MERGED.dat is one core's counts, merged over every replay of its
vector files (scripts/coverage.sh merges them with verilator_coverage).
Only points in the RTL directory (hdl/rtl, or $RTL_DIR) count: the testbench
and its vector player are not the design under test.

Coverage is counted per module, as an engineer reads it: a core's figures
take every point of every module in its hierarchy (the core's own file and
the modules it instantiates: can_controller in canopen_master, uart_rx and
crc_serial in esl_host), each point once however many instances or
parameter sets hold it, and a point is hit when any testbench that
instantiates its module hit it: the counts of every CORE=MERGED.dat given
and of every --merge-with CORE=MERGED.dat (a core whose counts are only
lent to the others, not reported). So can_controller's lines in
canopen_master's figures are merged with can_controller's own vectors; the
points of a core's own file can only come from its own vectors (no other
testbench instantiates it), and a shared module's points are the same in
every core's figures. The report also gives the figures of each module
file. Outputs that never changed are the core's own ports, from its own
testbench only. For each core it prints

  * line, branch and toggle figures (covered / total and percent):
    line    every source line of a Verilator line or branch point; a line is
            covered when any point spanning it was hit,
    branch  Verilator's branch points (each arm of an if or ?:),
    toggle  Verilator's toggle points (one per bit of every signal);
  * every uncovered line with its code;
  * the code excluded from the figures: every `/* verilator coverage_off */`
    .. `/* verilator coverage_on */` region of the core's RTL files (Verilator
    makes no points there), with its line count and the comment above it,
    which must say why no input reaches it (a defensive default);
  * every output port of the core (o_* of the testbench's `dut`) that never
    changed value, and the output bits that never toggled.

With --baseline, exits 1 when a figure falls below the baseline file's
(lines `core line% branch% toggle%`, '#' comments); --write-baseline writes
the measured figures of the cores given into that file (others are kept).
"""
import argparse
import os
import re
import sys
from collections import defaultdict

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def parse_dat(path):
    """Yields (fields, count) for every point of a Verilator coverage file."""
    with open(path, encoding="utf-8", errors="replace") as f:
        for raw in f:
            if not raw.startswith("C '"):
                continue
            key, _, count = raw.rstrip("\n").rpartition("' ")
            fields = {}
            for item in key[3:].split("\x01"):
                if "\x02" in item:
                    k, v = item.split("\x02", 1)
                    fields[k] = v
            yield fields, int(count)


def expand_lines(spec, first):
    """Lines of a point: its `S` list ("12-14,20") or its own line."""
    lines = set()
    for part in (spec or "").split(","):
        part = part.strip()
        if not part:
            continue
        if "-" in part:
            a, b = part.split("-", 1)
            lines.update(range(int(a), int(b) + 1))
        else:
            lines.add(int(part))
    return lines or {first}


def in_rtl(path, rtl_dir):
    # Relative names are the repository's (sim.sh runs Verilator from its
    # root, so that builds in any clone share ccache's entries).
    return os.path.realpath(os.path.join(ROOT, path)).startswith(rtl_dir + os.sep)


def repo_name(path):
    """One name per file, whether Verilator was given it relative to the
    repository (sim.sh) or absolute (counts of an older build)."""
    return os.path.relpath(path, ROOT) if path.startswith(ROOT + os.sep) else path


def pct(hit, total):
    return 100.0 * hit / total if total else 100.0


def points(dat, rtl_dir):
    """The RTL points of one merged counts file, keyed per module.

    A key leaves out the instance (`h`) and the page's module suffix
    (Verilator names a module per parameter set: ssi_master__Bc_Cc8...), so
    that the same line, branch or bit of a module, in any instance, under
    any parameter set and in any testbench, is one point.
    Returns {kind: {key: hits}} for line, branch, toggle, and the output
    bits of the testbench's `dut` ({port: {bit label: hits}})."""
    pts = {"line": defaultdict(int), "branch": defaultdict(int), "toggle": defaultdict(int)}
    out_bits = defaultdict(dict)
    dut = re.compile(r"(^|\.)dut$")
    for p, n in parse_dat(dat):
        page = p.get("page", "")
        fname = repo_name(p.get("f", ""))
        if not in_rtl(fname, rtl_dir):
            continue
        kind = page.split("/", 1)[0]
        if kind in ("v_line", "v_branch"):
            for ln in expand_lines(p.get("S"), int(p.get("l", "0"))):
                pts["line"][(fname, ln)] += n
            if kind == "v_branch":
                pts["branch"][(fname, p.get("l"), p.get("n"), p.get("o"))] += n
        elif kind == "v_toggle":
            name = p.get("o", "")
            pts["toggle"][(fname, name)] += n
            if dut.search(p.get("h", "")) and name.startswith("o_"):
                port = re.sub(r"\[.*$", "", name)
                out_bits[port][name] = out_bits[port].get(name, 0) + n
    return pts, out_bits


def analyse(core, own, pool):
    """One core's figures: the points of its own counts (own = points()),
    each hit when any counts file in pool ({kind: {key: hits}}, summed over
    every testbench) hit it."""
    pts, out_bits = own
    res = {"core": core, "outputs": out_bits, "modules": {}}
    for kind in ("line", "branch", "toggle"):
        keys = pts[kind]
        res[kind] = (sum(1 for k in keys if pool[kind][k] > 0), len(keys))
        for k in keys:
            mod = res["modules"].setdefault(k[0], {"line": [0, 0], "branch": [0, 0], "toggle": [0, 0]})
            mod[kind][1] += 1
            mod[kind][0] += pool[kind][k] > 0
    files = sorted(res["modules"])
    res["uncovered"] = sorted(k for k in pts["line"] if pool["line"][k] == 0)
    res["excluded"] = [x for f in files for x in excluded_regions(f)]
    return res


def excluded_regions(fname):
    """(file, first, last, code lines, reason) of every coverage_off region."""
    try:
        with open(os.path.join(ROOT, fname), encoding="utf-8", errors="replace") as f:
            text = f.read().split("\n")
    except OSError:
        return []
    out, start = [], None
    for i, raw in enumerate(text, 1):
        if re.search(r"verilator\s+coverage_off", raw):
            start = i
        elif start is not None and re.search(r"verilator\s+coverage_on", raw):
            body = [t.strip() for t in text[start:i - 1]]
            code = sum(1 for t in body if t and not t.startswith("//"))
            above, j = [], start - 2
            while j >= 0 and text[j].strip().startswith("//"):
                above.insert(0, text[j].strip().lstrip("/").strip())
                j -= 1
            reason = " ".join(above)
            out.append((fname, start + 1, i - 1, code, reason))
            start = None
    return out


def source_line(cache, fname, ln):
    if fname not in cache:
        try:
            with open(os.path.join(ROOT, fname), encoding="utf-8", errors="replace") as f:
                cache[fname] = f.read().split("\n")
        except OSError:
            cache[fname] = []
    text = cache[fname]
    return text[ln - 1].strip() if 0 < ln <= len(text) else "?"


def report(r, rtl_dir):
    print(f"== {r['core']}")
    for kind in ("line", "branch", "toggle"):
        hit, total = r[kind]
        print(f"   {kind:<7} {pct(hit, total):6.1f} %  ({hit}/{total})")
    if len(r["modules"]) > 1:
        for fname, mod in sorted(r["modules"].items()):
            figs = "  ".join(f"{k} {pct(*mod[k]):5.1f} %" for k in ("line", "branch", "toggle"))
            print(f"     {os.path.basename(fname):<22} {figs}")
    cache = {}
    if r["uncovered"]:
        print(f"   uncovered lines ({len(r['uncovered'])}):")
        for fname, ln in r["uncovered"]:
            print(f"     {repo_name(fname)}:{ln}: {source_line(cache, fname, ln)}")
    if r["excluded"]:
        total = sum(x[3] for x in r["excluded"])
        print(f"   excluded (coverage_off, unreachable): {total} line(s) in {len(r['excluded'])} region(s)")
        for fname, first, last, _, reason in r["excluded"]:
            print(f"     {repo_name(fname)}:{first}-{last}: {reason or '(no reason given above coverage_off)'}")
    never = sorted(p for p, bits in r["outputs"].items() if all(v == 0 for v in bits.values()))
    print(f"   outputs that never changed: {', '.join(never) if never else 'none'}")
    partial = []
    for port, bits in sorted(r["outputs"].items()):
        if port in never:
            continue
        dead = sorted((b for b, v in bits.items() if v == 0), key=bit_order)
        if dead:
            partial.append(f"{port} {compact(dead)}")
    if partial:
        print("   output bits that never toggled: " + "; ".join(partial))
    if not r["outputs"]:
        print("   (no toggle points on the dut's outputs: was it built with --coverage?)")


def bit_order(label):
    m = re.search(r"\[(\d+)\]$", label)
    return int(m.group(1)) if m else -1


def compact(labels):
    """o_abs[23], o_abs[22], o_abs[21] -> [21..23]"""
    idx = sorted(bit_order(b) for b in labels)
    if idx == [-1]:
        return ""
    runs, start, prev = [], idx[0], idx[0]
    for i in idx[1:] + [None]:
        if i is not None and i == prev + 1:
            prev = i
            continue
        runs.append(f"{start}" if start == prev else f"{start}..{prev}")
        if i is not None:
            start = prev = i
    return "[" + ",".join(runs) + "]"


def read_baseline(path):
    base = {}
    if not os.path.exists(path):
        return base
    with open(path, encoding="utf-8") as f:
        for n, raw in enumerate(f, 1):
            line = raw.split("#", 1)[0].split()
            if not line:
                continue
            if len(line) != 4:
                sys.exit(f"coverage: {path}:{n}: want `core line% branch% toggle%`, got {raw.strip()!r}")
            try:
                base[line[0]] = tuple(float(x) for x in line[1:])
            except ValueError:
                sys.exit(f"coverage: {path}:{n}: the figures must be numbers (percent), got {raw.strip()!r}")
    return base


def write_baseline(path, base):
    with open(path, "w", encoding="utf-8") as f:
        f.write("# RTL coverage baseline: scripts/coverage.sh fails when a core's figure falls\n")
        f.write("# below its line here. Percent, one decimal; rewrite with --write-baseline.\n")
        f.write("# core             line   branch  toggle\n")
        for core in sorted(base):
            l, b, t = base[core]
            f.write(f"{core:<16} {l:6.1f} {b:6.1f} {t:6.1f}\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--baseline", help="baseline file (core line%% branch%% toggle%%)")
    ap.add_argument("--write-baseline", action="store_true", help="store the measured figures in --baseline")
    ap.add_argument("--merge-with", action="append", default=[], metavar="CORE=MERGED.dat",
                    help="another core's counts, merged into the module points but not reported")
    ap.add_argument("cores", nargs="+", metavar="CORE=MERGED.dat")
    args = ap.parse_args()
    rtl_dir = os.path.realpath(os.environ.get("RTL_DIR", os.path.join(ROOT, "hdl", "rtl")))
    own, pool = [], {"line": defaultdict(int), "branch": defaultdict(int), "toggle": defaultdict(int)}
    for spec in args.cores + args.merge_with:
        core, sep, dat = spec.partition("=")
        if not sep or not os.path.exists(dat):
            sys.exit(f"coverage: want CORE=MERGED.dat with an existing file, got {spec!r}")
        pts = points(dat, rtl_dir)
        for kind, keys in pts[0].items():
            for k, n in keys.items():
                pool[kind][k] += n
        if spec in args.cores:
            own.append((core, pts))
    results = [analyse(core, pts, pool) for core, pts in own]
    if args.merge_with:
        print("coverage: module points also merged with the counts of "
              + ", ".join(m.partition("=")[0] for m in args.merge_with))
    for r in results:
        report(r, rtl_dir)
    status = 0
    if args.baseline:
        base = read_baseline(args.baseline)
        if args.write_baseline:
            for r in results:
                base[r["core"]] = tuple(round(pct(*r[k]), 1) for k in ("line", "branch", "toggle"))
            write_baseline(args.baseline, base)
            print(f"coverage: baseline written to {args.baseline}")
        else:
            for r in results:
                if r["core"] not in base:
                    print(f"coverage: {r['core']} has no line in {args.baseline} (add one with --write-baseline)")
                    status = 1
                    continue
                for kind, want in zip(("line", "branch", "toggle"), base[r["core"]]):
                    got = round(pct(*r[kind]), 1)
                    if got < want:
                        print(f"coverage: {r['core']} {kind} {got:.1f} % is below the baseline {want:.1f} %")
                        status = 1
            if status == 0:
                print(f"coverage: every figure at or above {args.baseline}")
    return status


if __name__ == "__main__":
    sys.exit(main())
