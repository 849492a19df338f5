#!/usr/bin/env python3
"""check_register_banks.py: the Icarus-only register-bank gates of hdl/rtl/ are exact.

Each core's clocked block writes its register bank (the registers that hold
between events) inside a `begin ... end` that Icarus, and only Icarus, runs
when `bank_change` is true (docs/rtl.md, "Register banks"):

    `ifdef __ICARUS__
    wire bank_change = {
        a_next, b_next
    } !== {
        a_reg, b_reg
    };
    `endif
    always @(posedge i_clk) begin
    `ifdef __ICARUS__
        if (bank_change)
    `endif
        begin
            a_reg <= a_next;
            b_reg <= b_next;
        end
        ...

Skipping the bank is the same behaviour only if bank_change compares exactly
the registers the bank writes, each with its own next value, and the bank
does nothing else. Verilator's lint (scripts/lint.sh, with __ICARUS__
defined) catches lists of different widths; this checks the names: the two
lists and the bank's statements name the same registers in the same order,
with nothing missing, repeated or added, and nothing else in the file is
Icarus-only. Exits 1 with file, line and fix on the first file that breaks
it.

    scripts/check_register_banks.py [FILE.v ...]   (default: hdl/rtl/*.v)
    scripts/check_register_banks.py --self-test    (each check can fail)
"""
import glob
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

DECL = re.compile(
    r"`ifdef __ICARUS__\nwire bank_change = \{\n(?P<next>.*?)\n\} !== \{\n(?P<reg>.*?)\n\};\n`endif\n"
    r"always @\(posedge i_clk\) begin\n`ifdef __ICARUS__\n    if \(bank_change\)\n`endif\n    begin\n"
    r"(?P<body>(?:        [^\n]*\n)*?)    end\n",
    re.S,
)
ASSIGN = re.compile(r"        (\w+)_reg <= (\w+)_next;")


class BankError(Exception):
    pass


def line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def names(listing, suffix, where):
    out = []
    for item in (x.strip() for x in listing.replace("\n", " ").split(",")):
        if not item.endswith(suffix) or not re.fullmatch(r"\w+", item):
            raise BankError(f"{where}: '{item}' is not a register's {suffix} name; "
                            f"list only names ending in {suffix}, separated by commas")
        out.append(item[: -len(suffix)])
    return out


def check_text(path, text):
    """The number of registers in the file's bank (0: no bank); raises BankError."""
    banks = list(DECL.finditer(text))
    code = re.sub(r"//[^\n]*", "", text)  # comments may name them freely
    mentions = len(re.findall(r"\bbank_change\b", code))
    icarus = len(re.findall(r"__ICARUS__", code))
    if not banks:
        if mentions or icarus:
            at = line_of(code, code.find("__ICARUS__" if icarus else "bank_change"))
            raise BankError(f"{path}:{at}: an Icarus-only section that is not the register-bank form; "
                            f"write the bank exactly as docs/rtl.md shows, or remove it")
        return 0
    if len(banks) > 1:
        raise BankError(f"{path}:{line_of(text, banks[1].start())}: a second register bank; "
                        f"a core has one bank, in its main clocked block")
    m = banks[0]
    if mentions != 2 or icarus != 2:
        raise BankError(f"{path}: bank_change or __ICARUS__ appears outside the bank's two places "
                        f"({mentions} and {icarus} times, 2 each expected); remove the others")
    at = line_of(text, m.start())
    nxt = names(m.group("next"), "_next", f"{path}:{at + 2}")
    reg = names(m.group("reg"), "_reg", f"{path}:{line_of(text, m.start('reg'))}")
    body_line = line_of(text, m.start("body"))
    body = []
    for k, line in enumerate(m.group("body").splitlines()):
        a = ASSIGN.fullmatch(line)
        if not a or a.group(1) != a.group(2):
            raise BankError(f"{path}:{body_line + k}: '{line.strip()}' in the register bank; "
                            f"the bank holds only 'x_reg <= x_next;' lines (move anything else after it)")
        body.append(a.group(1))
    for what, listed in (("the _reg list", reg), ("the bank's assignments", body)):
        if listed != nxt:
            missing = [x for x in nxt if x not in listed]
            extra = [x for x in listed if x not in nxt]
            detail = (f"missing {missing}" if missing else "") + (f" extra {extra}" if extra else "")
            if not detail:
                first = next(i for i, (a, b) in enumerate(zip(nxt, listed)) if a != b)
                detail = f"order differs at item {first + 1}: '{nxt[first]}' against '{listed[first]}'"
            raise BankError(f"{path}:{at}: {what} does not match the _next list ({detail.strip()}); "
                            f"list the same registers in the same order in all three places")
    if len(set(nxt)) != len(nxt):
        dup = sorted({x for x in nxt if nxt.count(x) > 1})
        raise BankError(f"{path}:{at}: {dup} listed twice in the bank; list each register once")
    return len(nxt)


def self_test(files):
    """Breaks each bank in the ways the check must catch; returns the number missed."""
    made = caught = 0
    for path in files:
        text = open(path).read()
        m = DECL.search(text)
        if not m:
            continue
        nxt = m.group("next")
        first = re.search(r"(\w+)_next", nxt).group(1)
        second = re.findall(r"(\w+)_next", nxt)[1]
        mutants = [
            # a register left out of the _next list only (same-width swap is the hard case)
            text.replace(f"{first}_next, {second}_next", f"{second}_next, {first}_next", 1),
            # one left out of the bank's statements
            text.replace(f"        {first}_reg <= {first}_next;\n", "", 1),
            # a statement of another form inside the bank
            text.replace(f"        {first}_reg <= {first}_next;\n",
                         f"        {first}_reg <= {first}_next;\n        {first}_reg <= 1'b0;\n", 1),
            # a register written from another's next value
            text.replace(f"        {second}_reg <= {second}_next;", f"        {second}_reg <= {first}_next;", 1),
            # a name repeated in all three places
            text.replace(f"{first}_next, ", f"{first}_next, {first}_next, ", 1)
                .replace(f"{first}_reg, ", f"{first}_reg, {first}_reg, ", 1)
                .replace(f"        {first}_reg <= {first}_next;\n",
                         f"        {first}_reg <= {first}_next;\n        {first}_reg <= {first}_next;\n", 1),
            # another Icarus-only section
            text + "`ifdef __ICARUS__\n`endif\n",
        ]
        for mutant in mutants:
            if mutant == text:
                raise SystemExit(f"self-test: a mutant of {path} came out unchanged (the test itself is stale)")
            made += 1
            try:
                check_text(path, mutant)
            except BankError:
                caught += 1
            else:
                print(f"self-test: a broken bank in {path} passed the check", file=sys.stderr)
    print(f"register banks self-test: {made} broken banks, {caught} caught")
    return made - caught if made else 1


def main(argv):
    if argv[:1] == ["--self-test"]:
        return 1 if self_test(sorted(glob.glob(os.path.join(ROOT, "hdl/rtl/*.v")))) else 0
    files = argv or sorted(glob.glob(os.path.join(ROOT, "hdl/rtl/*.v")))
    total = banks = 0
    for path in files:
        try:
            n = check_text(os.path.relpath(path, ROOT), open(path).read())
        except BankError as e:
            print(f"register bank: {e}", file=sys.stderr)
            return 1
        total += n
        banks += n > 0
    print(f"register banks: {banks} banks, {total} registers, every gate exact")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
