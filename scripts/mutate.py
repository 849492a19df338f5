#!/usr/bin/env python3
"""mutate.py: mutation testing of one RTL core against its golden vectors.

    scripts/mutate.py CORE [--count N] [--seed S] [--list] [--only ID,...]
                      [--accepted FILE] [--timeout SECONDS]

Makes mutants of hdl/rtl/<CORE>.v, each one small change a real bug could
make, picked deterministically (the same seed gives the same mutants):

  rel      a relational operator flipped or moved (<  >=  >  <=)
  eq       == and != swapped
  logic    && and || swapped
  bitwise  binary & and | swapped
  arith    binary + and - swapped
  const    a constant one more or one less (1-bit constants inverted)
  not      a logical ! removed
  cond     an if condition inverted
  reset    a value the reset branch (if (i_rst)) loads changed

and replays each in Verilator against vectors/<CORE>/*.hex, shortest file
first, stopping at the first file that fails (the mutant is killed). A
mutant that passes every file survives: either the vectors miss a
behaviour, or the change is equivalent. A mutant that does not build is
stillborn and does not count. Mutants build in a temporary directory
(scripts/sim.sh with RTL_DIR and SIM_BUILD_DIR), never in build/sim.

Prints every killed mutant (and the file that killed it), every survivor
with its diff, and the mutation score killed / (killed + survived).
Survivors listed in the accepted file (default
hdl/mutation/accepted_survivors.txt) are shown as accepted with their
reason; the exit status is 1 when a survivor is not accepted, 2 for bad
input. Entries of the accepted file:

    core: esl_host
    - <the original line, stripped>
    + <the mutated line, stripped>
    why: <the reason this survivor is accepted>

(blank lines and lines starting with '#' between entries are ignored).
"""
import argparse
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CATEGORIES = ["rel", "eq", "logic", "bitwise", "arith", "const", "not", "cond", "reset"]


class Mutant:
    def __init__(self, category, line, col, old, new, text):
        self.category = category
        self.line = line          # 1-based
        self.col = col            # 0-based column of the change
        self.old = old
        self.new = new
        self.orig = text          # the whole original line
        self.mutated = text[:col] + new + text[col + len(old):]
        self.id = ""

    def signature(self):
        return (self.orig.strip(), self.mutated.strip())


def blank_comments(lines):
    """The source with comments and strings replaced by spaces (same columns)."""
    out = []
    in_block = False
    for text in lines:
        res = []
        i = 0
        in_str = False
        while i < len(text):
            c = text[i]
            if in_block:
                if text.startswith("*/", i):
                    in_block = False
                    res.append("  ")
                    i += 2
                    continue
                res.append(" ")
            elif in_str:
                if c == "\\":
                    res.append("  ")
                    i += 2
                    continue
                if c == '"':
                    in_str = False
                res.append(" ")
            elif text.startswith("//", i):
                res.append(" " * (len(text) - i))
                break
            elif text.startswith("/*", i):
                in_block = True
                res.append("  ")
                i += 2
                continue
            elif c == '"':
                in_str = True
                res.append(" ")
            else:
                res.append(c)
            i += 1
        out.append("".join(res)[: len(text)].ljust(len(text)))
    return out


SKIP_START = re.compile(r"^\s*(localparam|parameter|input|output|inout|integer|genvar|`|module|endmodule|reg\b|\.|\)\s*[a-z_0-9]*\s*\()")
INSTANCE = re.compile(r"^\s*[A-Za-z_]\w*\s*#\s*\(|^\s*[A-Za-z_]\w*\s+[A-Za-z_]\w*\s*\(")
OPERAND_END = re.compile(r"[\w\)\]']\s*$")


def code_lines(code):
    """Indices of lines that hold logic: inside always/function/assign/wire
    bodies, not declarations, instances, initial blocks or port lists."""
    keep = []
    in_initial = 0
    in_ports = False
    in_instance = 0
    in_decl = False
    for i, text in enumerate(code):
        s = text.strip()
        if not s:
            continue
        if re.match(r"^module\b", s):
            in_ports = True
        if in_ports:
            if s.startswith(");"):
                in_ports = False
            continue
        if in_instance:
            in_instance += text.count("(") - text.count(")")
            if ");" in s or in_instance <= 0:
                in_instance = 0
            continue
        if re.match(r"^initial\b", s):
            in_initial = 1 if "begin" in s else 0
            continue
        if in_initial:
            in_initial += len(re.findall(r"\bbegin\b", s)) - len(re.findall(r"\bend\b", s))
            continue
        if INSTANCE.match(text) and not re.match(r"^\s*(wire|assign|if|else|case|always|function|for)\b", text):
            if ";" not in s:
                in_instance = max(1, text.count("(") - text.count(")"))
            continue
        if in_decl:
            in_decl = ";" not in s
            continue
        if SKIP_START.match(text):
            in_decl = ";" not in s and re.match(r"^\s*(localparam|parameter|reg|integer|input|output)\b", text) is not None
            continue
        keep.append(i)
    return keep


