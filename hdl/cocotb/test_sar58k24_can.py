"""cocotb example: the SAR58K24 in its CAN mode (seed 001 §3.4) read by our
can_controller, the command sequence in Python: click (the first answers the
manual's example 47 26 = 9799), zero, direction, start and its stop, timed
send and its stop, the 0x7E5 configuration channel (enter, node, bit rate)
and a power cycle, then random clicks. Every frame the SAR58K24 sends must
reach the core exactly as the emulator sent it, and each position must equal
the test's own prediction from the raw position, the zero and the direction."""

import os
import random

import cocotb
from cocotb.triggers import RisingEdge

from emu_common import bit, no_violations, open_emulator, planted, run_emulator, start

COMMANDS = int(os.environ.get("COSIM_TRANSACTIONS", "8"))
CONFIG_ID = 0x7E5


class Sar:
    """The command sequencer on can_controller and what it expects."""

    def __init__(self, dut, emu):
        self.dut, self.emu = dut, emu
        self.dev = int(os.environ.get("COSIM_SAR_DEVICE", "0"))
        self.node = int(os.environ.get("COSIM_SAR_NODE", "32"))
        self.bits = int(os.environ.get("COSIM_SAR_BITS", "14"))
        self.base = int(os.environ.get("COSIM_SAR_ANSWER_BASE", "256"))
        self.cycle_ms = int(os.environ.get("COSIM_SAR_CYCLE_MS", "2"))
        self.rate_code = int(os.environ.get("COSIM_SAR_RATE_CODE", "3"))
        self.f_hz = int(os.environ["F_SYS_HZ"])
        self.bit_clocks = int(dut.BRP.value) * (1 + int(dut.PROP_SEG.value) + int(dut.PHASE_SEG1.value) + int(dut.PHASE_SEG2.value))
        self.raw, self.zero, self.reverse = 0, 0, False
        self.frames, self.heard = [], 0

    def answer_id(self):
        return self.base + self.node

    def expected(self):
        mask = (1 << self.bits) - 1
        q = (self.raw - self.zero) & mask
        return (-q) & mask if self.reverse else q

    def set_raw(self, raw):
        self.raw = raw
        self.emu.set_position(self.dev, raw)

    async def collect(self):
        """Every frame on the SAR58K24's identifiers the core received."""
        while True:
            await RisingEdge(self.dut.i_clk)
            for e in ("o_err_bit", "o_err_stuff", "o_err_crc", "o_err_form", "o_err_ack"):
                assert not bit(getattr(self.dut, e)), f"the controller flagged {e}"
            if bit(self.dut.o_rx_valid):
                ident = int(self.dut.o_rx_id.value)
                if ident in (self.answer_id(), CONFIG_ID):
                    self.frames.append((ident, int(self.dut.o_rx_data.value)))

    async def send(self, ident, d0, d1, d2=0):
        dut = self.dut
        while bit(dut.o_tx_busy):
            await RisingEdge(dut.i_clk)
        dut.i_tx_id.value, dut.i_tx_dlc.value = ident, 8
        dut.i_tx_data.value = d0 << 56 | d1 << 48 | d2 << 40
        dut.i_tx_start.value = 1
        await RisingEdge(dut.i_clk)
        dut.i_tx_start.value = 0
        for _ in range(400 * self.bit_clocks):
            await RisingEdge(dut.i_clk)
            if bit(dut.o_tx_done):
                return
        raise AssertionError(f"the command {ident:03x} {d0:02x} {d1:02x} {d2:02x} was not sent")

    async def frame(self, limit=None):
        """The next frame from the SAR58K24, checked against what the emulator sent."""
        limit = limit or 400 * self.bit_clocks
        for _ in range(limit):
            if self.frames:
                break
            await RisingEdge(self.dut.i_clk)
        else:
            raise AssertionError(f"no answer within {limit} cycles")
        ident, data = self.frames.pop(0)
        self.heard += 1
        # The core takes the frame at EOF bit 6; the emulated node counts it sent at its end.
        for _ in range(3 * self.bit_clocks):
            await RisingEdge(self.dut.i_clk)
        data = planted(data)
        sent = (self.emu.last_value(self.dev + 16 * 5), self.emu.last_value(self.dev + 16 * 4))
        assert (ident, data) == sent, f"the SAR58K24 sent {sent[0]:03x} [{sent[1]:016x}]; core read {ident:03x} [{data:016x}]"
        assert self.emu.last_value(self.dev + 16) == self.heard, "a frame of the SAR58K24 did not reach the core"
        return ident, data

    async def position(self, limit=None):
        ident, data = await self.frame(limit)
        p = self.expected()
        want = int.from_bytes(p.to_bytes(4, "little") + bytes(4), "big")
        assert (ident, data) == (self.answer_id(), want), f"expected position {p}; core read {ident:03x} [{data:016x}]"
        assert self.emu.last_value(self.dev) == p
        return p

    async def ack(self, code, ident=None):
        got = await self.frame()
        assert got == (ident or self.answer_id(), code << 56), f"expected the acknowledgement {code:02x} 00; got {got[0]:03x} [{got[1]:016x}]"

    async def stop(self, tt):
        if self.expected() == 0x31:
            self.set_raw((self.raw + 1) % (1 << self.bits))
        await self.send(0x200 + self.node, 0x31, self.node, tt)
        for _ in range(400 * self.bit_clocks):
            if self.frames:
                break
            await RisingEdge(self.dut.i_clk)
        if self.frames and self.frames[0][1] != 0x31 << 56:
            await self.position()
        await self.ack(0x31)
        assert not self.emu.last_status(self.dev, "sending")


