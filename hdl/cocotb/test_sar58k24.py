"""cocotb example: sar_async_host (bus mode) against the SAR58K24 encoder
emulator on a half-duplex line: each BC AA Bx read must give the position
the emulator sent, with no error pulse and no two drivers on the line; the
pin-level monitor (sar58k24_monitor) decodes the same frame off the pins
and sees no break of the timing rules."""

import os

import cocotb
from cocotb.triggers import RisingEdge

from emu_common import bit, monitor_agrees, planted, no_violations, open_emulator, open_monitor, operation, run_emulator, run_monitor, start

READS = int(os.environ.get("COSIM_TRANSACTIONS", "3"))
ERRORS = ("o_err_checksum", "o_err_parity", "o_err_frame", "o_err_address", "o_err_timeout", "o_err_stale")


@cocotb.test()
async def bus_reads_equal_what_the_encoder_sent(dut):
    f_hz = int(os.environ["F_SYS_HZ"])
    emu = open_emulator("sar58k24", f_hz)
    dut.i_start.value = 0
    dut.i_zero.value = 0
    dut.i_address.value = int(os.environ.get("COSIM_ADDRESS", "1"))
    dut.i_rx.value = 1

    def pins():
        # bit 0 trigger, bit 1 the host's driver level, bit 2 its enable, bit 3 CLR.
        return bit(dut.o_trigger) | bit(dut.o_tx) << 1 | bit(dut.o_tx_en) << 2 | bit(dut.o_clr) << 3

    run_emulator(dut, emu, pins, lambda out: setattr(dut.i_rx, "value", (out >> 2) & 1))
    mon = open_monitor("sar58k24", f_hz)
    # bit 0 R, bit 1 D, bit 2 DE, bit 3 trigger, bit 4 CLR.
    run_monitor(dut, mon, lambda: bit(dut.i_rx) | bit(dut.o_tx) << 1 | bit(dut.o_tx_en) << 2 | bit(dut.o_trigger) << 3 | bit(dut.o_clr) << 4)
    await start(dut, f_hz)
    bits_per = int(dut.CLOCKS_PER_BIT.value)
    for n in range(READS):
        got, errors = await operation(dut, dut.i_start, dut.o_position, ERRORS)
        got = planted(got)
        assert emu.count() == n + 1, f"read {n}: the emulator sent {emu.count()} frames in all"
        assert not errors and got == emu.last_value(0), f"read {n}: core read {got} {errors}, the encoder sent {emu.last_value(0)}"
        monitor_agrees(mon, n + 1, emu.last_value(0), frame_ok=True)
        # The rest of the encoder's stop bit before the next command.
        for _ in range(2 * bits_per):
            await RisingEdge(dut.i_clk)
    no_violations(emu)
