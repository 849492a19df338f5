#!/usr/bin/env python3
"""mutate.py: mutation testing of one RTL core against its golden vectors.

    scripts/mutate.py CORE [--count N] [--seed S] [--list] [--only ID,...]
                      [--accepted FILE] [--timeout SECONDS] [--separate] [--show-schema]
                      [--jobs N]

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

The builds, not the replays, are what cost (a Verilator build is 5 to 15 s
on a 2-core machine, a replay 0.2 to 0.5 s, and a core's vectors use up to
17 parameter sets), so the mutants are built as one schema: a copy of the
core in which each mutated expression reads
((mutant_id == K) ? <mutated> : <original>), with mutant_id set from the
plusarg +mutant_id=K (see make_schema). The schema is built once per
parameter set, replayed once with +mutant_id=0 (the original core, which
must pass every file), then each mutant is a replay with its own id. A
mutant the schema cannot hold (a change in a for header or in a statement
over several lines) is built alone, as is every mutant with --separate;
if the schema does not build or the original fails in it, every mutant is
built alone. The selection (ids, seed, count) and the report do not
depend on the way they are built.

Prints every killed mutant (and the file that killed it), every survivor
with its diff, and the mutation score killed / (killed + survived).
Survivors listed in the accepted file (default
hdl/mutation/accepted_survivors.txt) are shown as accepted with their
reason; the exit status is 1 when a survivor is not accepted or the score
is below --min-score (default 90 %), 2 for bad input. Entries of the accepted file:

    core: esl_host
    - <the original line, stripped>
    + <the mutated line, stripped>
    why: <the reason this survivor is accepted>

(blank lines and lines starting with '#' between entries are ignored).
"""
import argparse
import concurrent.futures
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


# ---------------------------------------------------------------------------
# Mutant schemata: one source holding every selected mutant, each behind a
# run-time test of the plusarg +mutant_id=K, so that one Verilator build per
# parameter set serves every mutant instead of one build per mutant and
# parameter set. A mutant changes one token of one line; the schema wraps the
# smallest whole expression around the change that can be chosen at run time
# (a parenthesised expression, an if or case condition, the right-hand side
# of an assignment on one line, a case item label) as
#     ((mutant_id == K) ? <expression with the change> : <original expression>)
# (several mutants of the same expression chain their choices). Verilog gives
# both arms of ?: the width and signedness the expression had, so the mutant
# with mutant_id = K computes what the mutated file computes. A mutant whose
# change sits where a run-time choice cannot go (a for header, a statement
# that spans lines) is built on its own, as before.

OPEN, CLOSE = "([{", ")]}"


def depths(c):
    """Bracket depth (all of ( [ {) before each column of code line c."""
    out, d = [], 0
    for ch in c:
        if ch in CLOSE:
            d -= 1
        out.append(d)
        if ch in OPEN:
            d += 1
    return out


def paren_groups(c):
    """(open, close) columns of every ( ) pair on code line c."""
    stack, pairs = [], []
    for i, ch in enumerate(c):
        if ch == "(":
            stack.append(i)
        elif ch == ")" and stack:
            pairs.append((stack.pop(), i))
    return pairs


def assign_op(c, lo, hi, dep):
    """Column just after the first assignment operator (= or <=) at bracket
    depth 0 in c[lo:hi], or None."""
    for m in re.finditer(r"<=|(?<![<>=!])=(?!=)", c[lo:hi]):
        p = lo + m.start()
        if dep[p] == 0:
            return p + len(m.group())
    return None


