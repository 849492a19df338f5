"""cocotb example: endat_master against the EnDat 2.2 encoder emulator
(seed 004): random positions and F1/F2 set from Python, "send position
values" 2.2; each read compared with what the emulator latched and with what
the pin-level monitor (encoder_emu.Monitor("endat"), the library's
endat_monitor) decoded on the line, one frame bit flipped by the emulator
that the core must flag as a CRC error (and the monitor sees it too), no
timing rule broken: the monitor fails the test at the first violation.

The second test proves that it does: the monitor is told the encoder's
recovery time I is 40 us (the core waits 30.5 us after a type 2.2 frame), so
the second read breaks t_m and the test must fail (expect_fail) with the
monitor's t_m report, and with nothing else."""

import os
import random

import cocotb
from cocotb.triggers import RisingEdge

from emu_common import (bit, idle, monitor_agrees, no_violations, open_emulator, open_monitor, planted, request,
                        run_emulator, run_monitor, start)

READS = int(os.environ.get("COSIM_TRANSACTIONS", "8"))
ERRORS = ("o_err_crc", "o_err_timeout", "o_err_type2", "o_err_absent", "o_err_idle", "o_err_delay")


def endat_pins(dut):
    """The master's pins: bit 0 the clock, bit 1 its data, bit 2 its driver enable, bit 3 the data at its receiver."""
    return (bit(dut.o_endat_clk) | bit(dut.o_endat_data_out) << 1 | bit(dut.o_endat_data_oe) << 2
            | bit(dut.i_endat_data_in) << 3)


async def connect(dut, f_hz, monitor_extra="", fail_on_violation=True):
    """The core with the emulator and the monitor on its clock, out of reset and power-on measurement."""
    emu = open_emulator("endat", f_hz)
    mon = open_monitor("endat", f_hz, monitor_extra)
    for name in ("i_start", "i_meas", "i_mrs", "i_param", "i_cont_values"):
        getattr(dut, name).value = 0
    dut.i_mode.value = 0b111000
    dut.i_endat_data_in.value = 1
    # Emulator pins in: bit 0 the clock, bit 1 the master's data, bit 2 its driver enable.
    run_emulator(dut, emu, lambda: endat_pins(dut) & 7, lambda out: setattr(dut.i_endat_data_in, "value", out & 1))
    run_monitor(dut, mon, lambda: endat_pins(dut), fail_on_violation)
    await start(dut, f_hz)
    while bit(dut.o_busy):
        await RisingEdge(dut.i_clk)
    return emu, mon


@cocotb.test()
async def reads_equal_the_emulators_positions(dut):
    f_hz = int(os.environ["F_SYS_HZ"])
    bits = int(dut.POS_BITS.value)
    emu, mon = await connect(dut, f_hz)
    base, mbase = emu.count(), mon.count()
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
            await idle(dut, 0)
            monitor_agrees(mon, mbase + n + 1, crc_ok=False)
        else:
            assert not seen, f"read {n}: error pulses {seen}"
            assert emu.last_value(0) == p
            got = planted(int(dut.o_position.value) & ((1 << bits) - 1))
            assert got == p, f"read {n}: core read {got:#x}, the emulator sent {p:#x}"
            assert bit(dut.o_f1) == f1 and emu.last_status(0, "f1") == f1
            # The line as the monitor decoded it: F2 is low-active there.
            await idle(dut, 0)
            monitor_agrees(mon, mbase + n + 1, got, f1=f1, f2=not f2, crc_ok=True, error=False)
    no_violations(emu)
    assert not mon.violations()
    transcript = mon.transcript()
    assert '"protocol":"endat"' in transcript and '"monitor":true' in transcript


@cocotb.test(expect_fail=True)
async def a_monitor_that_asks_for_more_than_the_core_waits_fails_the_test(dut):
    f_hz = int(os.environ["F_SYS_HZ"])
    _, mon = await connect(dut, f_hz, "\n[endat.monitor]\nt_m_us = 40\n", fail_on_violation=False)
    try:
        for n in range(2):
            await request(dut, ERRORS, 200_000, f"read {n}")
            await idle(dut, 0)
    except AssertionError as e:  # anything but the monitor's report must not pass as the expected failure
        raise RuntimeError(str(e)) from e
    v = mon.violations()
    if any("t_m (seed 004" not in x for x in v):
        raise RuntimeError(f"violations other than t_m: {v}")
    # The expected failure: the second read started 30.5 us after the first, the monitor says t_m.
    assert not v, v[0]
