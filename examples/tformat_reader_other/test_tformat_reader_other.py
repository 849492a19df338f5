"""cocotb: tformat_reader (a master encoder-tb did not write) against the
T-format encoder emulator, driven from Python: encoder_emu.Emulator (the
library the HDL wrappers use, built into .venv by scripts/cocotb.sh) is
stepped on each rising clock edge with the reader's driver (D and DE) and
drives its receiver input. Each read sets a random single-turn and
multi-turn position and random ALMC flags and asks for Data ID 3 (every
fourth read Data ID 0); what the reader took must equal what the emulator
says it sent, and no timing rule may be broken.

    make cocotb                       (in this directory)
    COSIM_FLIP_BIT=3 make cocotb      (a planted misread: must fail)"""

import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge

import encoder_emu
# bit(): a pin as 0/1 (X or Z as the idle 1); planted(): the read with bit COSIM_FLIP_BIT
# flipped when that is set (a planted misread: the test must then fail). hdl/cocotb/.
from emu_common import bit, planted

F_HZ = 20_000_000                     # the reader's clock and the emulator's
READS = int(os.environ.get("COSIM_TRANSACTIONS", "100"))
FLAGS = ("over_speed", "full_absolute", "counting_error", "counter_overflow", None,
         "multi_turn_error", "battery_error", "battery_alarm")     # ALMC bits 0..7 (seed 002 Table 3)


@cocotb.test()
async def reads_equal_what_the_emulator_sent(dut):
    path = os.environ["COSIM_CONFIG"]
    with open(path, encoding="utf-8") as f:
        text = f.read()
        emu = encoder_emu.Emulator("tformat", text, F_HZ, path)
        mon = encoder_emu.Monitor("tformat", text, F_HZ, path)
    cocotb.start_soon(Clock(dut.sys_clk, round(1e12 / F_HZ), units="ps").start())
    dut.nreset.value = 0
    dut.go.value = 0
    dut.id.value = 3
    dut.rx.value = 1

    async def wire():
        # Pins in: bit 1 the host's driver level (D), bit 2 its enable (DE); out: bit 0 its receiver (R).
        while True:
            await RisingEdge(dut.sys_clk)
            mon.step(bit(dut.rx) | bit(dut.tx) << 1 | bit(dut.tx_en) << 2)  # R, D, DE
            dut.rx.value = emu.step(bit(dut.tx) << 1 | bit(dut.tx_en) << 2) & 1

    cocotb.start_soon(wire())
    for _ in range(3):
        await RisingEdge(dut.sys_clk)
    dut.nreset.value = 1
    rng = random.Random(17)
    for n in range(READS):
        st, mt, almc = rng.getrandbits(17), rng.getrandbits(16), rng.getrandbits(8) & 0xEF
        data_id = 0 if n % 4 == 3 else 3
        emu.set_position(0, mt << 17 | st)
        for b, name in enumerate(FLAGS):
            if name:
                emu.set_status(0, name, bool(almc >> b & 1))
        while not bit(dut.idle):
            await RisingEdge(dut.sys_clk)
        for _ in range(20):
            await RisingEdge(dut.sys_clk)
        dut.id.value = data_id
        dut.go.value = 1
        await RisingEdge(dut.sys_clk)
        dut.go.value = 0
        for _ in range(10_000):
            await RisingEdge(dut.sys_clk)
            if bit(dut.fresh) or bit(dut.bad):
                break
        else:
            raise AssertionError(f"read {n}: neither fresh nor bad")
        assert not bit(dut.bad), f"read {n} (Data ID {data_id}): the reader flagged an error ({int(dut.why.value)})"
        assert emu.count() == n + 1, f"read {n}: the emulator answered {emu.count()} requests"
        # last_value: ABM << 17 | ABS, ABS alone from an answer without ABM (Data ID 0).
        assert emu.last_value(0) == (mt << 17 | st if data_id == 3 else st), f"read {n}: last_value {emu.last_value(0):#x}"
        got = planted(int(dut.single_turn.value))
        assert got == st, f"read {n} (Data ID {data_id}): reader ABS {got:#x}, the emulator sent {st:#x}"
        if data_id == 3:
            assert int(dut.multi_turn.value) == mt, f"read {n}: reader ABM {int(dut.multi_turn.value):#x}, the emulator sent {mt:#x}"
            assert int(dut.alarms.value) == almc, f"read {n}: reader ALMC {int(dut.alarms.value):#x}, the emulator sent {almc:#x}"
        await RisingEdge(dut.sys_clk)
    assert mon.count() == READS, f"the monitor decoded {mon.count()} transactions on the line, expected {READS}"
    v = emu.violations() + mon.violations()
    assert not v, "the reader broke the seed's timing rules:\n" + "\n".join(v)
    dut._log.info("PASS tformat_reader: %d reads equal to what the emulator sent", READS)
