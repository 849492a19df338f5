"""pytest: the closed loops' cocotb tests (hdl/cocotb/test_<proto>.py), one
pytest test per closed loop of the protocol descriptors, each run under
Icarus by cocotb's runner (run.py). `scripts/cocotb.sh [proto ...]` runs
them; so does

    EMU_LIB_DIR=target/release .venv/bin/python -m pytest hdl/cocotb/closed_loops_test.py -k ssi

(after scripts/emu_lib.sh has built the library and scripts/cocotb.sh has
put encoder_emu on the venv's path once)."""

import pytest

import run

LOOPS = run.tests(run.lib_dir())


@pytest.mark.parametrize("name,core,closed_loop", LOOPS, ids=[loop[0] for loop in LOOPS])
def test_closed_loop(name, core, closed_loop):
    total, fails = run.run_closed_loop(name, core, closed_loop)
    assert total > 0, f"cocotb found no test in test_{name}.py"
    assert fails == 0, f"{fails} of {total} cocotb tests of test_{name}.py failed (the log above says which and why)"