def schema_span(c, mut):
    """Columns [lo, hi) of code line c holding a whole expression around the
    change of mut that a run-time choice can replace, or None."""
    lo_m, hi_m = mut.col, mut.col + len(mut.old)
    dep = depths(c)
    # Parenthesised groups around the change, outermost first; a group is a
    # plain expression unless it follows a name (a call: the arguments are
    # separate) or `for`, or holds a comma or ; of its own.
    groups = sorted((g for g in paren_groups(c) if g[0] <= lo_m and g[1] + 1 >= hi_m), key=lambda g: g[0])
    for o, e in groups:
        before = c[:o].rstrip()
        word = re.search(r"[\w$]+$", before)
        if word and word.group() not in ("if", "case", "casez", "casex", "while"):
            continue
        inner = range(o + 1, e)
        if any(c[i] in ",;" and dep[i] == dep[o] + 1 for i in inner):
            continue
        if re.search(r"\b(if|case|casez|casex|begin|end|else)\b", c[o:e + 1][1:-1]):
            continue
        return o, e + 1
    if dep[lo_m] != 0:
        return None
    # The statement around the change: from the last ; (or the line start)
    # to the next ; at depth 0, all on this line.
    start = max([i + 1 for i in range(lo_m) if c[i] == ";" and dep[i] == 0] or [0])
    ends = [i for i in range(hi_m, len(c)) if c[i] == ";" and dep[i] == 0]
    if ends:
        op = assign_op(c, start, lo_m, dep)
        if op is not None and not re.search(r"\b(if|case|begin|end|else)\b", c[op:ends[0]]):
            return op, ends[0]
    # A case item label (`6'd1, 6'd2: ...`): the comma-separated item.
    colon = next((i for i in range(len(c)) if c[i] == ":" and dep[i] == 0), None)
    if colon is not None and hi_m <= colon and assign_op(c, 0, colon, dep) is None \
            and not re.search(r"\b(if|else|case|casez|casex|begin|end|assign|wire)\b|\?", c[:colon]):
        lo = max([i + 1 for i in range(lo_m) if c[i] == "," and dep[i] == 0] or [0])
        hi = min([i for i in range(hi_m, colon) if c[i] == "," and dep[i] == 0] or [colon])
        return lo, hi
    return None


def make_schema(lines, code, picked):
    """The schema's lines, and the mutants it could not hold."""
    out = list(lines)
    by_line, rest = {}, []
    for m in picked:
        span = schema_span(code[m.line - 1], m)
        if span is None:
            rest.append(m)
        else:
            by_line.setdefault(m.line, []).append([m, span])
    for ln, items in by_line.items():
        text = lines[ln - 1]
        # Spans on a line nest or lie apart: each mutant takes the largest
        # span that holds its own, so that a span is replaced once.
        spans0 = [tuple(it[1]) for it in items]
        for it in items:
            s = tuple(it[1])
            for o in spans0:
                if o[0] <= s[0] and s[1] <= o[1] and o[1] - o[0] > s[1] - s[0]:
                    s = o
            it[1] = s
        spans = sorted({tuple(it[1]) for it in items}, reverse=True)
        if any(a[1] > b[0] for b, a in zip(spans, spans[1:])):
            rest.extend(it[0] for it in items)  # overlapping, not nested
            continue
        new = text
        for lo, hi in spans:
            orig = text[lo:hi]
            arms = []
            for m, span in items:
                if tuple(span) != (lo, hi):
                    continue
                mut = m.mutated[lo:hi + len(m.new) - len(m.old)]
                # The mutant's line is this line with its span replaced.
                assert m.mutated == text[:lo] + mut + text[hi:], (m.id, ln)
                arms.append(f"(mutant_id == {int(m.id[1:])}) ? ({mut.strip()}) : ")
            lead = orig[: len(orig) - len(orig.lstrip())]
            tail = orig[len(orig.rstrip()):]
            new = new[:lo] + lead + "(" + "".join(arms) + "(" + orig.strip() + "))" + tail + new[hi:]
        out[ln - 1] = new
    held = [m for m in picked if m not in rest]
    # The selector: one integer of the core module, set from +mutant_id=K
    # (0, the original, without it), declared right after the port list.
    for i, c in enumerate(code):
        if re.match(r"^\s*module\b", c):
            j = i
            while j < len(code) and not code[j].rstrip().endswith(";"):
                j += 1
            out[j] = out[j] + " integer mutant_id; initial if (!$value$plusargs(\"mutant_id=%d\", mutant_id)) mutant_id = 0;"
            break
    return out, held, rest


def sim_env(workdir, rtl, build):
    env = dict(os.environ, RTL_DIR=rtl, SIM_BUILD_DIR=build)
    if shutil.which("ccache"):
        # Verilator's runtime objects are the same for every build: a
        # compiler cache private to this run builds them once.
        env.update(OBJCACHE="ccache", CCACHE_DIR=os.path.join(workdir, "ccache"),
                   CCACHE_BASEDIR=workdir, CCACHE_NOHASHDIR="true")
    env.pop("COVERAGE", None)
    return env


def write_rtl(rtl_src, rtl, core, lines):
    os.makedirs(rtl)
    for f in os.listdir(rtl_src):
        if f.endswith(".v"):
            shutil.copy(os.path.join(rtl_src, f), rtl)
    with open(os.path.join(rtl, f"{core}.v"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines))


