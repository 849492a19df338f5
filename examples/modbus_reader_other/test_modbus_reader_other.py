"""cocotb: modbus_reader against the Modbus RTU device emulator, driven from
Python.

The same master and device.toml as tb_modbus_reader.v, but the emulator is
encoder_emu.Emulator stepped on each rising clock edge by a coroutine:
random 32-bit positions, every function-03 poll compared with what the
device answered, one request seen and answered per poll, no rule of the
line broken.

    python test_modbus_reader_other.py    (make cocotb: builds and runs it in Icarus)

READS=N sets the number of polls (default 6); COSIM_FLIP_BIT=k flips bit k
of every value the reader took before the comparison (a planted misread:
the test must then fail)."""

import os
import random
import sys
from pathlib import Path

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge

HERE = Path(__file__).resolve().parent
F_HZ = 153_600                        # 8 clocks per bit at 19200 baud
READS = int(os.environ.get("COSIM_TRANSACTIONS", os.environ.get("READS", "6")))
FLIP = int(os.environ.get("COSIM_FLIP_BIT", "-1"))


def level(signal):
    """A 1-bit signal as 0/1; X or Z (before reset) as 1, the idle line."""
    v = signal.value
    return int(v) if v.is_resolvable else 1


@cocotb.test()
async def polls_equal_what_the_device_answered(dut):
    import encoder_emu

    config = HERE / "device.toml"
    emu = encoder_emu.Emulator("modbus", config.read_text(), F_HZ, str(config))
    mon = encoder_emu.Monitor("modbus", config.read_text(), F_HZ, str(config))  # the pin-level monitor: it only listens
    dut.nreset.value = 0
    dut.poll.value = 0
    dut.slave.value = 0x11
    dut.ro.value = 1
    cocotb.start_soon(Clock(dut.clk, 2 * round(5e11 / F_HZ), units="ps").start())

    async def line():
        # pins in: bit 1 the reader's DI, bit 2 its DE; out: bit 2 the
        # resolved line at the reader's end (its RO)
        while True:
            await RisingEdge(dut.clk)
            mon.step(level(dut.ro) | level(dut.di) << 1 | level(dut.de) << 2)  # RO, DI, DE
            dut.ro.value = emu.step(level(dut.di) << 1 | level(dut.de) << 2) >> 2 & 1

    cocotb.start_soon(line())
    await ClockCycles(dut.clk, 3)
    dut.nreset.value = 1
    rng = random.Random(485)
    for n in range(READS):
        # t3.5 before each request is this reader's user's to keep (the
        # testbench says why): 400 clocks from the answer on.
        if n > 0:
            await ClockCycles(dut.clk, 400)
        position = rng.getrandbits(32)
        emu.set_position(0, position)
        dut.poll.value = 1
        await RisingEdge(dut.clk)
        dut.poll.value = 0
        for _ in range(8000):
            await RisingEdge(dut.clk)
            if level(dut.ok) or level(dut.err):
                break
        else:
            raise AssertionError(f"poll {n}: the reader neither read nor failed in 8000 clocks")
        assert not level(dut.err), f"poll {n}: the reader failed (code {int(dut.err_code.value)}); the device answered {emu.last_value(0):#x}"
        got = int(dut.position.value)
        if FLIP >= 0:
            got ^= 1 << FLIP
        assert got == emu.last_value(0) == position, f"poll {n}: the reader took {got:#x}, the device answered {emu.last_value(0):#x} (set {position:#x})"
        assert emu.count() == n + 1 and emu.last_status(0, "answered"), f"poll {n}: the device saw {emu.count()} requests"
    assert mon.count() == READS, f"the monitor decoded {mon.count()} transactions on the line, expected {READS}"
    violations = emu.violations() + mon.violations()
    assert not violations, "the reader broke the line's rules:\n" + "\n".join(violations)


def main():
    """Builds modbus_reader in Icarus and runs this module's test on it."""
    try:
        import encoder_emu  # noqa: F401
    except ImportError:
        sys.exit(f"{sys.executable} has no encoder_emu: run scripts/cocotb.sh of the encoder-tb checkout once "
                 "(after make deps), or give PYTHON= a Python that has it")
    from cocotb.runner import get_results, get_runner

    build = HERE / "build" / "cocotb"
    runner = get_runner("icarus")
    runner.build(verilog_sources=[HERE / "modbus_reader.v"], hdl_toplevel="modbus_reader", build_dir=build, always=True,
                 timescale=("1ns", "1ps"))
    xml = runner.test(hdl_toplevel="modbus_reader", test_module=Path(__file__).stem, test_dir=HERE, build_dir=build,
                      results_xml=str(build / "results.xml"))
    total, fails = get_results(xml)
    print(f"cocotb: modbus_reader (Icarus): {total - fails} of {total} passed")
    return 1 if fails or total == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
