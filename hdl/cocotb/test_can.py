"""cocotb example: can_controller on a wired-AND bus with emulated CAN nodes:
frames the core sends are received exactly by node 0, frames a node sends
(scripted from Python) are received exactly by the core; no node detects
an error. The pin-level monitor (encoder_emu.Monitor("can", ...)) watches
TXD and RXD: after each frame it has decoded exactly that frame, sent by
the core or by the node, and the core breaks none of the CAN rules it
checks."""

import os
import random

import cocotb
from cocotb.triggers import RisingEdge

from emu_common import bit, monitor_agrees, no_violations, open_emulator, open_monitor, run_emulator, run_monitor, start

FRAMES = int(os.environ.get("COSIM_TRANSACTIONS", "4"))


@cocotb.test()
async def frames_cross_the_bus_both_ways(dut):
    f_hz = int(os.environ["F_SYS_HZ"])
    emu = open_emulator("can", f_hz)
    nodes = int(os.environ.get("COSIM_NODES", "1"))
    for s, v in (("i_tx_start", 0), ("i_tx_id", 0), ("i_tx_rtr", 0), ("i_tx_dlc", 0), ("i_tx_data", 0),
                 ("i_filter_id", 0), ("i_filter_mask", 0), ("i_can_rx", 1)):
        getattr(dut, s).value = v
    run_emulator(dut, emu, lambda: bit(dut.o_can_tx) << 1, lambda out: setattr(dut.i_can_rx, "value", out & 1))
    mon = open_monitor("can", f_hz)
    run_monitor(dut, mon, lambda: bit(dut.i_can_rx) | bit(dut.o_can_tx) << 1)
    await start(dut, f_hz)
    bit_clocks = int(dut.BRP.value) * (1 + int(dut.PROP_SEG.value) + int(dut.PHASE_SEG1.value) + int(dut.PHASE_SEG2.value))
    for _ in range(20 * bit_clocks):
        await RisingEdge(dut.i_clk)
    rng = random.Random(3)
    for n in range(FRAMES):
        ident, data = rng.getrandbits(11), rng.getrandbits(64)
        if n % 2 == 0:
            dut.i_tx_id.value, dut.i_tx_dlc.value, dut.i_tx_data.value = ident, 8, data
            dut.i_tx_start.value = 1
            await RisingEdge(dut.i_clk)
            dut.i_tx_start.value = 0
            done = "o_tx_done"
        else:
            emu.schedule_fault(f"[[send]]\nnode = {nodes - 1}\nid = {ident}\ndlc = 8\ndata = {list(data.to_bytes(8, 'big'))}\n")
            done = "o_rx_valid"
        for _ in range(300 * bit_clocks):
            await RisingEdge(dut.i_clk)
            for e in ("o_err_bit", "o_err_stuff", "o_err_crc", "o_err_form", "o_err_ack"):
                assert not bit(getattr(dut, e)), f"frame {n}: {e}"
            if bit(getattr(dut, done)):
                break
        else:
            raise AssertionError(f"frame {n}: no {done}")
        if n % 2 == 0:
            for _ in range(2):
                await RisingEdge(dut.i_clk)
            assert (emu.last_value(16), emu.last_value(0)) == (ident, data), f"frame {n}: node 0 received {emu.last_value(16):x} {emu.last_value(0):x}"
        else:
            assert (int(dut.o_rx_id.value), int(dut.o_rx_data.value)) == (ident, data)
        for _ in range(12 * bit_clocks):
            await RisingEdge(dut.i_clk)
        monitor_agrees(mon, n + 1, data, master=(n % 2 == 0), error=False)
        assert mon.last_value(1) == ident, f"frame {n}: the monitor decoded identifier {mon.last_value(1):x}"
    no_violations(emu)
    assert not mon.violations(), "\n".join(mon.violations())