def replay(core, files, env, timeout, plusargs=""):
    """Replays files shortest first, stopping at the first that fails:
    (verdict, detail, files run); stillborn when the build fails."""
    env = dict(env, SIM_PLUSARGS=plusargs)
    for n, vec in enumerate(files, 1):
        try:
            p = subprocess.run([os.path.join(ROOT, "scripts", "sim.sh"), core, "verilator", vec],
                               env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout)
            ok, out = p.returncode == 0, p.stdout.decode(errors="replace")
        except subprocess.TimeoutExpired:
            return "killed", f"{os.path.basename(vec)} (timeout after {timeout} s)", n
        if not ok:
            built = any(os.path.exists(os.path.join(dp, "Vtb")) for dp, _, _ in os.walk(env["SIM_BUILD_DIR"]))
            if not built:
                return "stillborn", out.strip().split("\n")[0][:160], n
            why = next((l.strip() for l in out.split("\n") if "MISMATCH" in l or "rror" in l), "non-zero exit")
            return "killed", f"{os.path.basename(vec)}: {why[:160]}", n
    return "survived", "", len(files)


def run_mutant(core, mut, rtl_src, files, timeout, workdir):
    """One mutant on its own: its own source, its own builds."""
    tmp = tempfile.mkdtemp(prefix=f"{mut.id}-", dir=workdir)
    try:
        with open(os.path.join(rtl_src, f"{core}.v"), encoding="utf-8") as f:
            lines = f.read().split("\n")
        assert lines[mut.line - 1] == mut.orig
        lines[mut.line - 1] = mut.mutated
        write_rtl(rtl_src, os.path.join(tmp, "rtl"), core, lines)
        env = sim_env(workdir, os.path.join(tmp, "rtl"), os.path.join(tmp, "build"))
        return replay(core, files, env, timeout)
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
    ap.add_argument("--min-score", type=float, default=90.0,
                    help="fail below this score in percent, survivors accepted or not (default 90)")
    ap.add_argument("--timeout", type=int, default=600, help="seconds per replay, build included (default 600)")
    ap.add_argument("--separate", action="store_true",
                    help="build every mutant on its own (no schema; slow, the reference the schema is checked against)")
    ap.add_argument("--show-schema", action="store_true", help="print the schema's changed lines and stop")
    ap.add_argument("--jobs", type=int, default=1,
                    help="mutants replayed at once (default 1; 2 on an idle 2-core machine halves the run)")
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
        alone = picked
        env = None
        if not args.separate:
            schema, held, alone = make_schema(lines, code, picked)
            if args.show_schema:
                for n, (a, b) in enumerate(zip(lines, schema), 1):
                    if a != b:
                        print(f"{args.core}.v:{n}: {b.strip()}")
                print(f"held in the schema: {len(held)}; built alone: {' '.join(m.id for m in alone) or 'none'}")
                return 0
            # The schema with mutant_id = 0 is the original core: it builds
            # every parameter set (once, for every mutant) and must pass.
            t0 = time.time()
            write_rtl(rtl_src, os.path.join(workdir, "schema", "rtl"), args.core, schema)
            env = sim_env(workdir, os.path.join(workdir, "schema", "rtl"), os.path.join(workdir, "schema", "build"))
            verdict, detail, _ = replay(args.core, files, env, args.timeout, "+mutant_id=0")
            if verdict == "survived":
                print(f"schema: {len(held)} mutants in one build per parameter set "
                      f"({len(alone)} built alone); builds and the original's replay {time.time() - t0:.0f} s", flush=True)
            else:
                print(f"schema: the original core in the schema {'does not build' if verdict == 'stillborn' else 'fails'}"
                      f" ({detail}); every mutant is built alone", flush=True)
                held, alone, env = [], picked, None
        def one(m):
            t0 = time.time()
            if m in alone:
                verdict, detail, nrun = run_mutant(args.core, m, rtl_src, files, args.timeout, workdir)
            else:
                verdict, detail, nrun = replay(args.core, files, env, args.timeout, f"+mutant_id={int(m.id[1:])}")
            print(f"{m.id} {verdict:<9} {m.category:<8} {args.core}.v:{m.line}  {time.time() - t0:5.0f} s  "
                  f"({nrun} file{'s' if nrun != 1 else ''}) {detail}", flush=True)
            return m, verdict, detail
        # Each mutant's replays are separate processes (sim.sh locks a build
        # while it is made), so mutants can run side by side; the summary
        # below is in id order either way.
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
            results = list(pool.map(one, picked))
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
    if score < args.min_score:
        print(f"mutate: {args.core}: FAIL: the score is below --min-score {args.min_score:g} %")
    return 1 if unaccepted or score < args.min_score else 0


if __name__ == "__main__":
    sys.exit(main())
