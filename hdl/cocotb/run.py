"""Runs cocotb tests under Icarus through cocotb's runner: one test module
per protocol (test_<proto>.py) against our own core, with the emulator from
encoder_emu (pytest collects them from closed_loops_test.py, one pytest test
per closed loop); or, with --dir, a master we did not write
(examples/<dir>/test_<dir>.py, run by the example's `make cocotb`).

    .venv/bin/python -m pytest hdl/cocotb/closed_loops_test.py [-k proto]
    .venv/bin/python hdl/cocotb/run.py [--sim icarus|ghdl] --dir DIR --top TOP --config FILE [--test FILE.py] [NAME=VALUE ...]

The closed loops are the cocotb tests of the protocol descriptors
(`tbgen protocols --json`: each loop's `cocotb` names the test module
test_<cocotb>.py and its scenario file configs/<cocotb>.toml; the loop's
`top` is the core; cosim-params reads the core's and the harness's
parameters for the loop from that file).
Exit status 0 only when every test passed."""

import json
import os
import subprocess
import sys
from pathlib import Path

from cocotb.runner import get_results, get_runner

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent


def tests(lib_dir):
    """(test name, core, closed loop) of every closed loop with a cocotb test, from the descriptors."""
    tbgen = Path(lib_dir) / "tbgen"
    if not tbgen.is_file():
        raise SystemExit(f"run.py: no {tbgen}: build it first (make build)")
    out = subprocess.run([str(tbgen), "protocols", "--json"], check=True, capture_output=True, text=True).stdout
    return [(loop["cocotb"], loop["top"], loop["name"])
            for protocol in json.loads(out) for loop in protocol["closed_loops"] if loop["cocotb"]]


# The simulators a master may run in: (its name in messages, its sources'
# suffix, what cocotb's runner takes besides to build and to run).
SIMULATORS = {
    "icarus": ("Icarus", ".v", {"timescale": ("1ns", "1ps")}, {}),
    # VHDL-2008, as the VHDL wrappers; GHDL's time resolution stays its own.
    "ghdl": ("GHDL", ".vhd", {"build_args": ["--std=08"]}, {"test_args": ["--std=08"]}),
}


def run_master(argv):
    """`[--sim icarus|ghdl] --dir DIR --top TOP --config FILE [--test FILE.py] [NAME=VALUE ...]`:
    the test module DIR/FILE.py (by default DIR/test_<DIR's name>.py) drives
    TOP (every .v in DIR but the tb_*.v, or every .vhd but the tb_*.vhd with
    --sim ghdl, with the parameters or generics NAME=VALUE) against the
    emulator made from DIR/FILE. This is how an example's
    Makefile (`make cocotb`) runs its master, in this checkout or in a copy
    anywhere else; DIR comes first on the simulator's Python path, so a
    module of the same name elsewhere does not shadow the test. Returns the
    number of failed tests."""
    opts, parameters = {}, {}
    it = iter(argv)
    for a in it:
        if a in ("--dir", "--top", "--config", "--test", "--sim"):
            opts[a[2:]] = next(it, None)
        elif "=" in a:
            k, v = a.split("=", 1)
            parameters[k] = v
        else:
            raise SystemExit(f"run.py: `{a}`: give --dir DIR --top TOP --config FILE [--test FILE.py] and parameters as NAME=VALUE")
    if None in opts.values() or not {"dir", "top", "config"} <= set(opts):
        raise SystemExit("run.py: give --dir DIR --top TOP --config FILE [--test FILE.py] (and parameters as NAME=VALUE)")
    sim = opts.get("sim", "icarus")
    if sim not in SIMULATORS:
        raise SystemExit(f"run.py: --sim {sim}: give one of {', '.join(SIMULATORS)}")
    shown, suffix, build_extra, test_extra = SIMULATORS[sim]
    src = Path(opts["dir"]).resolve()
    test = src / opts.get("test", f"test_{src.name}.py")
    config = src / opts["config"]
    if test.suffix != ".py" or test.parent != src:
        raise SystemExit(f"run.py: --test {opts['test']}: give the test module's file name in {src}, e.g. test_{src.name}.py")
    for f, what in ((test, "the test module (--test FILE.py; by default test_<directory name>.py)"), (config, "the configuration (--config FILE)")):
        if not f.is_file():
            raise SystemExit(f"run.py: {f}: no such file: {what}")
    sources = sorted(str(p) for p in src.glob(f"*{suffix}") if not p.name.startswith("tb_"))
    build = src / "build" / "cocotb"
    runner = get_runner(sim)
    kind = "vhdl_sources" if suffix == ".vhd" else "verilog_sources"
    runner.build(**{kind: sources}, hdl_toplevel=opts["top"], parameters=parameters, build_dir=build, always=True,
                 **build_extra)
    # The runner hands the simulator its own sys.path as PYTHONPATH: the test module's directory goes there.
    sys.path.insert(0, str(src))
    env = {"COSIM_CONFIG": str(config)}
    results = runner.test(hdl_toplevel=opts["top"], test_module=test.stem, test_dir=build, build_dir=build,
                          extra_env=env, results_xml=str(build / "results.xml"), **test_extra)
    total, fails = get_results(results)
    print(f"cocotb: {src.name} ({opts['top']}, {shown}): {total - fails} of {total} passed")
    print(f"cocotb: {'pass' if fails == 0 and total > 0 else 'FAIL'}")
    return fails if total > 0 else 1


