"""cocotb: canopen_reader (mini_can and its sequencer, a master encoder-tb
did not write) against the CANopen emulator (canopen.toml: a DS 406 encoder
at node 5 and a SAR58K24 in CAN mode at node 0x20), stepped from Python on
every rising clock edge. The same checks as tb_canopen_reader.v: boot-up,
SDO upload of 6004h, NMT start, then random positions read by SDO, by SYNC
and TPDO2, and by SAR58K24 clicks, each equal to what was set and what the
emulator sent; the SAR58K24 moved to a new node through 0x7E5 and a power
cycle."""

import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge

from bench_common import level, open_emulator, planted, step_bus

CLKS_PER_BIT = 16


class Bench:
    def __init__(self, dut):
        self.dut = dut
        self.emu, self.mon = open_emulator("canopen")

    async def clocks(self, n):
        for _ in range(n):
            await RisingEdge(self.dut.clk)

    async def op(self, op, arg=0):
        dut = self.dut
        while not level(dut.ready):
            await RisingEdge(dut.clk)
        dut.op.value, dut.arg.value, dut.go.value = op, arg, 1
        await RisingEdge(dut.clk)
        dut.go.value = 0
        for _ in range(60_000):
            await RisingEdge(dut.clk)
            assert not level(dut.failed), f"op {op} (arg {arg:04x}) failed"
            if level(dut.done):
                value = planted(int(dut.value.value))
                # the reader takes a frame at EOF bit 6, the emulator counts it at its end
                await self.clocks(2 * CLKS_PER_BIT)
                return value
        raise AssertionError(f"op {op}: no done")


@cocotb.test()
async def canopen_reader_reads_what_the_emulator_sent(dut):
    bench = Bench(dut)
    emu = bench.emu
    dut.rst_n.value, dut.go.value, dut.op.value, dut.arg.value, dut.can_rxd.value = 0, 0, 0, 0, 1
    cocotb.start_soon(Clock(dut.clk, 250, units="ns").start())
    cocotb.start_soon(step_bus(dut, emu, bench.mon))
    await bench.clocks(4)
    dut.rst_n.value = 1
    await bench.op(0)  # boot-up: 0x85, no data (seed 003 §2.2)
    assert (emu.last_value(32), emu.last_value(80)) == (127, 0x085)
    # seed 001 §3.4: the click 80 20 on 0x220 answers 47 26 = 9799 on 0x120
    assert await bench.op(4, 0x20) == 9799 and (emu.last_value(1 + 16 * 5), emu.last_value(1 + 16 * 4)) == (0x120, 0x4726 << 48)
    rng = random.Random(int(os.environ.get("SEED", "5")))
    reads = int(os.environ.get("TRANSACTIONS", "6"))
    sar_node, counts = 0x20, {"sdo": 0, "pdo": 0, "click": 0}
    for n in range(reads):
        if n == 1:
            await bench.op(1)  # NMT start 01 05
            assert emu.last_status(0, "operational")
        if n == reads // 2 and n > 0:
            new = rng.randrange(0x10, 0x80)
            new = new ^ 1 if new == sar_node else new
            await bench.op(5, 0x0401)
            assert await bench.op(5, 0x1100 | new) == 0x1100, "no 11 00 answer on 0x7E5"
            assert emu.last_value(1 + 16 * 6) == new
            emu.set_status(1, "power", False)
            await bench.clocks(20 * CLKS_PER_BIT)
            emu.set_status(1, "power", True)
            await bench.clocks(20 * CLKS_PER_BIT)
            assert emu.last_value(1 + 16 * 2) == new
            sar_node = new
        if n == 0 or n % 3 == 0:
            p = rng.getrandbits(25)
            emu.set_position(0, p)
            got = await bench.op(2)
            assert emu.last_value(16 * 5) == 0x585
            assert emu.last_value(16 * 4) == int.from_bytes(bytes([0x43, 0x04, 0x60, 0x00]) + p.to_bytes(4, "little"), "big")
            assert got == p, f"read {n}: SDO upload of 6004h gave {got}, position set {p}"
            counts["sdo"] += 1
        elif n % 3 == 1:
            p = rng.getrandbits(25)
            emu.set_position(0, p)
            got = await bench.op(3)
            assert got == p == emu.last_value(0), f"read {n}: TPDO2 gave {got}, set {p}, sent {emu.last_value(0)}"
            counts["pdo"] += 1
        else:
            p = rng.getrandbits(14)
            emu.set_position(1, p)
            got = await bench.op(4, sar_node)
            assert got == p == emu.last_value(1), f"read {n}: SAR58K24 click gave {got}, set {p}, sent {emu.last_value(1)}"
            counts["click"] += 1
    v = emu.violations() + bench.mon.violations()
    assert not v, "the emulator saw errors in the reader's frames:\n" + "\n".join(v)
    dut._log.info("%d reads equal to what the emulator sent: %s; SAR58K24 at node 0x%02x", reads, counts, sar_node)
