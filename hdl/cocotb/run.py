"""Runs the cocotb examples under Icarus: one test module per protocol
(test_<proto>.py) against our own core, with the emulator from encoder_emu.

    .venv/bin/python hdl/cocotb/run.py [proto ...]

Each entry below names the test module, the core, the scenario file the
emulator and the core's parameters come from (cosim-params), and the
cosim-params protocol.
Exit status 0 only when every test passed."""

import os
import subprocess
import sys
from pathlib import Path

from cocotb.runner import get_results, get_runner

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent

TESTS = [
    ("ssi", "ssi_master", "ssi.toml", "ssi"),
    ("biss", "biss_master", "biss.toml", "biss"),
    ("sar58k24", "sar_async_host", "sar58k24.toml", "sar"),
    ("modbus", "modbus_master", "modbus.toml", "modbus"),
    ("can", "can_controller", "can.toml", "can"),
    ("sar58k24_can", "can_controller", "sar58k24_can.toml", "sar_can"),
    ("endat", "endat_master", "endat.toml", "endat"),
    ("tformat", "tformat_host", "tformat.toml", "tformat"),
    ("esl", "esl_host", "esl.toml", "esl"),
]


def params(tool, proto, config):
    out = subprocess.run([tool, proto, str(config)], check=True, capture_output=True, text=True).stdout
    values = dict(line.split("=", 1) for line in out.split())
    return values


def main(argv):
    chosen = set(argv) or {t[0] for t in TESTS}
    lib_dir = os.environ.get("EMU_LIB_DIR", str(ROOT / "target" / "release"))
    tool = str(Path(lib_dir) / "cosim-params")
    rtl = sorted(str(p) for p in (ROOT / "hdl" / "rtl").glob("*.v"))
    failed = 0
    for name, core, config, proto in TESTS:
        if name not in chosen:
            continue
        cfg = HERE / "configs" / config
        values = params(tool, proto, cfg)
        f_sys = values.pop("F_SYS_HZ")
        harness = {k: values.pop(k) for k in list(values) if k in ("ADDRESS", "COUNT", "NODES") or k.startswith("SAR_")}
        build = ROOT / "build" / "cocotb" / name
        runner = get_runner("icarus")
        runner.build(verilog_sources=rtl, hdl_toplevel=core, parameters=values, build_dir=build, always=True)
        env = {"COSIM_CONFIG": str(cfg), "F_SYS_HZ": f_sys, "PYTHONPATH": str(HERE),
               **{f"COSIM_{k}": v for k, v in harness.items()}}
        results = runner.test(hdl_toplevel=core, test_module=f"test_{name}", test_dir=build, build_dir=build,
                              extra_env=env, results_xml=str(build / "results.xml"))
        total, fails = get_results(results)
        print(f"cocotb: {name} ({core}, Icarus): {total - fails} of {total} passed")
        failed += fails
    print(f"cocotb: {'pass' if failed == 0 else 'FAIL'}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
