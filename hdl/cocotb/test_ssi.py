"""cocotb example: ssi_master against the SSI encoder emulator (seed 001,
SSI): random positions set from Python, each read compared with what the
emulator stored and with what the pin-level monitor (encoder_emu.Monitor("ssi"),
the library's ssi_monitor) decoded on the line, no timing rule broken (the
monitor fails the test at the first violation)."""

import os
import random

import cocotb
from cocotb.triggers import RisingEdge

from emu_common import (bit, monitor_agrees, planted, no_violations, open_emulator, open_monitor, run_emulator,
                        run_monitor, start, wait_for)

READS = int(os.environ.get("COSIM_TRANSACTIONS", "8"))


@cocotb.test()
async def reads_equal_the_emulators_positions(dut):
    f_hz = int(os.environ["F_SYS_HZ"])
    bits = int(dut.BITS.value)
    emu = open_emulator("ssi", f_hz)
    dut.i_start.value = 0
    dut.i_ssi_data.value = 1
    run_emulator(dut, emu, lambda: bit(dut.o_ssi_clk), lambda out: setattr(dut.i_ssi_data, "value", out & 1))
    # The monitor: bit 0 the master's clock, bit 1 the data at its input.
    mon = open_monitor("ssi", f_hz)
    run_monitor(dut, mon, lambda: bit(dut.o_ssi_clk) | bit(dut.i_ssi_data) << 1)
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
        monitor_agrees(mon, n + 1, got, error=False)
    no_violations(emu)
    assert not mon.violations()
