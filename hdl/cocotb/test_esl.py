"""cocotb example: esl_host against the ESL encoder emulator (seed 000):
random 40-bit positions and ALM flags set from Python, safety readouts
(Data ID 1) compared with what the emulator sent, one answer with a data bit
flipped by the emulator that the host must flag as a channel-1 CRC error, no
timing rule broken (turnaround, character timing, request spacing)."""

import os
import random

import cocotb

from emu_common import connect_rs485, idle, planted, no_violations, open_emulator, readout, start

READS = int(os.environ.get("COSIM_TRANSACTIONS", "8"))
ERRORS = ("o_err_crc1", "o_err_crc2", "o_err_timeout", "o_err_frame", "o_err_cf",
          "o_err_comm", "o_err_seq", "o_err_rs", "o_err_busy")
# ALM bits (Table 7); LED and LIS share bit 2 (LED is set here).
FLAGS = ("xc", "mt", "led", "overspeed", "mem", "st", "uv", "ov")


@cocotb.test()
async def readouts_equal_the_emulators_positions(dut):
    f_hz = int(os.environ["F_SYS_HZ"])
    emu = open_emulator("esl", f_hz)
    for name in ("i_start", "i_broadcast", "i_mem_address", "i_wdata"):
        getattr(dut, name).value = 0
    dut.i_address.value = int(os.environ.get("COSIM_ADDRESS", "0"))
    dut.i_data_id.value = 1
    connect_rs485(dut, emu)
    await start(dut, f_hz)
    rng = random.Random(3)
    for n in range(READS):
        st, mt, alm = rng.getrandbits(24), rng.getrandbits(16), rng.getrandbits(8)
        emu.set_position(0, mt << 24 | st)
        for b, name in enumerate(FLAGS):
            emu.set_status(0, name, bool(alm >> b & 1))
        # ABS1 (field 4) flipped in the middle readout.
        if await readout(dut, emu, n, n == READS // 2, ERRORS, "o_err_crc1"):
            assert emu.last_value(0) == mt << 24 | st
            got = planted(int(dut.o_abs.value))
            assert got == st, f"readout {n}: host read ABS {got:#x}, the emulator sent {st:#x}"
            assert int(dut.o_abm.value) == mt, f"readout {n}: ABM {int(dut.o_abm.value):#x}, sent {mt:#x}"
            assert int(dut.o_alm1.value) == alm and int(dut.o_alm2.value) == alm
            assert emu.last_status(0, "uv") == bool(alm >> 6 & 1)
        await idle(dut, 32)
    no_violations(emu)
