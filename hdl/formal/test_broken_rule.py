"""A core with a rule broken on purpose (a counter one short) fails its proof,
and the counterexample is a VCD that GTKWave itself opens.

Each case copies one core from hdl/rtl/ into a temporary folder, changes one
counter's load in the copy (hdl/rtl/ is never touched), runs
scripts/formal.py on the copy (--rtl-dir) and expects: exit status 1, the
named property failed from reset, its VCD named in the table; then GTKWave
(headless, under xvfb-run) loads that VCD and answers with its dump file,
its signals and its end time, which must cover the failing step.

Run: .venv/bin/python -m pytest -q hdl/formal/test_broken_rule.py
(make test runs the cases of the first tasks, -k "prove_plain-t_cs or prove_ma-tmasl").
"""

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

# (core, task, the line as the core has it, the line one count short,
#  the property that must catch it, the core's output it is about).
CASES = [
    ("ssi_master", "prove_plain",
     "localparam [31:0] T_CS_LAST_32 = T_CS_CLOCKS - 1;",
     "localparam [31:0] T_CS_LAST_32 = T_CS_CLOCKS - 2;",
     "t_cs", "o_ssi_clk"),
    ("ssi_master", "prove_plain",
     "localparam [31:0] HIGH_LAST_32 = HIGH_CLOCKS - 1;",
     "localparam [31:0] HIGH_LAST_32 = HIGH_CLOCKS - 2;",
     "clock_high", "o_ssi_clk"),
    ("biss_master", "prove_ma",
     "localparam [31:0] LOW_LAST_32 = LOW_CLOCKS - 1;",
     "localparam [31:0] LOW_LAST_32 = LOW_CLOCKS - 2;",
     "tmasl", "o_ma"),
    ("endat_master", "prove_clock",
     "localparam [31:0] T_ST_LAST_32 = T_ST_CLOCKS - 1;",
     "localparam [31:0] T_ST_LAST_32 = T_ST_CLOCKS - 2;",
     "t_st", "o_endat_clk"),
    # A bounded task on abc bmc3: the failure replayed on smtbmc for its trace.
    ("biss_master", "frames",
     "localparam [31:0] LOW_LAST_32 = LOW_CLOCKS - 1;",
     "localparam [31:0] LOW_LAST_32 = LOW_CLOCKS - 2;",
     "tmasl", "o_ma"),
]


def gtkwave_reads(vcd, work):
    """GTKWave's own answer on the VCD: (dump file name, facility names, end time)."""
    tcl = work / "query.tcl"
    tcl.write_text(
        'puts "dump: [gtkwave::getDumpFileName]"\n'
        'puts "max_time: [gtkwave::getMaxTime]"\n'
        "set n [gtkwave::getNumFacs]\n"
        'for {set i 0} {$i < $n} {incr i} { puts "fac: [gtkwave::getFacName $i]" }\n'
        'puts "end: answered"\n'
        "gtkwave::/File/Quit\n")
    out = subprocess.run(
        ["xvfb-run", "-a", "gtkwave", "-S", str(tcl), str(vcd)],
        capture_output=True, text=True, timeout=180).stdout
    assert "end: answered" in out, f"GTKWave did not answer on {vcd}:\n{out[-2000:]}"
    dump = re.search(r"^dump: (.*)$", out, re.M).group(1)
    facs = re.findall(r"^fac: (.*)$", out, re.M)
    max_time = int(re.search(r"^max_time: (\d+)", out, re.M).group(1))
    return dump, facs, max_time


@pytest.mark.parametrize("core,task,line,broken,prop,output", CASES, ids=[f"{c[0]}-{c[1]}-{c[4]}" for c in CASES])
def test_counter_one_short_fails_with_a_trace(tmp_path, core, task, line, broken, prop, output):
    rtl = tmp_path / "rtl"
    rtl.mkdir()
    for f in (ROOT / "hdl" / "rtl").glob("*.v"):
        shutil.copy(f, rtl / f.name)
    src = (rtl / f"{core}.v").read_text()
    assert src.count(line) == 1, f"hdl/rtl/{core}.v no longer has the line `{line}` once: update this case"
    (rtl / f"{core}.v").write_text(src.replace(line, broken))

    run = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "formal.py"), "--core", core, "--task", task,
         "--rtl-dir", str(rtl), "--out", str(tmp_path / "out")],
        capture_output=True, text=True, timeout=900)
    assert run.returncode == 1, f"the broken core was not caught (exit {run.returncode}):\n{run.stdout}\n{run.stderr}"
    m = re.search(rf"^\| `{prop}` \|.*\| failed at step (\d+) \((\S+\.vcd)\) \|$", run.stdout, re.M)
    assert m, f"`{prop}` did not fail with a trace:\n{run.stdout}"
    step, vcd = int(m.group(1)), Path(m.group(2))
    assert vcd.exists(), f"the trace {vcd} is missing"

    dump, facs, max_time = gtkwave_reads(vcd, tmp_path)
    assert Path(dump).name == vcd.name
    assert any(f.endswith(f"dut.{output}") for f in facs), \
        f"GTKWave does not show the core's {output} in {vcd}: {facs[:20]}"
    # smtbmc writes one step per 10 time units: the trace reaches the failing step.
    assert max_time >= 10 * step, f"GTKWave's trace ends at {max_time}, before step {step}"
