"""What sigrok/check.py holds each decoder to: one class per decoder, each
saying which committed waves it reads (vectors/<core>/), the decoder's
options for a scenario, how its frames compare with the transcript's
transactions, and which bit to invert in the bit-flip test."""



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


def partial(anns, transactions, transcript):
    """The transactions a decoder can see whole: one that starts at the
    wave's first cycle has lost its first edge, and the decoder must say
    so (a `Partial:` frame) instead of decoding it."""
    if transactions and transactions[0]["start_cycle"] == 0:
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


ALL = [Ssi()]
