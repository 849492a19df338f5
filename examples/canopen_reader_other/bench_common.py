"""What both cocotb tests of this example share: reading a pin, the planted
misread (FLIP_BIT=k flips bit k of every value read), the emulator from
EMU_CONFIG, and its stepping on every rising clock edge."""

import os

from cocotb.triggers import RisingEdge

import encoder_emu

F_HZ = 4_000_000
FLIP = int(os.environ.get("FLIP_BIT", "-1"))


def level(signal):
    v = signal.value
    return int(v) if v.is_resolvable else 1


def planted(value):
    return value if FLIP < 0 else value ^ (1 << FLIP)


def open_emulator(kind):
    path = os.environ["EMU_CONFIG"]
    with open(path, encoding="utf-8") as f:
        return encoder_emu.Emulator(kind, f.read(), F_HZ, path)


async def step_bus(dut, emu, each=None):
    """The emulator on the bus: the master's TXD in (bit 1, the other bits as
    the HDL wrapper ties them), the bus level out to its RXD; `each()` after
    every step."""
    while True:
        await RisingEdge(dut.clk)
        dut.can_rxd.value = emu.step(0b1001 | level(dut.can_txd) << 1) & 1
        if each:
            each()
