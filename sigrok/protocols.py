"""What sigrok/check.py holds each decoder to: one class per decoder, each
saying which committed waves it reads (vectors/<core>/), the decoder's
options for a scenario, how its frames compare with the transcript's
transactions, and which bit to invert in the bit-flip test."""

import re


class Mismatch(Exception):
    """A decoder's output that disagrees with a transcript."""


def frames_of(anns, prefix):
    """The frame annotations (text starting with prefix) in order, each
    with the errors reported over the same samples and the field and bit
    annotations inside it."""
    frames = []
    for ss, es, text in anns:
        if text.startswith(prefix):
            frames.append({"ss": ss, "es": es, "text": text[len(prefix):],
                           "errors": [], "inside": []})
    for ss, es, text in anns:
        for fr in frames:
            if fr["ss"] <= ss and es <= fr["es"]:
                if text.startswith("Error: ") and (ss, es) == (fr["ss"], fr["es"]):
                    fr["errors"].append(text[len("Error: "):])
                elif not text.startswith(prefix):
                    fr["inside"].append((ss, es, text))
                break
    return frames


def field(frame, name):
    """The value of the field annotation `name: value` inside a frame."""
    for _, _, text in frame["inside"]:
        if text.startswith(name + ": "):
            return text[len(name) + 2:]
    return None


def within(frame, t, where):
    """The frame lies inside the transaction's cycles."""
    if not (t["start_cycle"] <= frame["ss"] and frame["es"] <= t["done_cycle"] + 1):
        raise Mismatch(f"{where}: frame at cycles {frame['ss']}..{frame['es']}, "
                       f"the transaction at {t['start_cycle']}..{t['done_cycle']}")


def partial(anns, transactions, transcript, start=lambda t: t["start_cycle"]):
    """The transactions a decoder can see whole: one that starts at the
    wave's first cycle has lost its first edge, and the decoder must say
    so (a `Partial:` frame) instead of decoding it."""
    if transactions and start(transactions[0]) == 0:
        if not any(ss == 0 and t.startswith("Partial: ") for ss, _, t in anns):
            raise Mismatch(f"{transcript['scenario']}: the first transaction "
                           "starts at cycle 0 and the decoder did not report "
                           "a partial frame")
        return transactions[1:]
    return transactions


def bits_of(frame):
    return [(ss, es, t) for ss, es, t in frame["inside"] if t in ("0", "1")]


def expect(name, got, want, where):
    if got != want:
        raise Mismatch(f"{where}: {name} is {got!r}, the transcript says {want!r}")


def error_names(frame):
    """The decoder's short error names (the text after the last `: ` of
    the short form is not printed by sigrok-cli, so the long form's
    leading words name it)."""
    return frame["errors"]


