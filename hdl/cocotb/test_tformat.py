"""cocotb example: tformat_host against the T-format encoder emulator
(seed 002): random positions and ALMC flags set from Python, Data ID 3
readouts compared with what the emulator sent, one answer with a data bit
flipped by the emulator that the host must flag as a CRC error, no timing
rule broken."""

import os
import random

import cocotb

from emu_common import connect_rs485, idle, planted, no_violations, open_emulator, readout, start

READS = int(os.environ.get("COSIM_TRANSACTIONS", "8"))
ERRORS = ("o_err_crc", "o_err_timeout", "o_err_frame", "o_err_cf", "o_err_comm")
FLAGS = ("over_speed", "full_absolute", "counting_error", "counter_overflow", None,
         "multi_turn_error", "battery_error", "battery_alarm")


@cocotb.test()
async def readouts_equal_the_emulators_positions(dut):
    f_hz = int(os.environ["F_SYS_HZ"])
    emu = open_emulator("tformat", f_hz)
    for name in ("i_start", "i_address", "i_wdata"):
        getattr(dut, name).value = 0
    dut.i_data_id.value = 3
    connect_rs485(dut, emu)
    await start(dut, f_hz)
    rng = random.Random(2)
    for n in range(READS):
        st, mt, almc = rng.getrandbits(17), rng.getrandbits(16), rng.getrandbits(8) & 0xEF
        emu.set_position(0, mt << 17 | st)
        for b, name in enumerate(FLAGS):
            if name:
                emu.set_status(0, name, bool(almc >> b & 1))
        # ABS1 (field 4) flipped in the middle readout.
        if await readout(dut, emu, n, n == READS // 2, ERRORS, "o_err_crc"):
            assert emu.last_value(0) == mt << 17 | st
            got = planted(int(dut.o_abs.value))
            assert got == st, f"readout {n}: host read ABS {got:#x}, the emulator sent {st:#x}"
            assert int(dut.o_abm.value) == mt and int(dut.o_almc.value) == almc
        await idle(dut, 32)
    no_violations(emu)
