"""cocotb: biss_reader (a master encoder-tb did not write) against the BiSS-C
slave emulator, driven from Python: encoder_emu.Emulator (the library the
HDL wrappers use, built into .venv by scripts/cocotb.sh) is stepped on each
rising clock edge with the reader's MA and drives its SLO. Each frame sets a
random position and random error and warning bits; what the reader took
must equal what the emulator says it sent (`last_value`), with a good CRC,
and no timing rule may be broken.

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

F_HZ = 40_000_000                     # the reader's clock and the emulator's
READS = int(os.environ.get("COSIM_TRANSACTIONS", "100"))


@cocotb.test()
async def frames_equal_what_the_emulator_sent(dut):
    path = os.environ["COSIM_CONFIG"]
    with open(path, encoding="utf-8") as f:
        text = f.read()
        emu = encoder_emu.Emulator("biss", text, F_HZ, path)
        mon = encoder_emu.Monitor("biss", text, F_HZ, path)
    cocotb.start_soon(Clock(dut.clk, round(1e12 / F_HZ), units="ps").start())
    dut.reset_n.value = 0
    dut.go.value = 0
    dut.slo.value = 1

    async def wire():
        # Pins in: bit 0 MA; out: bit 0 SLO at the master.
        while True:
            await RisingEdge(dut.clk)
            mon.step(bit(dut.ma) | bit(dut.slo) << 1)  # MA, SLO at the master
            dut.slo.value = emu.step(bit(dut.ma)) & 1

    cocotb.start_soon(wire())
    for _ in range(3):
        await RisingEdge(dut.clk)
    dut.reset_n.value = 1
    bits = int(dut.DATA_BITS.value)
    rng = random.Random(11)
    for n in range(READS):
        p, error, warning = rng.getrandbits(bits), rng.random() < 0.5, rng.random() < 0.5
        emu.set_position(0, p)
        emu.set_status(0, "error", error)
        emu.set_status(0, "warning", warning)
        dut.go.value = 1
        await RisingEdge(dut.clk)
        dut.go.value = 0
        await RisingEdge(dut.clk)
        for _ in range(100_000):
            await RisingEdge(dut.clk)
            if bit(dut.ready):
                break
        else:
            raise AssertionError(f"frame {n}: no ready")
        got = planted(int(dut.pos.value))
        assert emu.count() == n + 1, f"frame {n}: the emulator answered {emu.count()} frames"
        assert got == emu.last_value(0) == p, f"frame {n}: reader {got}, the emulator sent {emu.last_value(0)} (set {p})"
        assert bit(dut.crc_good) == 1, f"frame {n}: the reader's CRC check failed"
        assert bit(dut.n_error) == (not error) and bit(dut.n_warning) == (not warning), \
            f"frame {n}: nE {bit(dut.n_error)} nW {bit(dut.n_warning)}, the emulator sent error {error} warning {warning}"
    assert mon.count() == READS, f"the monitor decoded {mon.count()} transactions on the line, expected {READS}"
    v = emu.violations() + mon.violations()
    assert not v, "the reader broke the seed's timing rules:\n" + "\n".join(v)
    dut._log.info("PASS biss_reader: %d frames equal to what the emulator sent", READS)
