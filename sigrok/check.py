#!/usr/bin/env python3
"""Holds the sigrok decoders in sigrok/decoders/ to the transcripts.

For every built-in scenario of a protocol with a decoder here, sigrok-cli
runs the decoder over the scenario's committed wave (vectors/<core>/, which
`make test` keeps equal to what the model generates) at the lines the master
sees, and its frames must agree with the transcript field by field:
positions, bits, CRC verdicts, error flags. Then, per protocol, a copy of
one wave with one data bit inverted must make the decoder report the error
that bit guards (a CRC error; for SSI, which has no CRC, the double read).

The decoders are an independent reading of the seeds; this script reads
only the transcripts, never the Rust decoders.

    python3 sigrok/check.py [--only PROTOCOL] [--keep DIR] [-v]
"""

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DECODERS = ROOT / "sigrok" / "decoders"
sys.path.insert(0, str(Path(__file__).resolve().parent))

import protocols  # noqa: E402  (sigrok/protocols.py: one entry per decoder)
from protocols import Mismatch  # noqa: E402


def scalars_only(text):
    """The VCD without its vector signals: libsigrok's VCD input (0.5)
    stops at the first vector value, and the lines are all scalars."""
    out = []
    for line in text.splitlines():
        t = line.lstrip()
        if t.startswith("$var") and t.split()[2] != "1":
            continue
        if t[:1] in ("b", "B"):
            continue
        out.append(line)
    return "\n".join(out) + "\n"


def invert(text, signal, t0, t1):
    """The VCD with scalar `signal` inverted from time t0 to t1 (ps)."""
    head, body = text.split("$enddefinitions $end", 1)
    code = next((w[3] for w in map(str.split, head.splitlines())
                 if w[:1] == ["$var"] and w[4] == signal), None)
    if code is None:
        raise Mismatch(f"no signal {signal} in the wave")
    pre, blocks = [], []
    for line in body.splitlines():
        if line.startswith("#"):
            blocks.append((int(line[1:]), []))
        elif blocks:
            blocks[-1][1].append(line)
        else:
            pre.append(line)
    times = {t for t, _ in blocks}
    blocks += [(t, []) for t in (t0, t1) if t not in times]
    blocks.sort(key=lambda b: b[0])
    flip = {"0": "1", "1": "0"}

    def is_data(line):
        return line[:1] in "01xz" and line[1:].strip() == code

    level = "x"
    out = [head + "$enddefinitions $end"] + pre
    for t, lines in blocks:
        changed = False
        for i, line in enumerate(lines):
            if is_data(line):
                level, changed = line[0], True
                if t0 <= t < t1:
                    lines[i] = flip.get(level, level) + code
        if t == t0 and not changed:
            lines.append(flip.get(level, level) + code)
        if t == t1 and not changed:
            lines.append(level + code)
        out.append(f"#{t}")
        out += lines
    return "\n".join(out) + "\n"


LINE = re.compile(r"^(\d+)-(\d+) (\S+)-\d+: (.*)$")


def run_sigrok(vcd, f_sys_hz, decoder):
    """sigrok-cli's annotations as (start, end, text), one sample per
    system clock so that samples are the transcript's cycles."""
    env = dict(os.environ, SIGROKDECODE_DIR=str(DECODERS))
    downsample = 1_000_000_000_000 // f_sys_hz
    cmd = ["sigrok-cli", "-I", f"vcd:downsample={downsample}", "-i", str(vcd),
           "-P", decoder, "--protocol-decoder-samplenum"]
    try:
        out = subprocess.run(cmd, env=env, capture_output=True, text=True)
    except FileNotFoundError:
        sys.exit("sigrok/check.py: sigrok-cli is not on PATH (`make deps` installs it)")
    if out.returncode != 0 or "Traceback" in out.stderr or "srd:" in out.stderr:
        raise Mismatch(f"sigrok-cli failed: {' '.join(cmd)}\n{out.stderr}")
    anns = []
    for line in out.stdout.splitlines():
        m = LINE.match(line)
        if m:
            anns.append((int(m.group(1)), int(m.group(2)), m.group(4)))
    return anns, " ".join(cmd)


def scenario_file(name):
    for path in (ROOT / "scenarios").glob("*/*.toml"):
        with open(path, "rb") as f:
            if tomllib.load(f).get("name") == name:
                return path
    raise Mismatch(f"no scenario file declares name = {name!r}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", help="one protocol (its decoder id)")
    ap.add_argument("--keep", help="keep the scalar waves in this folder")
    ap.add_argument("-v", "--verbose", action="store_true")
    args = ap.parse_args()
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(args.keep or tmp)
        tmp.mkdir(parents=True, exist_ok=True)
        for proto in protocols.ALL:
            if args.only and proto.decoder_id != args.only:
                continue
            scenarios = frames = values = 0
            flip_wave = None
            for js in sorted((ROOT / "vectors" / proto.core).glob("*.json")):
                transcript = json.loads(js.read_text())
                name = transcript["scenario"]
                with open(scenario_file(name), "rb") as f:
                    scenario = tomllib.load(f)
                vcd = tmp / f"{name}.vcd"
                text = scalars_only(js.with_suffix(".vcd").read_text())
                vcd.write_text(text)
                decoder = proto.decoder(transcript, scenario)
                try:
                    anns, cmd = run_sigrok(vcd, transcript["f_sys_hz"], decoder)
                    n, v = proto.compare(anns, transcript)
                except Mismatch as e:
                    failures += 1
                    print(f"FAIL {name}: {e}\n  decoder: -P {decoder}")
                    continue
                scenarios += 1
                frames += n
                values += v
                if args.verbose:
                    print(f"ok   {name}: {n} frames, {v} values")
                target = None if flip_wave else proto.flip(anns, transcript)
                if target:
                    flip_wave = (name, text, transcript, decoder, target)
            print(f"{proto.decoder_id:<9} {scenarios:>3} scenarios, {frames:>5} "
                  f"frames, {values:>6} values agree with the transcripts"
                  + (f" ({proto.not_compared} master verdicts not compared)"
                     if getattr(proto, "not_compared", 0) else ""))
            if scenarios < proto.minimum_scenarios:
                failures += 1
                print(f"FAIL {proto.decoder_id}: only {scenarios} scenarios "
                      f"compared, at least {proto.minimum_scenarios} expected")
            if flip_wave is None:
                failures += 1
                print(f"FAIL {proto.decoder_id}: no scenario to flip a bit in")
                continue
            name, text, transcript, decoder, (t0, t1, expect) = flip_wave
            ps = 1_000_000_000_000 // transcript["f_sys_hz"]
            flipped = tmp / f"{name}.flipped.vcd"
            flipped.write_text(invert(text, proto.data_signal, t0 * ps, t1 * ps))
            got, _ = run_sigrok(flipped, transcript["f_sys_hz"], decoder)
            if not any(expect in a[2] for a in got):
                failures += 1
                print(f"FAIL {proto.decoder_id}: {name} with the data line "
                      f"inverted over cycles {t0}..{t1}: no `{expect}`")
            else:
                print(f"{proto.decoder_id:<9} {name}, one data bit inverted "
                      f"at cycle {t0}: `{expect}` reported")
    if failures:
        print(f"{failures} failure(s)")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