class Ssi:
    core = "ssi_master"
    decoder_id = "ssi"
    data_signal = "ssi_data_master"
    minimum_scenarios = 15
    # The transcript's error names and the decoder's long texts.
    errors = {"double_read_mismatch": "Double read mismatch",
              "wire_check_failed": "Wire check failed"}

    def decoder(self, transcript, scenario):
        p = transcript["parameters"]
        delay_ns = p["SAMPLE_DELAY"] * 1e9 / transcript["f_sys_hz"]
        t_m = scenario["ssi"].get("encoder", {}).get("monoflop_us", 500)
        return ("ssi:clk=ssi_clk_master:data=ssi_data_master"
                f":bits={p['BITS']}:code={'gray' if p['GRAY'] else 'binary'}"
                f":double_read={'yes' if p['DOUBLE_READ'] else 'no'}"
                f":wire_check={'yes' if p['WIRE_CHECK'] else 'no'}"
                f":sample_delay_ns={delay_ns:g}:monoflop_us={t_m:g}")

    def on_wire(self, transcript):
        # A start the reader refused (line not idle) clocks nothing.
        return [t for t in transcript["transactions"] if t["received_bits"]]

    def compare(self, anns, transcript):
        frames = frames_of(anns, "Read: ")
        want = partial(anns, self.on_wire(transcript), transcript)
        expect("frame count", len(frames), len(want), transcript["scenario"])
        values = 0
        for fr, t in zip(frames, want):
            where = f"{transcript['scenario']} read {t['index']} (cycle {fr['ss']})"
            within(fr, t, where)
            got_bits = "".join(b[2] for b in bits_of(fr))
            expect("bits", got_bits, t["received_bits"], where)
            expect("position", field(fr, "Position"), str(t["position"]), where)
            flagged = sorted(k for k, text in self.errors.items()
                             if any(e.startswith(text) for e in fr["errors"]))
            expect("errors", flagged, sorted(t["errors"]), where)
            unexplained = [e for e in fr["errors"]
                           if not any(e.startswith(x) for x in self.errors.values())]
            expect("other errors", unexplained, [], where)
            values += 3 + len(t["errors"])
        return len(frames), values

    def flip(self, anns, transcript):
        """(first cycle, last cycle, the error expected) of a bit to invert
        in this wave, or None. SSI has no CRC: the double read is what an
        inverted bit trips."""
        if not transcript["parameters"]["DOUBLE_READ"]:
            return None
        for fr in frames_of(anns, "Read: "):
            if not fr["errors"]:
                ss, es, _ = bits_of(fr)[2]
                return ss, es, "Double read mismatch"
        return None


def packed(value, n):
    """A transcript parameter that packs one byte per slave, slave 0 low."""
    return [(value >> (8 * i)) & 0xFF for i in range(n)]


def named_errors(frame, table):
    """(transcript error names the decoder reported, decoder errors no
    name explains)."""
    names, other = [], []
    for e in frame["errors"]:
        hit = [k for k, text in table.items() if e.startswith(text)]
        names += hit
        if not hit:
            other.append(e)
    return sorted(names), other


