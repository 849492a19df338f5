"""cocotb: esl_reader against the ESL encoder emulator, driven from Python.

The same master and encoder.toml as tb_esl_reader.v, but the emulator is
encoder_emu.Emulator (encoder-tb's library as a Python module) stepped on
each rising clock edge by a coroutine: random 40-bit positions and random
alarm flags, every read compared with what the emulator sent (and SF's
EA0/EA1 with the flags), one request answered per read, no timing rule
broken.

    python test_esl_reader_other.py       (make cocotb: builds and runs it in Icarus)

COSIM_TRANSACTIONS=N (or READS=N) sets the number of reads (default 20); COSIM_FLIP_BIT=k flips bit k
of every value the reader took before the comparison (a planted misread:
the test must then fail)."""

import os
import random
import sys
from pathlib import Path

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge

HERE = Path(__file__).resolve().parent
F_HZ = 60_000_000                     # 6 clocks per bit at 10 Mbps
READS = int(os.environ.get("COSIM_TRANSACTIONS", os.environ.get("READS", "20")))
FLIP = int(os.environ.get("COSIM_FLIP_BIT", "-1"))


def level(signal):
    """A 1-bit signal as 0/1; X or Z (before reset) as 1, the idle line."""
    v = signal.value
    return int(v) if v.is_resolvable else 1


@cocotb.test()
async def reads_equal_what_the_encoder_sent(dut):
    import encoder_emu

    config = HERE / "encoder.toml"
    emu = encoder_emu.Emulator("esl", config.read_text(), F_HZ, str(config))
    mon = encoder_emu.Monitor("esl", config.read_text(), F_HZ, str(config))  # the pin-level monitor: it only listens
    dut.rst_n.value = 0
    dut.trigger.value = 0
    dut.enc_addr.value = 6
    dut.rxd.value = 1
    cocotb.start_soon(Clock(dut.clk, 2 * round(5e11 / F_HZ), units="ps").start())

    async def pair():
        # pins in: bit 1 the reader's DI, bit 2 its DE; out: bit 0 its RO
        while True:
            await RisingEdge(dut.clk)
            mon.step(level(dut.rxd) | level(dut.txd) << 1 | level(dut.txd_en) << 2)  # RO, DI, DE
            dut.rxd.value = emu.step(level(dut.txd) << 1 | level(dut.txd_en) << 2) & 1

    cocotb.start_soon(pair())
    for _ in range(3):
        await RisingEdge(dut.clk)
    dut.rst_n.value = 1
    rng = random.Random(10)
    for n in range(READS):
        single, multi = rng.getrandbits(24), rng.getrandbits(16)
        st_err, xc_err = rng.random() < 0.5, rng.random() < 0.5
        emu.set_position(0, multi << 24 | single)
        emu.set_status(0, "st", st_err)        # a safety error: EA0 (seed 000, Table 5)
        emu.set_status(0, "xc", xc_err)        # a non-safety error: EA1
        dut.trigger.value = 1
        await RisingEdge(dut.clk)
        dut.trigger.value = 0
        for _ in range(5000):
            await RisingEdge(dut.clk)
            if level(dut.fresh) or level(dut.fail):
                break
        else:
            raise AssertionError(f"read {n}: the reader neither read nor failed in 5000 clocks")
        assert not level(dut.fail), f"read {n}: the reader failed (why {int(dut.fail_why.value)}); the emulator sent {emu.last_value(0):#x}"
        got = int(dut.turns.value) << 24 | int(dut.angle.value)
        if FLIP >= 0:
            got ^= 1 << FLIP
        assert got == emu.last_value(0) == multi << 24 | single, \
            f"read {n}: the reader took {got:#x}, the emulator sent {emu.last_value(0):#x} (set {multi << 24 | single:#x})"
        status = int(dut.status.value)
        assert (status >> 2 & 1, status >> 3 & 1) == (st_err, xc_err), f"read {n}: SF {status:08b}, flags st {st_err} xc {xc_err}"
    assert emu.count() == READS, f"the emulator answered {emu.count()} requests for {READS} reads"
    assert mon.count() == READS, f"the monitor decoded {mon.count()} transactions on the line, expected {READS}"
    violations = emu.violations() + mon.violations()
    assert not violations, "the reader broke the seed's timing rules:\n" + "\n".join(violations)


def main():
    """Builds esl_reader in Icarus and runs this module's test on it."""
    try:
        import encoder_emu  # noqa: F401
    except ImportError:
        sys.exit(f"{sys.executable} has no encoder_emu: run scripts/cocotb.sh of the encoder-tb checkout once "
                 "(after make deps), or give PYTHON= a Python that has it")
    from cocotb.runner import get_results, get_runner

    build = HERE / "build" / "cocotb"
    runner = get_runner("icarus")
    runner.build(verilog_sources=[HERE / "esl_reader.v"], hdl_toplevel="esl_reader", build_dir=build, always=True,
                 timescale=("1ns", "1ps"))
    xml = runner.test(hdl_toplevel="esl_reader", test_module=Path(__file__).stem, test_dir=HERE, build_dir=build,
                      results_xml=str(build / "results.xml"))
    total, fails = get_results(xml)
    print(f"cocotb: esl_reader (Icarus): {total - fails} of {total} passed")
    return 1 if fails or total == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
