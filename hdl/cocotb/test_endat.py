"""cocotb example: endat_master against the EnDat 2.2 encoder emulator
(seed 004): random positions and F1/F2 set from Python, "send position
values" 2.2; each read compared with what the emulator latched, one frame
bit flipped by the emulator that the core must flag as a CRC error, no
timing rule broken."""

import os
import random

import cocotb
from cocotb.triggers import RisingEdge

from emu_common import bit, idle, planted, no_violations, open_emulator, request, run_emulator, start

READS = int(os.environ.get("COSIM_TRANSACTIONS", "8"))
ERRORS = ("o_err_crc", "o_err_timeout", "o_err_type2", "o_err_absent", "o_err_idle", "o_err_delay")


@cocotb.test()
async def reads_equal_the_emulators_positions(dut):
    f_hz = int(os.environ["F_SYS_HZ"])
    bits = int(dut.POS_BITS.value)
    emu = open_emulator("endat", f_hz)
    for name in ("i_start", "i_meas", "i_mrs", "i_param", "i_cont_values"):
        getattr(dut, name).value = 0
    dut.i_mode.value = 0b111000
    dut.i_endat_data_in.value = 1
    # Pins in: bit 0 the clock, bit 1 the master's data, bit 2 its driver enable.
    run_emulator(
        dut,
        emu,
        lambda: bit(dut.o_endat_clk) | bit(dut.o_endat_data_out) << 1 | bit(dut.o_endat_data_oe) << 2,
        lambda out: setattr(dut.i_endat_data_in, "value", out & 1),
    )
    await start(dut, f_hz)
    while bit(dut.o_busy):
        await RisingEdge(dut.i_clk)
    base = emu.count()
    rng = random.Random(4)
    for n in range(READS):
        p, f1, f2 = rng.getrandbits(bits), rng.random() < 0.5, rng.random() < 0.5
        emu.set_position(0, p)
        emu.set_status(0, "f1", f1)
        emu.set_status(0, "f2", f2)
        flip = n == READS // 2
        if flip:
            emu.schedule_fault(f"[faults]\nflips = [{{ request = {emu.count()}, bits = [3] }}]")
        seen = await request(dut, ERRORS, 200_000, f"read {n}")
        assert emu.count() == base + n + 1
        if flip:
            assert seen == ["o_err_crc"], f"read {n}: a flipped frame bit gave {seen}"
        else:
            assert not seen, f"read {n}: error pulses {seen}"
            assert emu.last_value(0) == p
            got = planted(int(dut.o_position.value) & ((1 << bits) - 1))
            assert got == p, f"read {n}: core read {got:#x}, the emulator sent {p:#x}"
            assert bit(dut.o_f1) == f1 and emu.last_status(0, "f1") == f1
        await idle(dut, 0)
    no_violations(emu)