class Biss:
    core = "biss_master"
    decoder_id = "biss_c"
    data_signal = "slo_master"
    minimum_scenarios = 31
    # What the decoder can see on the two lines; the master's delay
    # judgements (delay_beyond_compensation, delay_departs_from_mean) and
    # its wait for SLO (slo_not_released) are its own, not the line's.
    line_errors = {"no_ack": "No acknowledge",
                   "no_start_bit": "No start bit"}

    def decoder(self, transcript, scenario):
        p = transcript["parameters"]
        n = p["SLAVES"]
        join = lambda xs, f: "/".join(f(x) for x in xs)  # noqa: E731
        return ("biss_c:ma=ma_master:slo=slo_master"
                f":bits={join(packed(p['SLAVE_BITS'], n), str)}"
                f":crc_bits={join(packed(p['SLAVE_CRC_WIDTH'], n), str)}"
                f":crc_poly={join(packed(p['SLAVE_CRC_POLY'], n), hex)}")

    def errors(self, t):
        table = dict(self.line_errors)
        for s in t["slaves"]:
            table[f"crc_error_slave{s['slave']}"] = f"CRC error slave {s['slave']}"
        return table

    def compare(self, anns, transcript):
        frames = frames_of(anns, "Frame: ")
        # A start refused because SLO was low clocks nothing (its
        # received_bits repeat the previous frame's: done == start tells).
        on_wire = [t for t in transcript["transactions"]
                   if t["done_cycle"] > t["start_cycle"]]
        want = partial(anns, on_wire, transcript)
        expect("frame count", len(frames), len(want), transcript["scenario"])
        values = 0
        for fr, t in zip(frames, want):
            where = f"{transcript['scenario']} frame {t['index']} (cycle {fr['ss']})"
            within(fr, t, where)
            if not t["received_bits"] and not (set(t["errors"]) & set(self.line_errors)):
                # The master gave up for a reason of its own (a delay
                # beyond its range) before any bit: the line shows no data.
                if "slave 0 position" in fr["text"] or not fr["errors"]:
                    raise Mismatch(f"{where}: the master read nothing, the "
                                   f"decoder read {fr['text']!r} {fr['errors']}")
                continue
            table = self.errors(t)
            names, other = named_errors(fr, table)
            expect("errors", names, sorted(e for e in t["errors"] if e in table), where)
            expect("other errors", other, [], where)
            if any(e in self.line_errors for e in t["errors"]):
                continue
            m = re.search(r"; bits ([01]+)$", fr["text"])
            expect("bits", m and m.group(1), t["received_bits"], where)
            got = re.findall(r"slave (\d+) position (\d+) nE (\d) nW (\d) CDS (\d) CRC (\w+)", fr["text"])
            expect("slaves", len(got), len(t["slaves"]), where)
            for g, s in zip(got, t["slaves"]):
                w = f"{where} slave {s['slave']}"
                expect("position", int(g[1]), s["position"], w)
                expect("error (nE low)", g[2] == "0", s["error"], w)
                expect("warning (nW low)", g[3] == "0", s["warning"], w)
                expect("CDS", g[4] == "1", s["cds"], w)
                expect("CRC verdict", g[5] == "ok", s["crc_ok"], w)
                values += 5
            cdm = re.search(r"; CDM (\d)", fr["text"])
            expect("CDM", cdm and cdm.group(1) == "1", t["cdm"], where)
            values += 2
        values += self.compare_registers(anns, transcript)
        return len(frames), values

    def compare_registers(self, anns, transcript):
        got = [t for _, _, t in anns if t.startswith("Control: Register ")]
        # Accesses whose control frame was sent whole (33 CDM bits).
        want = [t["register"] for t in transcript["transactions"]
                if t["register"] and len(t["register"]["cdm"]) >= 33]
        expect("register accesses", len(got), len(want), transcript["scenario"])
        values = 0
        for text, r in zip(got, want):
            m = re.match(r"Control: Register (read|write): ID (\d+) address "
                         r"0x(\w+) data 0x(\w+), address CRC (\w+), data CRC (\w+)", text)
            where = f"{transcript['scenario']} register access {r}"
            if not m:
                raise Mismatch(f"{where}: decoder printed {text!r}")
            expect("direction", m.group(1) == "write", r["write"], where)
            expect("ID", int(m.group(2)), r["id"], where)
            expect("address", int(m.group(3), 16), r["addr"], where)
            data = r["wdata"] if r["write"] else r["rdata"]
            expect("data", int(m.group(4), 16), data, where)
            expect("address CRC", m.group(5), "ok", where)
            expect("data CRC verdict", m.group(6) == "ok", r["crc4_ok"], where)
            values += 6
        got = [t for _, _, t in anns if t.startswith("Control: Command: ")]
        want = [t["command"] for t in transcript["transactions"] if t["command"]]
        expect("commands", len(got), len(want), transcript["scenario"])
        for text, c in zip(got, want):
            m = re.match(r"Control: Command: IDS 0x(\w+) code (\d+), CRC (\w+)", text)
            where = f"{transcript['scenario']} command {c}"
            expect("IDS", m and int(m.group(1), 16), c["ids"], where)
            expect("code", int(m.group(2)), c["code"], where)
            expect("CRC", m.group(3), "ok", where)
            values += 3
        return values

    def flip(self, anns, transcript):
        for fr in frames_of(anns, "Frame: "):
            if not fr["errors"] and "slave 1" not in fr["text"]:
                ss, es, _ = bits_of(fr)[5]
                return ss, es, "CRC error slave 0"
        return None


SYNC_STAGES = 2


