"""cocotb example: modbus_master against the Modbus RTU device emulator:
each function-03 poll must give the value the device answered, no error
pulse, one request seen and answered per poll; the pin-level monitor
(modbus_monitor) decodes the same registers off the pins and sees no
break of the timing rules (t1.5, t3.5, turnaround, response timeout)."""

import os

import cocotb
from cocotb.triggers import RisingEdge

from emu_common import bit, monitor_agrees, planted, no_violations, open_emulator, open_monitor, operation, run_emulator, run_monitor, start

POLLS = int(os.environ.get("COSIM_TRANSACTIONS", "4"))
ERRORS = ("o_err_parity", "o_err_framing", "o_err_gap", "o_err_length", "o_err_crc", "o_err_address", "o_err_exception", "o_err_function", "o_err_count", "o_err_timeout")


@cocotb.test()
async def polls_equal_the_devices_answers(dut):
    f_hz = int(os.environ["F_SYS_HZ"])
    emu = open_emulator("modbus", f_hz)
    dut.i_start.value = 0
    dut.i_query.value = 0
    dut.i_write.value = 0
    dut.i_new_address.value = 0
    dut.i_address.value = int(os.environ.get("COSIM_ADDRESS", "1"))
    dut.i_count.value = int(os.environ.get("COSIM_COUNT", "1"))
    dut.i_rx.value = 1
    run_emulator(dut, emu, lambda: bit(dut.o_tx) << 1 | bit(dut.o_tx_en) << 2,
                 lambda out: setattr(dut.i_rx, "value", (out >> 2) & 1))
    mon = open_monitor("modbus", f_hz)
    # bit 0 R (the line at the master's receiver), bit 1 D, bit 2 DE.
    run_monitor(dut, mon, lambda: bit(dut.i_rx) | bit(dut.o_tx) << 1 | bit(dut.o_tx_en) << 2)
    await start(dut, f_hz)
    for n in range(POLLS):
        got, errors = await operation(dut, dut.i_start, dut.o_value, ERRORS)
        got = planted(got)
        assert emu.count() == n + 1 and emu.last_status(0, "answered")
        assert not errors and got == emu.last_value(0), f"poll {n}: core read {got} {errors}, the device answered {emu.last_value(0)}"
        monitor_agrees(mon, n + 1, emu.last_value(0), valid=True)
        while bit(dut.o_busy):
            await RisingEdge(dut.i_clk)
    no_violations(emu)