@cocotb.test()
async def sar58k24_can_commands_and_answers(dut):
    f_hz = int(os.environ["F_SYS_HZ"])
    emu = open_emulator("sar58k24_can", f_hz)
    for s, v in (("i_tx_start", 0), ("i_tx_id", 0), ("i_tx_rtr", 0), ("i_tx_dlc", 8), ("i_tx_data", 0),
                 ("i_filter_id", 0), ("i_filter_mask", 0), ("i_can_rx", 1)):
        getattr(dut, s).value = v
    run_emulator(dut, emu, lambda: bit(dut.o_can_tx) << 1, lambda out: setattr(dut.i_can_rx, "value", out & 1))
    await start(dut, f_hz)
    sar = Sar(dut, emu)
    cocotb.start_soon(sar.collect())
    for _ in range(200 * sar.bit_clocks):
        await RisingEdge(dut.i_clk)
    rng = random.Random(5)
    mask = (1 << sar.bits) - 1
    nn = lambda: sar.node  # noqa: E731
    # Seed 001 §3.4 (5): the configured raw position 9799 answers 47 26 on 0x120.
    sar.raw = 9799  # raw_position of the configuration
    await sar.send(0x200 + nn(), 0x80, nn())
    assert await sar.position() == 9799 and sar.frames == [] and (0x120, 0x4726 << 48) == (sar.answer_id(), emu.last_value(sar.dev + 64))
    for n in range(1, COMMANDS):
        sar.set_raw(rng.getrandbits(sar.bits))
        kind = n if n < 7 else 0
        if kind == 1:  # zero (⑥)
            await sar.send(0x200 + nn(), 0x20, nn())
            await sar.ack(0x20)
            sar.zero = sar.raw
        elif kind == 2:  # direction (④ ⑤: the toggle reading)
            await sar.send(0x200 + nn(), 0x22, nn())
            await sar.ack(0x22)
            sar.reverse = not sar.reverse
        elif kind == 3:  # start (①): at once and every cycle, then stopped
            await sar.send(0x200 + nn(), 0x01, nn())
            await sar.position()
            sar.set_raw(rng.getrandbits(sar.bits))
            await sar.position(sar.cycle_ms * f_hz // 1000 + 400 * sar.bit_clocks)
            await sar.stop(250)
        elif kind == 4:  # timed send TT times a second (⑦) and its stop (⑧)
            await sar.send(0x200 + nn(), 0x31, nn(), 250)
            await sar.ack(0x31)
            await sar.position(f_hz // 250 + 400 * sar.bit_clocks)
            await sar.stop(250)
        elif kind == 5:  # configuration channel (② ③) and a power cycle
            await sar.send(CONFIG_ID, 0x04, 0x01)
            for _ in range(3 * sar.bit_clocks):
                await RisingEdge(dut.i_clk)
            assert emu.last_status(sar.dev, "config_mode") and not sar.frames
            new = rng.randrange(0x10, 0x80)
            await sar.send(CONFIG_ID, 0x11, new)
            await sar.ack(0x11, CONFIG_ID)
            await sar.send(CONFIG_ID, 0x13, 0x00, 0x02)
            await sar.ack(0x13, CONFIG_ID)
            assert (emu.last_value(sar.dev + 96), emu.last_value(sar.dev + 112)) == (new, 500)
            await sar.send(CONFIG_ID, 0x13, 0x00, sar.rate_code)
            await sar.ack(0x13, CONFIG_ID)
            emu.set_status(sar.dev, "power", False)
            for _ in range(20 * sar.bit_clocks):
                await RisingEdge(dut.i_clk)
            emu.set_status(sar.dev, "power", True)
            for _ in range(20 * sar.bit_clocks):
                await RisingEdge(dut.i_clk)
            assert emu.last_value(sar.dev + 32) == new
            sar.node = new
        else:  # click (①)
            await sar.send(0x200 + nn(), 0x80, nn())
            await sar.position()
        assert not sar.frames, f"command {n}: an extra frame {sar.frames}"
        assert emu.last_value(sar.dev) is None or emu.last_value(sar.dev) <= mask
    no_violations(emu)
