"""cocotb example: biss_master against the BiSS-C slave emulator (seed 001,
BiSS-C): random positions, error and warning bits set from Python, each
frame's o_data, o_error and o_warning compared with what the slave sent."""

import os
import random

import cocotb
from cocotb.triggers import RisingEdge

from emu_common import bit, no_violations, open_emulator, run_emulator, start

FRAMES = int(os.environ.get("COSIM_TRANSACTIONS", "4"))
ERRORS = ("o_err_line", "o_err_ack", "o_err_delay", "o_err_start", "o_err_timeout", "o_err_drift")


@cocotb.test()
async def frames_equal_what_the_slave_sent(dut):
    f_hz = int(os.environ["F_SYS_HZ"])
    bits = int(dut.SLAVE_BITS.value) & 255
    emu = open_emulator("biss", f_hz)
    for s in ("i_start", "i_reg_start", "i_reg_write", "i_reg_id", "i_reg_addr", "i_reg_wdata", "i_cmd_start", "i_cmd_ids", "i_cmd_code"):
        getattr(dut, s).value = 0
    dut.i_slo.value = 1
    run_emulator(dut, emu, lambda: bit(dut.o_ma), lambda out: setattr(dut.i_slo, "value", out & 1))
    await start(dut, f_hz)
    rng = random.Random(2)
    for n in range(FRAMES):
        p, e, w = rng.getrandbits(bits), rng.random() < 0.3, rng.random() < 0.3
        emu.set_position(0, p)
        emu.set_status(0, "error", e)
        emu.set_status(0, "warning", w)
        dut.i_start.value = 1
        await RisingEdge(dut.i_clk)
        dut.i_start.value = 0
        got = None
        for _ in range(1_000_000):
            await RisingEdge(dut.i_clk)
            if bit(dut.o_slave_valid):
                got = (int(dut.o_data.value) & ((1 << bits) - 1), bit(dut.o_error), bit(dut.o_warning), bit(dut.o_crc_err))
            assert not any(bit(getattr(dut, x)) for x in ERRORS), f"frame {n}: an error pulse"
            if bit(dut.o_done):
                break
        else:
            raise AssertionError(f"frame {n}: no o_done")
        assert emu.count() == n + 1 and emu.last_value(0) == p
        assert got == (p, int(e), int(w), 0), f"frame {n}: core read {got}, the slave sent {(p, e, w)}"
        while bit(dut.o_busy):
            await RisingEdge(dut.i_clk)
    no_violations(emu)
