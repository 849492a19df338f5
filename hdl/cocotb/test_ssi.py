"""cocotb example: ssi_master against the SSI encoder emulator (seed 001,
SSI): random positions set from Python, each read compared with what the
emulator stored, no timing rule broken."""

import os
import random

import cocotb
from cocotb.triggers import RisingEdge

from emu_common import bit, planted, no_violations, open_emulator, run_emulator, start, wait_for

READS = int(os.environ.get("COSIM_TRANSACTIONS", "8"))


@cocotb.test()
async def reads_equal_the_emulators_positions(dut):
    f_hz = int(os.environ["F_SYS_HZ"])
    bits = int(dut.BITS.value)
    emu = open_emulator("ssi", f_hz)
    dut.i_start.value = 0
    dut.i_ssi_data.value = 1
    run_emulator(dut, emu, lambda: bit(dut.o_ssi_clk), lambda out: setattr(dut.i_ssi_data, "value", out & 1))
    await start(dut, f_hz)
    rng = random.Random(1)
    for n in range(READS):
        p = rng.getrandbits(bits)
        emu.set_position(0, p)
        dut.i_start.value = 1
        await RisingEdge(dut.i_clk)
        dut.i_start.value = 0
        await wait_for(dut, dut.o_done, 10_000_000, "o_done")
        assert emu.count() == n + 1
        assert emu.last_value(0) == p
        got = planted(int(dut.o_position.value))
        assert got == p, f"read {n}: core read {got}, the emulator sent {p}"
        while bit(dut.o_busy):
            await RisingEdge(dut.i_clk)
    no_violations(emu)