class Endat:
    # The master's delay counter stops when the start bit's edge leaves its
    # two-flop synchroniser (the model's documented reading of seed 2.1.2).
    core = "endat_master"
    decoder_id = "endat"
    data_signal = "endat_data_master"
    minimum_scenarios = 33
    # Errors the line shows; the rest (delay_drift,
    # delay_measurement_inconsistent, not_calibrated: the master's delay
    # judgements) are the master's own.
    line_errors = {"crc": "CRC error: ", "ad1_crc": "AD1 CRC error",
                   "ad2_crc": "AD2 CRC error", "f1_error": "F1: ",
                   "f2_error": "F2: ", "no_start_bit": "No start bit",
                   "line_not_driven": "Line not driven",
                   "type_ii": "Type II:", "type_iii": "Type III:",
                   "type_iv": "Type IV:",
                   "acknowledgement_mismatch": "Acknowledgement differs",
                   "type_i": "Mode command "}
    # Type II and a wrong acknowledgement with type 2.2 commands: judged
    # here only where the decoder judged (see acknowledge_22 in the
    # decoder); the master's other judgements of additional datum 1 are
    # counted as not compared.
    ack_errors = ("type_ii", "acknowledgement_mismatch")
    type21 = ("000111", "001110", "011100", "100011", "101010", "010101", "110001")
    not_compared = 0

    def decoder(self, transcript, scenario):
        p = transcript["parameters"]
        return ("endat:clk=endat_clk_master:data=endat_data_master"
                f":pos_bits={p['POS_BITS']}")

    def compare(self, anns, transcript):
        frames = frames_of(anns, "Frame: ")
        # Values of a continuous clock belong to their request's frame.
        requests = []
        for t in transcript["transactions"]:
            if t["kind"] == "continuous_value":
                requests[-1][1].append(t)
            else:
                requests.append((t, [t]))
        values = 0
        on_wire = [r for r in requests if r[0]["done_cycle"] > r[0]["start_cycle"]
                   and r[0]["kind"] != "delay_measurement"]
        partial(anns, on_wire, transcript, lambda r: r[0]["start_cycle"])
        # Each request owns the frame that starts within its cycles.
        pairs, rest = [], list(frames)
        for t, vals in on_wire:
            hit = [f for f in rest if t["start_cycle"] <= f["ss"] <= t["done_cycle"]]
            if len(hit) != 1:
                raise Mismatch(f"{transcript['scenario']} request {t['request']}: "
                               f"{len(hit)} frames within its cycles "
                               f"{t['start_cycle']}..{t['done_cycle']}")
            rest.remove(hit[0])
            pairs.append((hit[0], (t, vals)))
        self.cut_first = any(s == 0 and x.startswith("Partial: ") for s, _, x in anns)
        # A delay measurement is one summary (its mean, at its end) of
        # the "Encoder send position values" frames before it.
        for t, _ in requests:
            if t["kind"] == "delay_measurement":
                taken = [f for f in rest if f["ss"] <= t["done_cycle"]]
                rest = rest[len(taken):]
                values += self.compare_measurement(taken, t, transcript)
        rest = [f for f in rest if not f["text"].startswith("Partial")]
        if rest:
            raise Mismatch(f"{transcript['scenario']}: frames at cycles "
                           f"{[f['ss'] for f in rest]} are in no transaction")
        for fr, (t, vals) in pairs:
            where = f"{transcript['scenario']} request {t['request']} (cycle {fr['ss']})"
            if not (t["start_cycle"] <= fr["ss"] <= t["done_cycle"]):
                raise Mismatch(f"{where}: frame at {fr['ss']}, the request at "
                               f"{t['start_cycle']}..{t['done_cycle']}")
            errors = sorted({e for v in vals for e in v["errors"]})
            if t["encoder_answer"] == "type_i":
                errors.append("type_i")
            if t["mode"] not in self.type21 and "acknowledgement " not in fr["text"]:
                self.not_compared += len([e for e in errors if e in self.ack_errors])
                errors = [e for e in errors if e not in self.ack_errors]
            names, other = named_errors(fr, self.line_errors)
            if "line_not_driven" in errors:
                # A line stuck high reads as mode 111111 (type I) too.
                names = [n for n in names if n != "type_i"]
            expect("errors", sorted(set(names)),
                   [e for e in errors if e in self.line_errors], where)
            expect("other errors", other, [], where)
            text = fr["text"]
            if "line_not_driven" not in errors:
                expect("mode", re.match(r"mode (\d+)", text).group(1), t["mode"], where)
            values += 1 + len(errors)
            if set(errors) & {"no_start_bit", "line_not_driven"}:
                continue
            pos = [int(x) for x in re.findall(r"(?:position|test values) (\d+)", text)]
            wanted = [v["position"] for v in vals if v["position"] is not None]
            expect("positions", pos, wanted, where)
            f1 = [x == "1" for x in re.findall(r"F1 (\d)", text)]
            expect("F1", f1, [v["f1"] for v in vals][:len(f1)] if wanted else [], where)
            if " F2 " in text:
                expect("F2", re.search(r"F2 (\d)", text).group(1) == "1", t["f2"], where)
            for k in ("ad1", "ad2"):
                m = re.search(k.upper() + r" (\w{6})", text)
                expect(k, m and m.group(1), t[k], where)
            m = re.search(r"block (\w\w) (\w{4})", text)
            if m:
                expect("MRS/address", int(m.group(1), 16), t["mrs"], where)
                expect("parameter", int(m.group(2), 16), t["param"], where)
                values += 2
            m = re.search(r"ack (\w\w) (\w{4})", text)
            if t.get("ack") is not None or m:
                expect("acknowledgement", m and [int(m.group(1), 16), int(m.group(2), 16)],
                       t.get("ack"), where)
                values += 1
            values += 2 * len(pos) + 2
        return len(frames), values

    def compare_measurement(self, frames, t, transcript):
        """The measurement frames are position reads, and the master's
        mean delay is the decoder's mean start-bit delay of the last
        round, plus the master's synchroniser."""
        where = f"{transcript['scenario']} delay measurement ending at {t['done_cycle']}"
        p = transcript["parameters"]
        rounds = p["MEAS_COUNT"]
        if len(frames) < rounds and not (frames and self.cut_first):
            raise Mismatch(f"{where}: {len(frames)} frames, a round is {rounds}")
        delays = []
        for fr in frames[-rounds:]:
            expect("mode", re.match(r"mode (\d+)", fr["text"]).group(1), t["mode"], where)
            m = re.search(r"delay (\d+)", fr["text"])
            if m:
                delays.append(int(m.group(1)))
        mean = sum(delays) / max(1, len(delays))
        # A delay beyond the counter's range is the master's own verdict.
        consistent = "delay_measurement_inconsistent" not in t["errors"] and \
            t["delay_cycles"] is not None and t["delay_cycles"] < p["DELAY_MAX"]
        if consistent and abs(mean + SYNC_STAGES - t["delay_cycles"]) > 1:
            raise Mismatch(f"{where}: the start bits came {delays} cycles after "
                           f"their clock edges (+{SYNC_STAGES} synchroniser), the "
                           f"master measured {t['delay_cycles']}")
        return len(delays) + 1

    def flip(self, anns, transcript):
        for fr in frames_of(anns, "Frame: "):
            if not fr["errors"] and "AD1" in fr["text"] and "AD2" not in fr["text"]:
                # A bit of the position, a few after the start bit.
                ss, es, _ = [b for b in bits_of(fr)][12]
                return ss, es, "CRC error"
        return None


