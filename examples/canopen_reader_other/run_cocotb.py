"""Runs this example's cocotb tests in Icarus: canopen_reader (and under it
mini_can) against the CANopen emulator (test_canopen_reader_other.py), and
mini_can alone against the CAN node emulator (test_can_node_other.py), the
emulators from encoder-tb's Python module encoder_emu.

    <encoder-tb>/.venv/bin/python run_cocotb.py [transactions]

Environment: FLIP_BIT=k (or COSIM_FLIP_BIT=k, as in the other examples) flips bit k of every value read before the
comparison (a planted misread: the tests must then fail). Exit status 0
only when every test passed."""

import os
import sys
from pathlib import Path

from cocotb.runner import get_results, get_runner

HERE = Path(__file__).resolve().parent

# (test module, toplevel, sources, parameters, emulator configuration)
TESTS = [
    ("test_canopen_reader_other", "canopen_reader", ["mini_can.v", "canopen_reader.v"],
     {"NODE": 5, "TIMEOUT": 40000, "CLKS_PER_BIT": 16, "SAMPLE_AT": 11, "JUMP": 3}, "canopen.toml"),
    ("test_can_node_other", "mini_can", ["mini_can.v"],
     {"CLKS_PER_BIT": 32, "SAMPLE_AT": 22, "JUMP": 5}, "node.toml"),
]


def main(argv):
    count = os.environ.get("COSIM_TRANSACTIONS") or (argv[0] if argv else "6")
    failed = 0
    for module, top, sources, params, config in TESTS:
        build = HERE / "build" / "cocotb" / module
        runner = get_runner("icarus")
        runner.build(verilog_sources=[str(HERE / s) for s in sources], hdl_toplevel=top, parameters=params,
                     build_dir=build, always=True, timescale=("1ns", "1ps"))
        env = {"EMU_CONFIG": str(HERE / config), "TRANSACTIONS": count, "PYTHONPATH": os.pathsep.join(filter(None, [str(HERE), os.environ.get("PYTHONPATH")])),
               "FLIP_BIT": os.environ.get("COSIM_FLIP_BIT", os.environ.get("FLIP_BIT", "-1"))}
        results = runner.test(hdl_toplevel=top, test_module=module, test_dir=HERE, build_dir=build,
                              extra_env=env, results_xml=str(build / "results.xml"))
        total, fails = get_results(results)
        print(f"cocotb: {module} ({top}, Icarus): {total - fails} of {total} passed")
        failed += fails
    print(f"cocotb: {'pass' if failed == 0 else 'FAIL'}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