def operand_before(text, pos):
    return bool(OPERAND_END.search(text[:pos]))


def statement_assigns_before(text, pos):
    """Whether text[:pos] (this statement) already has an assignment or an
    open parenthesis, so that a following <= is a comparison."""
    head = text[:pos]
    depth = head.count("(") - head.count(")")
    if depth > 0 or "?" in head:
        return True
    stmt = re.split(r";|\bbegin\b|\belse\b", head)[-1]
    return bool(re.search(r"(?<![=!<>])=(?!=)", stmt))


def find_mutants(lines, code, core_lines, rst_lines):
    muts = []
    for i in core_lines:
        text, c = lines[i], code[i]
        # Relational and equality operators.
        for m in re.finditer(r"<=|>=|==|!=|(?<![<>=!])<(?![<=])|(?<![<>=-])>(?![>=])", c):
            op, pos = m.group(), m.start()
            if op in ("==", "!="):
                muts.append(Mutant("eq", i + 1, pos, op, "!=" if op == "==" else "==", text))
                continue
            if op == "<=" and not statement_assigns_before(c, pos):
                continue  # a non-blocking assignment
            if op in ("<", ">") and not operand_before(c, pos):
                continue
            flip = {"<": ">=", ">=": "<", ">": "<=", "<=": ">"}[op]
            muts.append(Mutant("rel", i + 1, pos, op, flip, text))
        for m in re.finditer(r"&&|\|\|", c):
            op = m.group()
            muts.append(Mutant("logic", i + 1, m.start(), op, "||" if op == "&&" else "&&", text))
        for m in re.finditer(r"(?<![&|~^])([&|])(?![&|=])", c):
            if operand_before(c, m.start()):
                op = m.group(1)
                muts.append(Mutant("bitwise", i + 1, m.start(), op, "|" if op == "&" else "&", text))
        for m in re.finditer(r"(?<![+\-:\[])([+\-])(?![+\-:=])", c):
            depth = c[: m.start()].count("[") - c[: m.start()].count("]")
            if depth == 0 and operand_before(c, m.start()):
                op = m.group(1)
                muts.append(Mutant("arith", i + 1, m.start(), op, "-" if op == "+" else "+", text))
        for m in re.finditer(r"!(?!=)", c):
            muts.append(Mutant("not", i + 1, m.start(), "!", "", text))
        for m in re.finditer(r"\bif\s*\(", c):
            start = m.end() - 1
            depth, j = 0, start
            while j < len(c):
                depth += (c[j] == "(") - (c[j] == ")")
                if depth == 0:
                    break
                j += 1
            if j < len(c):
                old = text[start: j + 1]
                muts.append(Mutant("cond", i + 1, start, old, "(!" + old + ")", text))
        cat = "reset" if i in rst_lines else "const"
        for m in re.finditer(r"(\d+)'([bdh])([0-9a-fA-F_]+)|(?<![\w'.$])(\d+)(?![\w'.])", c):
            depth = c[: m.start()].count("[") - c[: m.start()].count("]")
            if depth != 0:
                continue  # a bit index or a width
            if m.group(1):
                width, base, digits = int(m.group(1)), m.group(2), m.group(3).replace("_", "")
                radix = {"b": 2, "d": 10, "h": 16}[base]
                try:
                    value = int(digits, radix)
                except ValueError:
                    continue
                mask = (1 << width) - 1
                news = [(value ^ 1) & mask] if width == 1 else [(value + 1) & mask, (value - 1) & mask]
                for nv in news:
                    rendered = format(nv, {"b": "b", "d": "d", "h": "X"}[base])
                    muts.append(Mutant(cat, i + 1, m.start(), m.group(0), f"{width}'{base}{rendered}", text))
            else:
                value = int(m.group(4))
                for nv in (value + 1, value - 1):
                    if nv >= 0:
                        muts.append(Mutant(cat, i + 1, m.start(), m.group(0), str(nv), text))
    return muts