def hexes(text):
    m = re.search(r"bytes ((?:[0-9a-f]{2} ?)+)", text)
    return [int(x, 16) for x in m.group(1).split()] if m else []


class RequestAnswer:
    """A half-duplex line of requests and answers (T-format, ESL): per
    transaction, the requests and answers on the wire byte for byte, the
    errors the line shows, and the positions of clean answers."""

    data_signal = "line_at_host"
    # The transcript's name for the single-turn position and the
    # decoder's.
    position = ("abs", "ABS")

    def compare(self, anns, transcript):
        msgs = [(ss, es, t) for ss, es, t in anns
                if t.startswith(("Request: ", "Answer: ", "Answer continued: "))]
        errs = [(ss, es, t[len("Error: "):]) for ss, es, t in anns if t.startswith("Error: ")]
        values = 0
        used = 0
        ts = transcript["transactions"]
        key, label = self.position
        for i, t in enumerate(ts):
            end = ts[i + 1]["start_cycle"] if i + 1 < len(ts) else float("inf")
            where = f"{transcript['scenario']} transaction {t['index']}"
            mine = [m for m in msgs if t["start_cycle"] <= m[0] < end]
            used += len(mine)
            reqs = [hexes(x) for _, _, x in mine if x.startswith("Request")]
            answers = []
            for _, _, x in mine:
                if x.startswith("Answer continued") and answers:
                    answers[-1] += hexes(x)
                elif x.startswith("Answer"):
                    answers.append(hexes(x))
            expect("requests", reqs, t["wire_requests"], where)
            expect("answers", answers, [a for a in t["wire_answers"] if a], where)
            values += len(reqs) + len(answers)
            if any(r != t["sent"][:len(r)] for r in t["wire_requests"]):
                # A request corrupted on the wire: what the host then
                # received is its receiver's tale, not the line's.
                continue
            got = {k for k, text in self.line_errors.items()
                   for ss, _, e in errs if t["start_cycle"] <= ss < end and e.startswith(text)}
            if "timeout" in t["errors"]:
                # The host judged nothing of an answer after its timeout.
                got &= {"timeout"}
            expect("errors", sorted(got), sorted(set(t["errors"]) & set(self.line_errors)), where)
            values += len(t["errors"])
            for _, _, x in mine:
                m = re.search(label + r" (\d+)", x)
                if x.startswith("Answer") and m and not got and t[key]:
                    expect(label, int(m.group(1)), t[key], where)
                    values += 1
        expect("messages outside the transactions", used, len(msgs), transcript["scenario"])
        return len(msgs), values

    def flip(self, anns, transcript):
        for ss, es, t in anns:
            if t.startswith("Answer: ") and " ok" in t and "bad" not in t:
                # A data bit of the answer's third byte (a data field).
                bit = (es - ss) / len(hexes(t)) / 10
                at = int(ss + bit * (2 * 10 + 1 + 3))
                return at, int(at + bit), "Error: CRC"
        return None


