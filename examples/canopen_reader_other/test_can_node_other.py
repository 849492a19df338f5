"""cocotb: mini_can (a CAN controller encoder-tb did not write) against the
CAN node emulator (node.toml, 125 kbit/s, one node 40 m away), stepped from
Python on every rising clock edge. As tb_can_node.v: frames the controller
sends arrive exactly at the node, frames the node sends (scheduled from
Python) arrive exactly at the controller, and when both want the bus at
once the lower identifier wins, the controller reporting `lost` exactly when
its identifier is the higher one; no CAN error on either side."""

import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge

from bench_common import level, open_emulator, planted, step_bus

CLKS_PER_BIT = 32


def random_frame(rng):
    n = rng.randrange(9)
    return rng.getrandbits(11), n, rng.getrandbits(8 * n) << (64 - 8 * n) if n else 0


def send_toml(ident, n, data):
    payload = list(data.to_bytes(8, "big")[:n])
    return f"[[send]]\nnode = 0\nid = {ident}\ndlc = {n}\ndata = {payload}\n"


class Bench:
    def __init__(self, dut):
        self.dut = dut
        self.emu, self.mon = open_emulator("can")
        self.received, self.sent, self.lost = [], 0, 0

    def watch(self):
        """What the controller reports, after each step of the bus."""
        dut = self.dut
        if not level(dut.rst_n):
            return
        assert not level(dut.fault) and not level(dut.tx_fail), f"the controller reported CAN error {int(dut.fault_kind.value)}"
        if level(dut.got):
            assert not level(dut.got_rtr)
            self.received.append((int(dut.got_id.value), int(dut.got_len.value), planted(int(dut.got_bytes.value))))
        self.sent += level(dut.sent)
        self.lost += level(dut.lost)

    async def clocks(self, n):
        for _ in range(n):
            await RisingEdge(self.dut.clk)

    async def until(self, cond, what):
        for _ in range(400 * CLKS_PER_BIT):
            if cond():
                await self.clocks(2 * CLKS_PER_BIT)  # the node counts a frame at its end
                return
            await RisingEdge(self.dut.clk)
        raise AssertionError(f"no {what} within 400 bits")

    async def request(self, ident, n, data):
        dut = self.dut
        while level(dut.busy):
            await RisingEdge(dut.clk)
        dut.send_id.value, dut.send_len.value, dut.send_bytes.value, dut.send.value = ident, n, data, 1
        await RisingEdge(dut.clk)
        dut.send.value = 0

    def node_got(self, frame):
        emu = self.emu
        got = (emu.last_value(16), emu.last_value(32), planted(emu.last_value(0)))
        assert got == frame, f"the controller sent {frame}, the node received {got}"


@cocotb.test()
async def frames_both_ways_and_arbitration(dut):
    bench = Bench(dut)
    for s, v in (("rst_n", 0), ("send", 0), ("send_id", 0), ("send_len", 0), ("send_bytes", 0), ("can_rxd", 1)):
        getattr(dut, s).value = v
    cocotb.start_soon(Clock(dut.clk, 250, units="ns").start())
    cocotb.start_soon(step_bus(dut, bench.emu, bench.mon, bench.watch))
    await bench.clocks(4)
    dut.rst_n.value = 1
    await bench.clocks(12 * CLKS_PER_BIT)  # bus integration: 11 recessive bits
    rng = random.Random(int(os.environ.get("SEED", "9")))
    reads = int(os.environ.get("TRANSACTIONS", "6"))
    wins = losses = 0
    for n in range(reads):
        rx, tx, lost = len(bench.received), bench.sent, bench.lost
        if n % 3 == 0:
            frame = random_frame(rng)
            await bench.request(*frame)
            await bench.until(lambda: bench.sent > tx, "frame sent")
            bench.node_got(frame)
        elif n % 3 == 1:
            frame = random_frame(rng)
            bench.emu.schedule_fault(send_toml(*frame))
            await bench.until(lambda: len(bench.received) > rx, "frame received")
            assert bench.received[rx] == frame, f"the node sent {frame}, the controller received {bench.received[rx]}"
        else:
            first, second, ours = random_frame(rng), random_frame(rng), random_frame(rng)
            if ours[0] == second[0]:
                ours = (ours[0] ^ 1,) + ours[1:]
            bench.emu.schedule_fault(send_toml(*first))
            bench.emu.schedule_fault(send_toml(*second))
            while level(dut.can_rxd):
                await RisingEdge(dut.clk)
            await bench.clocks(4 * CLKS_PER_BIT)  # past the first frame's SOF
            await bench.request(*ours)
            await bench.until(lambda: len(bench.received) >= rx + 2 and bench.sent > tx, "arbitration's frames")
            assert bench.received[rx:rx + 2] == [first, second], f"the node sent {first} and {second}, the controller received {bench.received[rx:]}"
            bench.node_got(ours)
            assert bench.lost - lost == (1 if ours[0] > second[0] else 0), f"identifiers {ours[0]:03x} (ours) and {second[0]:03x}: {bench.lost - lost} losses"
            wins, losses = (wins, losses + 1) if ours[0] > second[0] else (wins + 1, losses)
    v = bench.emu.violations() + bench.mon.violations()
    assert not v, "the node saw errors in the controller's frames:\n" + "\n".join(v)
    dut._log.info("%d transactions equal on both sides (%d arbitrations won, %d lost and resent)", reads, wins, losses)