def params(tool, part, closed_loop, config):
    """cosim-params --part PART: the core's or the harness's parameters of the loop, as {NAME: value}."""
    out = subprocess.run([tool, "--part", part, closed_loop, str(config)], check=True, capture_output=True,
                         text=True).stdout
    return dict(line.split("=", 1) for line in out.split())


def lib_dir():
    """Where tbgen, cosim-params and the emulator library are (scripts/emu_lib.sh's EMU_LIB_DIR)."""
    return os.environ.get("EMU_LIB_DIR", str(ROOT / "target" / "release"))


def run_closed_loop(name, core, closed_loop):
    """The cocotb test test_<name>.py against the core `core` of the closed
    loop `closed_loop`, on configs/<name>.toml: (tests, failures)."""
    tool = str(Path(lib_dir()) / "cosim-params")
    rtl = sorted(str(p) for p in (ROOT / "hdl" / "rtl").glob("*.v"))
    cfg = HERE / "configs" / f"{name}.toml"
    values = params(tool, "core", closed_loop, cfg)
    f_sys = values.pop("F_SYS_HZ")
    harness = params(tool, "harness", closed_loop, cfg)
    build = ROOT / "build" / "cocotb" / name
    runner = get_runner("icarus")
    runner.build(verilog_sources=rtl, hdl_toplevel=core, parameters=values, build_dir=build, always=True)
    env = {"COSIM_CONFIG": str(cfg), "F_SYS_HZ": f_sys, "PYTHONPATH": str(HERE),
           **{f"COSIM_{k}": v for k, v in harness.items()}}
    # Under pytest the runner names the results file by the pytest test and
    # raises on a failed cocotb test itself (it refuses a results_xml then).
    under_pytest = os.getenv("PYTEST_CURRENT_TEST") is not None
    results = runner.test(hdl_toplevel=core, test_module=f"test_{name}", test_dir=build, build_dir=build,
                          extra_env=env, results_xml=None if under_pytest else str(build / "results.xml"))
    total, fails = get_results(results)
    print(f"cocotb: {name} ({core}, Icarus): {total - fails} of {total} passed")
    return total, fails


def main(argv):
    if not argv or not argv[0].startswith("--"):
        raise SystemExit("run.py: the closed loops run under pytest: .venv/bin/python -m pytest "
                         "hdl/cocotb/closed_loops_test.py [-k proto]; run.py itself takes --dir DIR --top TOP --config FILE")
    return 1 if run_master(argv) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