class Tformat(RequestAnswer):
    core = "tformat_host"
    decoder_id = "tformat"
    minimum_scenarios = 19
    line_errors = {"crc": "CRC error", "frame": ("Byte ", "Answer of "),
                   "cf_mismatch": "CF 0x", "comm_alarm": "Communication alarm",
                   "timeout": "No answer"}

    def decoder(self, transcript, scenario):
        baud = transcript["f_sys_hz"] / transcript["parameters"]["CLOCKS_PER_BIT"]
        timeout_us = transcript["parameters"]["TIMEOUT_CLOCKS"] * 1e6 / transcript["f_sys_hz"]
        return (f"uart:rx=line_at_host:baudrate={round(baud)}:format=hex,"
                f"tformat:timeout_us={timeout_us:g}")



class Esl(RequestAnswer):
    core = "esl_host"
    decoder_id = "esl"
    minimum_scenarios = 17
    # busy (the EEPROM stayed busy through the host's retries) is the
    # host's judgement.
    line_errors = {"crc1": "CRC1 error", "crc2": "CRC2 error",
                   "frame": ("Byte ", "Answer of "), "cf_mismatch": ("CF 0x", "CF2 0x"),
                   "channel_mismatch": "Channels disagree", "sequence": "Sequence",
                   "comm_alarm": "Communication alarm", "timeout": "No answer"}

    def decoder(self, transcript, scenario):
        p = transcript["parameters"]
        f = transcript["f_sys_hz"]
        return (f"uart:rx=line_at_host:baudrate={round(f / p['CLOCKS_PER_BIT'])}:format=hex,"
                f"esl:timeout_us={p['TIMEOUT_CLOCKS'] * 1e6 / f:g}"
                f":broadcast_address={p['BROADCAST_ADDRESS']}"
                f":rs_tolerance={p['RS_TOLERANCE']}")