def reset_lines(code):
    """Lines inside `if (i_rst) begin ... end` blocks."""
    out = set()
    depth = 0
    for i, c in enumerate(code):
        if depth == 0 and re.search(r"\bif\s*\(\s*i_rst\s*\)\s*begin\b", c):
            depth = 1
            continue
        if depth:
            depth += len(re.findall(r"\bbegin\b", c)) - len(re.findall(r"\bend\b", c))
            if depth > 0:
                out.add(i)
    return out


def select(muts, count, seed):
    rng = random.Random(seed)
    groups = {c: [m for m in muts if m.category == c] for c in CATEGORIES}
    for c in CATEGORIES:
        rng.shuffle(groups[c])
    picked = []
    while len(picked) < count and any(groups.values()):
        for c in CATEGORIES:
            if groups[c] and len(picked) < count:
                picked.append(groups[c].pop())
    picked.sort(key=lambda m: (m.line, m.col, m.category, m.new))
    for n, m in enumerate(picked, 1):
        m.id = f"M{n:02d}"
    return picked


def read_accepted(path):
    entries = {}
    if not os.path.exists(path):
        return entries
    cur = {}
    with open(path, encoding="utf-8") as f:
        for n, raw in enumerate(f, 1):
            line = raw.rstrip("\n")
            if not line.strip() or line.startswith("#"):
                continue
            key, sep, val = line.partition(" ")
            if key == "core:":
                cur = {"core": val.strip(), "at": n}
            elif key in ("-", "+") and cur:
                cur[key] = val.strip()
            elif key == "why:" and cur and "-" in cur and "+" in cur:
                entries[(cur["core"], cur["-"], cur["+"])] = val.strip()
                cur = {}
            else:
                sys.stderr.write(f"mutate: {path}:{n}: want `core: NAME`, `- original`, `+ mutant`, `why: reason` in that order\n")
                sys.exit(2)
    return entries


def vector_files(core):
    d = os.path.join(ROOT, "vectors", core)
    files = [os.path.join(d, f) for f in os.listdir(d) if f.endswith(".hex")] if os.path.isdir(d) else []

    def records(path):
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.startswith("// records: "):
                    return int(line.split()[2])
                if not line.startswith("//"):
                    break
        return os.path.getsize(path)
    return sorted(files, key=lambda p: (records(p), p))


