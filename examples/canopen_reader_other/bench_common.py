"""What both cocotb tests of this example share: reading a pin, the planted
misread (FLIP_BIT=k flips bit k of every value read), the emulator and its
pin-level monitor from EMU_CONFIG, and their stepping on every rising clock
edge."""

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
    """The emulator `kind` and its monitor, on the same configuration."""
    path = os.environ["EMU_CONFIG"]
    with open(path, encoding="utf-8") as f:
        text = f.read()
    return encoder_emu.Emulator(kind, text, F_HZ, path), encoder_emu.Monitor(kind, text, F_HZ, path)


async def step_bus(dut, emu, mon, each=None):
    """The emulator on the bus: the master's TXD in (bit 1, the other bits as
    the HDL wrapper ties them), the bus level out to its RXD; the monitor
    watching RXD (bit 0) and TXD (bit 1); `each()` after every step."""
    while True:
        await RisingEdge(dut.clk)
        mon.step(level(dut.can_rxd) | level(dut.can_txd) << 1)
        dut.can_rxd.value = emu.step(0b1001 | level(dut.can_txd) << 1) & 1
        if each:
            each()