class Sar:
    core = "sar_async_host"
    decoder_id = "sar58k24"
    data_signal = "line_at_host"
    minimum_scenarios = 15
    # stale (no fresh timed frame in time) is the host's judgement.
    line_errors = {"checksum": "Checksum error",
                   "frame": ("Byte ", "Not a frame"),
                   "parity": "Byte ", "address": "Answer tagged",
                   "timeout": "No answer"}

    def decoder(self, transcript, scenario):
        p = transcript["parameters"]
        f = transcript["f_sys_hz"]
        parity = scenario["sar"].get("parity", "none")
        return (f"uart:rx=line_at_host:baudrate={round(f / p['CLOCKS_PER_BIT'])}"
                f":parity={parity}:format=hex,"
                f"sar58k24:bits={p['BITS']}:code={'gray' if p['GRAY'] else 'binary'}"
                f":timeout_ms={p['TIMEOUT_CLOCKS'] * 1e3 / f:g}")

    def compare(self, anns, transcript):
        """Every byte on the line in order; every position the host read
        cleanly among the decoder's good frames, in order; an error of the
        decoder's near every transaction the host flagged, and none
        elsewhere. (With noise, gaps and truncations the host splits the
        byte stream by its own windows, which the line does not show.)"""
        msgs = [(ss, es, t) for ss, es, t in anns if t.startswith(("Command: ", "Answer: "))]
        errs = [(ss, es, t[len("Error: "):]) for ss, es, t in anns if t.startswith("Error: ")]
        ts = transcript["transactions"]
        line = [b for _, _, x in msgs for b in hexes(x)]
        wire = [b for t in ts for m in t["wire_requests"] + t["wire_answers"] for b in m]
        # libsigrokdecode 0.5 tells a stacked decoder nothing at the end of
        # a capture: a last message cut short by it is never shown.
        if line != wire[:len(line)] or len(wire) - len(line) > 6:
            expect("bytes on the line", line, wire, transcript["scenario"])
        good = [int(p) for _, _, x in msgs if "checksum ok" in x
                for p in re.findall(r"position (\d+)", x)]
        want = [t["position"] for t in ts if t["position"] is not None
                and not set(t["errors"]) & set(self.line_errors)]
        it = iter(good)
        if not all(any(g == w for g in it) for w in want):
            raise Mismatch(f"{transcript['scenario']}: the host's positions {want} "
                           f"are not in order among the decoder's {good}")
        frame_time = 10 * transcript["parameters"]["CLOCKS_PER_BIT"] * 8
        # A timeout in the handshake modes: the request is a pulse on the
        # trigger pin, not on this line.
        flagged = [t for t in ts if set(t["errors"]) & set(self.line_errors)
                   - ({"timeout"} if not any(t["wire_requests"]) else set())]
        cut = len(wire) > len(line)
        for t in flagged:
            if cut and t is ts[-1]:
                continue  # in the tail the decoder is never told of
            end = t["done_cycle"] + frame_time
            if not any(t["start_cycle"] - frame_time <= ss <= end for ss, _, _ in errs):
                raise Mismatch(f"{transcript['scenario']} transaction {t['index']}: the "
                               f"host flagged {t['errors']}, the decoder saw nothing wrong")
        for ss, _, e in errs:
            if not any(t["start_cycle"] - frame_time <= ss <= t["done_cycle"] + frame_time
                       for t in flagged):
                raise Mismatch(f"{transcript['scenario']}: the decoder's `{e}` at cycle "
                               f"{ss}, where the host flagged nothing")
        return len(msgs), len(line) + len(want) + len(flagged)

    def flip(self, anns, transcript):
        if transcript["parameters"]["PARITY"]:
            return None  # the parity bit would see it first
        for ss, es, t in anns:
            if t.startswith("Answer: ") and "checksum ok" in t:
                bit = (es - ss) / len(hexes(t)) / 10
                at = int(ss + bit * (2 * 10 + 1 + 3))
                return at, int(at + bit), "Checksum error"
        return None


ALL = [Ssi(), Biss(), Endat(), Tformat(), Esl(), Sar()]
