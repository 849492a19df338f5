"""cocotb: ssi_reader (a master encoder-tb did not write) against the SSI
encoder emulator, driven from Python: encoder_emu.Emulator (the library the
HDL wrappers use, built into .venv by scripts/cocotb.sh) is stepped on each
rising clock edge with the reader's clock pin and drives its data pin. Each
read sets a random position; the reader's value must equal what the
emulator says it sent (`last_value`), and no timing rule may be broken.

    make cocotb                       (in this directory)
    COSIM_FLIP_BIT=3 make cocotb      (a planted misread: must fail)

Copy it with the Makefile next to your own master and change the pin names
below."""

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
READS = int(os.environ.get("COSIM_TRANSACTIONS", "100"))


@cocotb.test()
async def reads_equal_what_the_emulator_sent(dut):
    path = os.environ["COSIM_CONFIG"]
    with open(path, encoding="utf-8") as f:
        text = f.read()
        emu = encoder_emu.Emulator("ssi", text, F_HZ, path)
        mon = encoder_emu.Monitor("ssi", text, F_HZ, path)
    cocotb.start_soon(Clock(dut.clk, round(1e12 / F_HZ), units="ps").start())
    dut.reset_n.value = 0
    dut.read_req.value = 0
    dut.sdata.value = 1

    async def wire():
        # Pins in: bit 0 the master's clock; out: bit 0 the data at its input.
        while True:
            await RisingEdge(dut.clk)
            mon.step(bit(dut.sclk) | bit(dut.sdata) << 1)  # the clock, the data at the master
            dut.sdata.value = emu.step(bit(dut.sclk)) & 1

    cocotb.start_soon(wire())
    for _ in range(3):
        await RisingEdge(dut.clk)
    dut.reset_n.value = 1
    bits = int(dut.WIDTH.value)
    rng = random.Random(7)
    for n in range(READS):
        p = rng.getrandbits(bits)
        emu.set_position(0, p)
        dut.read_req.value = 1
        await RisingEdge(dut.clk)
        dut.read_req.value = 0
        for _ in range(100_000):
            await RisingEdge(dut.clk)
            if bit(dut.value_ok):
                break
        else:
            raise AssertionError(f"read {n}: no value_ok")
        got = planted(int(dut.value.value))
        assert emu.count() == n + 1, f"read {n}: the emulator answered {emu.count()} reads"
        assert got == emu.last_value(0) == p, f"read {n}: reader {got}, the emulator sent {emu.last_value(0)} (set {p})"
    assert mon.count() == READS, f"the monitor decoded {mon.count()} transactions on the line, expected {READS}"
    v = emu.violations() + mon.violations()
    assert not v, "the reader broke the seed's timing rules:\n" + "\n".join(v)
    dut._log.info("PASS ssi_reader: %d reads equal to what the emulator sent", READS)
