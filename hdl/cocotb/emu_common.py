"""Shared helpers of the cocotb examples: an emulator from encoder_emu (the
PyO3 module built from the cosim crate by scripts/cocotb.sh) stepped on every
rising edge of the clock, with the master's pins in and the emulator's out."""

import logging
import os

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge

import encoder_emu


def config_path():
    """The scenario file the runner chose (COSIM_CONFIG)."""
    return os.environ["COSIM_CONFIG"]


def open_emulator(kind, f_emu_hz):
    """The emulator of `kind` from the runner's scenario file."""
    path = config_path()
    with open(path, encoding="utf-8") as f:
        return encoder_emu.Emulator(kind, f.read(), f_emu_hz, path)


# A driver enable is a pin whose name ends so (o_tx_en, o_endat_data_oe,
# dout_en): X or Z there means the master does not drive.
ENABLE_SUFFIXES = ("_en", "_oe", "_de", "_enable")
_x_enables_warned = set()


def bit(signal):
    """A 1-bit signal as 0/1. X or Z on a driver enable (a name ending in
    _en, _oe, _de or _enable) reads as 0, not driving, with one warning per
    pin and never a protocol report (a master before its reset); on any other
    pin as 1, the idle level of the line (a clock held X in reset reads idle;
    the HDL wrappers report it, a cocotb test asserts it away at reset)."""
    v = signal.value
    if v.is_resolvable:
        return int(v)
    name = signal._name
    if name.lower().endswith(ENABLE_SUFFIXES):
        if name not in _x_enables_warned:
            _x_enables_warned.add(name)
            logging.getLogger("cocotb").warning(
                "X or Z on the driver enable %s: read as 0, the master not driving (warned once)", name)
        return 0
    return 1


async def start(dut, f_hz):
    """Starts the clock at f_hz and holds reset for 4 cycles."""
    period_ps = round(1e12 / f_hz)
    cocotb.start_soon(Clock(dut.i_clk, period_ps, units="ps").start())
    dut.i_rst.value = 1
    for _ in range(4):
        await RisingEdge(dut.i_clk)
    dut.i_rst.value = 0
    for _ in range(4):
        await RisingEdge(dut.i_clk)


def run_emulator(dut, emu, pins_in, apply_out):
    """Steps `emu` on each rising edge: pins_in() -> int, apply_out(int)."""

    async def loop():
        while True:
            await RisingEdge(dut.i_clk)
            apply_out(emu.step(pins_in()))

    return cocotb.start_soon(loop())


async def wait_for(dut, signal, limit, what):
    """Waits until `signal` is 1 (at most `limit` cycles)."""
    for _ in range(limit):
        await RisingEdge(dut.i_clk)
        if bit(signal) == 1:
            return
    raise AssertionError(f"no {what} within {limit} cycles")


def no_violations(emu):
    v = emu.violations()
    assert not v, "the master broke the seed's timing rules:\n" + "\n".join(v)


async def operation(dut, start, value, errors, limit=2_000_000):
    """Pulses `start` for one cycle, then until o_done collects the value of
    `value` at o_valid and the names of the error pulses seen."""
    start.value = 1
    await RisingEdge(dut.i_clk)
    start.value = 0
    got, seen = None, []
    for _ in range(limit):
        await RisingEdge(dut.i_clk)
        if bit(dut.o_valid):
            got = int(value.value)
        seen += [e for e in errors if bit(getattr(dut, e))]
        if bit(dut.o_done):
            await RisingEdge(dut.i_clk)
            return got, seen
    raise AssertionError(f"no o_done within {limit} cycles")


def planted(value):
    """`value` with bit COSIM_FLIP_BIT flipped when that is set (a planted
    misread: the test must then fail)."""
    k = int(os.environ.get("COSIM_FLIP_BIT", "-1"))
    return value if value is None or k < 0 else value ^ (1 << k)


async def request(dut, errors, limit, what):
    """Pulses i_start for one cycle and waits for o_done (at most `limit`
    cycles); returns the names of the error outputs seen high on the way,
    each once (pulses, or flags that hold until the next operation)."""
    dut.i_start.value = 1
    await RisingEdge(dut.i_clk)
    dut.i_start.value = 0
    seen = []
    for _ in range(limit):
        await RisingEdge(dut.i_clk)
        seen += [e for e in errors if e not in seen and bit(getattr(dut, e))]
        if bit(dut.o_done):
            return seen
    raise AssertionError(f"{what}: no o_done within {limit} cycles")


async def idle(dut, cycles):
    """Waits until o_busy is low, then `cycles` more cycles."""
    while bit(dut.o_busy):
        await RisingEdge(dut.i_clk)
    for _ in range(cycles):
        await RisingEdge(dut.i_clk)


def connect_rs485(dut, emu):
    """A half-duplex host (o_tx, o_tx_en, i_rx) on the emulator's pair: pins
    in, bit 1 the host's driver level and bit 2 its enable (no clock)."""
    dut.i_rx.value = 1
    run_emulator(dut, emu, lambda: bit(dut.o_tx) << 1 | bit(dut.o_tx_en) << 2,
                 lambda out: setattr(dut.i_rx, "value", out & 1))


async def readout(dut, emu, n, flip, errors, crc_error):
    """One operation; with `flip`, one data bit of field 4 of the next answer
    inverted by the emulator, which the host must flag as `crc_error` and
    nothing else. Returns True when the answer was clean (to be compared)."""
    if flip:
        emu.schedule_fault(f"flips = [{{ answer = {emu.count()}, field = 4, bit = 2 }}]")
    seen = await request(dut, errors, 100_000, f"readout {n}")
    assert emu.count() == n + 1, f"readout {n}: the emulator answered {emu.count()} times"
    if flip:
        assert seen == [crc_error], f"readout {n}: a flipped data bit gave {seen}"
        return False
    assert not seen, f"readout {n}: error outputs {seen}"
    return True


def open_monitor(protocol, f_mon_hz, extra=""):
    """The pin-level monitor and protocol checker of `protocol` (ssi, biss,
    endat, ...: encoder_emu.Monitor) from the runner's scenario file, with
    `extra` TOML appended (a [monitor] table, say)."""
    path = config_path()
    with open(path, encoding="utf-8") as f:
        return encoder_emu.Monitor(protocol, f.read() + extra, f_mon_hz, path)


def run_monitor(dut, mon, pins_in, fail_on_violation=True):
    """Steps `mon` on each rising edge with pins_in() -> int (the master's
    pins, as the HDL monitor's ports). With fail_on_violation, the first
    violation of the seed's timing rules fails the test at once, naming it."""

    async def loop():
        while True:
            await RisingEdge(dut.i_clk)
            if mon.step(pins_in()) and fail_on_violation:
                raise AssertionError("the master broke the seed's timing rules (monitor):\n" + "\n".join(mon.violations()))

    return cocotb.start_soon(loop())


def monitor_agrees(mon, count, value=None, device=0, **status):
    """The monitor decoded `count` transactions, the last with position
    `value` (when given) and the statuses `status` (name=bool)."""
    assert mon.count() == count, f"the monitor decoded {mon.count()} transactions, expected {count}"
    if value is not None:
        assert mon.last_value(device) == value, f"transaction {count - 1}: the monitor read {mon.last_value(device)} on the line, expected {value}"
    for name, want in status.items():
        got = mon.last_status(device, name)
        assert got == want, f"transaction {count - 1}: the monitor's {name} is {got}, expected {want}"
