"""cocotb: sar_reader against the SAR58K24 encoder emulator (bus-command
mode), driven from Python.

The same master and encoder.toml as tb_sar_reader.v, but the emulator is
encoder_emu.Emulator stepped on each rising clock edge by a coroutine:
random 24-bit positions, every BC AA B5 read compared with what the
emulator sent, one frame per read, never two drivers on the line.

    python test_sar58k24_reader_other.py   (make cocotb: builds and runs it in Icarus)

COSIM_TRANSACTIONS=N (or READS=N) sets the number of reads (default 10); COSIM_FLIP_BIT=k flips bit k
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
READS = int(os.environ.get("COSIM_TRANSACTIONS", os.environ.get("READS", "10")))
FLIP = int(os.environ.get("COSIM_FLIP_BIT", "-1"))


def level(signal):
    """A 1-bit signal as 0/1; X or Z (before reset) as 1, the idle line."""
    v = signal.value
    return int(v) if v.is_resolvable else 1


@cocotb.test()
async def bus_reads_equal_what_the_encoder_sent(dut):
    import encoder_emu

    config = HERE / "encoder.toml"
    emu = encoder_emu.Emulator("sar58k24", config.read_text(), F_HZ, str(config))
    mon = encoder_emu.Monitor("sar58k24", config.read_text(), F_HZ, str(config))  # the pin-level monitor: it only listens
    dut.reset_b.value = 0
    dut.ask.value = 0
    dut.station.value = 5
    dut.rx_line.value = 1
    cocotb.start_soon(Clock(dut.clock, 2 * round(5e11 / F_HZ), units="ps").start())

    async def line():
        # pins in: bit 0 trigger and bit 3 CLR (idle high: unused in the bus
        # mode), bit 1 the reader's driver level, bit 2 its enable; out: bit 2
        # the resolved line at the reader's end
        while True:
            await RisingEdge(dut.clock)
            pins = 1 | level(dut.tx_line) << 1 | level(dut.tx_drive) << 2 | 1 << 3
            mon.step(level(dut.rx_line) | level(dut.tx_line) << 1 | level(dut.tx_drive) << 2 | 1 << 3 | 1 << 4)  # R, D, DE, trigger and CLR idle high
            dut.rx_line.value = emu.step(pins) >> 2 & 1

    cocotb.start_soon(line())
    await ClockCycles(dut.clock, 3)
    dut.reset_b.value = 1
    rng = random.Random(58)
    for n in range(READS):
        position = rng.getrandbits(24)
        emu.set_position(0, position)
        dut.ask.value = 1
        await RisingEdge(dut.clock)
        dut.ask.value = 0
        for _ in range(3000):
            await RisingEdge(dut.clock)
            if level(dut.got) or level(dut.bad):
                break
        else:
            raise AssertionError(f"read {n}: the reader neither read nor failed in 3000 clocks")
        assert not level(dut.bad), f"read {n}: the reader found no good answer (why {int(dut.why.value)}); the emulator sent {emu.last_value(0)}"
        got = int(dut.word.value)
        if FLIP >= 0:
            got ^= 1 << FLIP
        assert got == emu.last_value(0) == position, f"read {n}: the reader took {got}, the emulator sent {emu.last_value(0)} (set {position})"
        assert emu.count() == n + 1, f"read {n}: the emulator sent {emu.count()} frames in all"
        await ClockCycles(dut.clock, 80)
    assert mon.count() == READS, f"the monitor decoded {mon.count()} transactions on the line, expected {READS}"
    violations = emu.violations() + mon.violations()
    assert not violations, "the reader broke the line's rules:\n" + "\n".join(violations)


def main():
    """Builds sar_reader in Icarus and runs this module's test on it."""
    try:
        import encoder_emu  # noqa: F401
    except ImportError:
        sys.exit(f"{sys.executable} has no encoder_emu: run scripts/cocotb.sh of the encoder-tb checkout once "
                 "(after make deps), or give PYTHON= a Python that has it")
    from cocotb.runner import get_results, get_runner

    build = HERE / "build" / "cocotb"
    runner = get_runner("icarus")
    runner.build(verilog_sources=[HERE / "sar_reader.v"], hdl_toplevel="sar_reader", build_dir=build, always=True,
                 timescale=("1ns", "1ps"))
    xml = runner.test(hdl_toplevel="sar_reader", test_module=Path(__file__).stem, test_dir=HERE, build_dir=build,
                      results_xml=str(build / "results.xml"))
    total, fails = get_results(xml)
    print(f"cocotb: sar_reader (Icarus): {total - fails} of {total} passed")
    return 1 if fails or total == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
