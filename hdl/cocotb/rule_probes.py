"""The rule probes (cosim/src/probe/, exported by `tbgen probes --out DIR`)
from cocotb: each kit's probes in one Icarus simulation, its master's pins
driven into the top level DIR/<kind>/probe_pins.v (ports named as the
emulator wrapper's), read back through emu_common.bit as a cocotb test of a
master reads them (X or Z on a driver enable: 0, not driving, one warning),
and stepped through the emulator and the monitor of encoder_emu, wired by
the kit's table. Each probe's transcripts and warnings go to
DIR/<kind>/<probe>/cocotb/, where `tbgen probes --check DIR --sim cocotb`
judges them with the library's verdict.

    .venv/bin/python hdl/cocotb/rule_probes.py DIR     (hdl/tb_probe/run.sh does this)

The pins are held for a run of the stimulus (cycles of the emulator
clock), read once at its end and stepped through the emulator once per
cycle of the run: the simulator carries the pins and their X, Python steps
the clock."""

import json
import logging
import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent


def runs(path):
    """The stimulus runs of a probe: (cycles, unknown mask, levels), to the zero word."""
    for line in Path(path).read_text().split():
        w = int(line, 16)
        if w >> 32 == 0:
            return
        yield w >> 32, (w >> 16) & 0xFFFF, w & 0xFFFF


def source_level(s, master, answer):
    """A monitor pin from its source byte (hdl/tb_probe/tb_probe.v says the code)."""
    kind, n = s >> 4, s & 0xF
    bit = lambda v, k: (v >> k) & 1
    if kind == 0:
        return bit(master, n)
    if kind == 1:
        return bit(answer, n)
    if kind == 2:
        if bit(answer, 1):
            return bit(answer, 0)
        return 1 if not bit(master, 2) or bit(master, 1) else 0
    return bit(master, n) & bit(answer, 0)


class Collect(logging.Handler):
    """The warnings logged while a probe runs."""

    def __init__(self):
        super().__init__(logging.WARNING)
        self.lines = []

    def emit(self, record):
        self.lines.append(f"{record.levelname}: {record.getMessage()}")


def probe_dirs(out, kind):
    """The folders of `kind`'s probes, from the manifest."""
    for line in (out / "probes.tsv").read_text().splitlines():
        if not line.startswith("#"):
            k, _f, _depth, rel = line.split("\t")
            if k == kind:
                yield out / rel


try:
    import cocotb
    from cocotb.triggers import Timer
except ImportError:  # the launcher below needs no simulator
    cocotb = None

if cocotb is not None and os.environ.get("PROBES_KIND"):
    import encoder_emu

    import emu_common

    @cocotb.test()
    async def every_probe_of_the_kit(dut):
        out, kind = Path(os.environ["PROBES_DIR"]), os.environ["PROBES_KIND"]
        wiring = json.loads((out / kind / "wiring.json").read_text())
        inputs = [(i["bit"], getattr(dut, i["port"])) for i in wiring["inputs"]]
        sources = wiring["monitor_sources"]
        log = logging.getLogger("cocotb")
        for pd in probe_dirs(out, kind):
            run = pd / "cocotb"
            run.mkdir(exist_ok=True)
            for f in ("emulator.json", "monitor.json"):
                (run / f).unlink(missing_ok=True)
            # One warning per pin per probe, as each probe is a simulation
            # of its own in Icarus and Verilator.
            emu_common._x_enables_warned.clear()
            collect = Collect()
            log.addHandler(collect)
            try:
                emu, mon = await replay(pd, inputs, sources, wiring["idle"], kind)
                (run / "emulator.json").write_text(emu.transcript())
                (run / "monitor.json").write_text(mon.transcript())
            except Exception as e:  # the probe's failure, judged by tbgen probes --check
                collect.lines.append(f"ERROR: {e}")
            finally:
                log.removeHandler(collect)
            (run / "sim.log").write_text("".join(line + "\n" for line in collect.lines))

    async def replay(pd, inputs, sources, idle, kind):
        """Runs the probe of folder `pd`; returns its emulator and monitor."""
        p = json.loads((pd / "probe.json").read_text())
        toml = (pd / "probe.toml").read_text()
        emu = encoder_emu.Emulator(kind, toml, p["f_hz"], str(pd / "probe.toml"))
        mon = encoder_emu.Monitor(kind, toml, p["f_hz"], str(pd / "probe.toml"))
        period_ps = 1e12 / p["f_hz"]
        answer = idle
        for cycles, unknown, levels in runs(pd / "stimulus.mem"):
            for b, sig in inputs:
                sig.value = cocotb.binary.BinaryValue("x" if unknown >> b & 1 else str(levels >> b & 1))
            await Timer(round(cycles * period_ps), units="ps")
            master = sum(emu_common.bit(sig) << b for b, sig in inputs)
            for _ in range(cycles):
                mon.step(sum(source_level(s, master, answer) << i for i, s in enumerate(sources)))
                answer = emu.step(master)
        return emu, mon


def main(argv):
    """Runs every kit's probes of the export `argv[0]`, one simulation a kit."""
    if len(argv) != 1 or not (Path(argv[0]) / "probes.tsv").is_file():
        raise SystemExit("rule_probes.py: give the folder `tbgen probes --out DIR` wrote (it has probes.tsv)")
    from cocotb.runner import get_runner

    out = Path(argv[0]).resolve()
    lib_dir = Path(os.environ.get("EMU_LIB_DIR", HERE.parent.parent / "target" / "release"))
    # encoder_emu: the cdylib beside libcosim.so under the name Python imports.
    py = out / "python"
    py.mkdir(exist_ok=True)
    link = py / "encoder_emu.abi3.so"
    if link.is_symlink() or link.exists():
        link.unlink()
    link.symlink_to(lib_dir / "libencoder_emu.so")
    # The runner hands the simulator its own sys.path as PYTHONPATH.
    sys.path[:0] = [str(HERE), str(py)]
    kinds = []
    for line in (out / "probes.tsv").read_text().splitlines():
        k = line.split("\t")[0]
        if not line.startswith("#") and k not in kinds:
            kinds.append(k)
    for kind in kinds:
        build = out / kind / "cocotb_build"
        runner = get_runner("icarus")
        runner.build(verilog_sources=[str(out / kind / "probe_pins.v")], hdl_toplevel="probe_pins",
                     build_dir=build, always=True, timescale=("1ps", "1ps"))
        runner.test(hdl_toplevel="probe_pins", test_module="rule_probes", test_dir=build, build_dir=build,
                    extra_env={"PROBES_DIR": str(out), "PROBES_KIND": kind},
                    results_xml=str(build / "results.xml"))


if __name__ == "__main__":
    main(sys.argv[1:])
