"""cocotb on GHDL: ssi_gray_reader (a VHDL master encoder-tb did not write)
against the SSI encoder emulator, driven from Python: encoder_emu.Emulator
(the library the HDL wrappers use, built into .venv by scripts/cocotb.sh) is
stepped on each rising clock edge with the reader's clock pin and drives its
data pin; a Monitor listens. Each read sets a random position; the reader's
value must equal what the emulator says it sent (`last_value`), and no
timing rule may be broken.

    make cocotb                       (in this directory: GHDL)
    COSIM_FLIP_BIT=3 make cocotb      (a planted misread: must fail)

Copy it with the Makefile next to your own VHDL master and change the pin
names below."""

import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge

import encoder_emu
# bit(): a pin as 0/1 (X or Z as the idle 1); planted(): the read with bit COSIM_FLIP_BIT
# flipped when that is set (a planted misread: the test must then fail). hdl/cocotb/.
from emu_common import bit, planted

F_HZ = 8_000_000                      # the reader's clock and the emulator's
BITS = 13                             # the reader's generic BITS (the Makefile's MASTER_PARAMS)
READS = int(os.environ.get("COSIM_TRANSACTIONS", "30"))


@cocotb.test()
async def reads_equal_what_the_emulator_sent(dut):
    path = os.environ["COSIM_CONFIG"]
    with open(path, encoding="utf-8") as f:
        text = f.read()
        emu = encoder_emu.Emulator("ssi", text, F_HZ, path)
        mon = encoder_emu.Monitor("ssi", text, F_HZ, path)
    cocotb.start_soon(Clock(dut.clk, round(1e12 / F_HZ), units="ps").start())
    dut.rst.value = 1
    dut.start.value = 0
    dut.ssi_data.value = 1

    async def wire():
        # Pins in: bit 0 the master's clock; out: bit 0 the data at its input.
        while True:
            await RisingEdge(dut.clk)
            mon.step(bit(dut.ssi_clk) | bit(dut.ssi_data) << 1)  # the clock, the data at the master
            dut.ssi_data.value = emu.step(bit(dut.ssi_clk)) & 1

    cocotb.start_soon(wire())
    for _ in range(3):
        await RisingEdge(dut.clk)
    dut.rst.value = 0
    rng = random.Random(7)
    for n in range(READS):
        p = rng.getrandbits(BITS)
        emu.set_position(0, p)
        dut.start.value = 1
        await RisingEdge(dut.clk)
        dut.start.value = 0
        for _ in range(100_000):
            await RisingEdge(dut.clk)
            if bit(dut.ready):
                break
        else:
            raise AssertionError(f"read {n}: no ready")
        got = planted(int(dut.position.value))
        assert emu.count() == n + 1, f"read {n}: the emulator answered {emu.count()} reads"
        assert got == emu.last_value(0) == p, f"read {n}: reader {got}, the emulator sent {emu.last_value(0)} (set {p})"
        while bit(dut.busy):
            await RisingEdge(dut.clk)
    assert mon.count() == READS, f"the monitor decoded {mon.count()} transactions on the line, expected {READS}"
    v = emu.violations() + mon.violations()
    assert not v, "the reader broke the seed's timing rules:\n" + "\n".join(v)
    dut._log.info("PASS ssi_gray_reader: %d reads equal to what the emulator sent", READS)