def run_mutant(core, mut, rtl_src, files, timeout, workdir):
    tmp = tempfile.mkdtemp(prefix=f"{mut.id}-", dir=workdir)
    try:
        rtl = os.path.join(tmp, "rtl")
        os.mkdir(rtl)
        for f in os.listdir(rtl_src):
            if f.endswith(".v"):
                shutil.copy(os.path.join(rtl_src, f), rtl)
        path = os.path.join(rtl, f"{core}.v")
        with open(path, encoding="utf-8") as f:
            lines = f.read().split("\n")
        assert lines[mut.line - 1] == mut.orig
        lines[mut.line - 1] = mut.mutated
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join(lines))
        env = dict(os.environ, RTL_DIR=rtl, SIM_BUILD_DIR=os.path.join(tmp, "build"))
        if shutil.which("ccache"):
            # Verilator's runtime objects are the same for every mutant: a
            # compiler cache private to this run builds them once.
            env.update(OBJCACHE="ccache", CCACHE_DIR=os.path.join(workdir, "ccache"),
                       CCACHE_BASEDIR=workdir, CCACHE_NOHASHDIR="true")
        env.pop("COVERAGE", None)
        for n, vec in enumerate(files, 1):
            try:
                p = subprocess.run([os.path.join(ROOT, "scripts", "sim.sh"), core, "verilator", vec],
                                   env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout)
                ok, out = p.returncode == 0, p.stdout.decode(errors="replace")
            except subprocess.TimeoutExpired:
                return "killed", f"{os.path.basename(vec)} (timeout after {timeout} s)", n
            if not ok:
                built = any(os.path.exists(os.path.join(dp, "Vtb")) for dp, _, _ in os.walk(os.path.join(tmp, "build")))
                if not built:
                    return "stillborn", out.strip().split("\n")[0][:160], n
                why = next((l.strip() for l in out.split("\n") if "MISMATCH" in l or "rror" in l), "non-zero exit")
                return "killed", f"{os.path.basename(vec)}: {why[:160]}", n
        return "survived", "", len(files)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def main():
    ap = argparse.ArgumentParser(description="mutation testing of one RTL core against its vectors")
    ap.add_argument("core")
    ap.add_argument("--count", type=int, default=40, help="mutants to make (default 40)")
    ap.add_argument("--seed", type=int, default=1, help="selection seed (default 1)")
    ap.add_argument("--list", action="store_true", help="list the selected mutants and stop")
    ap.add_argument("--only", help="comma-separated mutant ids to run (M03,M17)")
    ap.add_argument("--accepted", default=os.path.join(ROOT, "hdl", "mutation", "accepted_survivors.txt"))
    ap.add_argument("--timeout", type=int, default=600, help="seconds per replay, build included (default 600)")
    args = ap.parse_args()

    rtl_src = os.path.realpath(os.environ.get("RTL_DIR", os.path.join(ROOT, "hdl", "rtl")))
    src = os.path.join(rtl_src, f"{args.core}.v")
    if not os.path.exists(src):
        sys.stderr.write(f"mutate: no RTL {src} for core '{args.core}'\n")
        return 2
    files = vector_files(args.core)
    if not files and not args.list:
        sys.stderr.write(f"mutate: no vectors in vectors/{args.core}/ (run make vectors)\n")
        return 2
    if args.count < 1:
        sys.stderr.write("mutate: --count must be at least 1\n")
        return 2
    with open(src, encoding="utf-8") as f:
        lines = f.read().split("\n")
    code = blank_comments(lines)
    muts = find_mutants(lines, code, code_lines(code), reset_lines(code))
    picked = select(muts, args.count, args.seed)
    print(f"mutate: {args.core}: {len(muts)} candidate mutants, {len(picked)} selected (seed {args.seed}); "
          f"{len(files)} vector files, shortest first")
    if args.only:
        want = set(args.only.split(","))
        picked = [m for m in picked if m.id in want]
    if args.list:
        for m in picked:
            print(f"{m.id} {m.category:<8} {args.core}.v:{m.line}\n    - {m.orig.strip()}\n    + {m.mutated.strip()}")
        return 0

    accepted = read_accepted(args.accepted)
    results = []
    workdir = tempfile.mkdtemp(prefix=f"mutate-{args.core}-")
    try:
        for m in picked:
            t0 = time.time()
            verdict, detail, nrun = run_mutant(args.core, m, rtl_src, files, args.timeout, workdir)
            results.append((m, verdict, detail))
            print(f"{m.id} {verdict:<9} {m.category:<8} {args.core}.v:{m.line}  {time.time() - t0:5.0f} s  "
                  f"({nrun} file{'s' if nrun != 1 else ''}) {detail}", flush=True)
    finally:
        shutil.rmtree(workdir, ignore_errors=True)

    killed = [r for r in results if r[1] == "killed"]
    survived = [r for r in results if r[1] == "survived"]
    stillborn = [r for r in results if r[1] == "stillborn"]
    print()
    print(f"killed ({len(killed)}):")
    for m, _, detail in killed:
        print(f"  {m.id} {m.category:<8} {args.core}.v:{m.line}  {m.orig.strip()}  ->  {m.mutated.strip()}\n      by {detail}")
    print(f"survived ({len(survived)}):")
    unaccepted = 0
    for m, _, _ in survived:
        why = accepted.get((args.core,) + m.signature())
        tag = f"accepted: {why}" if why else "NOT ACCEPTED"
        unaccepted += why is None
        print(f"  {m.id} {m.category:<8} {args.core}.v:{m.line}  [{tag}]\n    - {m.orig.strip()}\n    + {m.mutated.strip()}")
    if stillborn:
        print(f"stillborn, not counted ({len(stillborn)}):")
        for m, _, detail in stillborn:
            print(f"  {m.id} {m.category:<8} {args.core}.v:{m.line}  {m.mutated.strip()}  ({detail})")
    scored = len(killed) + len(survived)
    score = 100.0 * len(killed) / scored if scored else 0.0
    print(f"mutate: {args.core}: score {score:.1f} % ({len(killed)} killed of {scored}; "
          f"{len(survived)} survived, {len(survived) - unaccepted} of them accepted; {len(stillborn)} stillborn)")
    return 1 if unaccepted else 0


if __name__ == "__main__":
    sys.exit(main())
