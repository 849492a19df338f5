"""cocotb: endat_reader (a master encoder-tb did not write) against the EnDat
encoder emulator, driven from Python: encoder_emu.Emulator (the library the
HDL wrappers use, built into .venv by scripts/cocotb.sh) is stepped on each
rising clock edge with the reader's clock, data and driver-enable pins and
drives its receiver input. Each read sets a random position and F1; what
the reader took must equal what the emulator says it latched and sent
(`last_value`, `last_status`), with a good CRC, and no timing rule may be
broken (t_b, t_m, the send block, both drivers on).

    make cocotb                       (in this directory)
    COSIM_FLIP_BIT=3 make cocotb      (a planted misread: must fail)"""

import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge

import encoder_emu
# bit(): a pin as 0/1 (X or Z as the idle 1); planted(): the read with bit COSIM_FLIP_BIT
# flipped when that is set (a planted misread: the test must then fail). hdl/cocotb/.
from emu_common import bit, planted

F_HZ = 4_000_000                      # the reader's clock and the emulator's
READS = int(os.environ.get("COSIM_TRANSACTIONS", "20"))


@cocotb.test()
async def reads_equal_what_the_emulator_sent(dut):
    path = os.environ["COSIM_CONFIG"]
    with open(path, encoding="utf-8") as f:
        text = f.read()
        emu = encoder_emu.Emulator("endat", text, F_HZ, path)
        mon = encoder_emu.Monitor("endat", text, F_HZ, path)
    cocotb.start_soon(Clock(dut.clk, round(1e12 / F_HZ), units="ps").start())
    dut.arst_n.value = 0
    dut.trig.value = 0
    dut.din.value = 1

    async def wire():
        # Pins in: bit 0 the clock, bit 1 the master's data (D), bit 2 its driver enable (DE);
        # out: bit 0 the line at the master's receiver (R).
        while True:
            await RisingEdge(dut.clk)
            mon.step(bit(dut.ck) | bit(dut.dout) << 1 | bit(dut.dout_en) << 2 | bit(dut.din) << 3)  # the clock, D, DE, R
            dut.din.value = emu.step(bit(dut.ck) | bit(dut.dout) << 1 | bit(dut.dout_en) << 2) & 1

    cocotb.start_soon(wire())
    for _ in range(3):
        await RisingEdge(dut.clk)
    dut.arst_n.value = 1
    bits = int(dut.POS_BITS.value)
    rng = random.Random(13)
    for n in range(READS):
        p, f1 = rng.getrandbits(bits), rng.random() < 0.5
        emu.set_position(0, p)
        emu.set_status(0, "f1", f1)
        while not bit(dut.ready):
            await RisingEdge(dut.clk)
        dut.trig.value = 1
        await RisingEdge(dut.clk)
        dut.trig.value = 0
        for _ in range(10_000):
            await RisingEdge(dut.clk)
            if bit(dut.got) or bit(dut.no_start):
                break
        else:
            raise AssertionError(f"read {n}: neither got nor no_start")
        assert not bit(dut.no_start), f"read {n}: the reader found no start bit"
        got = planted(int(dut.pos_out.value))
        assert emu.count() == n + 1, f"read {n}: the emulator answered {emu.count()} transfers"
        assert got == emu.last_value(0) == p, f"read {n}: reader {got:#x}, the emulator sent {emu.last_value(0):#x} (set {p:#x})"
        assert bit(dut.crc_ok) == 1, f"read {n}: the reader's CRC check failed"
        assert bit(dut.err1_out) == f1 == emu.last_status(0, "f1"), f"read {n}: reader F1 {bit(dut.err1_out)}, set {f1}"
        await RisingEdge(dut.clk)
    assert mon.count() == READS, f"the monitor decoded {mon.count()} transactions on the line, expected {READS}"
    v = emu.violations() + mon.violations()
    assert not v, "the reader broke the seed's timing rules:\n" + "\n".join(v)
    dut._log.info("PASS endat_reader: %d reads equal to what the emulator sent", READS)
